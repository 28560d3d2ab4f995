#pragma once
// Caustic paths traced from the lights: the part of the image that next-event estimation cannot
// reach, found the other way round.
//
//   if (traces_caustics(scene)) ... caustic_splats splats(scene, frame, max_depth, seed, paths);
//
// A caustic is light that reaches a diffuse or glossy surface through glass or mirrors (light ->
// one or more delta lobes -> surface). Next-event estimation cannot find it: the shadow ray stops
// at the glass. The path tracer finds it only when a material-sampled ray happens to leave the
// surface along the one chain of delta directions that ends on the light, which for a small
// light is rare and bright: on book 3's Cornell box, the caustic under the glass sphere held a
// third of the `nee` image's squared error at 64 spp (BENCHMARKS.md, section 11). With a point
// light it cannot find it at all: no direction hits a point.
//
// Light tracing turns this round (Veach 1997, ch. 10, the bidirectional strategy with one camera
// vertex; Arvo's backward ray tracing): a path starts at a point of a light, follows delta lobes,
// and where it meets a surface with a density after at least one of them, it is joined to the
// camera by a shadow ray and adds to the pixel it lands in (a splat). The light is focused by the
// glass just as the path is, so every path that reaches the caustic contributes.
//
// The path tracer finds the same paths, and does better where the camera samples x densely (a
// close look at a caustic): the two are weighed against each other by the power heuristic
// (caustic_splats, below), so that light tracing and the path tracer (path_tracer.h,
// caustic_state) each keep a share of every path
//     camera -> x (seen directly, sampled by its non-delta part) -> k >= 1 delta vertices -> a light
// and the shares sum to 1. Both sides stop at the same things: user-written shapes and materials,
// volumes, smooth-shaded vertices (their folded lobes, path_tracer.h, are not symmetric under
// reversal) and textured lights; the path is at most max_depth rays long, as the path tracer's
// ray count allows.
//
// Caustics seen indirectly. The caustic under book 3's glass sphere lights the room in turn, and
// the glass shows it again: light -> glass -> floor -> glass -> wall, the floor a Lambertian
// "inner" vertex between two runs of delta vertices. A light path goes on from such a vertex by
// its cosine, so the pattern above admits inner vertices, each between runs of delta vertices:
//     camera -> x -> delta vertices -> (Lambertian -> delta vertices)* -> a light.
// And a caustic reached past the camera's first vertex, camera -> ... -> v -> x -> delta vertices
// -> (Lambertian -> delta vertices)* -> a light, v and x with densities, is joined the
// bidirectional way (Veach 1997, ch. 10, with two or more camera vertices): each camera sample
// traces a light path of its own (caustic_light_vertices), and each vertex v of the camera path
// is joined to the points x it reached by a shadow ray. In book 3's Cornell box the first of these
// held 40 % of the variance the pattern above left, and the second 48 % of what remained then
// (BENCHMARKS.md, section 13). Since a
// Lambertian vertex is left by its cosine from either end, the ratio of the two strategies'
// densities stays the light path starts per unit of the light's area against the path tracer's
// density at x, whatever the inner vertices (caustic_splats::deep_camera_path_weight).
//
// Reversing a delta chain. Mirrors and the exact Fresnel dielectric choose reflection and
// refraction by the same probability from either end (reflection angles are equal; the exact
// Fresnel reflectance is the same on both sides of a refraction). The book's glass uses Schlick's
// approximation of the cosine on the side the path tracer arrives from, which differs across a
// refraction; a light path refracting there is weighed by the ratio of the path tracer's
// probability to its own, so both estimate the same image: the book's.
//
// Throughput. A light of radiance Le and area A emits its power from a uniform point, in a
// cosine-distributed direction: each path carries Le pi A / P(light) (twice that for a two-sided
// light, which picks a side); a point light of intensity I, uniform directions, I 4 pi / P(light).
// At the surface point x, met from direction wi, joined to the lens along wo at distance d:
//     splat = throughput * f(wo, wi) |cos_s(wi)| / |cos_g(wi)| * |cos_g(wo)| * importance
// (importance: camera_frame::connect; cos_s against the shading normal, which eval includes;
// cos_g against the geometric one, the measure the path arrived in).

