#pragma once
// The path tracer: the book's ray_color as a loop, over the compiled scene.
//
//   const compiled_scene scene = compile_scene(world, origin);          // once (scene_compiler.h)
//   render_result r = path_trace(scene, frame, environment::sky(), settings);   // any camera
//   render_result r = path_trace(world, frame, environment::sky(), settings);   // both at once
//
// The scheduler (scheduler.h) takes settings.samples_per_pixel samples per pixel, each one camera
// ray from `frame` followed through at most settings.max_depth scattering events. A ray that
// leaves the scene gathers the environment's radiance times the product of the materials' weights.
// A compiled scene serves any number of cameras; it is most precise near its origin, so compile it
// around the cameras (path_trace(world, ...) compiles around the frame's position).

#include "../core/engine_linkage.h"
#include "../directional_light.h"
#include "../point_light.h"
#include "camera_frame.h"
#include "environment.h"
#include "render_settings.h"
#include "scheduler.h"

#include <vector>

namespace rt {

class compiled_scene;
class hittable;

// Renders the compiled scene through `frame` with the path tracer. Throws scene_error on bad input.
RTWEEKEND_ENGINE_FUNCTION render_result path_trace(const compiled_scene& scene, const camera_frame& frame,
                                                   const environment& env, const render_settings& settings);
// Compiles `world` around the frame's position (with point and directional lights, which only
// light sampling finds: the bsdf estimator never does), then renders it.
RTWEEKEND_ENGINE_FUNCTION render_result path_trace(const hittable& world, const camera_frame& frame,
                                                   const environment& env, const render_settings& settings,
                                                   const std::vector<point_light>& point_lights = {},
                                                   const std::vector<directional_light>& directional_lights = {});

} // namespace rt

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

#include "../hittable.h"
#include "caustic_paths.h"
#include "../scene/compiled_scene.h"
#include "../core/in_place_array.h"
#include "../scene/light_sampling.h"
#include "../scene/light_set.h"
#include "../core/ray_offset.h"
#include "../core/rng.h"
#include "sampler.h"
#include "../scene/scene_compiler.h"
#include "../scene/surface_coordinates.h"
#include "user_material.h"
#include "vertex_material.h"

#include <chrono>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <type_traits>

namespace rt {
namespace detail {

// Russian roulette (nee only): past a number of scattering events, a path whose throughput t
// (its largest channel) has fallen below roulette_weight goes on with probability
// q = t / roulette_weight and is weighed by 1/q when it does, so the mean is unchanged (Arvo and
// Kirk 1990; pbrt, 4th ed., 14.1.5) and every survivor carries roulette_weight. pbrt and the
// first version here used 1: survivors then carry the full weight of a camera ray, and in a
// closed room a caustic reached three to nine bounces deep (diffuse -> glass -> glass -> light)
// became a firefly of weight 1. With 1/2, fewer paths die in the first bounces and a caustic
// found deep counts half (BENCHMARKS.md, section 8, has the figures: 1.55x the efficiency on
// book 3's Cornell box). Roulette starts after two events in a scene with emitters (closed
// rooms, long paths: on book 3's Cornell box, 1.26x the efficiency of starting after five) and
// after five in a scene lit by the sky alone (paths escape soon; starting after three cost the
// cover scene 5 % of its efficiency).
inline constexpr float roulette_weight = 0.5f;
inline int roulette_depth(const light_set& lights) { return lights.empty() ? 5 : 2; }

// One path from the camera, taken a bounce at a time: ray() is the ray to trace
// next, advance(found, hit) takes what it met, and radiance_so_far() is what the path carries,
// all of it once done().
// Materials see the shading normal (a smooth mesh's interpolated one, folded as vertex_material
// says; else the geometric normal). Each decision draws from its own dimension of the sampler
// (sampler.h). With `caustics`, the paths light tracing also finds count here by the path
// tracer's share, which a caustic_connection (caustic_paths.h) works out in three hooks.
//
// The path tracer advances a batch's paths side by side, a bounce of each in turn: their rays
// are traced together (as packets, compiled_scene::intersect_batch), and the processor overlaps
// one path's steps with another's where a single path would wait on each of its own in turn.
//
// NeeOnly: the path tracer's default estimator (next-event estimation), compiled on its own for
// speed; otherwise the estimator is chosen at run time (book 1's and book 3's, and any with user
// code), which costs one test where a choice is made, and one copy of the code to compile.
template <bool NeeOnly, bool UserMaterials>
class camera_path {
  public:
    // camera_ray: a sample of pixel (x, y).
    camera_path(const compiled_scene& scene, const environment& env, const ray3f& camera_ray, int x, int y,
                int max_depth, pixel_sampler& ps, uint64_t& rays, path_estimator estimator,
                const caustic_splats* caustics = nullptr)
        : scene(scene), env(env), lights(scene.lights), roulette_start(roulette_depth(scene.lights)),
          max_depth(max_depth), ps(ps), rays(rays), estimator_(NeeOnly ? path_estimator::nee : estimator),
          r(camera_ray), x_(x), y_(y), done_(max_depth <= 0) {
        // The sample's own light path, its numbers from a stream split off the sample's own, which
        // it leaves as it was (joined to every vertex of the path, the light path gains little
        // from stratified numbers, which cost more to draw).
        if (caustics) caustic.start(scene, *caustics, max_depth, ps.rng().split(), camera_ray, rays);
    }

