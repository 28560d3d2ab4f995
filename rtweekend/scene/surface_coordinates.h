#pragma once
// Surface coordinates and textures at a point of the compiled scene.
//
//   surface_coordinates(scene, hit, u, v)    the (u, v) of a built-in shape's hit, as the books
//                                            define them (below)
//   textured(scene, m, hit)                  a copy of material m with its texture looked up at
//                                            the hit: a lambertian's albedo, a light's emission
//   textured_light_radiance(scene, lc)       the radiance of a textured light at the point a light
//                                            sample chose (light_set.h)
//
// (u, v) by shape kind (scene/shapes/): a sphere's from its outward normal (book 2's get_sphere_uv:
// u the angle around the y axis from -x, v from the south pole -y up); a quad's from its edges
// (book 2's alpha and beta, Q + u U + v V); a triangle's from its mesh's per-vertex uv weighted
// barycentrically, or 0 (as the book's shapes without coordinates have); an instance's from the
// shape inside it, in the object's own frame (found when its hit is completed). A sphere flattened under rotate_y
// keeps its world-space normal here, where the book's hit computes (u, v) in the object's frame:
// its texture turns with the world, not with the sphere.

#include "../core/material_kinds.h"
#include "compiled_scene.h"
#include "light_set.h"
#include "surface_hit.h"

#include <cmath>

namespace rt {

void surface_coordinates(const compiled_scene& scene, const surface_hit& hit, double& u, double& v);
compiled_material textured(const compiled_scene& scene, const compiled_material& m, const surface_hit& hit);
vec3f textured_light_radiance(const compiled_scene& scene, const light_choice& lc);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline void surface_coordinates(const compiled_scene& scene, const surface_hit& hit, double& u, double& v) {
    scene.surface_coordinates(hit, u, v);
}

namespace detail {
inline vec3f texture_at(const compiled_scene& scene, uint32_t texture, const surface_hit& hit) {
    double u = 0, v = 0;
    if (scene.textures.reads_uv(texture)) surface_coordinates(scene, hit, u, v);
    return scene.textures.eval(texture, float(u), float(v), scene.origin + hit.p.to_double());
}
} // namespace detail

inline compiled_material textured(const compiled_scene& scene, const compiled_material& m, const surface_hit& hit) {
    return m.with_colour(detail::texture_at(scene, m.texture, hit));
}

inline vec3f textured_light_radiance(const compiled_scene& scene, const light_choice& lc) {
    const light& l = scene.lights.lights[lc.light];
    surface_hit at;
    at.p = lc.y;
    at.normal = lc.n; // outward: the sampler's normal, seen from its front
    at.front_face = true;
    at.index = l.shape_index;
    at.kind = l.shape;
    return detail::texture_at(scene, lc.texture, at);
}

} // namespace rt