#include "../core/material_kinds.h"
#include "camera_frame.h"
#include "../scene/compiled_scene.h"
#include "../scene/light_set.h"
#include "../core/in_place_array.h"
#include "../core/rng.h"
#include "../core/sampling.h"
#include "../scene/surface_coordinates.h"
#include "../scene/surface_hit.h"
#include "../core/vec3f.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace rt {

// Whether light tracing has caustics to find in `scene`: an untextured light, and a material with
// a delta lobe, and no user-written code or front end's surface maps (which light paths do not
// follow).
inline bool traces_caustics(const compiled_scene& scene) {
    if (scene.calls_user_code() || !scene.surface_maps.empty()) return false;
    bool light = false;
    for (const auto& l : scene.lights.lights) light = light || l.texture == UINT32_MAX;
    if (!light) return false;
    for (const compiled_material& m : scene.materials)
        if (m.has_delta_lobe()) return true;
    return false;
}

// A vertex that a caustic path may pass: a built-in surface (no user shape, no volume), shaded with
// its geometric normal.
inline bool caustic_vertex(const surface_hit& hit, const compiled_material& m) {
    return !hit.user_shape && !m.is_user() && !m.is_phase_function() && !hit.smooth_shaded();
}

namespace detail {

// The density of light paths' starting points on light l (chosen with probability pmf), per unit
// of its area and per path: pmf / (sides * area), a two-sided light picking a side. 0 for a light
// light paths do not start from (textured) or a degenerate one; infinite for a point light.
inline float light_path_start_density(const light& l, float pmf) {
    if (l.texture != UINT32_MAX || !(pmf > 0)) return 0.0f;
    if (l.is_delta()) return std::numeric_limits<float>::infinity();
    const float density = pmf / ((l.two_sided ? 2.0f : 1.0f) * l.area());
    return std::isfinite(density) && density > 0 ? density : 0.0f;
}

// A box around every built-in shape whose material has a delta lobe (everything, when the scene
// places instances): a light path whose first ray misses it meets no delta vertex first.
inline box3f delta_shape_bounds(const compiled_scene& scene) {
    box3f b;
    auto delta = [&](uint32_t material) { return scene.materials[material].has_delta_lobe(); };
    for_each_kind<shape_kinds>([&](auto k) { scene.set<typename decltype(k)::type>().bound_where(scene, delta, b); });
    if (b.empty()) return b;
    // Grown by a margin, so that rounding in the slab test below never misses a shape.
    const vec3f pad = 1e-4f * (b.hi - b.lo) + vec3f{1e-3f, 1e-3f, 1e-3f} +
                      1e-5f * vec3f{std::fabs(b.lo.x) + std::fabs(b.hi.x), std::fabs(b.lo.y) + std::fabs(b.hi.y),
                                    std::fabs(b.lo.z) + std::fabs(b.hi.z)};
    b.lo = b.lo - pad;
    b.hi = b.hi + pad;
    return b;
}

// Whether the ray (from its origin on, any distance) may meet the box: a slab test in which an
// infinite box, or a NaN from a direction along an axis, counts as a meeting.
inline bool may_meet(const box3f& b, const ray3f& r) {
    if (b.empty()) return false;
    float t0 = 0, t1 = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
        const float inv = 1.0f / r.dir[a];
        float near = (b.lo[a] - r.origin[a]) * inv, far = (b.hi[a] - r.origin[a]) * inv;
        if (near > far) std::swap(near, far);
        if (near > t0) t0 = near; // a NaN compares false: no narrowing
        if (far < t1) t1 = far;
    }
    return !(t0 > t1);
}

} // namespace detail

