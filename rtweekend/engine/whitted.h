#pragma once
// The classic recursive ray tracer (T. Whitted, "An Improved Illumination Model for Shaded
// Display", CACM 1980), as the CENG795 course defines it (README, "Whitted mode"): one ray per
// pixel, point and ambient lights, Lambert diffuse plus Blinn-Phong specular, shadow rays, and
// recursion through mirrors, conductors and dielectrics up to max_recursion_depth bounces.
//
//   whitted_scene s = load_xml_scene("scene.xml");           // xml_scene.h
//   whitted_render r = render_whitted(s, 0);                   // camera 0
//   write_whitted_image("out.png", r.img);                     // clamp to 0..255, no gamma
//
// It traces the same compiled scene (BVH, float SIMD tests) as the path tracer. The image holds
// radiance in the course's units (255 is white), unclamped; encode_whitted_8bit clamps each
// channel to [0, 255] and truncates, as the course's reference images do.

#include "fresnel.h"
#include "../io/image_write.h"
#include "ray_offset.h"
#include "render_settings.h"
#include "scheduler.h"
#include "compiled_scene.h"
#include "scene_compiler.h"
#include "validate.h"
#include "../whitted_scene.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace rt {

struct whitted_options {
    int threads = 0;              // 0: one per hardware thread
    bool cull_back_faces = false; // skip back faces of opaque objects for primary and reflected rays
    bool quiet = true;            // no progress or statistics on stderr
};

struct whitted_render {
    image img;          // radiance, 0..255 per channel is the displayable range; not clamped
    render_stats stats; // rays counts camera, reflected, refracted and shadow rays
};

namespace detail {
// A material as the Whitted renderer's inner loop reads it: whitted_material in float, with the
// conductor's complex index per channel (the path tracer's conductors have one per channel).
struct whitted_shading {
    whitted_material::kind_t kind = whitted_material::kind_t::plain;
    vec3f ambient, diffuse, specular, mirror, absorption;
    float phong_exponent = 1;
    float refraction_index = 1;
    vec3f eta{1, 1, 1}, k{0, 0, 0}; // conductor
    bool absorbs = false;           // any absorption coefficient above zero
};
} // namespace detail

// Compiles the scene once, then renders any of its cameras.
class whitted_renderer {
  public:
    explicit whitted_renderer(const whitted_scene& scene, const whitted_options& options = {});
    whitted_render render(size_t camera_index) const;
    const compiled_scene& compiled() const { return compiled_; }

  private:
    using shading_material = detail::whitted_shading;
    vec3f trace(const ray3f& r, int depth, bool primary, const shading_material* medium, uint64_t& rays) const;
    vec3f radiance(const surface_hit& hit, const ray3f& r, int depth, uint64_t& rays) const;
    vec3f shade(const surface_hit& hit, const ray3f& r, const shading_material& m, uint64_t& rays) const;
    ray3f spawn(const surface_hit& hit, const vec3f& side, const vec3f& dir) const;

    // What rendering needs of the scene besides its geometry, copied: the renderer does not
    // depend on the whitted_scene staying alive.
    std::vector<view_camera> cameras_;
    vec3f background_, ambient_light_;
    float shadow_ray_epsilon_ = 0;
    int max_recursion_depth_ = 0;
    whitted_options options_;
    compiled_scene compiled_;
    std::vector<shading_material> materials_; // by compiled material index
    struct light_f {
        vec3f position; // relative to the compiled scene's origin
        vec3f intensity;
    };
    std::vector<light_f> lights_;
};

// Renders camera `camera_index` of the scene.
whitted_render render_whitted(const whitted_scene& scene, size_t camera_index, const whitted_options& options = {});

// The course's 8-bit encoding: each channel clamped to [0, 255] and truncated (NaN gives 0).
std::vector<unsigned char> encode_whitted_8bit(const image& img);

// Writes the image as .png or .ppm (P3) in that encoding, or .pfm with the raw radiance; atomically.
void write_whitted_image(const std::string& path, const image& img);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

