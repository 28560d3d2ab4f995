#pragma once
// rough_dielectric_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): rough glass, the
// GGX microfacet dielectric of Walter, Marschner, Li and Torrance ("Microfacet Models for
// Refraction through Rough Surfaces", EGSR 2007) with Smith's height-correlated masking-shadowing
// (core/microfacet.h) and the exact Fresnel reflectance at the microfacet. It reflects and
// refracts: a visible normal m is drawn (Heitz 2018), then reflection with probability F(wo.m),
// refraction otherwise. With eta = n on wi's side / n on wo's side:
//   reflection:   f = F D(h) G2 / (4 |cos_o| |cos_i|),            h = normalize(wo + wi)
//   refraction:   f = (1 - F) D(h) G2 |wi.h| |wo.h| / (|cos_o| |cos_i| (wi.h + wo.h / eta)^2),
//                 h = normalize(wo + eta wi)            (Walter et al., eqs. 16 and 21)
// The refracted radiance is not scaled by 1 / eta^2, as the books' glass does not scale it
// (dielectric_bsdf: weight 1 either way): so the smooth limit is our glass, and light tracing and
// path tracing agree. Single scattering only: a rough glass loses some light at high roughness
// (about 10 % at normal incidence at roughness 1 for index 1.5: tests/test_microfacet.cpp).
// Below alpha 1e-3 on both axes it is smooth, delta lobes, exactly as fresnel_glass_bsdf
// without absorption.

#include "../bsdf.h"
#include "../fresnel.h"
#include "../microfacet.h"
#include "../rng.h"
#include "../vec3f.h"
#include "dielectric_bsdf.h"

#include <cmath>

namespace rt {

struct rough_dielectric_bsdf {
    static constexpr const char* name = "rough_dielectric";
    float refraction_index = 1.5f; // inside over outside
    ggx distribution;

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        if (distribution.smooth()) return detail::sample_glass<false>(refraction_index, wo, sp, u, s, lobes);
        if (!(lobes & non_delta_lobe)) return false;
        const float eta = relative_index(sp);
        auto draw = [&](const vec3f& o, float u0, float u1, float u2, vec3f& i) {
            // A visible normal, then reflection with the probability F(wo.m), else refraction.
            const vec3f m = distribution.sample_visible(o, u1, u2);
            const float cos_om = dot(o, m);
            if (u0 < fresnel_dielectric_f(cos_om, eta)) {
                i = 2.0f * cos_om * m - o;
                return i.z > 0;
            }
            i = normalize(refract_f(-o, m, cos_om, 1.0f / eta));
            return i.z < 0;
        };
        return sample_in_frame(wo, sp.n, u, s, draw, [&](const vec3f& o, const vec3f& i) { return local_eval(o, i, eta); },
                               [&](const vec3f& o, const vec3f& i) { return local_pdf(o, i, eta); });
    }
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        if (distribution.smooth()) return {0, 0, 0};
        const float eta = relative_index(sp);
        return in_frame(sp.n, wo, wi, [&](const vec3f& o, const vec3f& i) { return local_eval(o, i, eta); });
    }
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        if (distribution.smooth()) return 0;
        const float eta = relative_index(sp);
        return in_frame(sp.n, wo, wi, [&](const vec3f& o, const vec3f& i) { return local_pdf(o, i, eta); });
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p = detail::glass_properties();
        p.has_delta_lobe = distribution.smooth();
        p.has_density = !distribution.smooth();
        p.density_crosses = !distribution.smooth();
        return p;
    }
    float lobe_weight() const { return 1; }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;

    // The index on the far side of the surface over the index on wo's side (sp.n is on wo's side;
    // a front-face hit has wo outside).
    float relative_index(const shading_point& sp) const {
        return sp.front_face ? refraction_index : 1.0f / refraction_index;
    }

    // The half vector of wo and wi, facing the normal (z > 0), and whether the pair is possible:
    // both on the sides of it the lobe they belong to requires.
    bool half_vector(const vec3f& o, const vec3f& i, float eta, vec3f& h) const {
        const bool reflect = i.z > 0;
        h = reflect ? o + i : o + eta * i;
        const float len2 = dot(h, h);
        if (!(len2 > 0)) return false;
        h = h * (1.0f / std::sqrt(len2));
        if (h.z < 0) h = -h;
        if (!(h.z > 0)) return false;
        return dot(o, h) > 0 && (reflect ? dot(i, h) > 0 : dot(i, h) < 0);
    }
    // In the frame of microfacet_frame: f |cos_i|.
    vec3f local_eval(const vec3f& o, const vec3f& i, float eta) const {
        vec3f h;
        if (!(o.z > 0) || i.z == 0 || !half_vector(o, i, eta, h)) return {0, 0, 0};
        const float cos_oh = dot(o, h), F = fresnel_dielectric_f(cos_oh, eta);
        const float dg = distribution.d(h) * distribution.g2(o, i);
        float value;
        if (i.z > 0) {
            value = F * dg / (4.0f * o.z);
        } else {
            const float cos_ih = dot(i, h), denom = cos_ih + cos_oh / eta;
            value = (1.0f - F) * dg * std::fabs(cos_ih * cos_oh) / (o.z * denom * denom);
        }
        return {value, value, value};
    }
    float local_pdf(const vec3f& o, const vec3f& i, float eta) const {
        vec3f h;
        if (!(o.z > 0) || i.z == 0 || !half_vector(o, i, eta, h)) return 0;
        const float cos_oh = dot(o, h), F = fresnel_dielectric_f(cos_oh, eta);
        const float visible = distribution.visible_pdf(o, h);
        if (i.z > 0) return F * visible / (4.0f * cos_oh);
        const float cos_ih = dot(i, h), denom = cos_ih + cos_oh / eta;
        return (1.0f - F) * visible * std::fabs(cos_ih) / (denom * denom);
    }
};

} // namespace rt
