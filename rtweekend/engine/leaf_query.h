#pragma once
// What a BVH leaf kernel is asked and what it reports. Every shape kind of the compiled scene has
// a kernel that tests a ray against one leaf of its shapes (sphere_set.h, triangle_set.h, ...);
// compiled_scene.h dispatches to them by the leaf's kind.
//
//   query::closest           lower t_best to the nearest hit in the leaf, remember which shape
//   query::any               return true at the first hit (shadow rays)
//   query::closest_culled    as closest, skipping back faces of shapes marked for culling

#include "simd.h"

#include <cstdint>
#include <limits>

namespace rt {

// The kinds of shape a BVH leaf can hold (each leaf holds one kind): built-in spheres, triangles
// and quads, user-written hittables with a bounding box, moving spheres (book 2's motion blur),
// and instances (an object's own compiled geometry under an affine transform, instance_set.h).
// The leaf reference has room for seven (bvh.h); a new kind adds a value here, a set of its own
// and a case in compiled_scene's dispatch.
enum class shape_kind : uint8_t { sphere = 0, triangle = 1, quad = 2, user = 3, moving_sphere = 4, instance = 5 };
inline constexpr int shape_kind_count = 6;

enum class query : uint8_t { closest, any, closest_culled };

// The closest hit found so far: which shape, by kind and position in its set.
struct hit_ref {
    shape_kind kind = shape_kind::sphere;
    uint32_t index = UINT32_MAX;
};

// Makes the nearest of the lanes in `hits` the best hit if it is nearer than t_best. Lane k
// holds shape first_lane + k of `kind`, at distance t[k].
inline void take_closest(maskv hits, floatv t, shape_kind kind, uint32_t first_lane, float& t_best, hit_ref& best) {
    const floatv candidates = select(hits, t, floatv(std::numeric_limits<float>::infinity()));
    const float nearest = reduce_min(candidates);
    if (!(nearest < t_best)) return;
    t_best = nearest;
    best = {kind, first_lane + unsigned(__builtin_ctz(bits(candidates == floatv(nearest))))};
}

} // namespace rt
