#pragma once
// course_surface_map: a CENG795 textured object's maps (course_textures.h) at a hit, in the
// course's way (section 8 of the course format notes, docs/course.md "Textures"), for every
// renderer: the Whitted integrator asks at() and shades by the course's own terms; the path
// tracer asks apply() (scene/surface_map.h), which gives it the material as the maps leave it.
//
//   course_surface_map m(object);                   // checks the maps and the object's placement
//   course_surface_map::surface s = m.at(scene, hit);
//   s.mapped     the object's material with its colour maps applied, in the file's order:
//                replace_kd, blend_kd, replace_ks (kd or ks of any course material: a mirror's,
//                a conductor's, a dielectric's diffuse base, a BRDF's kd and ks); none when no
//                colour map applies
//   s.normal     the shading normal a normal map (replace_normal) or bump map (bump_normal, an
//                image or Perlin noise) gives, unit, on the side of the hit's normal; zero when
//                none applies
//   s.replaced   a replace_all map: the local shading is its colour (s.replaced_shading)
//
// Where a hit is on the object: its point in the object's own frame (carried back by the
// object's map, or found in an instance's frame), its (u, v) (a mesh's interpolated coordinates,
// a sphere's from the point: u = (pi - phi) / (2 pi), v = theta / pi), and the frame the normal
// maps work in: for meshes the object's (dP/du, dP/dv from the corners and their coordinates,
// the object normal; carried out by M^-T), for spheres the world's (the sphere's dP/du, dP/dv
// carried out by M, the world normal). Those are the frames the instructor's images were matched
// in (the course format notes, 8.5 and 8.6).
//
// In the path tracer a replace_all surface shows its colour to every ray that meets it, and
// reflects nothing but its delta lobe (a mirror's, a dielectric's): the course's "local shading
// replaced" as a surface that glows its texel, unlit.

#include "../core/engine_linkage.h"
#include "../scene/surface_map.h"
#include "../transform.h"
#include "../vec3.h"
#include "../whitted_material.h"
#include "course_textures.h"

#include <optional>

namespace rt {

// Refuses a map the renderers cannot use: an image map without its picture, numbers that are
// not finite, a normalizer that is not positive.
void check_texture_map(const texture_map& map);

class course_surface_map final : public surface_map {
  public:
    // Throws scene_error for an object without a material, an unusable map, a map that cannot be
    // inverted or a sphere without a positive finite radius.
    explicit course_surface_map(textured_object object);
    const textured_object& object() const { return object_; }

    struct surface {
        std::optional<whitted_material> mapped;
        vec3f normal{0, 0, 0};
        bool replaced = false;
        vec3f replaced_shading{0, 0, 0};
    };
    // What the maps make of the surface at `hit` (a hit on this object's material).
    surface at(const compiled_scene& scene, const surface_hit& hit) const;
    // For the path tracer: the material recompiled from the mapped one (a replace_all surface's
    // without its diffuse and specular reflectances, and glowing its colour), and the normal.
    void apply(const compiled_scene& scene, const surface_hit& hit, surface_change& change) const override;

    // Where a hit is on the object: its object-space point, (u, v), and dP/du, dP/dv (not
    // normalised) and the unit outward normal in the frame normal maps work in (the object's for
    // meshes, `object_frame`; the world's for spheres). False for a hit the object's shape cannot
    // describe (then no map applies).
    struct point {
        vec3 p;
        double u = 0, v = 0;
        vec3 T, B, N;
        bool object_frame = true;
    };
    bool point_at(const compiled_scene& scene, const surface_hit& hit, point& s) const;

  private:
    textured_object object_;
    mat3 inverse_, normal_map_; // M^-1, M^-T
};

} // namespace rt

#if RTWEEKEND_ENGINE_BODIES

#include "../core/constants.h"
#include "../core/scene_error.h"
#include "../scene/compiled_scene.h"
#include "../scene/validate.h"

#include <cmath>
#include <utility>

