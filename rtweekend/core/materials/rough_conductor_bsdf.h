#pragma once
// rough_conductor_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): a rough metal, the
// GGX microfacet mirror (core/microfacet.h) with Smith's height-correlated masking-shadowing and
// the Fresnel reflectance of a complex index n + ik per channel (exact, core/fresnel.h) or of an
// albedo (Schlick's approximation with F(0) = albedo, the form artists' metals and glTF use),
// plus Kulla and Conty's multiple-scattering lobe for the energy single scattering loses: a white
// rough conductor reflects everything at every roughness (the furnace test). Visible normals are
// sampled (Heitz 2018), the compensation lobe by the cosine, in proportion to what each returns.
//
//   f(wo, wi) = F(wo.h) D(h) G2(wo, wi) / (4 cos_o cos_i) + f_ms(wo, wi)
// (Walter et al., EGSR 2007, eq. 20.) Below alpha 1e-3 on both axes it is a smooth mirror, a
// delta lobe of weight F(cos), exactly as conductor_bsdf.

#include "../bsdf.h"
#include "../fresnel.h"
#include "../microfacet.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"

#include <cmath>
#include <optional>

namespace rt {

// Schlick's approximation with a colour at normal incidence: f0 + (1 - f0)(1 - c)^5.
inline vec3f schlick_f0(const vec3f& f0, float cos_theta) {
    const float m = 1.0f - fmin_inline(fmax_inline(cos_theta, 0.0f), 1.0f), m5 = m * m * m * m * m;
    return f0 + (vec3f{1, 1, 1} - f0) * m5;
}

// A conductor's hemispherical mean Fresnel reflectance 2 int F(mu) mu dmu (per channel), by the
// midpoint rule on 256 cosines: the colour of rough_conductor_bsdf's multiple scattering.
inline vec3f conductor_fresnel_average(const vec3f& eta, const vec3f& k) {
    constexpr int n = 256;
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;
        for (int c = 0; c < 3; ++c) sum[c] += 2.0 * mu * fresnel_conductor(mu, eta[c], k[c]) / n;
    }
    return {float(sum[0]), float(sum[1]), float(sum[2])};
}

// What a rough conductor works out once and keeps beside its records: the complex index of its
// exact Fresnel reflectance, the mean of that reflectance, and an anisotropic distribution's
// albedo table. The rough_conductor material owns it (a scene keeps its materials for as long as
// it renders); the records point to it, so that they stay a few plain bytes (the material table's
// entries are trivially copyable, and a textured hit copies one).
struct rough_conductor_data {
    bool complex_index = false;         // Fresnel from eta + ik (exact), or from the record's f0
    vec3f eta{1, 1, 1}, k{0, 0, 0};
    vec3f fresnel_average{1, 1, 1};     // 2 int F(mu) mu dmu, per channel: the compensation's colour
    std::optional<ggx_anisotropic_albedo> anisotropic;
};

struct rough_conductor_bsdf {
    static constexpr const char* name = "rough_conductor";
    ggx distribution;
    vec3f f0{1, 1, 1}; // the reflectance at normal incidence (Schlick), unless data has an index
    // Null: Schlick's Fresnel from f0, and for an anisotropic distribution no compensation.
    const rough_conductor_data* data = nullptr;

    vec3f fresnel(float cos_theta) const {
        if (data && data->complex_index) return fresnel_conductor_f(cos_theta, data->eta, data->k);
        return schlick_f0(f0, cos_theta);
    }
    vec3f fresnel_average() const {
        if (data && data->complex_index) return data->fresnel_average;
        return f0 + (vec3f{1, 1, 1} - f0) * (1.0f / 21.0f); // Schlick's: f0 + (1 - f0) 2 int (1 - mu)^5 mu dmu
    }

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        if (distribution.smooth()) {
            if (!(lobes & delta_reflection)) return false;
            s.wi = normalize(reflect_f(-wo, sp.n));
            s.value = fresnel(dot(wo, sp.n));
            s.pdf = 1;
            s.sampled = delta_reflection;
            return true;
        }
        if (!(lobes & non_delta_lobe)) return false;
        auto draw = [&](const vec3f& o, float u0, float u1, float u2, vec3f& i) {
            return draw_mirror_or_cosine(distribution, o, 1.0f - multiple_scattering_probability(o), u0, u1, u2, i);
        };
        return sample_in_frame(wo, sp.n, u, s, draw, [&](const vec3f& o, const vec3f& i) { return local_eval(o, i); },
                               [&](const vec3f& o, const vec3f& i) { return local_pdf(o, i); });
    }
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        if (distribution.smooth()) return {0, 0, 0};
        return in_frame(sp.n, wo, wi, [&](const vec3f& o, const vec3f& i) { return local_eval(o, i); });
    }
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        if (distribution.smooth()) return 0;
        return in_frame(sp.n, wo, wi, [&](const vec3f& o, const vec3f& i) { return local_pdf(o, i); });
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_density = !distribution.smooth();
        p.has_delta_lobe = distribution.smooth();
        return p;
    }
    float lobe_weight() const { return max_component(fresnel_average()); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;

    // In the frame of microfacet_frame: f cos_i.
    vec3f local_eval(const vec3f& o, const vec3f& i) const {
        if (!(o.z > 0 && i.z > 0)) return {0, 0, 0};
        const vec3f h = normalize(o + i);
        const float single = distribution.d(h) * distribution.g2(o, i) / (4.0f * o.z);
        return fresnel(dot(o, h)) * single +
               ggx_multiple_scattering(white_albedo(o), white_albedo(i), i.z, white_average(), fresnel_average());
    }
    float local_pdf(const vec3f& o, const vec3f& i) const {
        if (!(o.z > 0 && i.z > 0)) return 0;
        return mirror_or_cosine_pdf(distribution, o, i, 1.0f - multiple_scattering_probability(o));
    }
    // The share of the light the compensation lobe returns towards o, for a white mirror.
    float multiple_scattering_probability(const vec3f& o) const { return fmax_inline(0.0f, 1.0f - white_albedo(o)); }
    // What a white mirror of this roughness reflects of light from w by single scattering, and
    // its mean over the hemisphere (1: nothing to compensate).
    float white_albedo(const vec3f& w) const {
        if (distribution.isotropic()) return ggx_albedo().albedo(w.z, distribution.alpha_u);
        return data && data->anisotropic ? data->anisotropic->albedo(w) : 1.0f;
    }
    float white_average() const {
        if (distribution.isotropic()) return ggx_albedo().average(distribution.alpha_u);
        return data && data->anisotropic ? data->anisotropic->average() : 1.0f;
    }
};

} // namespace rt
