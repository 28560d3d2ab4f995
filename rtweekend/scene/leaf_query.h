#pragma once
// What a BVH leaf kernel is asked and what it reports. Every shape kind of the compiled scene has
// a kernel that tests a ray against one leaf of its shapes (scene/shapes/sphere_set.h, ...);
// compiled_scene.h dispatches to them by the leaf's kind (scene/shape_kinds.h lists the kinds).
//
//   query::closest           lower t_best to the nearest hit in the leaf, remember which shape
//   query::any               return true at the first hit (shadow rays)
//   query::closest_culled    as closest, skipping back faces of shapes marked for culling

#include "../core/simd.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace rt {

// The kind of shape a BVH leaf holds (each leaf holds one kind): its number in the list of shape
// kinds, scene/shape_kinds.h (shape_id<sphere_set> is the sphere's).
enum class shape_kind : uint8_t {};

enum class query : uint8_t { closest, any, closest_culled };

// The closest hit found so far: which shape, by kind and position in its set.
struct hit_ref {
    static constexpr uint32_t none = UINT32_MAX; // no hit yet
    shape_kind kind{};
    uint32_t index = none;
};

// Rays in SIMD lanes, for the leaf kernels of a packet walk (bvh.h, traverse_packet): lane k
// holds ray k's origin, unit direction and tmin.
struct ray_lanes {
    floatv ox, oy, oz, dx, dy, dz, tmin;
};

// Whether a hit on shape `index` of `kind` at distance t beats the best so far: nearer, or at
// exactly the same distance (two triangles meeting at an edge the ray passes through, or shapes
// that touch) the lower (kind, index). Ties broken so do not depend on the order in which a walk
// meets the shapes, so a ray finds the same shape alone and in a packet with others (bvh.h,
// traverse_packet), whatever the packet. With no best yet, t must be below t_best (the ray's
// tmax: the range is open).
inline bool beats(float t, shape_kind kind, uint32_t index, float t_best, const hit_ref& best) {
    if (t != t_best) return t < t_best;
    return best.index != hit_ref::none && (kind < best.kind || (kind == best.kind && index < best.index));
}

// Which lanes of t a leaf kernel's query Q can take: within (tmin, t_best), or at t_best for a
// tie (above) when the query wants the closest hit; an any-hit query stops before t_best.
template <query Q>
inline maskv within_range(floatv t, floatv tmin, float t_best) {
    if constexpr (Q == query::any) return (t > tmin) & (t < floatv(t_best));
    return (t > tmin) & (t <= floatv(t_best));
}

// Makes the nearest of the lanes in `hits` the best hit if it beats the best so far, and says
// whether it did. Lane k holds shape first_lane + k of `kind`, at distance t[k]; among lanes at
// the same distance the first (lowest index) is the one a tie would favour anyway.
inline bool take_closest(maskv hits, floatv t, shape_kind kind, uint32_t first_lane, float& t_best, hit_ref& best) {
    const floatv candidates = select(hits, t, floatv(std::numeric_limits<float>::infinity()));
    const float nearest = reduce_min(candidates);
    const uint32_t index = first_lane + unsigned(__builtin_ctz(bits(candidates == floatv(nearest)) | (1u << 31)));
    if (!any(hits) || !beats(nearest, kind, index, t_best, best)) return false;
    t_best = nearest;
    best = {kind, index};
    return true;
}

// Back-face culling flags for a kind's laid-out shapes: 1 for the first `count` whose material
// index `cullable` accepts, 0 for the rest (the padding lanes, never hit anyway).
template <class Predicate>
std::vector<float> culling_flags(const std::vector<uint32_t>& material, size_t count, Predicate cullable) {
    std::vector<float> f(material.size(), 0.0f);
    for (size_t i = 0; i < count; ++i) f[i] = cullable(material[i]) ? 1.0f : 0.0f;
    return f;
}

} // namespace rt
