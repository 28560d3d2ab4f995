#pragma once
// emitter_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): an emitter, the books'
// diffuse_light. Radiance `emission` towards every direction on its front side (both sides when
// two_sided, as book 2's light is); it scatters nothing: a path that reaches it ends there.

#include "../bsdf.h"
#include "../vec3f.h"

namespace rt {

struct emitter_bsdf {
    static constexpr const char* name = "diffuse light";
    vec3f radiance{0, 0, 0};
    bool two_sided = false;

    // Absorbs what reaches it.
    template <class Uniform>
    bool sample(const vec3f&, const shading_point&, Uniform&, material_sample&, lobe) const {
        return false;
    }
    vec3f eval(const vec3f&, const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    float pdf(const vec3f&, const vec3f&, const shading_point&) const { return 0; }
    vec3f emitted(const vec3f& /*wo*/, const shading_point& sp) const {
        return sp.front_face || two_sided ? radiance : vec3f{0, 0, 0};
    }
    vec3f emission() const { return radiance; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.emits = radiance.x > 0 || radiance.y > 0 || radiance.z > 0;
        p.two_sided = two_sided;
        p.scatters = false;
        return p;
    }
    float lobe_weight() const { return 0; }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    // A texture gives the radiance at each point (book 2).
    static constexpr bool takes_texture = true;
    void set_colour(const vec3f& c) { radiance = c; }
    vec3f colour() const { return radiance; }
};

} // namespace rt
