#pragma once
// moving_sphere_set: the shape kind of the books' moving spheres (book 2's motion blur;
// scene/shape_kinds.h says what a kind answers): one float array per field in BVH leaf order, and
// the SIMD kernel that tests a ray against one leaf of them. The books' sphere class compiles
// into them (sphere_set::add) when it moves.
//
// A moving sphere's centre travels in a straight line, c(time) = c0 + time * m, over the shutter
// interval [0, 1): the kernel first moves every lane's centre to the ray's time, then runs the
// still sphere's stable test (sphere_set.h; Haines et al., Ray Tracing Gems ch. 7). They are a
// kind of their own, not spheres with zero motion, so that a still scene's kernel never pays the
// extra multiply-add per coordinate. The BVH box of a moving sphere covers its whole motion.

#include "../../core/box3f.h"
#include "../../core/constants.h"
#include "../../core/force_inline.h"
#include "../../core/simd.h"
#include "../../core/vec3f.h"
#include "../leaf_query.h"
#include "../lights/sphere_emitter.h"
#include "../surface_hit.h"
#include "../validate.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace rt {

namespace detail {
// Book 2's get_sphere_uv: (u, v) of a sphere's hit from its outward normal, u the angle around the
// y axis from -x, v from the south pole -y up.
inline void sphere_uv(const surface_hit& hit, double& u, double& v) {
    const vec3f outward = hit.front_face ? hit.normal : -hit.normal;
    const double theta = std::acos(fmax_inline(-1.0, fmin_inline(1.0, double(-outward.y))));
    const double phi = std::atan2(double(-outward.z), double(outward.x)) + pi;
    u = phi / (2 * pi);
    v = theta / pi;
}
} // namespace detail

struct moving_sphere_set {
    static constexpr const char* name = "moving sphere";
    // Whether its shapes move with the ray's time.
    static constexpr bool moves = true;
    // Scenes of these alone are rare: they share the walk of mixed scenes (shape_kinds.h).
    static constexpr bool own_walk = false;

    // --- compiling ---------------------------------------------------------------------------
    // A moving sphere as the compiler collects it (sphere_set::add): its centre at times 0 and 1,
    // relative to the scene origin, in double.
    struct input {
        vec3 c0, c1;
        double r;
        uint32_t material;
    };
    // Its box covers both ends of the motion, and a few ulps more: the kernel's centre
    // c0 + time * m, in float, may stray that far from the exact line.
    template <class Scene>
    static box3f bounds(const input& s, const Scene&) {
        const double pad = s.r + std::ldexp(fmax_inline(max_abs(s.c0), max_abs(s.c1)) + s.r, -20);
        box3f b;
        for (const vec3& c : {s.c0, s.c1})
            b.grow({float_below(c.x() - pad), float_below(c.y() - pad), float_below(c.z() - pad)}),
                b.grow({float_above(c.x() + pad), float_above(c.y() + pad), float_above(c.z() + pad)});
        return b;
    }
    template <class Scene>
    void lay_out(const Scene&, const std::vector<input>& inputs, const std::vector<uint32_t>& order) {
        count = order.size();
        for (uint32_t i : order) {
            const input& s = inputs[i];
            append(vec3f(s.c0), vec3f(s.c1 - s.c0), float(s.r), s.material);
        }
        if (count > 0)
            for (size_t k = 0; k < floatv::width; ++k) append({}, {}, 0, 0, /*padding=*/true);
    }

    // --- the compiled spheres ------------------------------------------------------------------
    size_t count = 0; // spheres; the arrays hold floatv::width more when count > 0 (padding)
    std::vector<float> x, y, z;    // the centre at time 0, relative to the scene origin
    std::vector<float> mx, my, mz; // its motion from time 0 to time 1
    std::vector<float> r2, r, offset;
    std::vector<uint32_t> material;
    // Back-face culling, as sphere_set's: empty until mark_culled.
    std::vector<float> cull;

    // Appends a sphere of radius `radius` whose centre moves from c0 (time 0) to c0 + motion
    // (time 1); a padding sphere is never hit.
    void append(const vec3f& c0, const vec3f& motion, float radius, uint32_t material_index, bool padding = false) {
        x.push_back(c0.x), y.push_back(c0.y), z.push_back(c0.z);
        mx.push_back(motion.x), my.push_back(motion.y), mz.push_back(motion.z);
        r2.push_back(padding ? -1.0f : radius * radius);
        r.push_back(radius);
        // As sphere_set's: a few ulps of the largest coordinate the centre takes, plus the radius.
        const float reach = fmax_inline(max_abs_component(c0), max_abs_component(c0 + motion));
        offset.push_back(std::ldexp(reach + radius, -21));
        material.push_back(material_index);
    }

