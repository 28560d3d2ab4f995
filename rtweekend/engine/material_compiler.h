#pragma once
// compile_material: the renderer's table entry (bsdf.h) for a material of the teaching surface,
// after checking its parameters. The built-in materials are recognised by their exact type; any
// other material (a user's own subclass, or a subclass of a built-in one) becomes a user entry,
// rendered through its virtual scatter().
//
// Throws scene_error for a parameter the renderer cannot use: a negative or non-finite colour,
// a NaN or negative fuzz, a refraction index that is not positive and finite, a conductor's n
// that is not positive.

#include "../material.h"
#include "../scene_error.h"
#include "bsdf.h"
#include "validate.h"
#include "vec3f.h"

#include <cmath>
#include <string>
#include <typeinfo>

namespace rt {

material_desc compile_material(const material& m);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline material_desc compile_material(const material& m) {
    material_desc d;
    const std::type_info& type = typeid(m);
    if (type == typeid(lambertian)) {
        auto& l = static_cast<const lambertian&>(m);
        check_color(l.albedo(), "lambertian albedo");
        d.kind = material_kind::lambertian;
        d.albedo = vec3f(l.albedo());
    } else if (type == typeid(metal)) {
        auto& mt = static_cast<const metal&>(m);
        check_color(mt.albedo(), "metal albedo");
        if (!(mt.fuzz() >= 0)) throw scene_error("metal fuzz must be non-negative, got " + std::to_string(mt.fuzz()));
        d.kind = material_kind::metal;
        d.albedo = vec3f(mt.albedo());
        d.fuzz = static_cast<float>(mt.fuzz());
    } else if (type == typeid(dielectric)) {
        auto& g = static_cast<const dielectric&>(m);
        double ri = g.refraction_index();
        if (!(std::isfinite(ri) && ri > 0))
            throw scene_error("dielectric refraction index must be positive and finite, got " + std::to_string(ri));
        d.kind = material_kind::dielectric;
        d.albedo = {1, 1, 1};
        d.refraction_index = static_cast<float>(ri);
        if (g.exact_fresnel()) {
            check_color(g.absorption(), "dielectric absorption");
            d.kind = material_kind::exact_dielectric;
            d.absorption = vec3f(g.absorption());
        }
    } else if (type == typeid(conductor)) {
        auto& c = static_cast<const conductor&>(m);
        check_color(c.tint(), "conductor tint");
        check_color(c.n(), "conductor n");
        check_color(c.k(), "conductor k");
        if (!(c.n().x() > 0 && c.n().y() > 0 && c.n().z() > 0))
            throw scene_error("conductor n must be positive, got " + point_text(c.n()));
        d.kind = material_kind::conductor;
        d.albedo = vec3f(c.tint());
        d.eta = vec3f(c.n());
        d.k = vec3f(c.k());
    } else {
        d.kind = material_kind::custom;
        d.custom = &m;
    }
    return d;
}

} // namespace rt