inline whitted_shading make_whitted_shading(const whitted_material& w) {
    check_color(w.ambient, "ambient reflectance");
    check_color(w.diffuse, "diffuse reflectance");
    check_color(w.specular, "specular reflectance");
    check_color(w.mirror, "mirror reflectance");
    check_color(w.absorption_coefficient, "absorption coefficient");
    if (!(std::isfinite(w.phong_exponent) && w.phong_exponent >= 0))
        throw scene_error("Phong exponent must be finite and non-negative, got " + std::to_string(w.phong_exponent));
    if (!(std::isfinite(w.refraction_index) && w.refraction_index > 0))
        throw scene_error("refraction index must be positive and finite, got " + std::to_string(w.refraction_index));
    if (!(std::isfinite(w.absorption_index) && w.absorption_index >= 0))
        throw scene_error("absorption index must be finite and non-negative, got " + std::to_string(w.absorption_index));
    whitted_shading m;
    m.kind = w.kind;
    // CENG477's files have no material types: a material with a MirrorReflectance is a mirror.
    if (m.kind == whitted_material::kind_t::plain && (w.mirror.x() > 0 || w.mirror.y() > 0 || w.mirror.z() > 0))
        m.kind = whitted_material::kind_t::mirror;
    m.ambient = vec3f(w.ambient);
    m.diffuse = vec3f(w.diffuse);
    m.specular = vec3f(w.specular);
    m.mirror = vec3f(w.mirror);
    m.absorption = vec3f(w.absorption_coefficient);
    m.phong_exponent = float(w.phong_exponent);
    m.refraction_index = float(w.refraction_index);
    m.eta = vec3f(m.refraction_index, m.refraction_index, m.refraction_index);
    float k = float(w.absorption_index);
    m.k = vec3f(k, k, k);
    m.absorbs = m.absorption.x > 0 || m.absorption.y > 0 || m.absorption.z > 0;
    return m;
}

// The Whitted material of an entry of the compiled scene's table: a whitted_surface's own, or the
// closest equivalent of a built-in path-tracer material, so that any scene can be rendered.
inline whitted_shading make_whitted_shading(const material_desc& d) {
    whitted_shading m;
    switch (d.kind) {
    case material_kind::lambertian: m.diffuse = d.albedo; break;
    case material_kind::metal:
        m.kind = whitted_material::kind_t::mirror;
        m.mirror = d.albedo;
        break;
    case material_kind::dielectric:
    case material_kind::exact_dielectric:
        m.kind = whitted_material::kind_t::dielectric;
        m.refraction_index = d.refraction_index;
        m.absorption = d.kind == material_kind::exact_dielectric ? d.absorption : vec3f{0, 0, 0};
        m.absorbs = m.absorption.x > 0 || m.absorption.y > 0 || m.absorption.z > 0;
        break;
    case material_kind::conductor:
        m.kind = whitted_material::kind_t::conductor;
        m.mirror = d.albedo;
        m.eta = d.eta;
        m.k = d.k;
        break;
    case material_kind::custom:
        if (auto* s = dynamic_cast<const whitted_surface*>(d.custom)) return make_whitted_shading(s->params());
        throw scene_error("the Whitted renderer cannot shade a user-defined material: use whitted_surface");
    }
    return m;
}

inline vec3f exp_neg(const vec3f& v) { return {std::exp(-v.x), std::exp(-v.y), std::exp(-v.z)}; }

} // namespace detail

inline whitted_renderer::whitted_renderer(const whitted_scene& scene, const whitted_options& options)
    : cameras_(scene.cameras), options_(options),
      compiled_(compile_scene(scene.world, scene.cameras.empty() ? point3(0, 0, 0) : scene.cameras[0].position)) {
    if (!std::isfinite(scene.shadow_ray_epsilon) || scene.shadow_ray_epsilon < 0)
        throw scene_error("shadow ray epsilon must be finite and non-negative");
    if (scene.max_recursion_depth < 0) throw scene_error("max recursion depth must be non-negative");
    check_color(scene.background, "background colour");
    check_color(scene.ambient_light, "ambient light");
    background_ = vec3f(scene.background);
    ambient_light_ = vec3f(scene.ambient_light);
    shadow_ray_epsilon_ = float(scene.shadow_ray_epsilon);
    max_recursion_depth_ = scene.max_recursion_depth;
    for (const material_desc& d : compiled_.materials) materials_.push_back(detail::make_whitted_shading(d));
    for (const point_light& l : scene.lights) {
        if (!finite3(l.position)) throw scene_error("point light position must be finite");
        check_color(l.intensity, "point light intensity");
        lights_.push_back({vec3f(l.position - compiled_.origin), vec3f(l.intensity)});
    }
    if (options_.cull_back_faces)
        compiled_.set_back_face_culling(
            [&](uint32_t m) { return materials_[m].kind != whitted_material::kind_t::dielectric; });
}

