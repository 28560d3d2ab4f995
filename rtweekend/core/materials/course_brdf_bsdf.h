#pragma once
// course_brdf_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): the BRDFs of the CENG795
// course's homework 6 (a <Material BRDF="k"> naming an entry of <BRDFs>), as the course defines
// them and its reference images confirm (docs/course.md, "BRDFs"). With theta_i the angle of wi to
// n, alpha_r the angle between wi's mirror image about n and wo, alpha_h the angle between n and
// h = normalize(wi + wo), p the exponent:
//
//   original Phong             kd + ks cos^p(alpha_r) / cos theta_i
//   modified Phong             kd + ks cos^p(alpha_r)
//     normalised               kd / pi + ks (p + 2) / (2 pi) cos^p(alpha_r)
//   original Blinn-Phong       kd + ks cos^p(alpha_h) / cos theta_i      (the course's level-1 model)
//   modified Blinn-Phong       kd + ks cos^p(alpha_h)
//     normalised               kd / pi + ks (p + 8) / (8 pi) cos^p(alpha_h)
//   Torrance-Sparrow           kd / pi + ks D F G / (4 cos theta_i cos theta_o), and with
//                              kdfresnel the first term (1 - F) kd / pi;
//                              D = (p + 2) / (2 pi) cos^p(alpha_h),
//                              G = min(1, 2 (n.h)(n.wo) / (wo.h), 2 (n.h)(n.wi) / (wo.h)),
//                              F the exact conductor Fresnel of (eta, k) at cos theta_i
//
// and 0 wherever cos theta_i <= 0. Units: the course's. Its level-1 materials take kd as the
// Lambertian albedo (a BRDF of kd / pi, with light intensities pi times radiometric ones:
// whitted_material.h), and the same conversion holds here for every model: eval() is
// f cos theta_i / pi, course_value() the course's own f cos theta_i (what its renderers multiply
// by a light's irradiance). The non-normalised models are not energy conserving; the course
// path-traces with the normalised ones.
//
// Sampling: a mixture of the cosine density and the lobe's: the Phong cosine lobe about wo's mirror
// direction, (p + 1) / (2 pi) cos^p(alpha_r), for the Phong models; the half-vector density
// (p + 1) / (2 pi) cos^p(alpha_h) reflected (blinn_phong_bsdf.h) for the others. A direction drawn
// below the surface is absorbed (f is 0 there), which keeps the estimate unbiased.

#include "../bsdf.h"
#include "../constants.h"
#include "../fresnel.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"
#include "blinn_phong_bsdf.h"

#include <cmath>

namespace rt {

struct course_brdf_bsdf {
    static constexpr const char* name = "course_brdf";
    enum class model_t { original_phong, modified_phong, original_blinn_phong, modified_blinn_phong, torrance_sparrow };
    model_t model = model_t::modified_blinn_phong;
    bool normalized = false; // the modified models: the normalised form
    bool kd_fresnel = false; // Torrance-Sparrow: the diffuse term times (1 - F)
    vec3f kd{0, 0, 0}, ks{0, 0, 0};
    float exponent = 1;
    float eta = 1, k = 0; // Torrance-Sparrow's Fresnel: refraction and absorption index

    bool phong_lobe() const { return model == model_t::original_phong || model == model_t::modified_phong; }
    // Whether the specular term can be non-zero. Without it the lobe's power is not taken: it
    // would be multiplied by ks = 0 (the walls of a path-traced room spent 4 % of their time so).
    bool glossy() const { return !detail::is_black(ks); } // ks is checked non-negative

