#pragma once
// compile_material: the renderer's table entry (the material contract, core/material_kinds.h) for a
// material of the teaching surface, after checking its parameters. The built-in materials are
// recognised by their exact class (classify.h's book_materials); any other material (a user's own
// subclass, or a subclass of a built-in one) becomes a user entry, rendered through its virtual
// functions. A lambertian or a diffuse_light
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
#include "../core/material_kinds.h"
#include "classify.h"
#include "texture_table.h"
#include "validate.h"

#include <cmath>
#include <string>

namespace rt {

compiled_material compile_material(const material& m, texture_table* textures = nullptr);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

inline void check_refraction_index(double ri, const char* what) {
    if (!(std::isfinite(ri) && ri > 0))
        throw scene_error(std::string(what) + " must be positive and finite, got " + number_text(ri));
}

inline void check_whitted_material(const whitted_material& w) {
    check_color(w.ambient, "ambient reflectance");
    check_color(w.diffuse, "diffuse reflectance");
    check_color(w.specular, "specular reflectance");
    check_color(w.mirror, "mirror reflectance");
    check_color(w.absorption_coefficient, "absorption coefficient");
    if (!(std::isfinite(w.phong_exponent) && w.phong_exponent >= 0))
        throw scene_error("Phong exponent must be finite and non-negative, got " + number_text(w.phong_exponent));
    check_refraction_index(w.refraction_index, "refraction index");
    if (!(std::isfinite(w.absorption_index) && w.absorption_index >= 0))
        throw scene_error("absorption index must be finite and non-negative, got " + number_text(w.absorption_index));
}

// A material the renderer calls through its virtual functions.
inline compiled_material user_entry(const material& m) { return compiled_material::of(user_bsdf{}, &m); }

// The books' materials, one rule each (classify.h's book_materials): the parameters checked, the
// entry the class's compiled() gives, and a texture compiled into the table when it is not a
// solid_color (without a table: a user entry, its value() asked per hit through scatter()).
inline compiled_material compile_book(const lambertian& l, texture_table* textures) {
    if (!l.tex()) throw scene_error("lambertian texture is null");
    if (!exact_solid_color(l.tex().get())) {
        if (!textures) return user_entry(l); // its value() per hit, through scatter()
        compiled_material c = l.compiled();
        c.texture = textures->add(*l.tex());
        return c;
    }
    check_color(l.albedo(), "lambertian albedo");
    return l.compiled();
}
inline compiled_material compile_book(const diffuse_light& d, texture_table* textures) {
    if (!d.tex()) throw scene_error("diffuse_light texture is null");
    if (!exact_solid_color(d.tex().get())) {
        if (!textures) return user_entry(d);
        compiled_material c = d.compiled();
        c.texture = textures->add(*d.tex());
        // The constant emission stands for the texture's mean: it makes emits() true and sets the
        // light's power for light selection (find_lights); the radiance itself is looked up where
        // the light is hit or sampled.
        const float mean = textures->average(c.texture);
        if (!std::isfinite(mean)) throw scene_error("diffuse_light texture's mean emission is too large for single precision");
        return c.with_colour(vec3f{mean, mean, mean});
    }
    check_color(d.emission(), "diffuse_light emission");
    return d.compiled();
}
inline compiled_material compile_book(const metal& mt, texture_table*) {
    check_color(mt.albedo(), "metal albedo");
    if (!(mt.fuzz() >= 0)) throw scene_error("metal fuzz must be non-negative, got " + number_text(mt.fuzz()));
    return mt.compiled();
}
inline compiled_material compile_book(const dielectric& g, texture_table*) {
    check_refraction_index(g.refraction_index(), "dielectric refraction index");
    if (g.exact_fresnel()) check_color(g.absorption(), "dielectric absorption");
    return g.compiled();
}
inline compiled_material compile_book(const conductor& c, texture_table*) {
    check_color(c.tint(), "conductor tint");
    check_color(c.n(), "conductor n");
    check_color(c.k(), "conductor k");
    if (!(c.n().x() > 0 && c.n().y() > 0 && c.n().z() > 0))
        throw scene_error("conductor n must be positive, got " + point_text(c.n()));
    return c.compiled();
}
// A textured one stays a user entry even with a table: a constant_medium reports it at its hits,
// and a user shape's material is compiled on the spot, without the table.
inline compiled_material compile_book(const isotropic& i, texture_table*) {
    if (!i.tex()) throw scene_error("isotropic texture is null");
    if (!exact_solid_color(i.tex().get())) return user_entry(i);
    check_color(i.albedo(), "isotropic albedo");
    return i.compiled();
}
inline compiled_material compile_book(const plastic& p, texture_table*) {
    check_color(p.diffuse(), "plastic diffuse colour");
    check_refraction_index(p.refraction_index(), "plastic refraction index");
    return p.compiled();
}
inline compiled_material compile_book(const blinn_phong& b, texture_table*) {
    check_color(b.diffuse(), "blinn_phong diffuse colour");
    check_color(b.specular(), "blinn_phong specular colour");
    if (!(std::isfinite(b.exponent()) && b.exponent() >= 0))
        throw scene_error("blinn_phong exponent must be finite and non-negative, got " + number_text(b.exponent()));
    return b.compiled();
}
inline void check_roughness(double r, const char* what) {
    if (!(r >= 0 && r <= 1)) throw scene_error(std::string(what) + " must be in [0, 1], got " + number_text(r));
}
inline compiled_material compile_book(const rough_conductor& c, texture_table*) {
    if (c.complex_index()) {
        check_color(c.n(), "rough_conductor n");
        check_color(c.k(), "rough_conductor k");
        if (!(c.n().x() > 0 && c.n().y() > 0 && c.n().z() > 0))
            throw scene_error("rough_conductor n must be positive, got " + point_text(c.n()));
    } else {
        check_color(c.albedo(), "rough_conductor albedo");
    }
    check_roughness(c.roughness_u(), "rough_conductor roughness");
    check_roughness(c.roughness_v(), "rough_conductor roughness");
    return c.compiled();
}
inline compiled_material compile_book(const rough_dielectric& g, texture_table*) {
    check_refraction_index(g.refraction_index(), "rough_dielectric refraction index");
    check_roughness(g.roughness_u(), "rough_dielectric roughness");
    check_roughness(g.roughness_v(), "rough_dielectric roughness");
    return g.compiled();
}
inline compiled_material compile_book(const metal_roughness& m, texture_table* textures) {
    if (!m.tex()) throw scene_error("metal_roughness texture is null");
    if (!(m.metallic() >= 0 && m.metallic() <= 1))
        throw scene_error("metal_roughness metallic must be in [0, 1], got " + number_text(m.metallic()));
    check_roughness(m.roughness(), "metal_roughness roughness");
    if (!exact_solid_color(m.tex().get())) {
        if (!textures) return user_entry(m); // its value() per hit, through scatter()
        compiled_material c = m.compiled();
        c.texture = textures->add(*m.tex());
        return c;
    }
    check_color(m.base_colour(), "metal_roughness base colour");
    return m.compiled();
}
inline compiled_material compile_book(const whitted_material& w, texture_table*) {
    check_whitted_material(w);
    return w.compiled();
}

} // namespace detail

inline compiled_material compile_material(const material& m, texture_table* textures) {
    return visit_book_class<book_materials>(
        m, [&](const auto& known) { return detail::compile_book(known, textures); },
        [](const material& other) { return detail::user_entry(other); });
}

} // namespace rt
