#pragma once
// instance_set: the shape kind of instances (scene/shape_kinds.h says what a kind answers). An
// instance is an object (a subtree of built-in
// shapes, compiled once into geometry of its own, with its own BVH: compiled_scene::objects)
// placed in the scene by an affine transform x -> A x + b. A mesh placed a thousand times is
// stored once; the top-level BVH holds one box per instance. The traversal (compiled_scene.h)
// moves the ray into the object's frame, walks the object's BVH, and moves the hit back: the
// point by A x + b, the normal by the inverse transpose of A (normals are gradients), and t by
// the length of the transformed direction (the object is traced with a unit direction, which
// its kernels expect).
//
// Spawned rays. A hit point computed in the object's frame and carried out by A x + b is good to
// a few ulps of sum_j |A_ij| |x_j| + |b_i|, not of the point itself; and a ray spawned from it
// re-enters the object's frame with an error of a few ulps of |A^-1| |p| + |c| (object units),
// which A stretches by up to |A|. complete_instance_hit adds both to the hit's offset, so a
// spawned ray clears the surface it leaves however the transform scales or shears it.

#include "../../core/box3f.h"
#include "../../core/material_kinds.h"
#include "../../core/constants.h"
#include "../../core/scene_error.h"
#include "../../core/vec3f.h"
#include "../affine_map.h"
#include "../leaf_query.h"
#include "../surface_hit.h"
#include "../validate.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace rt {

// x -> M x + t in float: rows of M, then t.
struct affine3f {
    float m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    vec3f t;

    vec3f vector(const vec3f& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    vec3f point(const vec3f& p) const { return vector(p) + t; }
    // M^T v: with M the inverse of an instance's matrix, how a normal goes out to the world.
    vec3f transposed(const vec3f& v) const {
        return {m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
                m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z};
    }
    // The largest |M v| / |v| in the max norm (the largest row sum of |M_ij|): how much M can
    // stretch an error.
    float max_stretch() const {
        float s = 0;
        for (const auto& row : m) s = fmax_inline(s, std::fabs(row[0]) + std::fabs(row[1]) + std::fabs(row[2]));
        return s;
    }
};

struct instance_set {
    static constexpr const char* name = "instance";
    // Whether its shapes move with the ray's time (an object that moves makes the scene move:
    // compiled_scene::has_motion).
    static constexpr bool moves = false;
    // Scenes of these alone are rare: they share the walk of mixed scenes (shape_kinds.h).
    static constexpr bool own_walk = false;

    // --- compiling ---------------------------------------------------------------------------
    // An instance as the compiler collects it (scene_compiler::place): which object, and the map
    // from the object's frame to the world's.
    struct input {
        uint32_t object; // in compiled_scene::objects
        affine_map map;
        vec3f motion{0, 0, 0}; // a moving instance's displacement over the shutter interval (transform.h: moving)
    };
    // The box, in the scene's frame, around the object's: its eight corners mapped, and padded by
    // a few ulps of their magnitude for the float maps the walk uses.
    template <class Scene>
    static box3f bounds(const input& in, const Scene& scene);
    // The maps in float, object frame -> scene (relative to its origin) and back, in the BVH's order.
    template <class Scene>
    void lay_out(const Scene& scene, const std::vector<input>& inputs, const std::vector<uint32_t>& order);

    // --- the compiled instances ----------------------------------------------------------------
    std::vector<affine3f> to_world;  // object frame -> scene (relative to the scene origin)
    std::vector<affine3f> to_object; // its inverse
    std::vector<uint32_t> object;    // index into compiled_scene::objects
    // Displacement at time 1 (at time t the instance is moved by t * motion), in the scene's frame;
    // empty when no instance moves, so that a still scene pays nothing for it.
    std::vector<vec3f> motion;

    size_t count() const { return object.size(); }
    size_t moving_count() const {
        size_t n = 0;
        for (const vec3f& m : motion) n += m.x != 0 || m.y != 0 || m.z != 0;
        return n;
    }
    vec3f shift(uint32_t i, float time) const { return motion.empty() ? vec3f{0, 0, 0} : time * motion[i]; }

    void append(const affine3f& world_from_object, const affine3f& object_from_world, uint32_t object_index) {
        to_world.push_back(world_from_object);
        to_object.push_back(object_from_world);
        object.push_back(object_index);
    }