// A light path's contribution at image point (c.px, c.py): to the pixel it lands in, with the
// box filter; with another (camera_frame::filter), to every pixel whose filter reaches the point,
// weighted f(dx) f(dy) / (integral f)^2, the pixel's share of the point as its camera samples
// weigh theirs (pixel_filter.h).
template <class Splat>
void splat_filtered(const camera_frame& frame, const camera_frame::connection& c, const vec3f& value, uint32_t light,
                    float density, Splat& splat) {
    const pixel_filter& f = frame.filter;
    if (f.is_box()) {
        splat(int(c.px), int(c.py), value, light, density);
        return;
    }
    const double r = f.radius(), norm = f.integral() * f.integral();
    const int x0 = std::max(0, int(std::floor(c.px - r - 0.5))), x1 = std::min(frame.width - 1, int(std::floor(c.px + r - 0.5)) + 1);
    const int y0 = std::max(0, int(std::floor(c.py - r - 0.5))), y1 = std::min(frame.height - 1, int(std::floor(c.py + r - 0.5)) + 1);
    for (int y = y0; y <= y1; ++y) {
        const double wy = f.eval(c.py - (y + 0.5));
        if (wy == 0) continue;
        for (int x = x0; x <= x1; ++x) {
            const double w = wy * f.eval(c.px - (x + 0.5)) / norm;
            if (w != 0) splat(x, y, float(w) * value, light, density);
        }
    }
}

// One light path (the numbers from rng): splat(x, y, value, light, camera_density) for each pixel
// it adds to, with the index of the light it started from and the camera's density at the surface
// point it was joined from (caustic_splats::camera_density); rays counts the rays traced.
// start_density: per light, detail::light_path_start_density.
template <class Splat>
void trace_caustic_path(const compiled_scene& scene, const camera_frame& frame, int max_depth,
                        const std::vector<float>& start_density, const box3f& aim, pcg32& rng, Splat&& splat, uint64_t& rays);

// The points a camera sample's own light path reaches past delta vertices, for joining the
// camera path's vertices to (caustic_splats::deep_light_path_weight): the light path starts as
// trace_caustic_path's do, goes through delta vertices of materials without a density, and stops
// at the first surface with a density; if that came after one or more of them, it is a point x
// kept here, and if it is Lambertian the path goes on by its cosine, at most `capacity` times.
struct caustic_light_vertices {
    static constexpr int capacity = 3;
    struct vertex {
        vec3f p, normal, shading_normal; // as surface_hit's: the normals facing the arriving path
        bool front_face = true;
        vec3f wi;                        // back along the light path, towards the light
        vec3f throughput;                // what the light path carries on arrival
        compiled_material material;      // its material (a textured one's coloured at p)
        int vertices;                    // the path's vertices between the light and p
    };
    // Built as the path reaches them: a camera path of a render without caustics holds an empty
    // one, whose room (252 bytes) is never written and so never takes cache lines.
    in_place_array<vertex, capacity> at;
    uint32_t light = 0; // the light the path started from
};

class caustic_splats;

// The light path of a camera sample in a render whose light tracing `splats` sets up: its numbers
// from u, at the camera path's time, at most most_vertices vertices between the light and a kept
// point, appended to `out` (empty on entry).
template <class Uniform>
void trace_caustic_light_vertices(const compiled_scene& scene, const caustic_splats& splats, int most_vertices,
                                  Uniform& u, float time, caustic_light_vertices& out, uint64_t& rays);

// The light paths of a render, as the scheduler's splat work (scheduler.h,
// render_samples_with_splats): for each sample index, `paths` light paths (rounded to a whole
// number, at least 1), each splatting 1/paths of its value, so that a pixel's mean is its camera
// samples' plus the mean of the light paths' splats. Path k of sample index s draws from its own
// generator, so the image is the same at any thread count.
//
// Both strategies find the paths camera -> x -> delta vertices -> light of an area light; each
// weighs them by the power heuristic (Veach 1997, ch. 9), so that every pixel gets whichever
// does better there. Per camera sample of the pixel, the path tracer draws x with area density
// p_c(x) = importance * |cos_x| (camera_frame::connect) and leaves x by its cosine; light tracing
// draws the point on light l with area density P(l) / (sides * A_l) per path, and leaves it by its
// cosine, `paths` times per sample. The delta vertices between are chosen alike from both ends,
// and the two cosine-weighted ray bundles have the same extent (etendue is conserved through
// mirrors and refraction in and out of glass), so their densities for the same path are in the
// ratio
//     r = light / camera = paths * P(l) / (sides * A_l * p_c(x)),
// the number of light-path starts per unit of the light's area against the camera samples per
// unit area at x. The path tracer keeps 1 / (1 + r^2) of such a path, light tracing
// r^2 / (1 + r^2). (The power heuristic rather than the balance heuristic: zoomed in on book 3's
// caustic, where r is near 1, it gave 16 % less variance, the camera paths' Sobol numbers being
// better stratified than the light paths' own; on the whole box the two were equal.)
// Seen wide, x's pixel covers a large patch and light tracing takes nearly all (book 3's Cornell
// box at 300x300: r about 12 on the floor); zoomed in on a caustic the camera samples it
// densely and the path tracer does. A caustic of a point light goes to light tracing in full: no
// camera path can end on a point (without light tracing it is missing from the image).
class caustic_splats {
  public:
    static constexpr int64_t paths_per_job = 4096;

