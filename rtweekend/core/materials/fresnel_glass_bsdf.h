#pragma once
// fresnel_glass_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): glass with the exact
// Fresnel reflectance (core/fresnel.h) and Beer's law inside: light that travels a distance d
// inside keeps exp(-absorption d) of itself, per channel. The books' dielectric with an absorption
// compiles to it.

#include "../bsdf.h"
#include "../fresnel.h"
#include "../vec3f.h"
#include "dielectric_bsdf.h"

namespace rt {

struct fresnel_glass_bsdf {
    static constexpr const char* name = "fresnel glass";
    float refraction_index = 1;  // inside over outside
    vec3f absorption{0, 0, 0};   // per unit length inside

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        return detail::sample_glass<false>(refraction_index, wo, sp, u, s, lobes);
    }
    vec3f eval(const vec3f&, const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    float pdf(const vec3f&, const vec3f&, const shading_point&) const { return 0; }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    bool absorbs() const { return absorption.x > 0 || absorption.y > 0 || absorption.z > 0; }
    vec3f transmittance(float distance) const {
        if (!absorbs()) return {1, 1, 1};
        return beer_transmittance(absorption, distance);
    }
    material_properties properties() const {
        material_properties p = detail::glass_properties();
        p.absorbs_inside = absorbs();
        return p;
    }
    float lobe_weight() const { return 1; }
    // The exact Fresnel reflectance is the same on both sides of a refraction: a light path draws
    // what the path tracer would.
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;
};

} // namespace rt
