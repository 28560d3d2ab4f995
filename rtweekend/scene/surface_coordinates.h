#pragma once
// Surface coordinates and textures at a point of the compiled scene.
//
//   surface_coordinates(scene, hit, u, v)    the (u, v) of a built-in shape's hit, as the books
//                                            define them (below)
//   textured(scene, m, hit)                  a copy of material m with its texture looked up at
//                                            the hit: a lambertian's albedo, a light's emission,
//                                            a metal_roughness's metallic and roughness map; a
//                                            mesh's vertex colours multiply the colour
//   textured_light_radiance(scene, lc)       the radiance of a textured light at the point a light
//                                            sample chose (light_set.h)
//   shading_normal_at(scene, hit)            the hit's shading normal with its material's normal
//                                            or bump map applied (material.h: normal_mapped,
//                                            bump_mapped), or as it is
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
vec3f shading_normal_at(const compiled_scene& scene, const surface_hit& hit);

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
    vec3f colour = detail::texture_at(scene, m.texture, hit);
    // A mesh's vertex colours multiply the colour (glTF's COLOR_0 the base colour); not a light's.
    vec3f vertex;
    if (scene.vertex_colours && !m.emits() && scene.vertex_colour(hit, vertex)) colour = colour * vertex;
    compiled_material out = m.with_colour(colour);
    // A metallic-roughness map (compiled_scene::metallic_roughness_maps): blue the metallic, green
    // the roughness, times the material's factors.
    if (hit.material < scene.metallic_roughness_maps.size() && !hit.user_shape) {
        const compiled_scene::metallic_roughness_map& map = scene.metallic_roughness_maps[hit.material];
        if (map.texture != UINT32_MAX) {
            const vec3f t = detail::texture_at(scene, map.texture, hit);
            out.edit<metal_rough_bsdf>([&](metal_rough_bsdf& b) { b.set_metallic_roughness(map.metallic * t.z, map.roughness * t.y); });
        }
    }
    return out;
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

namespace detail {
// A bump map (material.h: bump_mapped): the normal of the surface displaced by d = scale h(u, v)
// along N, cross(dp/du + dd/du N, dp/dv + dd/dv N), its slopes by central differences 1e-4 apart,
// h a texel's mean channel; facing the ray as the hit's normals do. Left as it is where the
// displaced tangents give no direction.
inline vec3f bumped_normal(const compiled_scene& scene, const surface_hit& hit, const compiled_scene::normal_map& map,
                           const vec3& dpdu, const vec3& dpdv) {
    double u = 0, v = 0;
    surface_coordinates(scene, hit, u, v);
    const vec3 p = scene.origin + hit.p.to_double();
    auto height = [&](double du, double dv) {
        const vec3f c = scene.textures.eval(map.texture, float(u + du), float(v + dv), p);
        return (double(c.x) + double(c.y) + double(c.z)) / 3;
    };
    constexpr double step = 1e-4;
    const double dddu = map.scale * (height(step, 0) - height(-step, 0)) / (2 * step);
    const double dddv = map.scale * (height(0, step) - height(0, -step)) / (2 * step);
    const vec3 n = (hit.front_face ? hit.shading_normal : -hit.shading_normal).to_double();
    vec3 m = cross(dpdu + dddu * n, dpdv + dddv * n);
    const double lm = m.length();
    if (!(lm > 0) || !std::isfinite(lm)) return hit.shading_normal;
    m /= lm;
    if (dot(m, n) < 0) m = -m; // a mirrored mapping: its tangents turn the other way
    return vec3f(hit.front_face ? m : -m);
}
} // namespace detail

// The normal map's texel c, n = (scale (2 c.x - 1), scale (2 c.y - 1), 2 c.z - 1), in the frame of
// the outward shading normal N, T = dp/du made perpendicular to N, and B = N x T or its opposite,
// whichever is on dp/dv's side (so a mirrored mapping turns B round with it); the result faces the ray
// as the hit's normals do. Left as it is where the hit has no frame: another shape, no texture
// coordinates, a degenerate triangle, or a texel that gives no direction.
inline vec3f shading_normal_at(const compiled_scene& scene, const surface_hit& hit) {
    if (scene.normal_maps.empty() || hit.user_shape || hit.material >= scene.normal_maps.size()) return hit.shading_normal;
    const compiled_scene::normal_map& map = scene.normal_maps[hit.material];
    if (map.texture == UINT32_MAX) return hit.shading_normal;
    vec3 dpdu, dpdv;
    if (!scene.surface_tangents(hit, dpdu, dpdv)) return hit.shading_normal;
    if (map.heights) return detail::bumped_normal(scene, hit, map, dpdu, dpdv);
    const vec3f c = detail::texture_at(scene, map.texture, hit);
    const double x = map.scale * (2.0 * c.x - 1), y = map.scale * (2.0 * c.y - 1), z = 2.0 * c.z - 1;
    const vec3 n = (hit.front_face ? hit.shading_normal : -hit.shading_normal).to_double();
    vec3 t = dpdu - dot(n, dpdu) * n;
    const double lt = t.length();
    if (!(lt > 0)) return hit.shading_normal;
    t /= lt;
    // B perpendicular to both, on dp/dv's side: a mirrored mapping turns it round, and a file's
    // tangent (triangle_mesh::tangents) at any angle to dp/dv still gives a frame.
    const vec3 b = dot(cross(n, t), dpdv) < 0 ? -cross(n, t) : cross(n, t);
    const vec3 m = x * t + y * b + z * n;
    const double lm = m.length();
    if (!(lm > 0) || !std::isfinite(lm)) return hit.shading_normal;
    return vec3f(hit.front_face ? m / lm : -m / lm);
}

} // namespace rt