    caustic_splats(const compiled_scene& scene, const camera_frame& frame, int max_depth, uint64_t seed, double paths)
        : scene_(scene), frame_(frame), max_depth_(max_depth), seed_(mix64(seed ^ 0x6c1d5e0b7f4a2c93ULL)),
          paths_(std::max<int64_t>(1, std::llround(std::min(paths, 1e15)))) {
        // Per light: light-path starts per unit area and per path (detail::light_path_start_density).
        start_density_.resize(scene.lights.lights.size(), 0.0f);
        for (uint32_t l = 0; l < start_density_.size(); ++l)
            start_density_[l] = detail::light_path_start_density(scene.lights.lights[l], scene.lights.pick_pmf(l));
    }

    // A box around the shapes with a delta lobe (detail::delta_shape_bounds): a light path whose
    // first ray misses it has nothing to find (trace_caustic_light_vertices).
    const box3f& delta_bounds() const { return delta_bounds_; }

    int jobs_per_sample() const { return int((paths_ + paths_per_job - 1) / paths_per_job); }

    // The path tracer's area density at x per camera sample, seen from lens point `lens`, x's
    // geometric normal `normal`: 0 where the camera cannot be joined to x (connect fails), which
    // light tracing cannot then reach.
    float camera_density(const vec3f& x, const vec3f& lens, const vec3f& normal) const {
        camera_frame::connection c;
        if (!frame_.connect(x, lens, c)) return 0.0f;
        return c.importance * std::fabs(dot(normal, c.dir));
    }
    // The power-heuristic weights of a path whose camera vertex has density camera_density and
    // whose light is l: the path tracer's and light tracing's, which sum to 1.
    float camera_path_weight(uint32_t l, float camera_density) const {
        return camera_share(float(paths_) * start_density_[l], camera_density);
    }
    float light_path_weight(uint32_t l, float camera_density) const { return 1.0f - camera_path_weight(l, camera_density); }

    // The same two weights for a path joined deeper: camera -> ... -> v -> x -> delta vertices
    // (and Lambertian inner vertices between runs of them) -> light l, v and x with densities, x
    // past the camera's first vertex. The path tracer finds it by sampling x's lobe; light tracing,
    // by joining v to the point x of the camera sample's own light path (one per camera sample,
    // caustic_light_vertices). As above, the ratio of their densities is the light path starts per
    // unit of the light's area against the path tracer's area density at x, which given v is
    // x_density = pdf_v(v -> x) |cos_x| / d^2.
    float deep_camera_path_weight(uint32_t l, float x_density) const { return camera_share(start_density_[l], x_density); }
    float deep_light_path_weight(uint32_t l, float x_density) const { return 1.0f - deep_camera_path_weight(l, x_density); }

    template <class Add, class Totals>
    void run(int s, int job, Add&& add, Totals& totals) const {
        const float share = float(1.0 / double(paths_));
        const int64_t end = std::min(paths_, int64_t(job + 1) * paths_per_job);
        for (int64_t k = int64_t(job) * paths_per_job; k < end; ++k) {
            pcg32 rng = sample_rng(seed_, uint64_t(k), uint64_t(s));
            trace_caustic_path(scene_, frame_, max_depth_, start_density_, delta_bounds_, rng,
                               [&](int x, int y, const vec3f& value, uint32_t l, float camera_density) {
                                   const float w = light_path_weight(l, camera_density);
                                   if (w > 0) add(x, y, value * (share * w));
                               },
                               totals.rays);
        }
    }

