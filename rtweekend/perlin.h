#pragma once
// perlin: book 2's gradient noise (Perlin, "Improving Noise", SIGGRAPH 2002, as the book builds
// it): a random unit vector at every lattice point, chosen through three permutations of 0..255,
// blended with Hermite weights, so the noise is smooth and tiles every 256 units.
//
//   perlin noise;                 draws its tables from random_double(), as the book does
//   noise.noise(p)                in about [-1, 1]; 0 at every lattice point
//   noise.turb(p, depth = 7)      |sum of depth octaves, each at twice the frequency and half
//                                 the weight of the last|
//
// The constructor draws exactly what the book's does, in the same order: 256 vectors of
// vec3::random(-1, 1) (three random_double() each: z, then y, then x, the order g++ evaluates the
// book's vec3(random_double(), ...) in; see vec3.h), then the shuffles of perm_x, perm_y and
// perm_z, each random_int(0, i) for i = 255 down to 1. Outside a render random_double() is the
// book's rand() / (RAND_MAX + 1.0), so a main that calls srand() as the book's would gets the
// book's noise; inside a render it is the sample's own generator (core/rng.h), so a texture
// made there is still the same at any thread count.

#include "core/rng.h"
#include "vec3.h"

#include <cmath>

namespace rt {

class perlin {
  public:
    perlin();

    double noise(const point3& p) const;
    double turb(const point3& p, int depth = 7) const;

    static constexpr int point_count = 256;

  private:
    vec3 randvec_[point_count];
    int perm_x_[point_count], perm_y_[point_count], perm_z_[point_count];

    static void generate_perm(int* p);
    static int lattice_index(double f);
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline perlin::perlin() {
    for (vec3& g : randvec_) g = unit_vector(vec3::random(-1, 1));
    generate_perm(perm_x_);
    generate_perm(perm_y_);
    generate_perm(perm_z_);
}

// The identity, shuffled from the top down (Fisher and Yates).
inline void perlin::generate_perm(int* p) {
    for (int i = 0; i < point_count; ++i) p[i] = i;
    for (int i = point_count - 1; i > 0; --i) {
        const int target = random_int(0, i);
        const int held = p[i];
        p[i] = p[target];
        p[target] = held;
    }
}

inline double perlin::noise(const point3& p) const {
    const double fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
    const int i = lattice_index(fx), j = lattice_index(fy), k = lattice_index(fz);
    const double u = p.x() - fx, v = p.y() - fy, w = p.z() - fz;
    // The gradient at corner (i + di, j + dj, k + dk) dotted with the offset from that corner.
    const int x0 = perm_x_[i], x1 = perm_x_[(i + 1) & 255], y0 = perm_y_[j], y1 = perm_y_[(j + 1) & 255],
              z0 = perm_z_[k], z1 = perm_z_[(k + 1) & 255];
    auto corner = [&](int px, int py, int pz, double du, double dv, double dw) {
        const vec3& g = randvec_[px ^ py ^ pz];
        return g.x() * du + g.y() * dv + g.z() * dw;
    };
    const double d000 = corner(x0, y0, z0, u, v, w), d001 = corner(x0, y0, z1, u, v, w - 1);
    const double d010 = corner(x0, y1, z0, u, v - 1, w), d011 = corner(x0, y1, z1, u, v - 1, w - 1);
    const double d100 = corner(x1, y0, z0, u - 1, v, w), d101 = corner(x1, y0, z1, u - 1, v, w - 1);
    const double d110 = corner(x1, y1, z0, u - 1, v - 1, w), d111 = corner(x1, y1, z1, u - 1, v - 1, w - 1);
    // Blended by the smoothstep (Hermite cubic 3t^2 - 2t^3) of the position in the cell, so the
    // noise's slope is continuous: the book's sum of the eight corners, each weighted by the
    // product of its three axis weights (t or 1 - t), taken as a lerp along z, then y, then x.
    const double uu = u * u * (3 - 2 * u), vv = v * v * (3 - 2 * v), ww = w * w * (3 - 2 * w);
    auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
    const double at_x0 = lerp(lerp(d000, d001, ww), lerp(d010, d011, ww), vv);
    const double at_x1 = lerp(lerp(d100, d101, ww), lerp(d110, d111, ww), vv);
    return lerp(at_x0, at_x1, uu);
}

// The lattice cell's index modulo 256 (only its low 8 bits are used). The book's int(f) & 255
// wherever an int holds f; beyond that (a point far from the origin, or a large noise scale),
// where the book's conversion is undefined, the same remainder taken in double.
inline int perlin::lattice_index(double f) {
    if (std::fabs(f) < 2147483648.0) return int(f) & 255;
    return std::isfinite(f) ? int(f - 256.0 * std::floor(f / 256.0)) : 0;
}

inline double perlin::turb(const point3& p, int depth) const {
    double sum = 0, weight = 1;
    point3 q = p;
    for (int octave = 0; octave < depth; ++octave) {
        sum += weight * noise(q);
        weight *= 0.5;
        q *= 2;
    }
    return std::fabs(sum);
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::perlin;
#endif
