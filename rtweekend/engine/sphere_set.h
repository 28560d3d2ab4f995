#pragma once
// sphere_set: the compiled scene's spheres, one float array per field in BVH leaf order, and the
// SIMD kernel that tests a ray against one leaf of them, floatv::width spheres per instruction.
//
// The test is the numerically stable one of sphere.h (Haines et al., Ray Tracing Gems ch. 7):
// the discriminant from the centre's distance to the ray's line, the near root from c / q.

#include "force_inline.h"
#include "leaf_query.h"
#include "simd.h"
#include "surface_hit.h"
#include "vec3f.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace rt {

struct sphere_set {
    size_t count = 0; // spheres; the arrays hold floatv::width more, never hit (padding)
    std::vector<float> x, y, z, r2, r, offset;
    std::vector<uint32_t> material;
    // Back-face culling: 1 where a hit on the back face (a ray from inside) is skipped; empty
    // until compiled_scene::set_back_face_culling.
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

    // Tests spheres [first, first + n) against the ray: see leaf_query.h.
    template <query Q>
    bool intersect_leaf(const ray3f& ray, uint32_t first, uint32_t n, float& t_best, hit_ref& best) const;

    // The hit on sphere i at distance t along the ray.
    void complete_hit(const ray3f& ray, float t, uint32_t i, surface_hit& hit) const {
        vec3f center{x[i], y[i], z[i]};
        // Re-project the hit point onto the sphere: removes the error of o + t d along the ray.
        vec3f outward = normalize(ray.at(t) - center);
        hit.p = center + r[i] * outward;
        hit.front_face = dot(ray.dir, outward) < 0;
        hit.normal = hit.front_face ? outward : -outward;
        hit.shading_normal = hit.normal;
        hit.offset = offset[i];
        hit.material = material[i];
    }

    size_t bytes() const { return (x.size() * 6 + cull.size()) * sizeof(float) + material.size() * sizeof(uint32_t); }
};

template <query Q>
RTWEEKEND_FORCE_INLINE bool sphere_set::intersect_leaf(const ray3f& ray, uint32_t first, uint32_t n, float& t_best, hit_ref& best) const {
    constexpr size_t W = floatv::width;
    const floatv tmin(ray.tmin), zero(0.0f);
    const floatv ox(ray.origin.x), oy(ray.origin.y), oz(ray.origin.z);
    const floatv dx(ray.dir.x), dy(ray.dir.y), dz(ray.dir.z);
    bool found = false;
    for (uint32_t i = first; i < first + n; i += W) {
        floatv ocx = floatv::load(&x[i]) - ox, ocy = floatv::load(&y[i]) - oy, ocz = floatv::load(&z[i]) - oz;
        floatv rr = floatv::load(&r2[i]);
        // Compute the quadratic's h = d.(C - O) and its discriminant from the distance to the line.
        floatv h = fmadd(dx, ocx, fmadd(dy, ocy, dz * ocz));
        floatv px = fnmadd(h, dx, ocx), py = fnmadd(h, dy, ocy), pz = fnmadd(h, dz, ocz);
        floatv disc = rr - fmadd(px, px, fmadd(py, py, pz * pz));
        maskv crosses = (disc >= zero) & first_lanes(first + n - i);
        if (!any(crosses)) continue;
        floatv c = fmadd(ocx, ocx, fmadd(ocy, ocy, ocz * ocz)) - rr;
        floatv s = sqrt(max(disc, zero));
        floatv q = select(h >= zero, h + s, h - s);
        floatv ta = c / q;
        floatv t0 = min(ta, q), t1 = max(ta, q);
        floatv t = select(t0 > tmin, t0, t1);
        // Culled: a ray that starts inside (or past) the sphere only meets its back face.
        if constexpr (Q == query::closest_culled)
            t = select((t0 > tmin) | (floatv::load(&cull[i]) == zero), t, floatv(-1.0f));
        maskv hits = crosses & (t > tmin) & (t < floatv(t_best));
        if (!any(hits)) continue;
        if constexpr (Q == query::any) return true;
        take_closest(hits, t, shape_kind::sphere, i, t_best, best);
        found = true;
    }
    return found;
}

} // namespace rt