    // Light-path starts per unit of light l's area, per path (detail::light_path_start_density),
    // worked out once per render.
    float start_density(uint32_t l) const { return start_density_[l]; }

  private:
    // The path tracer's power-heuristic share of a path that light tracing makes with density
    // `light` and the path tracer with density `camera`, per unit of the same measure.
    static float camera_share(float light, float camera) {
        if (!(light > 0) || !(camera > 0)) return 1.0f; // light tracing cannot make it
        if (std::isinf(light)) return 0.0f;               // a point light: the path tracer cannot
        const float r = light / camera;
        return 1.0f / (1.0f + r * r);
    }

    const compiled_scene& scene_;
    const camera_frame& frame_;
    int max_depth_;
    uint64_t seed_;
    int64_t paths_;
    std::vector<float> start_density_;
    box3f delta_bounds_ = detail::delta_shape_bounds(scene_);
};

// A camera path's part in caustics: what the path tracer (path_tracer.h, camera_path) keeps and
// asks, in three hooks, so that light tracing and the path tracer share every path both find.
//   weigh_emission(lights, hit, weight)   an emitter the path hits: multiplies weight by the path
//                                   tracer's share of the path, when light tracing finds it too
//   join(...)                       a vertex v with a density: v joined to each point its sample's
//                                   own light path reached past delta vertices, added to radiance
//   bounced(...)                    after the vertex's lobe is sampled: where the path now stands
//                                   in the patterns both strategies find
// A default-made one is inactive (a render without caustics), and its hooks are never asked.
class caustic_connection {
  public:
    // Makes it active for the camera path that starts with camera_ray: traces the sample's own
    // light path (when a join can fit in max_depth rays) from light_rng.
    void start(const compiled_scene& scene, const caustic_splats& splats, int max_depth, pcg32 light_rng,
               const ray3f& camera_ray, uint64_t& rays);

    bool active() const { return splats_ != nullptr; }
    // Whether the sample's light path reached any point join() would join a vertex to.
    bool has_points() const { return light_path.at.size() > 0; }
    void weigh_emission(const light_set& lights, const surface_hit& hit, float& weight) const;
    template <class VertexMaterial>
    void join(const compiled_scene& scene, const VertexMaterial& vm, const surface_hit& hit, const vec3f& throughput,
              int depth, int max_depth, vec3f& radiance, uint64_t& rays) const;
    // The vertex at `hit` (scattering event `depth`, reached along arriving_dir from a vertex
    // that drew it with density arriving_pdf) sampled s from its material m.
    void bounced(int depth, const surface_hit& hit, const compiled_material& m, const material_sample& s,
                 const vec3f& arriving_dir, float arriving_pdf);

