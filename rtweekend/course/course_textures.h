#pragma once
// course_textures: the texture maps of the CENG795 course scenes (homework 4; section 8 of the
// course format notes, docs/course.md "Textures"). A map is an image, the course's Perlin noise or
// a checkerboard, and its decal mode says what it changes at a surface point: the diffuse or
// specular reflectance, the whole local shading, the shading normal (normal and bump maps), or the
// background of the film.
//
//   texture_map wood;
//   wood.picture = std::make_shared<const image>(read_image("wood.png").pixels);
//   wood.decal = texture_map::decal_t::replace_kd;   // kd = texel / 255
//   scene.textured_objects.push_back({material_copy, {wood}, textured_object::shape_t::mesh});
//
// The formulas (each checked by the course's maintainers against the instructor's images, as the
// format notes record):
//   (u, v) -> texel     u runs left to right, v = 0 is the top row; nearest: (floor(u W),
//                       floor(v H)); bilinear: x = u W, y = v H, p = floor(x), q = floor(y), the
//                       four texels (p..p+1, q..q+1) weighted by the fractions (no half-texel
//                       shift); indices clamped to the image.
//   colour              image: texel / Normalizer (c^2.2 of it with degamma); Perlin: the grey of
//                       its converted noise; checkerboard: BlackColor or WhiteColor.
//   checkerboard        at the object-space point p: x = (int)((p.x + Offset) Scale) % 2 != 0 with C
//                       truncation and remainder (so the cells touching 0 are twice as wide), y, z
//                       likewise; black where (x != y) != z.
//   Perlin              the lecture's noise: 16 gradient vectors, a permutation of 0..15 (fixed
//                       here, so renders repeat; the course's is random), weight
//                       w(t) = -6|t|^5 + 15|t|^4 - 10|t|^3 + 1 per axis over the 8 lattice corners;
//                       `linear` conversion (n + 1) / 2, `absval` |n|.
//   bump height         the mean of R, G, B of the nearest texel in the file's units, whatever
//                       Interpolation and Normalizer say.
// How the renderers use them (course/course_surface_map.h): the colour decals change a copy of the object's
// material; normal and bump maps change the shading normal, in the object's frame for meshes and
// in the world's for spheres (the frames the instructor's images were matched in).

#include "../core/rng.h"
#include "../core/vec3f.h"
#include "../image/image.h"
#include "../texture.h"
#include "../transform.h"
#include "../vec3.h"
#include "../whitted_material.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace rt {

// The course's Perlin noise: a value in about [-1, 1] at any point.
struct course_perlin {
    std::array<uint8_t, 16> permutation{};

    // A permutation of 0..15 drawn from `seed` (Fisher-Yates): the same seed, the same noise.
    static course_perlin seeded(uint64_t seed) {
        course_perlin p;
        for (uint8_t i = 0; i < 16; ++i) p.permutation[i] = i;
        pcg32 rng(seed);
        for (uint32_t i = 15; i > 0; --i) std::swap(p.permutation[i], p.permutation[rng.next_u32() % (i + 1)]);
        return p;
    }

    static double weight(double t) {
        const double a = std::fabs(t), a3 = a * a * a;
        return a3 * (a * (-6 * a + 15) - 10) + 1; // -6|t|^5 + 15|t|^4 - 10|t|^3 + 1
    }

    // The gradient of lattice point (i, j, k): G[P[(i + P[(j + P[k mod 16]) mod 16]) mod 16]].
    vec3 gradient(long long i, long long j, long long k) const {
        static constexpr double g[16][3] = {{1, 1, 0},  {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                            {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1},  {0, 1, -1}, {0, -1, -1},
                                            {1, 1, 0},  {-1, 1, 0}, {0, -1, 1}, {0, -1, -1}};
        auto mod16 = [](long long x) { return size_t(((x % 16) + 16) % 16); };
        const size_t index = permutation[mod16(i + permutation[mod16(j + permutation[mod16(k)])])];
        return vec3(g[index][0], g[index][1], g[index][2]);
    }

    double noise(const vec3& p) const {
        // Far from the origin a double's fraction is gone and the lattice index would overflow:
        // the noise is 0 there (its value at a lattice point).
        if (!(std::fabs(p.x()) < 1e15 && std::fabs(p.y()) < 1e15 && std::fabs(p.z()) < 1e15)) return 0;
        const double fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
        double n = 0;
        for (int c = 0; c < 8; ++c) {
            const double cx = fx + (c & 1), cy = fy + ((c >> 1) & 1), cz = fz + ((c >> 2) & 1);
            const vec3 d(p.x() - cx, p.y() - cy, p.z() - cz);
            n += weight(d.x()) * weight(d.y()) * weight(d.z()) *
                 dot(gradient((long long)cx, (long long)cy, (long long)cz), d);
        }
        return n;
    }
};

// One <TextureMap>.
struct texture_map {
    enum class pattern_t { image, perlin, checkerboard };
    enum class decal_t { replace_kd, blend_kd, replace_ks, replace_all, replace_normal, bump_normal, replace_background };
    pattern_t pattern = pattern_t::image;
    decal_t decal = decal_t::replace_kd;
    // image
    std::shared_ptr<const image> picture;
    bool bilinear = false;   // Interpolation: nearest (the default) or bilinear
    float normalizer = 255;  // texel / normalizer is the colour
    bool degamma = false;    // the colour read as c^2.2
    float bump_factor = 1;   // bump_normal: the height's scale
    // perlin
    float noise_scale = 1;   // the point is multiplied by it
    bool absval = false;     // NoiseConversion absval: |n|; else linear: (n + 1) / 2
    course_perlin perlin = course_perlin::seeded(795);
    // checkerboard
    double scale = 1, offset = 0;
    vec3f black{0, 0, 0}, white{1, 1, 1};

