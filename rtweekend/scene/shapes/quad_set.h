#pragma once
// quad_set: the shape kind of book 2's quads, the parallelograms Q + a u + b v, a and b in [0, 1]
// (scene/shape_kinds.h says what a kind answers): one float array per field in BVH leaf order, and
// the SIMD kernel that tests a ray against one leaf of them, floatv::width quads per instruction.
//
// The test is book 2's: the ray meets the quad's plane at t = n.(Q - o) / n.d, with n = u x v;
// the point's coordinates in the (u, v) frame are a = (v x w).(p - Q) and b = (w x u).(p - Q)
// with w = n / n.n, and the quad is hit when both lie in [0, 1]. The two dual vectors v x w and
// w x u are made once, by the compiler, so a lane costs three dot products more than a plane.

#include "../../core/box3f.h"
#include "../../core/force_inline.h"
#include "../../core/scene_error.h"
#include "../../core/simd.h"
#include "../../core/vec3f.h"
#include "../../quad.h"
#include "../affine_map.h"
#include "../leaf_query.h"
#include "../lights/quad_emitter.h"
#include "../surface_hit.h"
#include "../validate.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rt {

struct quad_set {
    static constexpr const char* name = "quad";
    // Whether its shapes move with the ray's time.
    static constexpr bool moves = false;
    // A scene of these alone walks its BVH without asking each leaf its kind (shape_kinds.h).
    static constexpr bool own_walk = true;

    // --- compiling ---------------------------------------------------------------------------
    // A quad as the compiler collects it: corner relative to the scene origin, and edges, in double.
    struct input {
        vec3 q, u, v;
        uint32_t material;
    };
    // The book's quad under the map xf.
    template <class Compiler>
    static void add(Compiler& compiler, const quad& q, const affine_map& xf);
    // The box of its four corners, each rounded outwards.
    template <class Scene>
    static box3f bounds(const input& q, const Scene&) {
        box3f b;
        for (const vec3& c : {q.q, q.q + q.u, q.q + q.v, q.q + q.u + q.v})
            b.grow({float_below(c.x()), float_below(c.y()), float_below(c.z())}),
                b.grow({float_above(c.x()), float_above(c.y()), float_above(c.z())});
        return b;
    }
    // In the BVH's leaf order: the normal and the duals computed in double and rounded once.
    template <class Scene>
    void lay_out(const Scene&, const std::vector<input>& inputs, const std::vector<uint32_t>& order) {
        count = order.size();
        for (uint32_t i : order) {
            const input& q = inputs[i];
            const vec3 n = cross(q.u, q.v);
            const vec3 w = n / dot(n, n);
            append(vec3f(q.q), vec3f(q.u), vec3f(q.v), vec3f(n), vec3f(cross(q.v, w)), vec3f(cross(w, q.u)), q.material);
        }
        if (count > 0)
            for (size_t k = 0; k < floatv::width; ++k) append_padding();
    }

    // --- the compiled quads --------------------------------------------------------------------
    size_t count = 0; // quads; the arrays hold floatv::width more when count > 0 (padding)
    // Coordinate `axis` of field f of quad i is field[3 * f + axis][i], for the fields corner Q,
    // normal n = u x v, dual_u = v x w and dual_v = w x u (w = n / n.n).
    std::array<std::vector<float>, 12> field;
    std::vector<float> ux, uy, uz, vx, vy, vz; // the edges, for completing a hit
    std::vector<uint32_t> material;
    // Back-face culling: 1 where a hit on the back face is skipped; empty until
    // mark_culled.
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

    size_t size() const { return count; }
    uint32_t material_of(uint32_t i) const { return material[i]; }

    struct ray_state {};
    // Tests quads [first, first + n) against the ray: see leaf_query.h.
    template <query Q, shape_kind Self, class Scene>
    bool intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n, float& t_best, hit_ref& best,
                        ray_state&) const;
    // The hit on quad i at distance t along the ray.
    template <class Scene>
    void complete_hit(const Scene&, const ray3f& ray, float t, uint32_t i, const ray_state&, surface_hit& hit) const;
    // Book 2's (u, v): the point's coordinates (alpha, beta) along the edges, Q + u U + v V.
    void surface_coordinates(const surface_hit& hit, double& u, double& v) const {
        const vec3 q = corner(hit.index).to_double(), eu = edge_u(hit.index).to_double(), ev = edge_v(hit.index).to_double();
        const vec3 n = cross(eu, ev), w = n / dot(n, n), rel = hit.p.to_double() - q;
        u = dot(w, cross(rel, ev));
        v = dot(w, cross(eu, rel));
    }

    // An emitting quad is light-sampled by solid angle or by area.
    static constexpr bool light_sampled = true;
    quad_emitter light_of(uint32_t i) const { return {corner(i), edge_u(i), edge_v(i)}; }

    // Grows b by the quads whose material `selected` accepts.
    template <class Scene, class Predicate>
    void bound_where(const Scene&, Predicate selected, box3f& b) const {
        for (uint32_t i = 0; i < count; ++i)
            if (selected(material[i])) {
                const vec3f q = corner(i), u = edge_u(i), v = edge_v(i);
                for (const vec3f& p : {q, q + u, q + v, q + u + v}) b.grow(p);
            }
    }
    template <class Predicate>
    void mark_culled(Predicate cullable) { cull = culling_flags(material, count, cullable); }

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

// --- IMPLEMENTATION -----------------------------------------------------------------------------

template <class Compiler>
void quad_set::add(Compiler& compiler, const quad& q, const affine_map& xf) {
    if (!finite3(q.corner()) || !finite3(q.edge_u()) || !finite3(q.edge_v()))
        throw scene_error("quad corner and edges must be finite, got " + point_text(q.corner()) + " " +
                          point_text(q.edge_u()) + " " + point_text(q.edge_v()));
    if (!q.mat()) throw scene_error("quad at " + point_text(q.corner()) + " has no material");
    const vec3 corner = xf.point(q.corner()) - compiler.origin(), u = xf.vector(q.edge_u()), v = xf.vector(q.edge_v());
    for (const vec3& p : {corner, corner + u, corner + v, corner + u + v})
        if (!(max_abs(p) < max_float_extent))
            throw scene_error("quad at " + point_text(q.corner()) +
                              " is out of single-precision range: it must be within 1e18 of the camera");
    // Zero area in float: no ray could hit it, and its dual vectors would be infinite.
    if (length_squared(cross(vec3f(u), vec3f(v))) == 0)
        throw scene_error("quad at " + point_text(q.corner()) + " with edges " + point_text(q.edge_u()) + " " +
                          point_text(q.edge_v()) + " has zero area");
    compiler.template inputs<quad_set>().push_back({corner, u, v, compiler.material_index(q.mat().get())});
}

template <query Q, shape_kind Self, class Scene>
RTWEEKEND_FORCE_INLINE bool quad_set::intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n,
                                                     float& t_best, hit_ref& best, ray_state&) const {
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
        found |= take_closest(hits, t, Self, i, t_best, best);
    }
    return found;
}

template <class Scene>
void quad_set::complete_hit(const Scene&, const ray3f& ray, float t, uint32_t i, const ray_state&, surface_hit& hit) const {
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