namespace rt {

RTWEEKEND_ENGINE_FUNCTION void check_texture_map(const texture_map& map) {
    if (map.pattern == texture_map::pattern_t::image && (!map.picture || map.picture->empty()))
        throw scene_error("texture map has no image");
    if (!(map.normalizer > 0) || !std::isfinite(map.normalizer) || !std::isfinite(map.bump_factor) ||
        !std::isfinite(map.noise_scale) || !std::isfinite(map.scale) || !std::isfinite(map.offset))
        throw scene_error("texture map numbers must be finite, with a positive normalizer");
}

RTWEEKEND_ENGINE_FUNCTION course_surface_map::course_surface_map(textured_object object) : object_(std::move(object)) {
    if (!object_.surface) throw scene_error("textured object has no material");
    for (const texture_map& map : object_.maps) check_texture_map(map);
    const double det = object_.linear.determinant();
    if (!(std::fabs(det) > 0) || !std::isfinite(det) || !finite3(object_.offset))
        throw scene_error("textured object must be placed by an invertible finite map");
    if (object_.shape == textured_object::shape_t::sphere &&
        (!(object_.radius > 0) || !std::isfinite(object_.radius) || !finite3(object_.center)))
        throw scene_error("textured sphere must have a positive finite radius");
    inverse_ = object_.linear.inverse();
    normal_map_ = inverse_.transpose();
}

RTWEEKEND_ENGINE_FUNCTION bool course_surface_map::point_at(const compiled_scene& scene, const surface_hit& hit,
                                                            point& s) const {
    const compiled_scene* holder = &scene; // the scene or object whose sets hold the shape hit
    shape_kind kind = hit.kind;
    uint32_t index = hit.index;
    const bool in_instance = hit.kind == shape_id<instance_set>;
    if (in_instance) {
        // Traced in the object's own frame: its point and triangle are there already.
        const instance_set& instances = scene.set<instance_set>();
        holder = scene.objects[instances.object[hit.index]].get();
        kind = hit.object_kind;
        index = hit.object_index;
        s.p = instances.to_object[hit.index].point(hit.p - instances.shift(hit.index, hit.time)).to_double();
    } else {
        // Flattened into the scene's frame: carried back by the object's own map.
        s.p = inverse_ * (scene.origin + hit.p.to_double() - object_.offset);
    }
    const vec3 outward = hit.front_face ? hit.normal.to_double() : -hit.normal.to_double();
    if (object_.shape == textured_object::shape_t::sphere) {
        const vec3 P = s.p - object_.center;
        const double r = object_.radius;
        const course_sphere_coordinates c(P, r);
        const double theta = c.theta, phi = c.phi;
        s.u = c.u;
        s.v = c.v;
        s.T = object_.linear * (2 * pi * vec3(P.z(), 0, -P.x()));
        s.B = object_.linear * (pi * vec3(P.y() * std::cos(phi), -r * std::sin(theta), P.y() * std::sin(phi)));
        s.N = outward;
        s.object_frame = false;
        return true;
    }
    if (kind != shape_id<triangle_set>) return false;
    const triangle_set& ts = holder->set<triangle_set>();
    vec3 c[3];
    double uv[3][2] = {{0, 0}, {0, 0}, {0, 0}};
    for (size_t k = 0; k < 3; ++k) {
        c[k] = vec3(ts.vertex[3 * k][index], ts.vertex[3 * k + 1][index], ts.vertex[3 * k + 2][index]);
        if (!in_instance) c[k] = inverse_ * (scene.origin + c[k] - object_.offset);
        if (!ts.uv[0].empty())
            for (size_t a = 0; a < 2; ++a) uv[k][a] = ts.uv[2 * k + a][index];
    }
    // Barycentric coordinates of p by least squares in the triangle's plane (as triangle_set's).
    const vec3 e1 = c[1] - c[0], e2 = c[2] - c[0], d = s.p - c[0];
    const double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(d, e1), d21 = dot(d, e2);
    const double det = d00 * d11 - d01 * d01;
    if (!(det > 0)) return false;
    const double b1 = (d11 * d20 - d01 * d21) / det, b2 = (d00 * d21 - d01 * d20) / det, b0 = 1 - b1 - b2;
    s.u = b0 * uv[0][0] + b1 * uv[1][0] + b2 * uv[2][0];
    s.v = b0 * uv[0][1] + b1 * uv[1][1] + b2 * uv[2][1];
    // dP/du and dP/dv from the uv differences along the edges (the course's formula).
    const double du1 = uv[1][0] - uv[0][0], dv1 = uv[1][1] - uv[0][1];
    const double du2 = uv[2][0] - uv[0][0], dv2 = uv[2][1] - uv[0][1];
    const double uv_det = du1 * dv2 - du2 * dv1;
    s.N = unit_vector(cross(e1, e2)); // the course's winding: (b - a) x (c - a)
    if (uv_det != 0 && std::isfinite(uv_det)) {
        s.T = (dv2 * e1 - dv1 * e2) / uv_det;
        s.B = (du1 * e2 - du2 * e1) / uv_det;
    } else { // no coordinates to differentiate: any frame of the plane
        s.T = unit_vector(e1);
        s.B = cross(s.N, s.T);
    }
    s.object_frame = true;
    return true;
}

RTWEEKEND_ENGINE_FUNCTION course_surface_map::surface course_surface_map::at(const compiled_scene& scene,
                                                                             const surface_hit& hit) const {
    surface out;
    point s;
    if (!point_at(scene, hit, s)) return out;
    whitted_material mapped = *object_.surface;
    bool recoloured = false;
    vec3 normal(0, 0, 0); // the new shading normal, in the point's frame; zero: unchanged
    bool normal_in_object_frame = s.object_frame;
    for (const texture_map& map : object_.maps) {
        using decal = texture_map::decal_t;
        switch (map.decal) {
        case decal::replace_kd: mapped.diffuse = map.colour(s.u, s.v, s.p).to_double(); recoloured = true; break;
        case decal::blend_kd:
            mapped.diffuse = (mapped.diffuse + map.colour(s.u, s.v, s.p).to_double()) / 2;
            recoloured = true;
            break;
        case decal::replace_ks: mapped.specular = map.colour(s.u, s.v, s.p).to_double(); recoloured = true; break;
        case decal::replace_all:
            out.replaced = true;
            out.replaced_shading = map.colour(s.u, s.v, s.p);
            break;
        case decal::replace_normal: {
            if (map.pattern != texture_map::pattern_t::image) break;
            // n_t = 2 c / 255 - 1 of the interpolated texel, in the frame (T^, B^, N).
            const vec3f c = map.lookup(s.u, s.v);
            const vec3 nt(2 * c.x / 255.0 - 1, 2 * c.y / 255.0 - 1, 2 * c.z / 255.0 - 1);
            normal = nt.x() * unit_vector(s.T) + nt.y() * unit_vector(s.B) + nt.z() * s.N;
            normal_in_object_frame = s.object_frame;
            break;
        }
        case decal::bump_normal: {
            if (map.pattern == texture_map::pattern_t::perlin) {
                // The converted noise times BumpFactor as a height over the object's space: its
                // gradient g by central differences, n' = n - (g - (g . n) n).
                const vec3 n = s.object_frame ? s.N : unit_vector(s.p - object_.center);
                auto h = [&](const vec3& x) { return map.bump_factor * map.noise_value(x); };
                const double e = 1e-3;
                const vec3 g((h(s.p + vec3(e, 0, 0)) - h(s.p - vec3(e, 0, 0))) / (2 * e),
                             (h(s.p + vec3(0, e, 0)) - h(s.p - vec3(0, e, 0))) / (2 * e),
                             (h(s.p + vec3(0, 0, e)) - h(s.p - vec3(0, 0, e))) / (2 * e));
                normal = n - (g - dot(g, n) * n);
                normal_in_object_frame = true;
                break;
            }
            if (map.pattern != texture_map::pattern_t::image) break;
            // Forward differences of one texel of the nearest heights; the surface displaced by
            // k h N: n' = (B + k h_v N) x (T + k h_u N), turned to N's side.
            const double W = map.picture->width(), H = map.picture->height();
            const double h0 = map.height(s.u, s.v);
            const double hu = map.height(s.u + 1 / W, s.v) - h0, hv = map.height(s.u, s.v + 1 / H) - h0;
            const double k = map.bump_factor;
            normal = cross(s.B + k * hv * s.N, s.T + k * hu * s.N);
            if (dot(normal, s.N) < 0) normal = -normal;
            normal_in_object_frame = s.object_frame;
            break;
        }
        case decal::replace_background: break; // the film's, not the object's (the renderers')
        }
    }
    if (normal.length_squared() > 0 && finite3(normal)) {
        vec3 world = normal_in_object_frame ? normal_map_ * normal : normal;
        const double len = world.length();
        if (len > 0 && std::isfinite(len)) {
            vec3f n(world / len);
            if (dot(n, hit.normal) < 0) n = -n; // on the side the ray came from, as the geometric normal
            out.normal = n;
        }
    }
    if (recoloured) out.mapped = std::move(mapped);
    return out;
}

RTWEEKEND_ENGINE_FUNCTION void course_surface_map::apply(const compiled_scene& scene, const surface_hit& hit,
                                                         surface_change& change) const {
    surface s = at(scene, hit);
    if (s.normal.x != 0 || s.normal.y != 0 || s.normal.z != 0) change.shading_normal = s.normal;
    if (!s.mapped && !s.replaced) return;
    whitted_material m = s.mapped ? std::move(*s.mapped) : *object_.surface;
    if (s.replaced) {
        change.glow = s.replaced_shading;
        m.diffuse = color(0, 0, 0);
        m.specular = color(0, 0, 0);
    }
    change.material = m.compiled();
    change.material.source = object_.surface.get(); // not the copy, which goes when this returns
}

} // namespace rt

#endif // RTWEEKEND_ENGINE_BODIES

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::course_surface_map;
#endif