    // The ray r (in the scene's frame) in instance i's frame, with a unit direction; `scale` is
    // the length of the transformed direction, by which every distance along the ray grows
    // (t_object = scale * t_scene). False for a transform that loses the direction.
    bool local_ray(uint32_t i, const ray3f& r, ray3f& local, float& scale) const {
        const affine3f& inv = to_object[i];
        const vec3f d = inv.vector(r.dir);
        scale = length(d);
        if (!(scale > 0) || !std::isfinite(scale)) return false;
        local.origin = inv.point(motion.empty() ? r.origin : r.origin - shift(i, r.time));
        local.dir = d / scale;
        local.tmin = r.tmin * scale;
        local.tmax = r.tmax * scale;
        local.time = r.time;
        return true;
    }

    size_t size() const { return count(); }

    // What a walk found inside an instance: the object's own closest hit, at the object's distance.
    struct ray_state {
        hit_ref inner;
        float inner_t = 0;
    };
    // Instances [first, first + n): each object's own walk, in its frame. Out of line: the
    // object's walk calls Scene::trace again (an object holds no instances, so it never comes back
    // here), and inlined into every leaf dispatch it would crowd the traversal loop.
    template <query Q, shape_kind Self, class Scene>
#if defined(__GNUC__)
    __attribute__((noinline))
#endif
    bool intersect_leaf(const Scene& scene, const ray3f& r, uint32_t first, uint32_t n, float& t_best, hit_ref& best,
                        ray_state& state) const;
    // The object's own hit, completed in its frame, carried out to the scene's (see the top).
    template <class Scene>
    void complete_hit(const Scene& scene, const ray3f& r, float t, uint32_t i, const ray_state& state,
                      surface_hit& hit) const;
    // Found in the object's frame when the hit was completed (hit.has_uv): nothing to add.
    void surface_coordinates(const surface_hit& hit, double& u, double& v) const {
        u = hit.u;
        v = hit.v;
    }

    // An object's emitters are not light-sampled: a path that hits one counts it in full.
    static constexpr bool light_sampled = false;
    // Everything, when there is an instance: its object's shapes are not looked into.
    template <class Scene, class Predicate>
    void bound_where(const Scene&, Predicate, box3f& b) const {
        if (count() == 0) return;
        const float inf = std::numeric_limits<float>::infinity();
        b.grow(vec3f{-inf, -inf, -inf});
        b.grow(vec3f{inf, inf, inf});
    }
    // The objects are marked by the compiled scene (each is a compiled scene of its own).
    template <class Predicate>
    void mark_culled(Predicate) {}