  private:
    // Where the path stands in the pattern light tracing also finds: none, at x (the camera's first
    // vertex, which sampled its non-delta lobe), past one or more delta vertices after x, or at a
    // Lambertian inner vertex after them; and x itself, whose camera density weighs the two (asked
    // only of the paths that end on a light).
    enum class state : uint8_t { none, at_x, past_delta, inner };
    const caustic_splats* splats_ = nullptr;
    state first_ = state::none;
    vec3f x_p, x_normal, lens;
    // The same deeper (caustic_splats::deep_camera_path_weight): the path went from a vertex v
    // past the first, by its non-delta lobe, to x, and on by x's non-delta lobe through delta
    // vertices of materials without a density, with inner_vertices Lambertian ones between them;
    // x_density is x's area density given v.
    state deep_ = state::none;
    int inner_vertices = 0;
    bool left_by_density = false; // the ray left a caustic vertex by its non-delta lobe
    float x_density = 0;
    // The points the sample's own light path reached, which vertices like v are joined to. Last:
    // most paths never fill it.
    caustic_light_vertices light_path;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// Where a light path starts: a point of light l (chosen with probability pmf; density, its
// light_path_start_density, worked out once per render), a direction, and the throughput the path
// carries. False when l is textured (left to the path tracer) or degenerate (density 0).
template <class Uniform>
bool start_light_path(const light& l, float pmf, float density, const box3f& aim, Uniform& u, ray3f& r, vec3f& throughput) {
    if (!(density > 0)) return false;
    l.visit([&](const auto& e) { e.start_path(l.emission, l.two_sided, pmf, density, aim, u, r, throughput); });
    return true;
}

// One step of a light path: the surface r meets (hit), its material (a textured one's copy with
// its colour, in looked_up) and the throughput past absorbing glass; nullptr where the path ends:
// it escapes, or meets a light or what light paths do not pass (caustic_vertex).
inline const compiled_material* light_path_step(const compiled_scene& scene, const ray3f& r, surface_hit& hit,
                                                compiled_material& looked_up, vec3f& throughput, uint64_t& rays) {
    ++rays;
    if (!scene.intersect(r, hit)) return nullptr;
    const compiled_material& stored = scene.materials[hit.material];
    if (stored.texture != no_texture) looked_up = textured(scene, stored, hit);
    const compiled_material& m = stored.texture != no_texture ? looked_up : stored;
    if (!caustic_vertex(hit, m) || !m.scatters()) return nullptr;
    if (!hit.front_face && m.absorbs_inside()) throughput *= m.transmittance(hit.t);
    return &m;
}

} // namespace detail

template <class Splat>
void trace_caustic_path(const compiled_scene& scene, const camera_frame& frame, int max_depth,
                        const std::vector<float>& start_density, const box3f& aim, pcg32& rng, Splat&& splat, uint64_t& rays) {
    float pmf = 0;
    const uint32_t chosen = scene.lights.pick(rng.next_float(), pmf);
    if (chosen == light_set::none) return;
    ray3f r;
    vec3f throughput;
    if (!detail::start_light_path(scene.lights.lights[chosen], pmf, start_density[chosen], aim, rng, r, throughput)) return;
    r.tmin = 0;
    r.tmax = std::numeric_limits<float>::infinity();
    if (scene.has_motion) r.time = rng.next_float();
    surface_hit hit;
    compiled_material looked_up;
    // vertices: the path's vertices before this one; since_delta: of them, the delta vertices
    // since the light or the last vertex with a density.
    for (int vertices = 0, since_delta = 0;; ++vertices) {
        const compiled_material* met = detail::light_path_step(scene, r, hit, looked_up, throughput, rays);
        if (!met) return;
        const compiled_material& m = *met;
        const vec3f wi = -r.dir; // back towards the light

        // Light straight from the light or from an inner vertex is not a caustic.
        if (m.has_non_delta_lobe() && since_delta > 0) {
            // Joined to the camera: a point of the lens, and a shadow ray to it.
            vec3f lens = frame.eye; // the lens point, relative to the scene origin as x is
            if (frame.thin_lens) {
                const auto [l1, l2] = draw_2d(rng);
                const vec3f d = sample_unit_disk(l1, l2);
                lens = d.x * frame.defocus_disk_u + d.y * frame.defocus_disk_v;
                if (!frame.eye_at_origin) lens = frame.eye + lens;
            }
            camera_frame::connection c;
            if (frame.connect(hit.p, lens, c)) {
                // The surface as the camera sees it: normals on the camera's side.
                const vec3f wo = -c.dir;
                surface_hit seen = hit;
                if (dot(wo, hit.normal) < 0) {
                    seen.normal = -hit.normal;
                    seen.shading_normal = -hit.shading_normal;
                    seen.front_face = !hit.front_face;
                }
                const vec3f f = m.eval(wo, wi, shading_point{seen.shading_normal, seen.front_face});
                const float cos_in = std::fabs(dot(hit.normal, wi)), cos_out = std::fabs(dot(hit.normal, wo));
                if (!detail::is_black(f) && cos_in > 0) {
                    const float density = c.importance * cos_out; // the camera's, at x
                    const vec3f value = throughput * f * (density / cos_in);
                    ++rays;
                    if (!detail::is_black(value) &&
                        !scene.occluded(detail::spawn_ray(seen, wo, c.distance * (1.0f - 1e-4f))))
                        splat_filtered(frame, c, value, chosen, density, splat);
                }
            }
        }
        // One more vertex would make the path tracer's path longer than max_depth rays.
        if (vertices + 1 > max_depth - 2) return;
        material_sample s;
        const shading_point sp{hit.shading_normal, hit.front_face};
        if (!m.sample(wi, sp, rng, s)) return;
        if (s.is_delta()) {
            ++since_delta;
        } else {
            // An inner vertex (see the top): a Lambertian surface past delta vertices, left by its
            // cosine towards more of them.
            if (!m.lambertian_only() || since_delta == 0) return;
            since_delta = 0;
        }
        throughput *= s.value * m.reversal_ratio(hit.shading_normal, wi, hit.front_face, s);
        if (detail::is_black(throughput)) return;
        r = detail::spawn_ray(hit, s.wi, std::numeric_limits<float>::infinity());
    }
}

