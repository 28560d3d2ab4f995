#pragma once
// sphere_set: the shape kind of the books' still spheres (scene/shape_kinds.h says what a kind
// answers). The compiled spheres are one float array per field in BVH leaf order; the SIMD kernel
// tests a ray against one leaf of them, floatv::width spheres per instruction, and a packet of
// rays against one sphere at a time (intersect_leaf_packet: compiled_scene::intersect_batch).
//
// The test is the numerically stable one of sphere.h (Haines et al., Ray Tracing Gems ch. 7):
// the discriminant from the centre's distance to the ray's line, the near root from c / q.
//
// The books' sphere class is compiled here: a moving one (book 2) goes to moving_sphere_set; a
// negative radius (the older books' hollow glass) is the sphere of radius |r| turned inside out.

#include "../../core/box3f.h"
#include "../../core/constants.h"
#include "../../core/force_inline.h"
#include "../../core/scene_error.h"
#include "../../core/simd.h"
#include "../../core/vec3f.h"
#include "../../sphere.h"
#include "../affine_map.h"
#include "../leaf_query.h"
#include "../lights/sphere_emitter.h"
#include "../surface_hit.h"
#include "../validate.h"
#include "moving_sphere_set.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace rt {

struct sphere_set {
    static constexpr const char* name = "sphere";
    // Whether its shapes move with the ray's time.
    static constexpr bool moves = false;
    // A scene of these alone walks its BVH without asking each leaf its kind (shape_kinds.h).
    static constexpr bool own_walk = true;

    // --- compiling ---------------------------------------------------------------------------
    // A sphere as the compiler collects it: centre relative to the scene origin, in double.
    struct input {
        vec3 c;
        double r;
        uint32_t material;
    };
    // The book's sphere under the map xf (which keeps it round: the compiler instances it
    // otherwise), into the compiler's inputs of this kind or of moving_sphere_set.
    template <class Compiler>
    static void add(Compiler& compiler, const sphere& s, const affine_map& xf);
    // The box the BVH holds it in, rounded outwards: it must contain the float sphere the kernel sees.
    template <class Scene>
    static box3f bounds(const input& s, const Scene&) {
        box3f b;
        b.lo = {float_below(s.c.x() - s.r), float_below(s.c.y() - s.r), float_below(s.c.z() - s.r)};
        b.hi = {float_above(s.c.x() + s.r), float_above(s.c.y() + s.r), float_above(s.c.z() + s.r)};
        return b;
    }
    // The inputs in the BVH's leaf order, then floatv::width padding spheres (a leaf's loads read
    // that far).
    template <class Scene>
    void lay_out(const Scene&, const std::vector<input>& inputs, const std::vector<uint32_t>& order) {
        count = order.size();
        for (uint32_t i : order) append(vec3f(inputs[i].c), static_cast<float>(inputs[i].r), inputs[i].material);
        for (size_t k = 0; k < floatv::width; ++k) append(vec3f(0, 0, 0), 0, 0, /*padding=*/true);
    }

    // --- the compiled spheres ------------------------------------------------------------------
    size_t count = 0; // spheres; the arrays hold floatv::width more, never hit (padding)
    std::vector<float> x, y, z, r2, r, offset;
    std::vector<uint32_t> material;
    // Back-face culling: 1 where a hit on the back face (a ray from inside) is skipped; empty
    // until mark_culled.
    std::vector<float> cull;

    // Appends a sphere with centre c (relative to the scene origin) and radius `radius`; a
    // padding sphere is never hit.
    void append(const vec3f& c, float radius, uint32_t material_index, bool padding = false) {
        x.push_back(c.x);
        y.push_back(c.y);
        z.push_back(c.z);
        r2.push_back(padding ? -1.0f : radius * radius); // negative squared radius: no ray crosses
        r.push_back(radius);
        // Float evaluation of |o - c|^2 - r^2 is only good to a few ulps of the larger of |c| and
        // r, so a spawned ray must start at least that far off the surface (on top of the
        // hit-point offset) or it may re-hit the sphere it leaves: 2^-21 is about 8 ulps.
        offset.push_back(std::ldexp(max_abs_component(c) + radius, -21));
        material.push_back(material_index);
    }

    size_t size() const { return count; }
    uint32_t material_of(uint32_t i) const { return material[i]; }
    vec3f center(uint32_t i) const { return {x[i], y[i], z[i]}; }