// A secondary ray from the hit point, offset by the shadow-ray epsilon (and the float error of
// the hit point) to the side `side` of the surface.
inline ray3f whitted_renderer::spawn(const surface_hit& hit, const vec3f& side, const vec3f& dir) const {
    ray3f r;
    r.origin = offset_ray_origin(hit.p, side) + (hit.offset + shadow_ray_epsilon_) * side;
    r.dir = dir;
    r.tmin = 0;
    r.tmax = std::numeric_limits<float>::infinity();
    return r;
}

// Ambient, plus diffuse and Blinn-Phong specular from every point light the point sees.
inline vec3f whitted_renderer::shade(const surface_hit& hit, const ray3f& r, const shading_material& m,
                                     uint64_t& rays) const {
    vec3f L = m.ambient * ambient_light_;
    if (lights_.empty()) return L;
    const vec3f n = hit.shading_normal, v = -r.dir;
    const ray3f base = spawn(hit, hit.normal, r.dir); // origin on the side the ray came from
    for (const light_f& light : lights_) {
        vec3f to_light = light.position - hit.p;
        float d2 = dot(to_light, to_light);
        float d = std::sqrt(d2);
        vec3f l = to_light / d;
        // Shadow ray towards the light; only something closer than the light blocks it.
        ray3f shadow = base;
        vec3f to_light_from_origin = light.position - shadow.origin;
        shadow.tmax = length(to_light_from_origin);
        shadow.dir = to_light_from_origin / shadow.tmax;
        ++rays;
        if (compiled_.occluded(shadow)) continue;
        vec3f E = light.intensity / d2; // irradiance at distance d: I / d^2
        float diffuse = std::fmax(0.0f, dot(n, l));
        vec3f h = normalize(l + v);
        float specular = std::pow(std::fmax(0.0f, dot(n, h)), m.phong_exponent);
        L += E * (diffuse * m.diffuse + specular * m.specular);
    }
    return L;
}

// The radiance arriving along r. `medium` is the absorbing dielectric the ray travels inside,
// if any: its radiance is then attenuated over the distance to the next surface, exp(-c t)
// (Beer's law).
inline vec3f whitted_renderer::trace(const ray3f& r, int depth, bool primary, const shading_material* medium,
                                     uint64_t& rays) const {
    ++rays;
    surface_hit hit;
    bool found = options_.cull_back_faces ? compiled_.intersect_culling_back_faces(r, hit) : compiled_.intersect(r, hit);
    if (!found) return primary ? background_ : vec3f{0, 0, 0};
    const vec3f L = radiance(hit, r, depth, rays);
    return medium ? detail::exp_neg(hit.t * medium->absorption) * L : L;
}

// What leaves the hit point towards the ray's origin: local shading, then the mirror,
// conductor or dielectric part while bounces remain.
inline vec3f whitted_renderer::radiance(const surface_hit& hit, const ray3f& r, int depth, uint64_t& rays) const {
    // A user-written hittable reports its own material; built-in shapes index the table.
    shading_material custom;
    if (hit.user_shape) custom = detail::make_whitted_shading(compile_reported_material(hit.user_record));
    const shading_material& m = hit.user_shape ? custom : materials_[hit.material];
    vec3f L = shade(hit, r, m, rays);
    if (depth >= max_recursion_depth_ || m.kind == whitted_material::kind_t::plain) return L;

    const vec3f n = hit.shading_normal;
    const float cos_i = std::fmin(1.0f, std::fmax(0.0f, -dot(r.dir, n)));
    const ray3f reflected = spawn(hit, hit.normal, normalize(r.dir + 2.0f * cos_i * n));

    switch (m.kind) {
    case whitted_material::kind_t::mirror: L += m.mirror * trace(reflected, depth + 1, false, nullptr, rays); break;
    case whitted_material::kind_t::conductor: {
        vec3f fr{fresnel_conductor_f(cos_i, m.eta.x, m.k.x), fresnel_conductor_f(cos_i, m.eta.y, m.k.y),
                 fresnel_conductor_f(cos_i, m.eta.z, m.k.z)};
        L += fr * m.mirror * trace(reflected, depth + 1, false, nullptr, rays);
        break;
    }
    case whitted_material::kind_t::dielectric: {
        // Entering through the front face the index ratio is n / 1; leaving, 1 / n. The
        // reflected ray stays on the side it came from; the refracted one crosses over.
        const float eta = hit.front_face ? m.refraction_index : 1.0f / m.refraction_index;
        const float fr = fresnel_dielectric_f(cos_i, eta);
        const shading_material* inside = m.absorbs ? &m : nullptr;
        L += fr * trace(reflected, depth + 1, false, hit.front_face ? nullptr : inside, rays);
        if (fr < 1.0f) {
            // Snell's law in vector form (d and n unit, n facing d): t = d / eta + (cos_i / eta - cos_t) n.
            float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
            float cos_t = std::sqrt(std::fmax(0.0f, 1.0f - sin2_t));
            ray3f refracted = spawn(hit, -hit.normal, normalize(r.dir / eta + (cos_i / eta - cos_t) * n));
            L += (1.0f - fr) * trace(refracted, depth + 1, false, hit.front_face ? inside : nullptr, rays);
        }
        break;
    }
    case whitted_material::kind_t::plain: break;
    }
    return L;
}