    // The course's f(wo, wi) cos theta_i.
    vec3f course_value(const vec3f& wo, const vec3f& wi, const vec3f& n) const {
        const float cos_i = dot(wi, n);
        if (!(cos_i > 0)) return {0, 0, 0};
        const float p = exponent;
        switch (model) {
        case model_t::original_phong:
        case model_t::modified_phong: {
            const float cos_r = fmax_inline(0.0f, dot(2.0f * cos_i * n - wi, wo));
            const float lobe = glossy() ? std::pow(cos_r, p) : 0.0f;
            if (model == model_t::original_phong) return kd * cos_i + ks * lobe;
            if (!normalized) return (kd + ks * lobe) * cos_i;
            return (kd * (1.0f / pi_f) + ks * ((p + 2) * (1.0f / (2 * pi_f)) * lobe)) * cos_i;
        }
        case model_t::original_blinn_phong:
        case model_t::modified_blinn_phong: {
            const float cos_h = fmax_inline(0.0f, dot(n, normalize(wi + wo)));
            const float lobe = glossy() ? std::pow(cos_h, p) : 0.0f;
            if (model == model_t::original_blinn_phong) return kd * cos_i + ks * lobe;
            if (!normalized) return (kd + ks * lobe) * cos_i;
            return (kd * (1.0f / pi_f) + ks * ((p + 8) * (1.0f / (8 * pi_f)) * lobe)) * cos_i;
        }
        case model_t::torrance_sparrow: {
            const float cos_o = dot(wo, n);
            const float F = fresnel_conductor_f(cos_i, eta, k);
            const vec3f diffuse = kd * ((kd_fresnel ? 1 - F : 1.0f) * (1.0f / pi_f) * cos_i);
            if (!(cos_o > 0)) return diffuse;
            const vec3f h = normalize(wi + wo);
            const float n_h = fmax_inline(0.0f, dot(n, h)), wo_h = dot(wo, h);
            if (!(wo_h > 0)) return diffuse;
            const float D = (p + 2) * (1.0f / (2 * pi_f)) * std::pow(n_h, p);
            const float G = fmin_inline(1.0f, fmin_inline(2 * n_h * cos_o / wo_h, 2 * n_h * cos_i / wo_h));
            return diffuse + ks * (D * F * G / (4 * cos_o)); // the cos theta_i of f cos theta_i cancels
        }
        }
        return {0, 0, 0};
    }

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        const vec3f& n = sp.n;
        if (!(lobes & non_delta_lobe)) return false;
        const float ps = lobe_probability();
        const float u0 = u.next_float();
        const auto [u1, u2] = draw_2d(u);
        if (u0 < ps) {
            // The Phong lobe about wo's mirror direction, or the half vector about n.
            if (phong_lobe()) {
                s.wi = normalize(sample_cosine_power(reflect_f(-wo, n), exponent, u1, u2));
            } else {
                const vec3f h = sample_cosine_power(n, exponent, u1, u2);
                s.wi = normalize(2.0f * dot(wo, h) * h - wo);
            }
        } else {
            s.wi = sample_cosine_direction(n, u1, u2);
        }
        if (!(dot(s.wi, n) > 0)) return false; // below the surface: f is 0 there
        s.pdf = pdf(wo, s.wi, sp);
        if (!(s.pdf > 0)) return false;
        s.value = eval(wo, s.wi, sp) * (1.0f / s.pdf);
        s.sampled = non_delta_lobe;
        return true;
    }
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        return course_value(wo, wi, sp.n) * (1.0f / pi_f);
    }
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        const float cos_i = dot(wi, sp.n);
        if (!(cos_i > 0)) return 0;
        const float ps = lobe_probability();
        float lobe_pdf;
        if (phong_lobe()) {
            const float cos_r = fmax_inline(0.0f, dot(reflect_f(-wo, sp.n), wi));
            lobe_pdf = (exponent + 1) * (1.0f / (2 * pi_f)) * std::pow(cos_r, exponent);
        } else {
            lobe_pdf = blinn_phong_lobe_pdf(wo, wi, sp.n, exponent);
        }
        return (1.0f - ps) * cos_i * (1.0f / pi_f) + ps * lobe_pdf;
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_density = true;
        return p;
    }
    float lobe_weight() const { return max_component(kd) + max_component(ks); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;

    // The probability sample() draws from the specular lobe: its share of the largest reflectances.
    float lobe_probability() const {
        const float s = max_component(ks), total = s + max_component(kd);
        return total > 0 ? s / total : 0.0f;
    }
};

} // namespace rt