template <class Uniform>
void trace_caustic_light_vertices(const compiled_scene& scene, const caustic_splats& splats, int most_vertices,
                                  Uniform& u, float time, caustic_light_vertices& out, uint64_t& rays) {
    float pmf = 0;
    const uint32_t chosen = scene.lights.pick(u.next_float(), pmf);
    if (chosen == light_set::none) return;
    out.light = chosen;
    ray3f r;
    vec3f throughput;
    if (!detail::start_light_path(scene.lights.lights[chosen], pmf, splats.start_density(chosen), splats.delta_bounds(), u, r,
                                  throughput))
        return;
    r.tmin = 0;
    r.tmax = std::numeric_limits<float>::infinity();
    r.time = time;
    // Most light paths meet a surface with a density first, where they stop: those that cannot
    // meet a delta vertex first are not traced at all.
    if (!detail::may_meet(splats.delta_bounds(), r)) return;
    surface_hit hit;
    compiled_material looked_up;
    for (int vertices = 0, since_delta = 0; vertices <= most_vertices; ++vertices) {
        const compiled_material* met = detail::light_path_step(scene, r, hit, looked_up, throughput, rays);
        if (!met) return;
        const compiled_material& m = *met;
        const vec3f wi = -r.dir; // back towards the light
        if (m.has_non_delta_lobe()) {
            if (since_delta == 0) return; // light no delta vertex has bent: not a caustic
            caustic_light_vertices::vertex& x = out.at.emplace_back();
            x.p = hit.p;
            x.normal = hit.normal;
            x.shading_normal = hit.shading_normal;
            x.front_face = hit.front_face;
            x.wi = wi;
            x.throughput = throughput;
            x.material = m;
            x.vertices = vertices;
            if (!m.lambertian_only() || out.at.size() == caustic_light_vertices::capacity) return;
            since_delta = 0;
        } else {
            ++since_delta;
        }
        material_sample s;
        const shading_point sp{hit.shading_normal, hit.front_face};
        if (!m.sample(wi, sp, u, s)) return;
        throughput *= s.value * m.reversal_ratio(hit.shading_normal, wi, hit.front_face, s);
        if (detail::is_black(throughput)) return;
        r = detail::spawn_ray(hit, s.wi, std::numeric_limits<float>::infinity());
    }
}

inline void caustic_connection::start(const compiled_scene& scene, const caustic_splats& splats, int max_depth,
                                      pcg32 light_rng, const ray3f& camera_ray, uint64_t& rays) {
    splats_ = &splats;
    lens = camera_ray.origin;
    if (max_depth >= 3)
        trace_caustic_light_vertices(scene, splats, max_depth - 3, light_rng, camera_ray.time, light_path, rays);
}

inline void caustic_connection::weigh_emission(const light_set& lights, const surface_hit& hit, float& weight) const {
    if (first_ != state::past_delta && deep_ != state::past_delta) return; // light tracing cannot find it
    const uint32_t light = lights.light_at(hit.kind, hit.index);
    if (light == light_set::none) return;
    // Light tracing finds this path too: the path tracer's share of it.
    if (first_ == state::past_delta) weight *= splats_->camera_path_weight(light, splats_->camera_density(x_p, lens, x_normal));
    if (deep_ == state::past_delta) weight *= splats_->deep_camera_path_weight(light, x_density);
}