inline whitted_render whitted_renderer::render(size_t camera_index) const {
    auto start = std::chrono::steady_clock::now();
    if (camera_index >= cameras_.size())
        throw scene_error("camera " + std::to_string(camera_index) + " does not exist (the scene has " +
                          std::to_string(cameras_.size()) + ")");
    const view_camera& c = cameras_[camera_index];
    if (c.width <= 0 || c.height <= 0)
        throw scene_error("image resolution must be positive, got " + std::to_string(c.width) + "x" +
                          std::to_string(c.height));
    if (!finite3(c.position) || !finite3(c.gaze) || !finite3(c.up) ||
        !std::isfinite(c.left + c.right + c.bottom + c.top + c.near_distance))
        throw scene_error("camera settings must be finite numbers");

    // The camera's basis: w = -gaze, v' = up, u = v' x w, v = w x u (gaze and up need not be
    // perpendicular; u is normalised so that they need not be).
    const vec3 w = -unit_vector(c.gaze);
    const vec3 u = unit_vector(cross(c.up, w));
    const vec3 v = cross(w, u);
    if (!finite3(u) || !finite3(w)) throw scene_error("camera gaze and up must be non-zero and not parallel");
    // Pixel (i, j), j = 0 the top row: s = e - d w + (l + (i + 0.5)(r - l)/nx) u + (t - (j + 0.5)(t - b)/ny) v.
    const vec3 corner = -c.near_distance * w + c.left * u + c.top * v; // relative to e
    const vec3 du = (c.right - c.left) / c.width * u, dv = -(c.top - c.bottom) / c.height * v;
    const vec3f eye(c.position - compiled_.origin);

    render_settings settings; // one ray through the centre of each pixel
    settings.samples_per_pixel = 1;
    settings.threads = options_.threads;
    settings.quiet = options_.quiet;
    render_result out = render_samples(
        c.width, c.height, settings,
        [&](int x, int y, int, pcg32&, uint64_t& rays) {
            vec3 dir = corner + (x + 0.5) * du + (y + 0.5) * dv;
            ray3f r;
            r.origin = eye;
            r.dir = vec3f(unit_vector(dir));
            r.tmin = 0;
            r.tmax = std::numeric_limits<float>::infinity();
            return trace(r, 0, true, nullptr, rays);
        },
        start);
    return {std::move(out.img), out.stats};
}

inline whitted_render render_whitted(const whitted_scene& scene, size_t camera_index, const whitted_options& options) {
    return whitted_renderer(scene, options).render(camera_index);
}

inline std::vector<unsigned char> encode_whitted_8bit(const image& img) {
    std::vector<unsigned char> bytes(img.data().size());
    for (size_t i = 0; i < bytes.size(); ++i) {
        float value = img.data()[i];
        bytes[i] = value >= 255.0f ? 255 : (value > 0.0f ? static_cast<unsigned char>(value) : 0); // NaN fails both
    }
    return bytes;
}

inline void write_whitted_image(const std::string& path, const image& img) {
    if (img.empty()) throw scene_error("cannot write '" + path + "': the image is empty");
    std::string contents = detail::image_format(path) == ".pfm"
                               ? detail::encode_pfm(img)
                               : encode_8bit_image(path, img.width(), img.height(), encode_whitted_8bit(img));
    write_file_atomically(path, contents);
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::render_whitted;
using rt::whitted_options;
using rt::whitted_render;
using rt::whitted_renderer;
#endif
