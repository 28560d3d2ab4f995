#pragma once
// The compiled scene: what the renderer traces. Built by compile_scene (scene_compiler.h).
//
//   scene.intersect(ray, hit)   the closest hit        scene.occluded(ray)   any hit at all
//
// It holds one set per shape kind (sphere_set.h, triangle_set.h, user_shape_set.h), each in the
// order of the leaves of one BVH over all of them (bvh.h), and the table of built-in materials
// (bsdf.h). User-written hittables are called through their virtual hit(): from the BVH when they
// report a bounding box, after it (for every ray) when they do not. Positions are relative to
// `origin` (the camera).
//
// One dispatch: a query walks the BVH and hands each leaf to the kernel of the leaf's shape kind
// (leaf_kernel below; with_shape_kind maps a kind to its kernel). A scene pays only for what it
// has: when all its shapes are of one kind (the book's scenes are all spheres, a mesh all
// triangles) the walk calls that kind's kernel directly, without asking each leaf its kind; the
// triangle test's ray set-up is made at the first triangle leaf a ray reaches; and a scene of a
// handful of shapes has no BVH nodes at all.

#include "../hittable.h"
#include "bsdf.h"
#include "bvh.h"
#include "force_inline.h"
#include "leaf_query.h"
#include "light_set.h"
#include "quad_set.h"
#include "sphere_set.h"
#include "surface_hit.h"
#include "triangle_set.h"
#include "user_shape_set.h"
#include "vec3f.h"

#include <cstdint>
#include <optional>
#include <type_traits>
#include <vector>

namespace rt {

// Calls f(std::integral_constant<shape_kind, K>{}) for the kind K = `kind`: the one place that
// turns a shape kind known at run time into the compile-time kind a kernel is chosen by.
template <class F>
RTWEEKEND_FORCE_INLINE decltype(auto) with_shape_kind(shape_kind kind, F&& f) {
    switch (kind) {
    case shape_kind::sphere: return f(std::integral_constant<shape_kind, shape_kind::sphere>{});
    case shape_kind::triangle: return f(std::integral_constant<shape_kind, shape_kind::triangle>{});
    case shape_kind::quad: return f(std::integral_constant<shape_kind, shape_kind::quad>{});
    case shape_kind::user: break;
    }
    return f(std::integral_constant<shape_kind, shape_kind::user>{});
}

class compiled_scene {
  public:
    vec3 origin; // world position that float coordinates are relative to
    std::vector<compiled_material> materials;
    sphere_set spheres;
    triangle_set triangles;
    quad_set quads;
    user_shape_set user_shapes; // user-written hittables with a bounding box
    bvh8 bvh;                   // over every set
    light_set lights;           // the emitters among the shapes (and point lights), for light sampling

    // User-written hittables without a bounding box (the default hittable::bounding_box, or a box
    // that is empty, infinite or beyond float's range), tested after the BVH. Owned by the world.
    std::vector<const hittable*> unbounded_user_shapes;
    bool has_user_materials = false;

    // The kind of every shape in the BVH when there is only one kind; empty for a mix (or none).
    std::optional<shape_kind> single_kind;

    // Whether rendering calls user code (shapes or materials), which may call random_double().
    bool calls_user_code() const { return !user_shapes.shapes.empty() || !unbounded_user_shapes.empty() || has_user_materials; }

    // The closest hit with t in (ray.tmin, ray.tmax); false when the ray escapes.
    bool intersect(const ray3f& r, surface_hit& hit) const;
    // The same, skipping back faces of the shapes set_back_face_culling marked (a sphere's back
    // face is the exit point of a ray that starts inside it). User hittables are never culled.
    bool intersect_culling_back_faces(const ray3f& r, surface_hit& hit) const;
    // Whether anything at all is hit with t in (ray.tmin, ray.tmax): for shadow rays.
    bool occluded(const ray3f& r) const;

    // Marks the shapes whose back faces intersect_culling_back_faces skips: those whose material
    // index `cullable` accepts (opaque ones: a glass object's back face must be found).
    template <class Predicate>
    void set_back_face_culling(Predicate cullable);

    // Bytes held for tracing: the sets and the BVH nodes.
    size_t geometry_bytes() const {
        return bvh.stats.bytes() + spheres.bytes() + triangles.bytes() + quads.bytes() + user_shapes.bytes();
    }