// This vertex v joined to each point x its sample's light path reached: the path camera -> ... ->
// v -> x -> delta vertices -> light, as trace_caustic_path joins x to the camera, with v's
// throughput and f in place of the camera's importance:
//     throughput f_v(wo, dir) |cos_x| / d^2 * f_x(-dir, wi) / |cos_g(wi)| * light throughput,
// weighed against the path tracer's finding it (caustic_splats::deep_light_path_weight).
template <class VertexMaterial>
void caustic_connection::join(const compiled_scene& scene, const VertexMaterial& vm, const surface_hit& hit,
                              const vec3f& throughput, int depth, int max_depth, vec3f& radiance, uint64_t& rays) const {
    for (int k = 0; k < light_path.at.size(); ++k) {
        const caustic_light_vertices::vertex& x = light_path.at[k];
        // The path tracer's path would be longer than max_depth rays.
        if (depth + x.vertices + 3 > max_depth) return;
        const vec3f to = x.p - hit.p;
        const float d2 = length_squared(to);
        if (!(d2 > 0)) continue;
        const vec3f dir = to / sqrt_f(d2);
        const vec3f f_v = vm.eval(dir);
        if (detail::is_black(f_v)) continue;
        // x as seen from v: normals on v's side.
        const vec3f wo = -dir;
        const bool flip = dot(wo, x.normal) < 0;
        const shading_point sp{flip ? -x.shading_normal : x.shading_normal, flip != x.front_face};
        const compiled_material& m = x.material; // a textured one's coloured at x
        const vec3f f_x = m.eval(wo, x.wi, sp);
        const float cos_in = std::fabs(dot(x.normal, x.wi)), cos_out = std::fabs(dot(x.normal, dir));
        if (detail::is_black(f_x) || !(cos_in > 0)) continue;
        const float weight = splats_->deep_light_path_weight(light_path.light, vm.pdf(dir) * cos_out / d2);
        const vec3f value = throughput * f_v * f_x * x.throughput * (weight * cos_out / (d2 * cos_in));
        if (detail::is_black(value) || !is_finite(value)) continue;
        // The shadow ray, from v to x pushed off x on v's side.
        light_choice end;
        end.wi = dir;
        end.y = x.p;
        end.n = x.normal;
        ++rays;
        if (!scene.occluded(detail::shadow_ray(hit, end, false))) radiance += value;
    }
}

RTWEEKEND_FORCE_INLINE void caustic_connection::bounced(int depth, const surface_hit& hit, const compiled_material& m,
                                        const material_sample& s, const vec3f& arriving_dir, float arriving_pdf) {
    const bool plain = caustic_vertex(hit, m); // caustics: no user code in the scene
    if (depth == 0) {
        first_ = plain && !s.is_delta() ? state::at_x : state::none;
        x_p = hit.p;
        x_normal = hit.normal;
    } else if (first_ != state::none && plain && s.is_delta()) {
        first_ = state::past_delta;
    } else if (first_ == state::past_delta && plain && m.lambertian_only()) {
        first_ = state::inner; // its non-delta lobe sampled: the only one it has
    } else {
        first_ = state::none;
    }
    if (depth >= 1 && plain && !s.is_delta() && left_by_density) {
        deep_ = state::at_x;
        inner_vertices = 0;
        x_density = arriving_pdf * std::fabs(dot(hit.normal, arriving_dir)) / (hit.t * hit.t);
    } else if (deep_ != state::none && plain && s.is_delta() && !m.has_non_delta_lobe()) {
        deep_ = state::past_delta;
    } else if (deep_ == state::past_delta && plain && m.lambertian_only() &&
               inner_vertices + 1 < caustic_light_vertices::capacity) {
        deep_ = state::inner;
        ++inner_vertices;
    } else {
        deep_ = state::none;
    }
    left_by_density = plain && !s.is_delta();
}

} // namespace rt
