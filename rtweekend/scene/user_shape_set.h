#pragma once
// user_shape_set: the user's own hittables that report a bounding box, in BVH leaf order. Their
// leaf kernel calls each shape's virtual hit() in double precision and world coordinates, as the
// book's code would; the BVH around them means a ray only asks the few whose boxes it enters.
// (Hittables without a box stay in compiled_scene::unbounded_user_shapes and meet every ray.)

#include "../hittable.h"
#include "../interval.h"
#include "../ray.h"
#include "leaf_query.h"
#include "surface_hit.h"
#include "../core/vec3f.h"

#include <cstdint>
#include <vector>

namespace rt {

struct user_shape_set {
    std::vector<const hittable*> shapes; // owned by the world

    // Tests shapes [first, first + n) against the ray (relative to `origin`, the scene's origin):
    // see leaf_query.h. A closest hit's record goes to *record. Kept out of line: it makes virtual
    // calls anyway, and inlined it would crowd the traversal loop every other kind runs in.
    template <query Q>
#if defined(__GNUC__)
    __attribute__((noinline))
#endif
    bool intersect_leaf(const ray3f& r, const vec3& origin, uint32_t first, uint32_t n, float& t_best, hit_ref& best,
                        hit_record* record) const {
        const ray world_ray(origin + r.origin.to_double(), r.dir.to_double(), r.time);
        hit_record rec;
        bool found = false;
        for (uint32_t i = first; i < first + n; ++i) {
            if (!shapes[i]->hit(world_ray, interval(r.tmin, t_best), rec)) continue;
            if constexpr (Q == query::any) return true;
            // Rounded to nearest, a t below t_best stays at or below it.
            t_best = static_cast<float>(rec.t);
            best = {shape_kind::user, i};
            *record = rec;
            found = true;
        }
        return found;
    }

    size_t bytes() const { return shapes.size() * sizeof(const hittable*); }
};

// Fills `hit` from the record a user's hittable `shape` reported (in world coordinates).
inline void complete_user_hit(const hittable* shape, const hit_record& rec, const vec3& origin, surface_hit& hit) {
    hit.user_shape = shape;
    hit.kind = shape_kind::user;
    if (&hit.user_record != &rec) hit.user_record = rec;
    hit.t = static_cast<float>(rec.t);
    hit.p = vec3f(rec.p - origin);
    hit.normal = normalize(vec3f(rec.normal));
    hit.shading_normal = hit.normal;
    hit.front_face = rec.front_face;
    hit.offset = 0;
}

} // namespace rt