    size_t size() const { return count; }
    uint32_t material_of(uint32_t i) const { return material[i]; }
    // The centre of sphere i at `time`.
    vec3f center(uint32_t i, float time) const { return {x[i] + time * mx[i], y[i] + time * my[i], z[i] + time * mz[i]}; }

    struct ray_state {};
    // Tests spheres [first, first + n) against the ray, at the ray's time: see leaf_query.h.
    template <query Q, shape_kind Self, class Scene>
    bool intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n, float& t_best, hit_ref& best,
                        ray_state&) const;
    // The hit on sphere i at distance t along the ray, where the sphere is at the ray's time.
    template <class Scene>
    void complete_hit(const Scene&, const ray3f& ray, float t, uint32_t i, const ray_state&, surface_hit& hit) const {
        // Re-projected onto the sphere where it is at the ray's time.
        const vec3f c = center(i, ray.time);
        const vec3f outward = normalize(ray.at(t) - c);
        hit.p = c + r[i] * outward;
        hit.set_face_normal(ray.dir, outward);
        hit.offset = offset[i];
        hit.material = material[i];
    }
    // As a still sphere's, from the outward normal at the hit.
    void surface_coordinates(const surface_hit& hit, double& u, double& v) const { detail::sphere_uv(hit, u, v); }

    // A moving emitter is not light-sampled (its position depends on the ray's time): a path that
    // hits it counts its emission in full.
    static constexpr bool light_sampled = false;

    // Grows b by the spheres whose material `selected` accepts, at both ends of their motion.
    template <class Scene, class Predicate>
    void bound_where(const Scene&, Predicate selected, box3f& b) const {
        for (uint32_t i = 0; i < count; ++i)
            if (selected(material[i]))
                for (float time : {0.0f, 1.0f}) {
                    b.grow(center(i, time) - vec3f{r[i], r[i], r[i]});
                    b.grow(center(i, time) + vec3f{r[i], r[i], r[i]});
                }
    }
    template <class Predicate>
    void mark_culled(Predicate cullable) { cull = culling_flags(material, count, cullable); }

    size_t bytes() const { return (x.size() * 9 + cull.size()) * sizeof(float) + material.size() * sizeof(uint32_t); }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

template <query Q, shape_kind Self, class Scene>
RTWEEKEND_FORCE_INLINE bool moving_sphere_set::intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n,
                                                              float& t_best, hit_ref& best, ray_state&) const {
    constexpr size_t W = floatv::width;
    const floatv tmin(ray.tmin), zero(0.0f), time(ray.time);
    const floatv ox(ray.origin.x), oy(ray.origin.y), oz(ray.origin.z);
    const floatv dx(ray.dir.x), dy(ray.dir.y), dz(ray.dir.z);
    bool found = false;
    for (uint32_t i = first; i < first + n; i += W) {
        // The centres at the ray's time, relative to the ray origin.
        floatv ocx = (floatv::load(&x[i]) + time * floatv::load(&mx[i])) - ox;
        floatv ocy = (floatv::load(&y[i]) + time * floatv::load(&my[i])) - oy;
        floatv ocz = (floatv::load(&z[i]) + time * floatv::load(&mz[i])) - oz;
        floatv rr = floatv::load(&r2[i]);
        floatv h = dx * ocx + dy * ocy + dz * ocz;
        floatv px = ocx - h * dx, py = ocy - h * dy, pz = ocz - h * dz;
        floatv disc = rr - (px * px + py * py + pz * pz);
        maskv crosses = (disc >= zero) & first_lanes(first + n - i);
        if (!any(crosses)) continue;
        floatv c = (ocx * ocx + ocy * ocy + ocz * ocz) - rr;
        floatv s = sqrt(max(disc, zero));
        floatv q = select(h >= zero, h + s, h - s);
        floatv ta = c / q;
        floatv t0 = min(ta, q), t1 = max(ta, q);
        floatv t = select(t0 > tmin, t0, t1);
        if constexpr (Q == query::closest_culled)
            t = select((t0 > tmin) | (floatv::load(&cull[i]) == zero), t, floatv(-1.0f));
        maskv hits = crosses & within_range<Q>(t, tmin, t_best);
        if (!any(hits)) continue;
        if constexpr (Q == query::any) return true;
        found |= take_closest(hits, t, Self, i, t_best, best);
    }
    return found;
}

} // namespace rt
