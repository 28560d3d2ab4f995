#pragma once
// plastic_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): a Lambertian base under a
// smooth dielectric coat. The coat's mirror reflection (a delta lobe of weight F(cos_o)) and the
// base coupled to it (plastic_base_factor below); energy-conserving, reciprocal.

#include "../bsdf.h"
#include "../constants.h"
#include "../fresnel.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"

namespace rt {

// The cosine-weighted hemispherical average of the Fresnel reflectance of a smooth dielectric
// interface of index ratio eta (n_transmitted / n_incident), 2 int_0^1 F(mu) mu dmu: the fraction
// of uniformly diffuse light the interface reflects. Computed in double by the midpoint rule over
// mu (4096 points; 2 mu F(mu) is smooth but for a square-root kink at the critical angle when
// eta < 1: error below 1e-6).
double fresnel_average(double eta);

// plastic's base: f_base(wo, wi) = albedo / pi * plastic_base_factor, with
//   plastic_base_factor = (1 - F(cos_i)) (1 - F(cos_o)) / (1 - F_avg),
// the coupling of Kelemen and Szirmay-Kalos ("A Microfacet Based Coupled Specular-Matte BRDF
// Model with Importance Sampling", Eurographics 2001 short papers) with a smooth coat, whose
// directional albedo is F itself. Light entering at wo reaches the base with weight 1 - F(cos_o);
// the base's exit is weighted by 1 - F(cos_i) and normalised by 1 - F_avg, the integral of
// (1 - F(cos_i)) cos_i / pi over the hemisphere, so the base reflects albedo (1 - F(cos_o)) in all:
// with the coat's F(cos_o), a plastic reflects F + albedo (1 - F) of what it receives. A white
// plastic (albedo 1) reflects all of it, as a lossless coat over a white base would after all its
// inner bounces; a coloured one absorbs (1 - albedo)(1 - F). Symmetric in wo and wi: reciprocal.
float plastic_base_factor(float cos_i, float cos_o, float eta, float coat_average);

struct plastic_bsdf {
    static constexpr const char* name = "plastic";
    vec3f albedo{0.5f, 0.5f, 0.5f}; // the base's diffuse reflectance
    float refraction_index = 1.5f;  // the coat's
    float coat_average = 0;         // the coat's mean Fresnel reflectance (fresnel_average)

    // The coat's mirror reflection with probability q (delta), else the base, cosine-weighted.
    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        const vec3f d = -wo;
        const vec3f& n = sp.n;
        const float cos_o = fmin_inline(fmax_inline(dot(wo, n), 0.0f), 1.0f);
        const bool want_coat = (lobes & delta_reflection) != 0, want_base = (lobes & non_delta_lobe) != 0;
        if (!want_coat && !want_base) return false;
        const float q = !want_base ? 1.0f : !want_coat ? 0.0f : coat_probability(cos_o);
        if (q > 0 && (q >= 1 || u.next_float() < q)) {
            const float f = fresnel_dielectric_f(cos_o, refraction_index);
            s.wi = reflect_f(d, n);
            s.value = vec3f{f, f, f} * (1.0f / q);
            s.pdf = q;
            s.sampled = delta_reflection;
            return f > 0;
        }
        const auto [u1, u2] = draw_2d(u);
        s.wi = sample_cosine_direction(n, u1, u2);
        const float cos_i = dot(s.wi, n);
        if (!(cos_i > 0)) return false;
        s.value = albedo * (plastic_base_factor(cos_i, cos_o, refraction_index, coat_average) / (1.0f - q));
        s.pdf = (1.0f - q) * cos_i * (1.0f / pi_f);
        s.sampled = non_delta_lobe;
        return true;
    }
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        const float cos_i = dot(wi, sp.n);
        if (!(cos_i > 0)) return {0, 0, 0};
        const float cos_o = fmin_inline(fmax_inline(dot(wo, sp.n), 0.0f), 1.0f);
        return albedo * (plastic_base_factor(cos_i, cos_o, refraction_index, coat_average) * cos_i * (1.0f / pi_f));
    }
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        const float cos_i = dot(wi, sp.n);
        if (!(cos_i > 0)) return 0;
        const float cos_o = fmin_inline(fmax_inline(dot(wo, sp.n), 0.0f), 1.0f);
        return (1.0f - coat_probability(cos_o)) * cos_i * (1.0f / pi_f); // the coat is a delta lobe
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_delta_lobe = true;
        p.has_density = true;
        return p;
    }
    float lobe_weight() const { return max_component(albedo); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;

    // The probability sample() picks the coat's mirror reflection, for cos_o = wo.n: in proportion
    // to what each lobe returns, F for the coat, albedo (1 - F) for the base.
    float coat_probability(float cos_o) const {
        const float f = fresnel_dielectric_f(cos_o, refraction_index);
        const float total = f + (1.0f - f) * max_component(albedo);
        return total > 0 ? f / total : 1.0f;
    }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline double fresnel_average(double eta) {
    const int n = 4096;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;
        sum += 2 * mu * fresnel_dielectric(mu, eta);
    }
    return sum / n;
}

inline float plastic_base_factor(float cos_i, float cos_o, float eta, float coat_average) {
    const float ti = 1.0f - fresnel_dielectric_f(cos_i, eta), to = 1.0f - fresnel_dielectric_f(cos_o, eta);
    return ti * to / (1.0f - coat_average);
}

} // namespace rt
