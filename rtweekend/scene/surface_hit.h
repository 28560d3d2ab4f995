#pragma once
// surface_hit: what the compiled scene's closest-hit query reports about the surface a ray meets.

#include "../hittable.h"
#include "../core/force_inline.h"
#include "leaf_query.h"
#include "../core/ray_offset.h"
#include "../core/vec3f.h"

#include <cstdint>
#include <limits>

namespace rt {

struct surface_hit {
    float t = std::numeric_limits<float>::infinity();
    vec3f p;               // hit point, relative to the scene origin
    vec3f normal;          // unit geometric normal, facing the incoming ray
    vec3f shading_normal;  // unit normal to shade with, on the same side: the geometric normal,
                           // or a smooth mesh's interpolated vertex normals
    bool front_face = true;
    float offset = 0;      // extra push off the surface for spawned rays (the shape's own error)
    float time = 0;        // the time of the ray that found the hit: rays spawned from it keep it
    // An instance's hit on a textured material: the texture coordinates of the shape inside it,
    // found in the object's own frame (surface_coordinates.h); other hits work theirs out on demand.
    bool has_uv = false;
    float u = 0, v = 0;
    uint32_t material = 0; // index into compiled_scene::materials
    shape_kind kind{};     // which shape was hit: its kind and index in its set
    uint32_t index = 0;
    // An instance's hit (kind is the instance kind, index the instance): the shape inside its
    // object, by kind and index in the object's own sets. The course's textures find the
    // triangle's corners and texture coordinates in the object's frame through it.
    shape_kind object_kind{};
    uint32_t object_index = 0;
    // Set when a user-written hittable was hit: its record, in world coordinates.
    const hittable* user_shape = nullptr;
    hit_record user_record;

    // The book's set_face_normal: front_face, and the normal (the shading normal too) facing the
    // ray of direction `dir`, from the surface's outward normal. Negated by flipping sign bits, not
    // by a branch: which face a ray meets is a coin toss in glass, and the branch was mispredicted
    // often enough to be a fifth of the cover scene's hit completion (perf, 2026-11-29).
    void set_face_normal(const vec3f& dir, const vec3f& outward) {
        const uint32_t back = uint32_t(!(dot(dir, outward) < 0)) << 31;
        front_face = back == 0;
        normal = {detail::flip_sign(outward.x, back), detail::flip_sign(outward.y, back),
                  detail::flip_sign(outward.z, back)};
        shading_normal = normal;
    }

    // Whether the shading normal differs from the geometric one (a smooth mesh's hit).
    bool smooth_shaded() const {
        return !(shading_normal.x == normal.x && shading_normal.y == normal.y && shading_normal.z == normal.z);
    }
};

namespace detail {

// Where a ray leaving the surface at `hit` in direction wi starts: pushed off the surface on the
// side wi points to. A scattering point inside a volume (in_volume) lies on no surface, so it has
// nothing to escape from and the ray starts at the point itself (see trace_path).
RTWEEKEND_FORCE_INLINE ray3f spawn_ray(const surface_hit& hit, const vec3f& wi, float tmax, bool in_volume = false) {
    // The normal, negated when wi goes below it: its sign bits flipped by a mask, not a branch
    // (a glass sphere's rays go either way at random).
    const uint32_t flip = uint32_t(!(dot(wi, hit.normal) >= 0)) << 31;
    ray3f r;
#if defined(__SSE2__)
    // In SSE lanes, as offset_ray_origin is computed: the same bits as below.
    const __m128 side = _mm_xor_ps(lanes_of(hit.normal), _mm_castsi128_ps(_mm_set1_epi32(int(flip))));
    const __m128 pushed = offset_lanes(lanes_of(hit.p), side);
#if defined(__FMA__)
    r.origin = in_volume ? hit.p : vec3f_of(_mm_fmadd_ps(_mm_set1_ps(hit.offset), side, pushed));
#else
    r.origin = in_volume ? hit.p : vec3f_of(_mm_add_ps(pushed, _mm_mul_ps(_mm_set1_ps(hit.offset), side)));
#endif
#else
    const vec3f side{flip_sign(hit.normal.x, flip), flip_sign(hit.normal.y, flip), flip_sign(hit.normal.z, flip)};
    r.origin = in_volume ? hit.p : offset_ray_origin(hit.p, side) + hit.offset * side;
#endif
    r.dir = wi;
    r.tmin = 0;
    r.tmax = tmax;
    r.time = hit.time; // the path's moment: shadow and continuation rays see the scene as it was
    return r;
}

} // namespace detail

} // namespace rt
