#pragma once
// compile_material: the renderer's table entry (the material contract, bsdf.h) for a material of
// the teaching surface, after checking its parameters. The built-in materials are recognised by
// their exact type; any other material (a user's own subclass, or a subclass of a built-in one)
// becomes a user entry, rendered through its virtual functions. A lambertian or a diffuse_light
// whose texture is not a solid_color is compiled with its texture into `textures` (its entry's
// texture index; texture_table.h) when a table is given, and is a user entry otherwise (the
// material a user's hittable reports at a hit, compiled on the spot without the scene's table).
//
// Throws scene_error for a parameter the renderer cannot use: a negative or non-finite colour,
// a NaN or negative fuzz, a null texture, a refraction index that is not positive and finite, a
// conductor's n that is not positive, a negative or non-finite Phong exponent or absorption index.

#include "../material.h"
#include "../core/scene_error.h"
#include "../texture.h"
#include "../whitted_material.h"
#include "../core/bsdf.h"
#include "texture_table.h"
#include "validate.h"

#include <cmath>
#include <string>
#include <typeinfo>

namespace rt {

compiled_material compile_material(const material& m, texture_table* textures = nullptr);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

inline void check_refraction_index(double ri, const char* what) {
    if (!(std::isfinite(ri) && ri > 0))
        throw scene_error(std::string(what) + " must be positive and finite, got " + std::to_string(ri));
}

inline void check_whitted_material(const whitted_material& w) {
    check_color(w.ambient, "ambient reflectance");
    check_color(w.diffuse, "diffuse reflectance");
    check_color(w.specular, "specular reflectance");
    check_color(w.mirror, "mirror reflectance");
    check_color(w.absorption_coefficient, "absorption coefficient");
    if (!(std::isfinite(w.phong_exponent) && w.phong_exponent >= 0))
        throw scene_error("Phong exponent must be finite and non-negative, got " + std::to_string(w.phong_exponent));
    check_refraction_index(w.refraction_index, "refraction index");
    if (!(std::isfinite(w.absorption_index) && w.absorption_index >= 0))
        throw scene_error("absorption index must be finite and non-negative, got " + std::to_string(w.absorption_index));
}

// A material the renderer calls through its virtual functions.
inline compiled_material user_entry(const material& m) {
    compiled_material user;
    user.kind = material_kind::user;
    user.source = &m;
    return user;
}

} // namespace detail

inline compiled_material compile_material(const material& m, texture_table* textures) {
    const std::type_info& type = typeid(m);
    if (type == typeid(lambertian)) {
        auto& l = static_cast<const lambertian&>(m);
        if (!l.tex()) throw scene_error("lambertian texture is null");
        if (!exact_solid_color(l.tex().get())) {
            if (!textures) return detail::user_entry(m); // its value() per hit, through scatter()
            compiled_material c = l.compiled();
            c.texture = textures->add(*l.tex());
            return c;
        }
        check_color(l.albedo(), "lambertian albedo");
        return l.compiled();
    }
    if (type == typeid(diffuse_light)) {
        auto& d = static_cast<const diffuse_light&>(m);
        if (!d.tex()) throw scene_error("diffuse_light texture is null");
        if (!exact_solid_color(d.tex().get())) {
            if (!textures) return detail::user_entry(m);
            compiled_material c = d.compiled();
            c.texture = textures->add(*d.tex());
            // The constant emission stands for the texture's mean: it makes emits() true and sets
            // the light's power for light selection (find_lights); the radiance itself is looked
            // up where the light is hit or sampled.
            const float mean = textures->average(c.texture);
            c.emission = vec3f{mean, mean, mean};
            return c;
        }
        check_color(d.emission(), "diffuse_light emission");
        return d.compiled();
    }
    if (type == typeid(metal)) {
        auto& mt = static_cast<const metal&>(m);
        check_color(mt.albedo(), "metal albedo");
        if (!(mt.fuzz() >= 0)) throw scene_error("metal fuzz must be non-negative, got " + std::to_string(mt.fuzz()));
        return mt.compiled();
    }
    if (type == typeid(dielectric)) {
        auto& g = static_cast<const dielectric&>(m);
        detail::check_refraction_index(g.refraction_index(), "dielectric refraction index");
        if (g.exact_fresnel()) check_color(g.absorption(), "dielectric absorption");
        return g.compiled();
    }
    if (type == typeid(conductor)) {
        auto& c = static_cast<const conductor&>(m);
        check_color(c.tint(), "conductor tint");
        check_color(c.n(), "conductor n");
        check_color(c.k(), "conductor k");
        if (!(c.n().x() > 0 && c.n().y() > 0 && c.n().z() > 0))
            throw scene_error("conductor n must be positive, got " + point_text(c.n()));
        return c.compiled();
    }
    if (type == typeid(isotropic)) {
        // A textured one stays a user entry even with a table: a constant_medium reports it at
        // its hits, and a user shape's material is compiled on the spot, without the table.
        auto& i = static_cast<const isotropic&>(m);
        if (!i.tex()) throw scene_error("isotropic texture is null");
        if (!exact_solid_color(i.tex().get())) return detail::user_entry(m);
        check_color(i.albedo(), "isotropic albedo");
        return i.compiled();
    }
    if (type == typeid(plastic)) {
        auto& p = static_cast<const plastic&>(m);
        check_color(p.diffuse(), "plastic diffuse colour");
        detail::check_refraction_index(p.refraction_index(), "plastic refraction index");
        return p.compiled();
    }
    if (type == typeid(blinn_phong)) {
        auto& b = static_cast<const blinn_phong&>(m);
        check_color(b.diffuse(), "blinn_phong diffuse colour");
        check_color(b.specular(), "blinn_phong specular colour");
        if (!(std::isfinite(b.exponent()) && b.exponent() >= 0))
            throw scene_error("blinn_phong exponent must be finite and non-negative, got " + std::to_string(b.exponent()));
        return b.compiled();
    }
    if (type == typeid(whitted_material)) {
        auto& w = static_cast<const whitted_material&>(m);
        detail::check_whitted_material(w);
        return w.compiled();
    }
    return detail::user_entry(m);
}

} // namespace rt
