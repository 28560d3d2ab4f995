#pragma once
// surface_map: what a scene's front end changes at every hit on one of its materials, beyond the
// compiled scene's own tables (a texture that colours a kind, a tangent-space normal or bump map,
// a metallic-roughness map): any of the material's reflectances, its shading normal in a frame of
// the front end's choosing, and a radiance the surface shows whatever lights it. The CENG795
// course's texture maps are one (course/course_surface_map.h: its decal modes on any course
// material, in the course's frames).
//
//   scene.surface_maps.resize(scene.materials.size());
//   scene.surface_maps[k] = std::make_shared<const course_surface_map>(object);
//
// The path tracer asks the map of the material it hit (compiled_scene::surface_maps, by material
// index) before it shades; a scene without maps pays one test of an empty table per hit. A map is
// engine-side code: it must not draw random numbers, so the paths still walk in packets.

#include "../core/material_kinds.h"
#include "../core/vec3f.h"
#include "surface_hit.h"

namespace rt {

class compiled_scene;

// The surface at a hit as a map leaves it. apply() receives the stored material and the hit's
// shading normal, and changes what its maps change.
struct surface_change {
    compiled_material material;
    vec3f shading_normal; // unit, on the side of the ray as surface_hit::shading_normal is
    vec3f glow{0, 0, 0};  // radiance it shows along every ray that meets it, unlit (not a light)
};

class surface_map {
  public:
    virtual ~surface_map() = default;
    virtual void apply(const compiled_scene& scene, const surface_hit& hit, surface_change& at) const = 0;
};

} // namespace rt