  private:
    // What a walk prepares for the kernels on demand: the sheared ray of the triangle test.
    struct leaf_state {
        std::optional<triangle_ray> sheared;
        hit_record* user_record; // where a user shape's closest-hit record goes
    };
    // Tests the ray against the leaf `ref` of shapes of kind K (see leaf_query.h).
    template <query Q, shape_kind K>
    bool leaf_kernel(const ray3f& r, uint32_t ref, float& t_best, hit_ref& best, leaf_state& state) const;
    // Walks the BVH; a user shape's closest-hit record goes to *user_record.
    template <query Q>
    bool trace(const ray3f& r, float& tmax, hit_ref& best, hit_record* user_record) const;
    void complete_hit(const ray3f& r, float t, const hit_ref& best, surface_hit& hit) const;
    bool intersect_unbounded(const ray3f& r, bool found, surface_hit& hit) const;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

template <query Q, shape_kind K>
RTWEEKEND_FORCE_INLINE bool compiled_scene::leaf_kernel(const ray3f& r, uint32_t ref, float& t_best, hit_ref& best, leaf_state& state) const {
    const uint32_t first = bvh_ref::first(ref), count = bvh_ref::count(ref);
    if constexpr (K == shape_kind::sphere) {
        return spheres.intersect_leaf<Q>(r, first, count, t_best, best);
    } else if constexpr (K == shape_kind::triangle) {
        if (!state.sheared) state.sheared.emplace(r); // the ray's first triangle leaf
        return triangles.intersect_leaf<Q>(r, *state.sheared, first, count, t_best, best);
    } else if constexpr (K == shape_kind::quad) {
        return quads.intersect_leaf<Q>(r, first, count, t_best, best);
    } else {
        return user_shapes.intersect_leaf<Q>(r, origin, first, count, t_best, best, state.user_record);
    }
}

template <query Q>
bool compiled_scene::trace(const ray3f& r, float& tmax, hit_ref& best, hit_record* user_record) const {
    leaf_state state{std::nullopt, user_record};
    if (single_kind) {
        return with_shape_kind(*single_kind, [&](auto kind) {
            return traverse<Q == query::any>(bvh, r, tmax, [&](uint32_t ref, float& t_best) {
                return leaf_kernel<Q, decltype(kind)::value>(r, ref, t_best, best, state);
            });
        });
    }
    return traverse<Q == query::any>(bvh, r, tmax, [&](uint32_t ref, float& t_best) {
        return with_shape_kind(bvh_ref::kind(ref), [&](auto kind) {
            return leaf_kernel<Q, decltype(kind)::value>(r, ref, t_best, best, state);
        });
    });
}

inline void compiled_scene::complete_hit(const ray3f& r, float t, const hit_ref& best, surface_hit& hit) const {
    hit.t = t;
    hit.user_shape = nullptr;
    hit.kind = best.kind;
    hit.index = best.index;
    switch (best.kind) {
    case shape_kind::sphere: spheres.complete_hit(r, t, best.index, hit); break;
    case shape_kind::triangle: triangles.complete_hit(r, t, best.index, hit); break;
    case shape_kind::quad: quads.complete_hit(r, t, best.index, hit); break;
    case shape_kind::user: complete_user_hit(user_shapes.shapes[best.index], hit.user_record, origin, hit); break;
    }
}

// The user's hittables without a box, in double precision and world coordinates, after the BVH
// found `hit` (if `found`); one of them wins if it is nearer.
inline bool compiled_scene::intersect_unbounded(const ray3f& r, bool found, surface_hit& hit) const {
    const ray world_ray(origin + r.origin.to_double(), r.dir.to_double());
    double closest = found ? hit.t : r.tmax;
    hit_record rec;
    const hittable* nearest = nullptr;
    for (const hittable* shape : unbounded_user_shapes) {
        if (shape->hit(world_ray, interval(r.tmin, closest), rec)) {
            closest = rec.t;
            nearest = shape;
            hit.user_record = rec;
        }
    }
    if (!nearest) return found;
    complete_user_hit(nearest, hit.user_record, origin, hit);
    return true;
}

inline bool compiled_scene::intersect(const ray3f& r, surface_hit& hit) const {
    hit.user_shape = nullptr;
    float t = r.tmax;
    hit_ref best;
    bool found = trace<query::closest>(r, t, best, &hit.user_record);
    if (found) complete_hit(r, t, best, hit);
    if (!unbounded_user_shapes.empty()) found = intersect_unbounded(r, found, hit);
    return found;
}

inline bool compiled_scene::intersect_culling_back_faces(const ray3f& r, surface_hit& hit) const {
    if (spheres.cull.empty() && triangles.cull.empty() && quads.cull.empty()) return intersect(r, hit);
    hit.user_shape = nullptr;
    float t = r.tmax;
    hit_ref best;
    bool found = trace<query::closest_culled>(r, t, best, &hit.user_record); // user shapes: never culled
    if (found) complete_hit(r, t, best, hit);
    if (!unbounded_user_shapes.empty()) found = intersect_unbounded(r, found, hit);
    return found;
}

inline bool compiled_scene::occluded(const ray3f& r) const {
    float t = r.tmax;
    hit_ref best;
    if (trace<query::any>(r, t, best, nullptr)) return true;
    if (!unbounded_user_shapes.empty()) {
        const ray world_ray(origin + r.origin.to_double(), r.dir.to_double());
        hit_record rec;
        for (const hittable* shape : unbounded_user_shapes)
            if (shape->hit(world_ray, interval(r.tmin, r.tmax), rec)) return true;
    }
    return false;
}

template <class Predicate>
void compiled_scene::set_back_face_culling(Predicate cullable) {
    auto flags = [&](const std::vector<uint32_t>& material, size_t count) {
        std::vector<float> f(material.size(), 0.0f); // the padding lanes never hit anyway
        for (size_t i = 0; i < count; ++i) f[i] = cullable(material[i]) ? 1.0f : 0.0f;
        return f;
    };
    spheres.cull = flags(spheres.material, spheres.count);
    triangles.cull = flags(triangles.material, triangles.count);
    quads.cull = flags(quads.material, quads.count);
}

} // namespace rt
