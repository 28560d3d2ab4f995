#pragma once
// The compiled scene: what the renderer traces. Built by compile_scene (scene_compiler.h).
//
//   scene.intersect(ray, hit)   the closest hit        scene.occluded(ray)   any hit at all
//
// It holds one set per shape kind (sphere_set.h, triangle_set.h), each in the order of the
// leaves of one BVH over all of them (bvh.h), the table of built-in materials (bsdf.h), and the
// user's own hittables, which are called through their virtual hit(). Positions are relative to
// `origin` (the camera).
//
// One dispatch: a query walks the BVH and hands each leaf to the kernel of the leaf's shape kind.
// A scene pays only for what it has: a kind it lacks is a branch never taken, the triangle test's
// ray set-up is made at the first triangle leaf a ray reaches, and a scene of a handful of shapes
// has no BVH nodes at all.

#include "../hittable.h"
#include "bsdf.h"
#include "bvh.h"
#include "leaf_query.h"
#include "sphere_set.h"
#include "surface_hit.h"
#include "triangle_set.h"
#include "vec3f.h"

#include <cstdint>
#include <vector>

namespace rt {

class compiled_scene {
  public:
    vec3 origin; // world position that float coordinates are relative to
    std::vector<material_desc> materials;
    sphere_set spheres;
    triangle_set triangles;
    bvh8 bvh; // over every set

    // User-written hittables, rendered through their virtual hit(). Owned by the world.
    std::vector<const hittable*> custom_objects;
    bool has_custom_materials = false;

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
    size_t geometry_bytes() const { return bvh.stats.bytes() + spheres.bytes() + triangles.bytes(); }

  private:
    template <query Q>
    bool trace(const ray3f& r, float& tmax, hit_ref& best) const;
    void complete_hit(const ray3f& r, float t, const hit_ref& best, surface_hit& hit) const;
    bool intersect_custom_objects(const ray3f& r, bool found, surface_hit& hit) const;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

template <query Q>
bool compiled_scene::trace(const ray3f& r, float& tmax, hit_ref& best) const {
    triangle_ray tr;
    bool tr_ready = false;
    return traverse<Q == query::any>(bvh, r, tmax, [&](uint32_t ref, float& t_best) {
        const uint32_t first = bvh_ref::first(ref), count = bvh_ref::count(ref);
        switch (bvh_ref::kind(ref)) {
        case shape_kind::sphere: return spheres.intersect_leaf<Q>(r, first, count, t_best, best);
        case shape_kind::triangle:
            if (!tr_ready) { // the first triangle leaf of this ray: shear the ray once
                tr = triangle_ray(r);
                tr_ready = true;
            }
            return triangles.intersect_leaf<Q>(r, tr, first, count, t_best, best);
        }
        return false;
    });
}

inline void compiled_scene::complete_hit(const ray3f& r, float t, const hit_ref& best, surface_hit& hit) const {
    hit.t = t;
    hit.custom_object = nullptr;
    switch (best.kind) {
    case shape_kind::sphere: spheres.complete_hit(r, t, best.index, hit); break;
    case shape_kind::triangle: triangles.complete_hit(r, t, best.index, hit); break;
    }
}

// The user's hittables, in double precision and world coordinates, after the built-in shapes
// found `hit` (if `found`); one of them wins if it is nearer.
inline bool compiled_scene::intersect_custom_objects(const ray3f& r, bool found, surface_hit& hit) const {
    ray world_ray(origin + r.origin.to_double(), r.dir.to_double());
    double closest = found ? hit.t : r.tmax;
    hit_record rec;
    for (const hittable* object : custom_objects) {
        if (object->hit(world_ray, interval(r.tmin, closest), rec)) {
            found = true;
            closest = rec.t;
            hit.custom_object = object;
            hit.custom_record = rec;
        }
    }
    if (hit.custom_object) {
        const hit_record& h = hit.custom_record;
        hit.t = static_cast<float>(h.t);
        hit.p = vec3f(h.p - origin);
        hit.normal = normalize(vec3f(h.normal));
        hit.shading_normal = hit.normal;
        hit.front_face = h.front_face;
        hit.offset = 0;
    }
    return found;
}

inline bool compiled_scene::intersect(const ray3f& r, surface_hit& hit) const {
    hit.custom_object = nullptr;
    float t = r.tmax;
    hit_ref best;
    bool found = trace<query::closest>(r, t, best);
    if (found) complete_hit(r, t, best, hit);
    if (!custom_objects.empty()) found = intersect_custom_objects(r, found, hit);
    return found;
}

inline bool compiled_scene::intersect_culling_back_faces(const ray3f& r, surface_hit& hit) const {
    if (spheres.cull.empty() && triangles.cull.empty()) return intersect(r, hit);
    hit.custom_object = nullptr;
    float t = r.tmax;
    hit_ref best;
    bool found = trace<query::closest_culled>(r, t, best);
    if (found) complete_hit(r, t, best, hit);
    if (!custom_objects.empty()) found = intersect_custom_objects(r, found, hit); // never culled
    return found;
}

inline bool compiled_scene::occluded(const ray3f& r) const {
    float t = r.tmax;
    hit_ref best;
    if (trace<query::any>(r, t, best)) return true;
    if (!custom_objects.empty()) {
        ray world_ray(origin + r.origin.to_double(), r.dir.to_double());
        hit_record rec;
        for (const hittable* object : custom_objects)
            if (object->hit(world_ray, interval(r.tmin, r.tmax), rec)) return true;
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
}

} // namespace rt