    bool changes_normal() const { return decal == decal_t::replace_normal || decal == decal_t::bump_normal; }

    // Texel (x, y) clamped to the image, in the file's units.
    vec3f texel(long long x, long long y) const {
        const long long w = picture->width(), h = picture->height();
        x = std::clamp(x, 0LL, w - 1);
        y = std::clamp(y, 0LL, h - 1);
        return vec3f(picture->pixel(int(x), int(y)));
    }
    // floor(t) as an integer index, for any t (NaN and far-out values land outside the image and
    // are clamped by texel()).
    static long long cell(double t) { return t >= -1e9 && t <= 1e9 ? (long long)std::floor(t) : (t > 0 ? 1LL << 40 : -1); }

    vec3f nearest(double u, double v) const { return texel(cell(u * picture->width()), cell(v * picture->height())); }
    // The image at (u, v) through its Interpolation, in the file's units.
    vec3f lookup(double u, double v) const {
        if (!bilinear) return nearest(u, v);
        const double x = u * picture->width(), y = v * picture->height();
        const long long p = cell(x), q = cell(y);
        const float dx = std::isfinite(x) ? float(x - double(p)) : 0, dy = std::isfinite(y) ? float(y - double(q)) : 0;
        const float ex = std::clamp(dx, 0.0f, 1.0f), ey = std::clamp(dy, 0.0f, 1.0f);
        return ((1 - ex) * (1 - ey)) * texel(p, q) + (ex * (1 - ey)) * texel(p + 1, q) + ((1 - ex) * ey) * texel(p, q + 1) +
               (ex * ey) * texel(p + 1, q + 1);
    }
    // The bump height at (u, v): the nearest texel's mean channel.
    float height(double u, double v) const {
        const vec3f c = nearest(u, v);
        return (c.x + c.y + c.z) / 3;
    }
    // The converted noise at object-space point p.
    double noise_value(const vec3& p) const {
        const double n = perlin.noise(double(noise_scale) * p);
        return absval ? std::fabs(n) : (n + 1) / 2;
    }
    bool checker_black(const vec3& p) const {
        auto odd = [&](double x) { return std::fmod(std::trunc((x + offset) * scale), 2.0) != 0; };
        return (odd(p.x()) != odd(p.y())) != odd(p.z());
    }
    // The colour a colour decal uses at (u, v) and object-space point p.
    vec3f colour(double u, double v, const vec3& p) const {
        switch (pattern) {
        case pattern_t::perlin: {
            const float n = float(noise_value(p));
            return {n, n, n};
        }
        case pattern_t::checkerboard: return checker_black(p) ? black : white;
        case pattern_t::image: break;
        }
        vec3f c = lookup(u, v) / normalizer;
        if (degamma) c = {std::pow(std::fmax(c.x, 0.0f), 2.2f), std::pow(std::fmax(c.y, 0.0f), 2.2f), std::pow(std::fmax(c.z, 0.0f), 2.2f)};
        return c;
    }
};

// An object with <Textures>: its own copy of its material (which is how the renderer knows a hit
// is on it), its maps in the file's order, and what gives its surface coordinates.
struct textured_object {
    std::shared_ptr<const whitted_material> surface;
    std::vector<texture_map> maps;
    // sphere: (u, v) from the object-space point relative to `center` (u = (pi - phi) / (2 pi),
    // v = theta / pi, theta from +y, phi = atan2(z, x)); mesh: its corners' texture coordinates.
    enum class shape_t { sphere, mesh } shape = shape_t::mesh;
    point3 center{0, 0, 0};
    double radius = 1;
    mat3 linear;           // where the object is placed: x -> linear x + offset (object -> world)
    vec3 offset{0, 0, 0};
};

// The course's (u, v) of a sphere's point P (relative to its centre, in its own frame) of radius
// r: theta from +y, phi = atan2(z, x), u = (pi - phi) / (2 pi), v = theta / pi.
struct course_sphere_coordinates {
    double theta, phi, u, v;
    course_sphere_coordinates(const vec3& P, double r) {
        const double pi_d = 3.14159265358979323846;
        theta = std::acos(std::clamp(P.y() / r, -1.0, 1.0));
        phi = std::atan2(P.z(), P.x());
        u = (pi_d - phi) / (2 * pi_d);
        v = theta / pi_d;
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::course_perlin;
using rt::texture_map;
using rt::textured_object;
#endif
