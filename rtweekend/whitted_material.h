#pragma once
// whitted_material: a material of the CENG795 / CENG477 course scenes (io/xml_scene.h reads them):
// Blinn-Phong shading (ambient, diffuse and specular reflectance with a Phong exponent) plus, by
// kind, a perfect mirror, a conductor (exact Fresnel from n and k, tinted by `mirror`) or a
// dielectric (exact Fresnel, refraction, Beer's law absorption inside).
//
//   auto red = make_shared<whitted_material>();
//   red->diffuse = color(0.8, 0.1, 0.1);
//   red->specular = color(1, 1, 1);
//   red->phong_exponent = 50;
//
// In the renderer's material contract (core/bsdf.h) it is a Lambertian base of albedo `diffuse`
// under its mirror, conductor or dielectric lobe. The Whitted integrator (course/whitted.h) adds
// the course's ambient and Blinn-Phong specular terms, which describe point-light shading rather
// than a BSDF. For the path tracer a plain material with a specular reflectance is a blinn_phong
// surface (material.h: diffuse plus a normalised glossy lobe of that reflectance and exponent, both
// scaled down where their sum exceeds 1); mirrors, conductors and dielectrics ignore `specular`.
//
// Colours here are in the course's units: 0..255 per channel on output, no gamma.

#include "color.h"
#include "core/material_kinds.h"
#include "core/vec3f.h"
#include "material.h"

#include <optional>

namespace rt {

class whitted_material : public material {
  public:
    enum class kind_t { plain, mirror, conductor, dielectric };
    kind_t kind = kind_t::plain;
    color ambient{0, 0, 0};   // ka: multiplies the ambient light
    color diffuse{0, 0, 0};   // kd
    color specular{0, 0, 0};  // ks
    double phong_exponent = 1;
    color mirror{0, 0, 0};    // MirrorReflectance: mirror and conductor
    double refraction_index = 1;  // conductor and dielectric
    double absorption_index = 0;  // k: conductor
    color absorption_coefficient{0, 0, 0}; // c per unit length: dielectric (Beer's law)
    // Roughness (homework 3): the Whitted integrator tilts each mirror, conductor or dielectric ray
    // d to normalize(d + roughness (xi1 u + xi2 v)), xi uniform in [-1/2, 1/2) and u, v unit and
    // perpendicular to d (course/whitted.h). 0: the ideal ray. The path tracer ignores it.
    double roughness = 0;
    // Radiance it emits (homework 6's LightMesh and LightSphere): the Whitted integrator adds it to
    // what the surface reflects, so that rays that hit a light see it. The path tracer ignores it.
    color radiance{0, 0, 0};
    // BRDF (homework 6): the model of a <Material BRDF="k"> (core/materials/course_brdf_bsdf.h; its
    // colours and indices are taken from this material by course_brdf()). It replaces the course's
    // Blinn-Phong shading (diffuse and specular) in every renderer; the ambient term stays. On a
    // mirror, conductor or dielectric the Whitted integrator shades with it and follows the delta
    // lobe as before; the path tracers keep a Lambertian base there.
    std::optional<course_brdf_bsdf> brdf;

    // The BRDF's record with this material's kd, ks, refraction and absorption index.
    course_brdf_bsdf course_brdf() const {
        course_brdf_bsdf b = brdf.value_or(course_brdf_bsdf{});
        b.kd = vec3f(diffuse);
        b.ks = vec3f(specular);
        b.eta = static_cast<float>(refraction_index);
        b.k = static_cast<float>(absorption_index);
        return b;
    }

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    // The kind the renderer treats it as: CENG477's files give materials no type, and a material
    // with a MirrorReflectance is a mirror there.
    kind_t effective_kind() const {
        if (kind == kind_t::plain && (mirror.x() > 0 || mirror.y() > 0 || mirror.z() > 0)) return kind_t::mirror;
        return kind;
    }

    // The material as the renderer's contract sees it (unchecked: material_compiler.h checks).
    // glossy = false leaves out the blinn_phong lobe of a plain material (the Whitted integrator,
    // which shades specular highlights by the course's own formula, asks for that).
    compiled_material compiled(bool glossy = true) const {
        const float n = static_cast<float>(refraction_index), k = static_cast<float>(absorption_index);
        compiled_material m;
        switch (effective_kind()) {
        case kind_t::plain:
            if (brdf) return compiled_material::of(course_brdf(), this);
            if (glossy && (specular.x() > 0 || specular.y() > 0 || specular.z() > 0))
                return blinn_phong::contract(diffuse, specular, phong_exponent, this);
            return compiled_material::of(lambertian_bsdf{vec3f(diffuse)}, this);
        case kind_t::mirror: // a perfect mirror
            m = compiled_material::of(metal_bsdf{vec3f(mirror), 0}, this);
            break;
        case kind_t::conductor:
            m = compiled_material::of(conductor_bsdf{vec3f(mirror), {n, n, n}, {k, k, k}}, this);
            break;
        case kind_t::dielectric:
            m = compiled_material::of(fresnel_glass_bsdf{n, vec3f(absorption_coefficient)}, this);
            break;
        }
        m.set_diffuse_base(vec3f(diffuse));
        return m;
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::whitted_material;
#endif
