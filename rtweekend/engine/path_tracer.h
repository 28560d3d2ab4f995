#pragma once
// The path tracer: the book's ray_color as a loop, over the compiled scene.
//
//   render_result r = path_trace(world, frame, environment::sky(), settings);
//
// The world is first compiled into a flat scene (scene_compiler.h); then the scheduler
// (scheduler.h) takes settings.samples_per_pixel samples per pixel, each one camera ray from
// `frame` followed through at most settings.max_depth scattering events. A ray that leaves the
// scene gathers the environment's radiance times the product of the materials' weights.

#include "../hittable.h"
#include "camera_frame.h"
#include "compiled_scene.h"
#include "environment.h"
#include "ray_offset.h"
#include "render_settings.h"
#include "rng.h"
#include "scene_compiler.h"
#include "scheduler.h"
#include "user_material.h"

#include <chrono>
#include <cstdint>
#include <limits>
#include <optional>

namespace rt {

// Renders `world` through `frame` with the path tracer. Throws scene_error on bad input.
render_result path_trace(const hittable& world, const camera_frame& frame, const environment& env,
                         const render_settings& settings);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// One path from the camera: the book's ray_color, as a loop. Returns the radiance it carries.
inline vec3f trace_path(const compiled_scene& scene, const environment& env, ray3f r, int max_depth, pcg32& rng,
                        uint64_t& rays) {
    vec3f throughput{1, 1, 1};
    surface_hit hit;
    std::optional<compiled_material> reported; // the material a user-written hittable reports at its hit
    for (int depth = 0; depth < max_depth; ++depth) {
        ++rays;
        if (!scene.intersect(r, hit)) return throughput * env.eval(r.dir);

        if (hit.user_shape) reported = compile_reported_material(hit.user_record);
        const compiled_material& m = hit.user_shape ? *reported : scene.materials[hit.material];
        // Beer's law: a ray that reaches the back face of absorbing glass has travelled hit.t
        // inside it (directions are unit).
        if (!hit.front_face && m.absorbs_inside()) throughput *= m.transmittance(hit.t);

        // Materials see the geometric normal: the path tracer does not use smooth shading normals.
        material_sample s;
        const bool scattered = m.kind == material_kind::user
                                   ? sample_user_material(scene, *m.source, r, hit, s)
                                   : m.sample(-r.dir, shading_point{hit.normal, hit.front_face}, rng, s);
        if (!scattered) return {0, 0, 0};
        throughput *= s.value;

        // Leave the surface on the side the new direction points to.
        vec3f side = dot(s.wi, hit.normal) >= 0 ? hit.normal : -hit.normal;
        r.origin = offset_ray_origin(hit.p, side) + hit.offset * side;
        r.dir = s.wi;
        r.tmin = 0;
        r.tmax = std::numeric_limits<float>::infinity();
    }
    return {0, 0, 0}; // the book: no more light is gathered past the bounce limit
}

} // namespace detail

inline render_result path_trace(const hittable& world, const camera_frame& frame, const environment& env,
                                const render_settings& settings) {
    auto start = std::chrono::steady_clock::now();
    settings.check();
    const compiled_scene scene = compile_scene(world, frame.position);
    const int spp = settings.samples_per_pixel, max_depth = settings.max_depth;
    const bool user_code = scene.calls_user_code();
    return render_samples(
        frame.width, frame.height, settings,
        [&](int x, int y, int, pcg32& rng, uint64_t& rays) {
            ray3f r = frame.sample_ray(x, y, spp, rng);
            if (user_code) {
                // User-written shapes and materials may call random_double(): give them this
                // sample's generator so the image stays deterministic.
                detail::scoped_sample_rng guard(rng);
                return detail::trace_path(scene, env, r, max_depth, rng, rays);
            }
            return detail::trace_path(scene, env, r, max_depth, rng, rays);
        },
        start);
}

} // namespace rt
