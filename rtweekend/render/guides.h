#pragma once
// render_guides: the images a denoiser takes beside the render (Intel Open Image Denoise's and
// OptiX's "albedo" and "normal" guides), and the depth and position of what each pixel sees:
// arbitrary output variables (AOVs), `render --aov albedo,normal,depth,position` (docs/apps.md).
//
//   const guide_images g = render_guides(scene, frame, env, settings);   // scene: compile_scene(...)
//
// Each pixel is the mean over `samples` camera rays (the render's first ones: the same pixel
// positions, lens points and times as its samples 0, 1, ...), each followed through delta
// bounces (mirrors, smooth glass; the direction each one's own sample draws) to the first surface
// with a non-delta lobe, at most 8 of them:
//   albedo    that surface's directional albedo, the fraction of light from the ray's direction it
//             scatters (the mean of its material samples' weights, 16 a pixel in all: exactly a
//             Lambertian's albedo, a textured one's texel); an emitter's radiance and, for a ray that leaves the
//             scene, the sky's, each clamped to [0, 1] (as OIDN asks); a user-written material 1
//   normal    its shading normal (with its material's normal map), facing the ray, in world
//             space; (0, 0, 0) where the ray leaves
//   depth     the distance from the camera to the first surface the camera ray hits, delta or not
//             (all three channels); a pixel none of whose rays hits anything has +infinity
//   position  that point, in world space; (0, 0, 0) where no ray hits
// depth and position average the rays that hit. Deterministic: every ray's numbers come from its
// pixel and sample number (sample_rng), at any thread count.

#include "../core/engine_linkage.h"
#include "../image/image.h"
#include "camera_frame.h"
#include "environment.h"
#include "render_settings.h"

namespace rt {

class compiled_scene;

struct guide_images {
    image albedo, normal, depth, position;
};

// Traces the guides of every pixel of `frame` with min(settings.samples_per_pixel, 16) rays each
// (guide_samples), on settings.threads threads.
RTWEEKEND_ENGINE_FUNCTION guide_images render_guides(const compiled_scene& scene, const camera_frame& frame,
                                                     const environment& env, const render_settings& settings);

// The rays per pixel render_guides takes for a render of `samples_per_pixel`.
inline int guide_samples(int samples_per_pixel) { return samples_per_pixel < 16 ? (samples_per_pixel > 0 ? samples_per_pixel : 1) : 16; }

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/rng.h"
#include "../scene/compiled_scene.h"
#include "../scene/scene_compiler.h"
#include "../scene/surface_coordinates.h"
#include "scheduler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

namespace rt {

namespace detail {

struct guide_sample {
    vec3f albedo{0, 0, 0}, normal{0, 0, 0};
    bool hit = false;
    float depth = 0;
    vec3 position{0, 0, 0};
};

inline vec3f clamp_unit(const vec3f& c) {
    auto one = [](float x) { return x > 0 ? (x < 1 ? x : 1.0f) : 0.0f; };
    return {one(c.x), one(c.y), one(c.z)};
}

// One camera ray's guides (the rules at the top of the file).
inline guide_sample trace_guide(const compiled_scene& scene, const environment& env, ray3f r, pcg32& rng,
                                int albedo_samples) {
    constexpr int max_delta_bounces = 8;
    guide_sample g;
    surface_hit hit;
    for (int bounce = 0; bounce <= max_delta_bounces; ++bounce) {
        if (!scene.intersect(r, hit)) {
            g.albedo = clamp_unit(env.eval(r.dir));
            return g;
        }
        if (bounce == 0) {
            g.hit = true;
            g.depth = hit.t;
            g.position = scene.origin + hit.p.to_double();
        }
        compiled_material m = hit.user_shape ? compile_reported_material(hit.user_record) : scene.materials[hit.material];
        if (m.texture != no_texture) m = textured(scene, m, hit);
        vec3f shading_normal = shading_normal_at(scene, hit); // with its normal map, if any
        if (const surface_map* map = hit.user_shape ? nullptr : scene.surface_map_of(hit.material)) {
            surface_change change{m, shading_normal}; // a front end's map (surface_map.h)
            map->apply(scene, hit, change);
            m = change.material;
            shading_normal = change.shading_normal;
        }
        const shading_point sp{shading_normal, hit.front_face};
        const vec3f wo = -r.dir;
        if (m.emits() || !m.scatters() || m.is_user()) {
            g.albedo = m.is_user() ? vec3f{1, 1, 1} : clamp_unit(m.emitted(wo, sp));
            g.normal = shading_normal;
            return g;
        }
        if (m.has_delta_lobe() && !m.has_non_delta_lobe() && bounce < max_delta_bounces) {
            material_sample s;
            if (!m.sample(wo, sp, rng, s)) return g; // absorbed: black, no normal
            r = spawn_ray(hit, s.wi, std::numeric_limits<float>::infinity(), false);
            continue;
        }
        vec3f sum{0, 0, 0};
        for (int k = 0; k < albedo_samples; ++k) {
            material_sample s;
            if (m.sample(wo, sp, rng, s) && std::isfinite(s.value.x + s.value.y + s.value.z)) sum += s.value;
        }
        g.albedo = sum * (1.0f / float(albedo_samples));
        g.normal = shading_normal;
        return g;
    }
    return g;
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION guide_images render_guides(const compiled_scene& scene, const camera_frame& frame,
                                                     const environment& env, const render_settings& settings) {
    settings.check();
    const int w = frame.width, h = frame.height, n = guide_samples(settings.samples_per_pixel);
    const int albedo_samples = (16 + n - 1) / n; // 16 material samples a pixel in all
    guide_images out{image(w, h), image(w, h), image(w, h), image(w, h)};
    const bool with_time = scene.uses_time();
    auto rows = [&](int first, int step) {
        for (int y = first; y < h; y += step)
            for (int x = 0; x < w; ++x) {
                const uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
                vec3f albedo{0, 0, 0}, normal{0, 0, 0};
                vec3 position(0, 0, 0);
                double depth = 0;
                int hits = 0;
                for (int s = 0; s < n; ++s) {
                    pcg32 rng = sample_rng(settings.seed, pixel, uint64_t(s));
                    const ray3f r = frame.sample_ray(x, y, n, rng, with_time);
                    const detail::guide_sample g = detail::trace_guide(scene, env, r, rng, albedo_samples);
                    albedo += g.albedo;
                    normal += g.normal;
                    if (g.hit) {
                        ++hits;
                        depth += g.depth;
                        position += g.position;
                    }
                }
                const float inv = 1.0f / float(n);
                out.albedo.set_pixel(x, y, (albedo * inv).to_double());
                const float len = length(normal);
                out.normal.set_pixel(x, y, len > 0 ? (normal * (1.0f / len)).to_double() : color(0, 0, 0));
                const double d = hits ? depth / hits : std::numeric_limits<double>::infinity();
                out.depth.set_pixel(x, y, color(d, d, d));
                out.position.set_pixel(x, y, hits ? position / hits : vec3(0, 0, 0));
            }
    };
    const int threads = detail::render_threads(settings, h);
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(rows, t, threads);
    rows(0, threads);
    for (std::thread& t : pool) t.join();
    return out;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::guide_images;
using rt::render_guides;
#endif
