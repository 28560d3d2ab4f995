#pragma once
// lambertian_bsdf: a material kind (core/bsdf.h says what a kind answers; core/material_kinds.h
// lists them): ideal diffuse reflection, the books' lambertian. Cosine-weighted: value = albedo,
// pdf = cos / pi.

#include "../bsdf.h"
#include "../constants.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"

namespace rt {

struct lambertian_bsdf {
    static constexpr const char* name = "lambertian";
    vec3f albedo{0.5f, 0.5f, 0.5f};

    template <class Uniform>
    bool sample(const vec3f& /*wo*/, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        if (!(lobes & non_delta_lobe)) return false;
        const auto [u1, u2] = draw_2d(u);
        s.wi = sample_cosine_direction(sp.n, u1, u2);
        s.value = albedo;
        s.pdf = fmax_inline(dot(s.wi, sp.n), 0.0f) * (1.0f / pi_f);
        s.sampled = non_delta_lobe;
        return true;
    }
    vec3f eval(const vec3f& /*wo*/, const vec3f& wi, const shading_point& sp) const {
        const float cos_i = dot(wi, sp.n);
        if (!(cos_i > 0)) return {0, 0, 0};
        return albedo * (cos_i * (1.0f / pi_f));
    }
    float pdf(const vec3f& /*wo*/, const vec3f& wi, const shading_point& sp) const {
        const float cos_i = dot(wi, sp.n);
        return cos_i > 0 ? cos_i * (1.0f / pi_f) : 0.0f;
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_density = true;
        p.lambertian_only = true;
        return p;
    }
    float lobe_weight() const { return max_component(albedo); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    // A texture gives the albedo at each hit (book 2).
    static constexpr bool takes_texture = true;
    void set_colour(const vec3f& c) { albedo = c; }
    vec3f colour() const { return albedo; }
};

} // namespace rt
