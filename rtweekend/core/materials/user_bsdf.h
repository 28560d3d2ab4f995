#pragma once
// user_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): a user's own material
// subclass. It has no contract of its own: the integrators call its virtual scatter() through
// compiled_material::source (render/user_material.h), which answers as a delta lobe or, for book
// 3's materials with a pdf, as a lobe with a density. Here every query says nothing.

#include "../bsdf.h"
#include "../vec3f.h"

namespace rt {

struct user_bsdf {
    static constexpr const char* name = "user material";

    template <class Uniform>
    bool sample(const vec3f&, const shading_point&, Uniform&, material_sample&, lobe) const {
        return false;
    }
    vec3f eval(const vec3f&, const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    float pdf(const vec3f&, const vec3f&, const shading_point&) const { return 0; }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.user = true;
        p.transmits = true; // it may let light through: never culled
        return p;
    }
    float lobe_weight() const { return 1; }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;
};

} // namespace rt
