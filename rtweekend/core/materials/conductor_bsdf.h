#pragma once
// conductor_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): a smooth metal of complex
// index eta + ik per channel, a mirror weighted by tint * Fr(cos) (the exact Fresnel reflectance,
// core/fresnel.h).

#include "../bsdf.h"
#include "../fresnel.h"
#include "../vec3f.h"

namespace rt {

struct conductor_bsdf {
    static constexpr const char* name = "conductor";
    vec3f tint{1, 1, 1};
    vec3f eta{1, 1, 1}, k{0, 0, 0};

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform&, material_sample& s, lobe lobes) const {
        if (!(lobes & delta_reflection)) return false;
        const vec3f d = -wo;
        s.wi = normalize(reflect_f(d, sp.n));
        s.value = tint * fresnel_conductor_f(-dot(d, sp.n), eta, k);
        s.pdf = 1;
        s.sampled = delta_reflection;
        return true;
    }
    vec3f eval(const vec3f&, const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    float pdf(const vec3f&, const vec3f&, const shading_point&) const { return 0; }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_delta_lobe = true;
        return p;
    }
    float lobe_weight() const { return max_component(tint); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;
};

} // namespace rt