    // Nothing a ray's walk keeps for this kind.
    struct ray_state {};
    // Tests spheres [first, first + n) against the ray: see leaf_query.h. Self: this kind's number.
    template <query Q, shape_kind Self, class Scene>
    bool intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n, float& t_best, hit_ref& best,
                        ray_state&) const;
    // The same for a packet of rays, one per lane (closest hits): each lane of `lanes` lowers
    // t_best[lane] and sets best[lane] exactly as intersect_leaf would for its ray alone.
    template <shape_kind Self>
    void intersect_leaf_packet(const ray_lanes& rays, uint32_t first, uint32_t n, unsigned lanes, float* t_best,
                               hit_ref* best) const;
    // The hit on sphere i at distance t along the ray.
    template <class Scene>
    void complete_hit(const Scene&, const ray3f& ray, float t, uint32_t i, const ray_state&, surface_hit& hit) const {
        vec3f c = center(i);
        // Re-project the hit point onto the sphere: removes the error of o + t d along the ray.
        vec3f outward = normalize(ray.at(t) - c);
        hit.p = c + r[i] * outward;
        hit.set_face_normal(ray.dir, outward);
        hit.offset = offset[i];
        hit.material = material[i];
    }
    // Book 2's get_sphere_uv, from the outward normal (detail::sphere_uv).
    void surface_coordinates(const surface_hit& hit, double& u, double& v) const { detail::sphere_uv(hit, u, v); }

    // An emitting sphere is light-sampled by the cone it subtends.
    static constexpr bool light_sampled = true;
    sphere_emitter light_of(uint32_t i) const { return {center(i), r[i]}; }

    // Grows b by the spheres whose material `selected` accepts.
    template <class Scene, class Predicate>
    void bound_where(const Scene&, Predicate selected, box3f& b) const {
        for (uint32_t i = 0; i < count; ++i)
            if (selected(material[i])) {
                b.grow(center(i) - vec3f{r[i], r[i], r[i]});
                b.grow(center(i) + vec3f{r[i], r[i], r[i]});
            }
    }
    // Marks the spheres whose material `cullable` accepts for back-face culling.
    template <class Predicate>
    void mark_culled(Predicate cullable) { cull = culling_flags(material, count, cullable); }

    size_t bytes() const { return (x.size() * 6 + cull.size()) * sizeof(float) + material.size() * sizeof(uint32_t); }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

template <class Compiler>
void sphere_set::add(Compiler& compiler, const sphere& s, const affine_map& xf) {
    if (!finite3(s.center()) || !finite3(s.center(1)))
        throw scene_error("sphere centre must be finite, got " + point_text(s.center()) +
                          (s.is_moving() ? " moving to " + point_text(s.center(1)) : std::string()));
    if (!(std::isfinite(s.radius()) && s.radius() != 0))
        throw scene_error("sphere radius must be finite and not zero, got " + number_text(s.radius()));
    if (!s.mat()) throw scene_error("sphere at " + point_text(s.center()) + " has no material");
    // A negative radius is the books' v3 hollow glass: the sphere of radius |r|, inside out.
    const bool inside_out = s.radius() < 0;
    const uint32_t material =
        inside_out ? compiler.inside_out_material_index(s.mat().get()) : compiler.material_index(s.mat().get());
    const double radius = std::fabs(s.radius()) * xf.sphere_scale(); // the compiler saw to it that the map keeps it round
    const vec3 c = xf.point(s.center()) - compiler.origin(), c1 = xf.point(s.center(1)) - compiler.origin();
    if (!(fmax_inline(max_abs(c), max_abs(c1)) + radius < max_float_extent))
        throw scene_error("sphere at " + point_text(s.center()) + " with radius " + number_text(s.radius()) +
                          " is out of single-precision range: its distance from the camera plus its radius must "
                          "be below 1e18");
    if (s.is_moving()) {
        compiler.template inputs<moving_sphere_set>().push_back({c, c1, radius, material});
        return;
    }
    compiler.template inputs<sphere_set>().push_back({c, radius, material});
}

namespace detail {

// The stable sphere test (sphere.h's, in float), lane by lane, in two steps: first whether each
// lane's ray line crosses its sphere (C - O = oc, squared radius rr), from the quadratic's
// h = d.(C - O) and the discriminant taken from the distance to the line; then, for lanes that
// cross, the distance: the near root from c / q, or the far one from inside. The single-ray
// kernel has a sphere in each lane, the packet kernel a ray: the same operations in the same
// order, so both find the same distances.
struct sphere_crossing {
    floatv h, disc;
    RTWEEKEND_FORCE_INLINE sphere_crossing(floatv ocx, floatv ocy, floatv ocz, floatv rr, floatv dx, floatv dy, floatv dz) {
        h = fmadd(dx, ocx, fmadd(dy, ocy, dz * ocz));
        const floatv px = fnmadd(h, dx, ocx), py = fnmadd(h, dy, ocy), pz = fnmadd(h, dz, ocz);
        disc = rr - fmadd(px, px, fmadd(py, py, pz * pz));
    }
    maskv crosses() const { return disc >= floatv(0.0f); }
    // The distance past tmin (the exit from inside); t0 is the nearer root.
    RTWEEKEND_FORCE_INLINE floatv distance(floatv ocx, floatv ocy, floatv ocz, floatv rr, floatv tmin, floatv& t0) const {
        const floatv zero(0.0f);
        const floatv c = fmadd(ocx, ocx, fmadd(ocy, ocy, ocz * ocz)) - rr;
        const floatv s = sqrt(max(disc, zero));
        const floatv q = select(h >= zero, h + s, h - s);
        const floatv ta = c / q;
        t0 = min(ta, q);
        const floatv t1 = max(ta, q);
        return select(t0 > tmin, t0, t1);
    }
};

} // namespace detail

