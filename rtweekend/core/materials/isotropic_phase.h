#pragma once
// isotropic_phase: a material kind (core/bsdf.h; core/material_kinds.h): book 2's phase function
// of a constant_medium, uniform over the sphere of directions. eval = albedo / (4 pi) with no
// cosine: a phase function p(wo, wi) takes the place of f |cos theta_i|, since radiance scattered
// in a volume has no surface to be foreshortened by (pbrt, 4th ed., 11.3); pdf = 1 / (4 pi).

#include "../bsdf.h"
#include "../constants.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"

namespace rt {

struct isotropic_phase {
    static constexpr const char* name = "isotropic";
    vec3f albedo{0.5f, 0.5f, 0.5f};

    template <class Uniform>
    bool sample(const vec3f&, const shading_point&, Uniform& u, material_sample& s, lobe lobes) const {
        if (!(lobes & non_delta_lobe)) return false;
        const auto [u1, u2] = draw_2d(u);
        s.wi = sample_unit_sphere(u1, u2);
        s.value = albedo;
        s.pdf = 1.0f / (4.0f * pi_f);
        s.sampled = non_delta_lobe;
        return true;
    }
    vec3f eval(const vec3f&, const vec3f&, const shading_point&) const { return albedo * (1.0f / (4.0f * pi_f)); }
    float pdf(const vec3f&, const vec3f&, const shading_point&) const { return 1.0f / (4.0f * pi_f); }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_density = true;
        p.phase_function = true;
        p.transmits = true;
        return p;
    }
    float lobe_weight() const { return max_component(albedo); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    // A texture gives the albedo at each point (book 2; the book's scatter() looks it up).
    static constexpr bool takes_texture = true;
    void set_colour(const vec3f& c) { albedo = c; }
    vec3f colour() const { return albedo; }
};

} // namespace rt
