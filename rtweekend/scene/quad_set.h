#pragma once
// quad_set: the compiled scene's quads (book 2's parallelograms Q + a u + b v, a and b in [0, 1]),
// one float array per field in BVH leaf order, and the SIMD kernel that tests a ray against one
// leaf of them, floatv::width quads per instruction.
//
// The test is book 2's: the ray meets the quad's plane at t = n.(Q - o) / n.d, with n = u x v;
// the point's coordinates in the (u, v) frame are a = (v x w).(p - Q) and b = (w x u).(p - Q)
// with w = n / n.n, and the quad is hit when both lie in [0, 1]. The two dual vectors v x w and
// w x u are made once, by the compiler, so a lane costs three dot products more than a plane.

#include "../core/force_inline.h"
#include "leaf_query.h"
#include "../core/simd.h"
#include "surface_hit.h"
#include "../core/vec3f.h"

#include <array>
#include <cstdint>
#include <vector>

namespace rt {

struct quad_set {
    size_t count = 0; // quads; the arrays hold floatv::width more when count > 0 (padding)
    // Coordinate `axis` of field f of quad i is field[3 * f + axis][i], for the fields corner Q,
    // normal n = u x v, dual_u = v x w and dual_v = w x u (w = n / n.n).
    std::array<std::vector<float>, 12> field;
    std::vector<float> ux, uy, uz, vx, vy, vz; // the edges, for completing a hit
    std::vector<uint32_t> material;
    // Back-face culling: 1 where a hit on the back face is skipped; empty until
    // compiled_scene::set_back_face_culling.
    std::vector<float> cull;

    enum : int { corner_field = 0, normal_field = 1, dual_u_field = 2, dual_v_field = 3 };

    // Appends the quad Q + a u + b v (relative to the scene origin). The compiler computes
    // n, the duals and the edges in double and rounds each once.
    void append(const vec3f& q, const vec3f& u, const vec3f& v, const vec3f& n, const vec3f& dual_u,
                const vec3f& dual_v, uint32_t material_index) {
        const vec3f fields[4] = {q, n, dual_u, dual_v};
        for (int f = 0; f < 4; ++f)
            for (int axis = 0; axis < 3; ++axis) field[size_t(3 * f + axis)].push_back(fields[f][axis]);
        ux.push_back(u.x), uy.push_back(u.y), uz.push_back(u.z);
        vx.push_back(v.x), vy.push_back(v.y), vz.push_back(v.z);
        material.push_back(material_index);
    }

    // A quad no ray hits (its normal is zero: every t is NaN or infinite).
    void append_padding() { append({}, {}, {}, {}, {}, {}, 0); }

    // Tests quads [first, first + n) against the ray: see leaf_query.h.
    template <query Q>
    bool intersect_leaf(const ray3f& ray, uint32_t first, uint32_t n, float& t_best, hit_ref& best) const;

    // The hit on quad i at distance t along the ray.
    void complete_hit(const ray3f& ray, float t, uint32_t i, surface_hit& hit) const;

    vec3f corner(uint32_t i) const { return get(corner_field, i); }
    vec3f edge_u(uint32_t i) const { return {ux[i], uy[i], uz[i]}; }
    vec3f edge_v(uint32_t i) const { return {vx[i], vy[i], vz[i]}; }

    size_t bytes() const {
        size_t b = material.size() * sizeof(uint32_t) + (cull.size() + 6 * ux.size()) * sizeof(float);
        for (const auto& f : field) b += f.size() * sizeof(float);
        return b;
    }

  private:
    vec3f get(int f, uint32_t i) const {
        return {field[size_t(3 * f)][i], field[size_t(3 * f + 1)][i], field[size_t(3 * f + 2)][i]};
    }
};

template <query Q>
RTWEEKEND_FORCE_INLINE bool quad_set::intersect_leaf(const ray3f& ray, uint32_t first, uint32_t n, float& t_best,
                                                     hit_ref& best) const {
    constexpr size_t W = floatv::width;
    const floatv tmin(ray.tmin), zero(0.0f), one(1.0f);
    const floatv ox(ray.origin.x), oy(ray.origin.y), oz(ray.origin.z);
    const floatv dx(ray.dir.x), dy(ray.dir.y), dz(ray.dir.z);
    bool found = false;
    for (uint32_t i = first; i < first + n; i += W) {
        auto load = [&](int f, int axis) { return floatv::load(&field[size_t(3 * f + axis)][i]); };
        // The corner relative to the ray origin, and the plane's distance and slope along the ray.
        floatv qx = load(corner_field, 0) - ox, qy = load(corner_field, 1) - oy, qz = load(corner_field, 2) - oz;
        floatv nx = load(normal_field, 0), ny = load(normal_field, 1), nz = load(normal_field, 2);
        floatv denom = nx * dx + ny * dy + nz * dz;
        floatv t = (nx * qx + ny * qy + nz * qz) / denom; // parallel: infinite or NaN, rejected below
        maskv candidates = within_range<Q>(t, tmin, t_best) & first_lanes(first + n - i);
        // The ray meets the back face when it travels along n: culled quads keep only front hits.
        if constexpr (Q == query::closest_culled)
            candidates = candidates & ((denom < zero) | (floatv::load(&cull[i]) == zero));
        if (!any(candidates)) continue;
        // The hit point relative to the corner: o + t d - Q.
        floatv px = t * dx - qx, py = t * dy - qy, pz = t * dz - qz;
        floatv a = load(dual_u_field, 0) * px + load(dual_u_field, 1) * py + load(dual_u_field, 2) * pz;
        floatv b = load(dual_v_field, 0) * px + load(dual_v_field, 1) * py + load(dual_v_field, 2) * pz;
        maskv hits = candidates & (a >= zero) & (a <= one) & (b >= zero) & (b <= one);
        if (!any(hits)) continue;
        if constexpr (Q == query::any) return true;
        found |= take_closest(hits, t, shape_kind::quad, i, t_best, best);
    }
    return found;
}

inline void quad_set::complete_hit(const ray3f& ray, float t, uint32_t i, surface_hit& hit) const {
    // The point from its (a, b) coordinates lies on the plane, unlike o + t d.
    const vec3f q = corner(i), rel = ray.at(t) - q;
    const float a = dot(get(dual_u_field, i), rel), b = dot(get(dual_v_field, i), rel);
    hit.p = q + a * edge_u(i) + b * edge_v(i);
    const vec3f outward = normalize(get(normal_field, i));
    hit.set_face_normal(ray.dir, outward);
    hit.offset = 0; // the reconstructed point is within an ulp or so of the plane: the ray offset suffices
    hit.material = material[i];
}

} // namespace rt