template <query Q, shape_kind Self, class Scene>
RTWEEKEND_FORCE_INLINE bool sphere_set::intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n,
                                                       float& t_best, hit_ref& best, ray_state&) const {
    constexpr size_t W = floatv::width;
    const floatv tmin(ray.tmin), zero(0.0f);
    const floatv ox(ray.origin.x), oy(ray.origin.y), oz(ray.origin.z);
    const floatv dx(ray.dir.x), dy(ray.dir.y), dz(ray.dir.z);
    bool found = false;
    for (uint32_t i = first; i < first + n; i += W) {
        const floatv ocx = floatv::load(&x[i]) - ox, ocy = floatv::load(&y[i]) - oy, ocz = floatv::load(&z[i]) - oz;
        const floatv rr = floatv::load(&r2[i]);
        const detail::sphere_crossing crossing(ocx, ocy, ocz, rr, dx, dy, dz);
        const maskv crosses = crossing.crosses() & first_lanes(first + n - i);
        if (!any(crosses)) continue;
        floatv t0;
        floatv t = crossing.distance(ocx, ocy, ocz, rr, tmin, t0);
        // Culled: a ray that starts inside (or past) the sphere only meets its back face.
        if constexpr (Q == query::closest_culled)
            t = select((t0 > tmin) | (floatv::load(&cull[i]) == zero), t, floatv(-1.0f));
        maskv hits = crosses & within_range<Q>(t, tmin, t_best);
        if (!any(hits)) continue;
        if constexpr (Q == query::any) return true;
        found |= take_closest(hits, t, Self, i, t_best, best);
    }
    return found;
}

template <shape_kind Self>
RTWEEKEND_FORCE_INLINE void sphere_set::intersect_leaf_packet(const ray_lanes& rays, uint32_t first, uint32_t n,
                                                              unsigned lanes, float* t_best, hit_ref* best) const {
    // Each lane's nearest sphere of the leaf within (tmin, t_best], the first at one distance, as
    // intersect_leaf's take_closest finds it for one ray; then whether it beats the lane's best.
    const maskv active = lanes_of(lanes);
    const floatv limit = floatv::load(t_best);
    floatv nearest_t(std::numeric_limits<float>::infinity()), nearest_i(-1.0f);
    for (uint32_t i = first; i < first + n; ++i) {
        const floatv ocx = floatv(x[i]) - rays.ox, ocy = floatv(y[i]) - rays.oy, ocz = floatv(z[i]) - rays.oz;
        const floatv rr(r2[i]);
        const detail::sphere_crossing crossing(ocx, ocy, ocz, rr, rays.dx, rays.dy, rays.dz);
        const maskv crosses = crossing.crosses() & active;
        if (!any(crosses)) continue;
        floatv t0;
        const floatv t = crossing.distance(ocx, ocy, ocz, rr, rays.tmin, t0);
        const maskv nearer = crosses & (t > rays.tmin) & (t <= limit) & (t < nearest_t);
        nearest_t = select(nearer, t, nearest_t);
        nearest_i = select(nearer, floatv(float(i - first)), nearest_i); // exact: below 16
    }
    // Lanes whose sphere is nearer than their best take it, their distances all at once; a lane at
    // exactly its best distance asks the tie rule (beats). A test per lane, as for a lone ray,
    // was a branch mispredicted as often as the lanes' fates differ.
    const maskv found = nearest_i >= floatv(0.0f);
    const unsigned nearer = bits(found & (nearest_t < limit)) & lanes;
    const unsigned tied = bits(found & (nearest_t == limit)) & lanes;
    if ((nearer | tied) == 0) return;
    select(lanes_of(nearer), nearest_t, limit).store(t_best);
    alignas(64) float leaf_i[floatv::width];
    nearest_i.store(leaf_i);
    for (unsigned m = nearer; m; m &= m - 1) {
        const unsigned k = unsigned(__builtin_ctz(m));
        best[k] = {Self, first + uint32_t(leaf_i[k])};
    }
    for (unsigned m = tied; m; m &= m - 1) {
        const unsigned k = unsigned(__builtin_ctz(m));
        const uint32_t index = first + uint32_t(leaf_i[k]);
        if (beats(t_best[k], Self, index, t_best[k], best[k])) best[k] = {Self, index};
    }
}

} // namespace rt
