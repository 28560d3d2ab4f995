#pragma once
// instance_set: the compiled scene's instances. An instance is an object (a subtree of built-in
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

#include "leaf_query.h"
#include "../core/vec3f.h"

#include <cmath>
#include <cstdint>
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
    std::vector<affine3f> to_world;  // object frame -> scene (relative to the scene origin)
    std::vector<affine3f> to_object; // its inverse
    std::vector<uint32_t> object;    // index into compiled_scene::objects

    size_t count() const { return object.size(); }

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
        local.origin = inv.point(r.origin);
        local.dir = d / scale;
        local.tmin = r.tmin * scale;
        local.tmax = r.tmax * scale;
        local.time = r.time;
        return true;
    }

    size_t bytes() const { return count() * (2 * sizeof(affine3f) + sizeof(uint32_t)); }
};

} // namespace rt