    bool done() const { return done_; }
    // Scattering events so far: the bounce whose dimensions (sample_dimension::bounce) the path
    // draws from next.
    int bounces() const { return depth; }
    const ray3f& ray() const { return r; }
    const vec3f& radiance_so_far() const { return radiance; }
    // One bounce: ray() hit `hit` if `found`, else it left the scene.
    void advance(bool found, const surface_hit& hit);

  private:
    void finish() { done_ = true; }
    bool nee() const { return NeeOnly || estimator_ == path_estimator::nee; }
    bool mixture() const { return !NeeOnly && estimator_ == path_estimator::mixture; }

    const compiled_scene& scene;
    const environment& env;
    const light_set& lights;
    const int roulette_start, max_depth;
    pixel_sampler& ps;
    uint64_t& rays;
    const path_estimator estimator_;
    ray3f r;
    int x_, y_; // the pixel
    int depth = 0;
    vec3f radiance{0, 0, 0}, throughput{1, 1, 1};
    // The vertex the ray left from, for weighing an emitter it hits against light sampling there:
    // its position and the density its material drew the ray with. A camera ray, a ray after a
    // delta lobe, and every ray of the bsdf and mixture estimators count emission in full.
    bool count_emission_fully = true;
    vec3f last_p;
    float last_pdf = 0;
    bool done_;
    // Its part in caustics traced from the lights (caustic_paths.h); inactive without them. Last:
    // most renders never fill it.
    caustic_connection caustic;
};

template <bool NeeOnly, bool UserMaterials>
void camera_path<NeeOnly, UserMaterials>::advance(bool found, const surface_hit& hit) {
    ++rays;
    if (!found) {
        if (depth == 0) {
            radiance += throughput * env.camera_miss(r.dir, x_, y_);
        } else if (!env.camera_rays_only) {
            // An environment map is light-sampled at every vertex too (below): weighed as an
            // emitter that is hit.
            const float weight = env.map && nee() && !count_emission_fully ? power_heuristic(last_pdf, env.map->pdf(r.dir)) : 1.0f;
            radiance += throughput * env.eval(r.dir) * weight;
        }
        return finish();
    }
    // The material at the hit: the scene's, or one built here, as a user-written hittable reports
    // it (built from its record) or as a textured one is asked (a copy holding the texture's
    // colour at this hit). An untextured material of the scene pays only the tests.
    in_place_array<compiled_material, 2> built;
    const compiled_material* at_hit = hit.user_shape ? &built.emplace_back(compile_reported_material(hit.user_record))
                                                     : &scene.materials[hit.material];
    if (at_hit->texture != no_texture) at_hit = &built.emplace_back(textured(scene, *at_hit, hit));
    // A normal map (compiled_scene::normal_maps) turns the shading normal; a scene without one
    // pays the test of an empty table.
    const bool mapped = !scene.normal_maps.empty() || !scene.surface_maps.empty();
    vec3f shading_normal = mapped ? shading_normal_at(scene, hit) : hit.shading_normal;
    // A front end's surface map (surface_map.h) may change the material and the normal, and make
    // the surface glow: seen in full by every ray, as it is no light to sample.
    vec3f glow{0, 0, 0};
    if (mapped && !hit.user_shape)
        if (const surface_map* map = scene.surface_map_of(hit.material)) {
            surface_change change{*at_hit, shading_normal};
            map->apply(scene, hit, change);
            at_hit = &built.emplace_back(change.material);
            shading_normal = change.shading_normal;
            glow = change.glow;
        }
    const compiled_material& m = *at_hit;
    // Beer's law: a ray that reaches the back face of absorbing glass has travelled hit.t
    // inside it (directions are unit).
    if (!hit.front_face && m.absorbs_inside()) throughput *= m.transmittance(hit.t);
    if (mapped) radiance += throughput * glow;
    const shading_point sp{shading_normal, hit.front_face};
    const vec3f wo = -r.dir;

    if (m.emits()) {
        const vec3f le = m.emitted(wo, sp);
        float weight = 1;
        if (nee() && !count_emission_fully && !is_black(le)) {
            // Light sampling at the last vertex could have drawn this point too: weigh the two
            // strategies by the power heuristic (Veach 1997, ch. 9).
            const uint32_t l = lights.light_at(hit.kind, hit.index);
            if (l != light_set::none) {
                const vec3f outward = hit.front_face ? hit.normal : -hit.normal;
                weight = power_heuristic(last_pdf, lights.pdf(l, last_p, hit.p, outward));
            }
        }
        // Light tracing may find this path too: the path tracer's share of it.
        if (caustic.active()) caustic.weigh_emission(lights, hit, weight);
        radiance += throughput * le * weight;
    }
    if (!m.scatters()) return finish(); // emitters scatter nothing

    // A user's material: its own emission, counted in full (it is not light-sampled), then
    // its scatter(), asked once.
    std::optional<user_material_hit> user;
    if (UserMaterials && m.is_user()) {
        user.emplace(scene, *m.source, r, hit);
        radiance += throughput * user->emitted();
        if (!user->scatter()) return finish();
    }
    const bool smooth = hit.smooth_shaded() || (mapped && !(shading_normal.x == hit.shading_normal.x &&
                                                            shading_normal.y == hit.shading_normal.y &&
                                                            shading_normal.z == hit.shading_normal.z));
    const vertex_material<UserMaterials> vm{m, sp, wo, UserMaterials && user ? &*user : nullptr, hit.normal,
                                            smooth && !m.is_phase_function() && !m.density_crosses()};
    const bool has_density = vm.has_density();
    // A constant_medium's scattering point (a user shape's hit with the isotropic phase
    // function) is inside the fog, not on a surface: its rays start at the point itself.
    // Pushed off along the medium's arbitrary normal (1, 0, 0) as a surface point is, by 256
    // float ulps of x, its rays would start beside it for no reason.
    const bool in_volume = hit.user_shape && m.is_phase_function();

    // A light sample's contribution, if its shadow ray is clear: f Le / pdf, weighed by the
    // power heuristic against material sampling (a point light has no rival strategy).
    auto add_light_sample = [&](const light_choice& lc) {
        vec3f le = lc.radiance; // a textured light's: looked up at the sampled point
        if (lc.texture != no_texture && !is_black(le)) le = textured_light_radiance(scene, lc);
        if (is_black(le)) return;
        const vec3f f = vm.eval(lc.wi);
        if (is_black(f)) return;
        ++rays;
        if (scene.occluded(shadow_ray(hit, lc, in_volume))) return;
        const float weight = !lc.delta ? power_heuristic(lc.pdf, vm.pdf(lc.wi)) : 1.0f;
        radiance += throughput * f * le * (weight / lc.pdf);
    };

    // Next-event estimation: a point on a light, and a shadow ray to it.
    if (nee() && !lights.empty() && has_density) {
        light_choice lc;
        dimension_uniforms u = light_uniforms(ps, depth);
        if (lights.sample(hit.p, u, lc)) add_light_sample(lc);
    }
    // An environment map: a direction of its own at every vertex, beside the scene's light (two
    // estimators of two lights, summed), from the light's dimensions when the scene has no other
    // light, else from the sample's stream; weighed against material sampling, which may find it too.
    if (nee() && env.map && has_density) {
        dimension_uniforms u = lights.empty() ? light_uniforms(ps, depth)
                                              : dimension_uniforms(ps, dimension_uniforms::stream, dimension_uniforms::stream);
        const auto [u1, u2] = u.next_2d();
        light_choice lc;
        vec3f le;
        if (env.map->sample(u1, u2, lc.wi, lc.pdf, le) && !is_black(le)) {
            const vec3f f = vm.eval(lc.wi);
            if (!is_black(f)) {
                ++rays;
                if (!scene.occluded(spawn_ray(hit, lc.wi, std::numeric_limits<float>::infinity(), in_volume)))
                    radiance += throughput * f * le * (power_heuristic(lc.pdf, vm.pdf(lc.wi)) / lc.pdf);
            }
        }
    }
    // The mixture below covers area lights only; a point light, which no direction can hit,
    // is sampled on its own (next-event estimation without a second strategy to weigh).
    if (mixture() && lights.has_point_lights() && has_density) {
        light_choice lc;
        dimension_uniforms u = light_uniforms(ps, depth);
        if (lights.sample_point(hit.p, u, lc)) add_light_sample(lc);
    }

    // Caustics past this vertex, by light tracing: joined to the points the sample's light path
    // reached past delta vertices.
    if (caustic.active() && caustic.has_points() && has_density && caustic_vertex(hit, m))
        caustic.join(scene, vm, hit, throughput, depth, max_depth, radiance, rays);

    material_sample s;
    dimension_uniforms material_u = material_uniforms(ps, depth);
    if (mixture() && lights.has_area_lights() && has_density) {
        // Book 3's one-sample mixture: the direction comes from the lights or from the
        // material, half the time each, and is weighed by the mixture of both densities.
        if (ps.get1d(sample_dimension::bounce(depth) + sample_dimension::strategy) < 0.5f) {
            light_choice lc;
            dimension_uniforms u = light_uniforms(ps, depth);
            if (!lights.sample_area(hit.p, u, lc)) return finish();
            s.wi = lc.wi;
            s.sampled = non_delta_lobe;
        } else {
            if (!vm.sample(material_u, s)) return finish();
            if (s.is_delta()) s.value *= 2.0f; // chosen half as often as the material alone would
        }
        if (!s.is_delta()) {
            const vec3f f = vm.eval(s.wi);
            const float pdf = 0.5f * lights.area_pdf_along(hit.p, s.wi) + 0.5f * vm.pdf(s.wi);
            if (is_black(f) || !(pdf > 0)) return finish();
            s.value = f / pdf;
        }
    } else if (!vm.sample(material_u, s)) {
        return finish();
    }
    throughput *= s.value;
    if (caustic.active()) caustic.bounced(depth, hit, m, s, r.dir, last_pdf);
    count_emission_fully = !nee() || s.is_delta();
    last_p = hit.p;
    last_pdf = s.pdf;

    if (nee() && depth >= roulette_start) {
        const float q = max_component(throughput) * (1.0f / roulette_weight);
        if (q < 1.0f) {
            if (!(ps.get1d(sample_dimension::bounce(depth) + sample_dimension::roulette) < q)) return finish();
            throughput *= 1.0f / q;
        }
    }
    r = spawn_ray(hit, s.wi, std::numeric_limits<float>::infinity(), in_volume);
    // The book: no more light is gathered past the bounce limit.
    if (++depth >= max_depth) finish();
}

// A batch's rays and hits, kept in sample_batch::workspace from batch to batch: built for each
// batch, the 32 hits (each with room for a user shape's hit_record) and 64 rays were 8 KB written
// with their defaults every 32 samples, about 1.4 % of the cover's render time.
struct batch_buffers {
    ray3f camera_rays[sample_batch::capacity];
    ray3f next[sample_batch::capacity];
    surface_hit hits[sample_batch::capacity];
};

// One path from start to end: the radiance it carries.
template <bool NeeOnly, bool UserMaterials>
vec3f trace_path(const compiled_scene& scene, const environment& env, const ray3f& r, int x, int y, int max_depth,
                 pixel_sampler& ps, uint64_t& rays, path_estimator estimator, const caustic_splats* caustics = nullptr) {
    camera_path<NeeOnly, UserMaterials> path(scene, env, r, x, y, max_depth, ps, rays, estimator, caustics);
    surface_hit hit;
    while (!path.done()) {
        const bool found = scene.intersect(path.ray(), hit);
        path.advance(found, hit);
    }
    return path.radiance_so_far();
}

} // namespace detail

namespace detail {
render_result path_trace_from(const compiled_scene& scene, const camera_frame& frame, const environment& env,
                              const render_settings& settings, std::chrono::steady_clock::time_point start);
} // namespace detail

RTWEEKEND_ENGINE_FUNCTION render_result path_trace(const compiled_scene& scene, const camera_frame& frame,
                                                      const environment& env, const render_settings& settings) {
    return detail::path_trace_from(scene, frame, env, settings, std::chrono::steady_clock::now());
}

RTWEEKEND_ENGINE_FUNCTION render_result path_trace(const hittable& world, const camera_frame& frame,
                                                      const environment& env, const render_settings& settings,
                                                      const std::vector<point_light>& point_lights,
                                                      const std::vector<directional_light>& directional_lights) {
    const auto start = std::chrono::steady_clock::now(); // the statistics' time includes the compile
    settings.check();
    return detail::path_trace_from(compile_scene(world, frame.position, point_lights, directional_lights), frame, env,
                                   settings, start);
}

// The render itself: the scene seen through `frame`, from `start` on.
RTWEEKEND_ENGINE_FUNCTION render_result detail::path_trace_from(const compiled_scene& scene,
                                                                   const camera_frame& camera,
                                                                   const environment& env,
                                                                   const render_settings& settings,
                                                                   std::chrono::steady_clock::time_point start) {
    settings.check();
    const camera_frame frame = camera.placed_in(scene.origin);
    if (env.film && (env.film->width() != frame.width || env.film->height() != frame.height))
        throw scene_error("the film's background picture is " + std::to_string(env.film->width()) + "x" +
                          std::to_string(env.film->height()) + ", the image " + std::to_string(frame.width) + "x" +
                          std::to_string(frame.height) + ": they must be the same size");
    const int spp = settings.samples_per_pixel, max_depth = settings.max_depth;
    const bool user_code = scene.calls_user_code();
    const bool with_time = scene.uses_time();
    const sampler_plan plan(settings.sampler, settings.seed, spp);
    // Caustics by light tracing (caustic_paths.h): nee with uniform sampling, in a scene that has them.
    const bool caustics = settings.estimator == path_estimator::nee && settings.caustic_paths > 0 &&
                          settings.adaptive_error == 0 && traces_caustics(scene);
    // A batch of samples: their camera rays together (camera_frame::sample_rays), then each
    // path on its own.
    auto trace_batch = [&](auto nee_only, sample_batch& b, const caustic_splats* splats) {
        constexpr bool NeeOnly = decltype(nee_only)::value;
        in_place_array<pixel_sampler, sample_batch::capacity> samplers;
        pixel_sampler* lanes[sample_batch::capacity];
        for (int k = 0; k < b.count; ++k) lanes[k] = &samplers.emplace_back(plan, b.x[k], b.y[k], b.s[k], b.rng[k]);
        if (!b.workspace) b.workspace = std::make_shared<detail::batch_buffers>();
        detail::batch_buffers& buffers = *static_cast<detail::batch_buffers*>(b.workspace.get());
        ray3f* camera_rays = buffers.camera_rays;
        // A filter other than the box weighs each sample (camera_frame::filter, pixel_filter.h).
        float filter_weight[sample_batch::capacity];
        const bool weighted = !frame.filter.is_box();
        frame.sample_rays(b.count, b.x, b.y, lanes, spp, with_time, camera_rays, weighted ? filter_weight : nullptr);
        auto weigh = [&] {
            if (weighted)
                for (int k = 0; k < b.count; ++k) b.color[k] *= filter_weight[k];
        };
        if (user_code) {
            // User-written shapes and materials may call random_double(): give them this sample's
            // generator so the image stays deterministic, and let each path draw in its own order,
            // one path after another.
            for (int k = 0; k < b.count; ++k) {
                detail::scoped_sample_rng guard(b.rng[k]);
                b.color[k] = detail::trace_path<false, true>(scene, env, camera_rays[k], b.x[k], b.y[k], max_depth, *lanes[k], b.rays[k],
                                                             settings.estimator);
            }
            weigh();
            return;
        }
        // The paths side by side, a bounce of each in turn (camera_path), their rays traced
        // together (as packets: the camera rays start together and point nearly the same way;
        // later bounces' rays less so, but the walk through the top of the tree, which most of
        // them share, is paid once, and the processor overlaps the rays' work).
        in_place_array<detail::camera_path<NeeOnly, false>, sample_batch::capacity> paths;
        for (int k = 0; k < b.count; ++k)
            paths.emplace_back(scene, env, camera_rays[k], b.x[k], b.y[k], max_depth, *lanes[k], b.rays[k], settings.estimator,
                               splats);
        int live[sample_batch::capacity], n = 0;
        for (int k = 0; k < b.count; ++k)
            if (!paths[k].done()) live[n++] = k;
        ray3f* next = buffers.next;
        surface_hit* hits = buffers.hits;
        bool found[sample_batch::capacity];
        while (n > 0) {
            for (int i = 0; i < n; ++i) next[i] = paths[live[i]].ray();
            scene.intersect_batch(n, next, hits, found);
            // The live paths are all at one bounce (they started together and each advance is
            // one): their directions' Sobol pairs together, for about what two cost one by one.
            if (n >= 3) {
                pixel_sampler* live_samplers[sample_batch::capacity];
                for (int i = 0; i < n; ++i) live_samplers[i] = lanes[live[i]];
                sample_lanes numbers(live_samplers, n);
                if (numbers.vectorised())
                    numbers.prepare2d(sample_dimension::bounce(paths[live[0]].bounces()) + sample_dimension::direction);
            }
            int still = 0;
            for (int i = 0; i < n; ++i) {
                detail::camera_path<NeeOnly, false>& path = paths[live[i]];
                path.advance(found[i], hits[i]);
                if (!path.done()) live[still++] = live[i];
            }
            n = still;
        }
        for (int k = 0; k < b.count; ++k) b.color[k] = paths[k].radiance_so_far();
        weigh();
    };
    if (caustics) {
        caustic_splats splats(scene, frame, max_depth, settings.seed,
                              settings.caustic_paths * double(frame.width) * double(frame.height));
        return render_samples_with_splats(
            frame.width, frame.height, settings,
            [&](sample_batch& b) { trace_batch(std::true_type{}, b, &splats); }, splats, start);
    }
    if (settings.estimator == path_estimator::nee)
        return render_samples(
            frame.width, frame.height, settings, [&](sample_batch& b) { trace_batch(std::true_type{}, b, nullptr); },
            start);
    return render_samples(
        frame.width, frame.height, settings, [&](sample_batch& b) { trace_batch(std::false_type{}, b, nullptr); },
        start);
}

} // namespace rt

#endif // RTWEEKEND_ENGINE_BODIES