    size_t bytes() const { return count() * (2 * sizeof(affine3f) + sizeof(uint32_t)); }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

template <class Scene>
box3f instance_set::bounds(const input& in, const Scene& scene) {
    const box3f& b = scene.objects[in.object]->bounds;
    vec3 lo(infinity, infinity, infinity), hi(-infinity, -infinity, -infinity);
    const vec3 motion(in.motion.x, in.motion.y, in.motion.z);
    for (float x : {b.lo.x, b.hi.x})
        for (float y : {b.lo.y, b.hi.y})
            for (float z : {b.lo.z, b.hi.z})
                for (const vec3& shift : {vec3(0, 0, 0), motion}) { // where it starts and where it ends
                    const vec3 corner = in.map.point(vec3(x, y, z)) - scene.origin + shift;
                    for (int c = 0; c < 3; ++c) lo[c] = fmin_inline(lo[c], corner[c]), hi[c] = fmax_inline(hi[c], corner[c]);
                }
    if (!(max_abs(lo) < max_float_extent && max_abs(hi) < max_float_extent))
        throw scene_error("an instance is out of single-precision range: it must be within 1e18 of the camera");
    const double pad = std::ldexp(fmax_inline(max_abs(lo), max_abs(hi)), -20);
    box3f out;
    out.lo = {float_below(lo.x() - pad), float_below(lo.y() - pad), float_below(lo.z() - pad)};
    out.hi = {float_above(hi.x() + pad), float_above(hi.y() + pad), float_above(hi.z() + pad)};
    return out;
}

template <class Scene>
void instance_set::lay_out(const Scene& scene, const std::vector<input>& inputs, const std::vector<uint32_t>& order) {
    for (uint32_t i : order) {
        const input& in = inputs[i];
        const mat3& a = in.map.m;
        const vec3 b = in.map.t - scene.origin;
        const mat3 inv = a.inverse();
        const vec3 c = -(inv * b);
        affine3f world, local;
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) {
                world.m[r][k] = static_cast<float>(a(r, k));
                local.m[r][k] = static_cast<float>(inv(r, k));
            }
        world.t = vec3f(b);
        local.t = vec3f(c);
        append(world, local, in.object);
        motion.push_back(in.motion);
    }
    if (moving_count() == 0) motion.clear(); // a still scene's walk never looks
}

template <query Q, shape_kind Self, class Scene>
bool instance_set::intersect_leaf(const Scene& scene, const ray3f& r, uint32_t first, uint32_t n, float& t_best,
                                  hit_ref& best, ray_state& state) const {
    bool found = false;
    for (uint32_t i = first; i < first + n; ++i) {
        ray3f local;
        float scale;
        if (!local_ray(i, r, local, scale)) continue;
        float t_local = t_best * scale;
        hit_ref inner;
        typename Scene::leaf_state inner_state;
        if (!scene.objects[object[i]]->template trace<Q>(local, t_local, inner, inner_state)) continue;
        if constexpr (Q == query::any) return true;
        // Back in the scene's distances; rounding must not make a hit farther than t_best.
        t_best = fmin_inline(t_local / scale, t_best);
        best = {Self, i};
        state.inner = inner;
        state.inner_t = t_local;
        found = true;
    }
    return found;
}

template <class Scene>
void instance_set::complete_hit(const Scene& scene, const ray3f& r, float, uint32_t i, const ray_state& state,
                                surface_hit& hit) const {
    ray3f local;
    float scale;
    local_ray(i, r, local, scale); // it succeeded in the walk: the same ray again
    surface_hit inner;
    const Scene& obj = *scene.objects[object[i]];
    obj.complete_hit(local, state.inner_t, state.inner, typename Scene::leaf_state{}, inner);
    const affine3f& world = to_world[i];
    const affine3f& back = to_object[i];
    hit.p = world.point(inner.p);
    if (!motion.empty()) hit.p += shift(i, r.time);
    // Normals as gradients, by the inverse transpose; each still faces the ray (the transform
    // keeps which side of the surface a point is on), and front_face carries over.
    hit.normal = normalize(back.transposed(inner.normal));
    hit.shading_normal = normalize(back.transposed(inner.shading_normal));
    hit.front_face = inner.front_face;
    hit.material = inner.material;
    hit.object_kind = inner.kind;
    hit.object_index = inner.index;
    if (scene.materials[inner.material].texture != no_texture ||
        (inner.material < scene.normal_maps.size() && scene.normal_maps[inner.material].texture != UINT32_MAX)) {
        // Texture coordinates belong to the shape in its own frame (as the book's transforms
        // compute them, hitting the object in its frame): asked of the object now.
        double u, v;
        obj.surface_coordinates(inner, u, v);
        hit.has_uv = true;
        hit.u = float(u);
        hit.v = float(v);
    }
    // The error of the carried-out point, and of a spawned ray's origin carried back in.
    const auto& a = world.m;
    const vec3f a_p = {std::fabs(a[0][0] * inner.p.x) + std::fabs(a[0][1] * inner.p.y) + std::fabs(a[0][2] * inner.p.z),
                       std::fabs(a[1][0] * inner.p.x) + std::fabs(a[1][1] * inner.p.y) + std::fabs(a[1][2] * inner.p.z),
                       std::fabs(a[2][0] * inner.p.x) + std::fabs(a[2][1] * inner.p.y) + std::fabs(a[2][2] * inner.p.z)};
    const float out_error =
        std::ldexp(max_abs_component(a_p) + max_abs_component(world.t) + max_abs_component(shift(i, r.time)), -21);
    const float in_error =
        std::ldexp(back.max_stretch() * max_abs_component(hit.p) + max_abs_component(back.t), -20);
    hit.offset = world.max_stretch() * (inner.offset + in_error) + out_error;
}

} // namespace rt
