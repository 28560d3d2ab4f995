#pragma once
// surface_hit: what the compiled scene's closest-hit query reports about the surface a ray meets.

#include "../hittable.h"
#include "leaf_query.h"
#include "vec3f.h"

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
    shape_kind kind = shape_kind::sphere; // which shape was hit: its kind and index in its set
    uint32_t index = 0;
    // Set when a user-written hittable was hit: its record, in world coordinates.
    const hittable* user_shape = nullptr;
    hit_record user_record;
};

} // namespace rt
