#pragma once
// blinn_phong_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): a Lambertian lobe plus a
// normalised Blinn-Phong glossy lobe (blinn_phong_lobe below), sampled by a mixture of the cosine
// and the half-vector densities. The books' blinn_phong and the CENG795 course's plain materials
// with a specular colour compile to it.

#include "../bsdf.h"
#include "../constants.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"

#include <cmath>

namespace rt {

// blinn_phong's glossy lobe, f_s(wo, wi) |cos_i| = ks * blinn_phong_lobe(...), after the specular
// term of Ashikhmin and Shirley ("An Anisotropic Phong BRDF Model", JGT 5(2), 2000, eq. 4, with
// n_u = n_v = n and their Fresnel term replaced by the constant ks):
//   f_s = ks (n + 1) / (8 pi) cos^n theta_h / ((wi.h) max(cos_i, cos_o)).
// The half vector h drawn with density p_h = (n + 1) / (2 pi) cos^n theta_h and reflected gives wi
// the density p_h / (4 wo.h) (Walter et al., EGSR 2007, eq. 14), so f_s cos_i = ks pdf(wi)
// cos_i / max(cos_i, cos_o) <= ks pdf(wi): the lobe reflects at most ks of what it receives, at
// every angle, for every n (not so for the (n + 8) / (8 pi) normalisation of Real-Time Rendering,
// 3rd ed., eq. 7.49, exact only at normal incidence). Symmetric in wo and wi: reciprocal.
float blinn_phong_lobe(const vec3f& wo, const vec3f& wi, const vec3f& n, float exponent);
// The density of wi when h is drawn from p_h and wo reflected about it.
float blinn_phong_lobe_pdf(const vec3f& wo, const vec3f& wi, const vec3f& n, float exponent);

struct blinn_phong_bsdf {
    static constexpr const char* name = "blinn_phong";
    vec3f albedo{0.5f, 0.5f, 0.5f}; // the diffuse reflectance
    vec3f specular{0, 0, 0};        // the glossy lobe's reflectance
    float exponent = 0;             // the Phong exponent

    // One-sample mixture of the cosine density and the half-vector density; the weight is eval
    // over the mixture's pdf.
    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        const vec3f& n = sp.n;
        if (!(lobes & non_delta_lobe)) return false;
        const float ps = glossy_probability();
        const float u0 = u.next_float();
        const auto [u1, u2] = draw_2d(u);
        if (u0 < ps) {
            // The half vector with density (n + 1) / (2 pi) cos^n theta_h, wo reflected about it.
            const vec3f h = sample_cosine_power(n, exponent, u1, u2);
            s.wi = normalize(2.0f * dot(wo, h) * h - wo);
        } else {
            s.wi = sample_cosine_direction(n, u1, u2);
        }
        if (!(dot(s.wi, n) > 0)) return false; // reflected below the surface: f is 0 there
        s.pdf = pdf(wo, s.wi, sp);
        if (!(s.pdf > 0)) return false;
        s.value = eval(wo, s.wi, sp) * (1.0f / s.pdf);
        s.sampled = non_delta_lobe;
        return true;
    }
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        const float cos_i = dot(wi, sp.n);
        if (!(cos_i > 0)) return {0, 0, 0};
        return albedo * (cos_i * (1.0f / pi_f)) + specular * blinn_phong_lobe(wo, wi, sp.n, exponent);
    }
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        const float cos_i = dot(wi, sp.n);
        if (!(cos_i > 0)) return 0;
        const float ps = glossy_probability();
        return (1.0f - ps) * cos_i * (1.0f / pi_f) + ps * blinn_phong_lobe_pdf(wo, wi, sp.n, exponent);
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_density = true;
        return p;
    }
    float lobe_weight() const { return max_component(albedo); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    // A texture colours the diffuse lobe (a CENG795 texture map's kd): kept within 1 - specular
    // per channel, so that the two lobes reflect at most what they receive.
    static constexpr bool takes_texture = true;
    void set_colour(const vec3f& c) {
        albedo = {std::fmin(c.x, std::fmax(0.0f, 1.0f - specular.x)), std::fmin(c.y, std::fmax(0.0f, 1.0f - specular.y)),
                  std::fmin(c.z, std::fmax(0.0f, 1.0f - specular.z))};
    }
    vec3f colour() const { return albedo; }

    // The probability sample() draws from the glossy lobe.
    float glossy_probability() const {
        const float s = max_component(specular), total = s + max_component(albedo);
        return total > 0 ? s / total : 0.0f;
    }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {
// The half vector between two unit directions on the normal's side, and its cosines.
struct half_vector {
    vec3f h;
    float cos_h = 0, wo_h = 0; // h.n and wo.h
    half_vector(const vec3f& wo, const vec3f& wi, const vec3f& n) : h(normalize(wo + wi)) {
        cos_h = fmax_inline(dot(h, n), 0.0f);
        wo_h = dot(wo, h);
    }
};

} // namespace detail

inline float blinn_phong_lobe(const vec3f& wo, const vec3f& wi, const vec3f& n, float exponent) {
    const float cos_i = dot(wi, n), cos_o = dot(wo, n);
    if (!(cos_i > 0 && cos_o > 0)) return 0;
    const detail::half_vector hv(wo, wi, n);
    if (!(hv.wo_h > 0)) return 0;
    const float d = (exponent + 1) * (1.0f / (8.0f * pi_f)) * std::pow(hv.cos_h, exponent);
    return d * cos_i / (hv.wo_h * fmax_inline(cos_i, cos_o));
}

inline float blinn_phong_lobe_pdf(const vec3f& wo, const vec3f& wi, const vec3f& n, float exponent) {
    if (!(dot(wi, n) > 0)) return 0;
    const detail::half_vector hv(wo, wi, n);
    if (!(hv.wo_h > 0)) return 0;
    return (exponent + 1) * (1.0f / (2.0f * pi_f)) * std::pow(hv.cos_h, exponent) / (4.0f * hv.wo_h);
}

} // namespace rt
