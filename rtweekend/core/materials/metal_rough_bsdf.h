#pragma once
// metal_rough_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): glTF 2.0's
// metallic-roughness material (the glTF 2.0 specification, appendix B): a blend by `metallic` of
// a metal, a GGX mirror (core/microfacet.h) whose Fresnel reflectance is Schlick's with
// F(0) = base colour c, and a dielectric, a Lambertian base of colour c under a GGX clear coat of
// F(0) = 0.04 (index 1.5):
//   metal      = F_m(v.h) D G2 / (4 cos_o cos_i) + f_ms,      F_m = c + (1 - c)(1 - v.h)^5
//   dielectric = F_d(v.h) D G2 / (4 cos_o cos_i) + c / pi (1 - E_d(cos_o)) (1 - E_d(cos_i)) / (1 - E_d,avg),
//                F_d = 0.04 + 0.96 (1 - v.h)^5
//   f          = (1 - metallic) dielectric + metallic metal,   alpha = roughness^2
// f_ms is Kulla and Conty's multiple scattering (as rough_conductor_bsdf): a white metal reflects
// everything at every roughness. The base is weighted by what the coat leaves over, E_d being the
// coat's directional albedo (microfacet.h's table with f0 = 0.04), in place of the
// specification's per-microfacet mix (1 - F_d(v.h)) c / pi: that mix is not energy-conserving (a
// white base under a coat of roughness 0.05 returned 1.35 of the light at 80 degrees), while this
// coupling returns exactly 1 for a white base and is reciprocal (Kulla and Conty 2017 use it for
// a layer over a diffuse base). Sampled by the visible normals for the mirrors and the cosine for
// the rest, in proportion to estimates of what each returns.

#include "../bsdf.h"
#include "../microfacet.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"

#include <cmath>

namespace rt {

struct metal_rough_bsdf {
    static constexpr const char* name = "metal_rough";
    vec3f base_colour{0.8f, 0.8f, 0.8f};
    float metallic = 0;
    ggx distribution{0.25f, 0.25f}; // alpha = roughness^2; isotropic (glTF's core material is)

    static constexpr float coat_f0 = 0.04f; // index 1.5: ((1.5 - 1) / (1.5 + 1))^2

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        if (!(lobes & non_delta_lobe)) return false;
        auto draw = [&](const vec3f& o, float u0, float u1, float u2, vec3f& i) {
            return draw_mirror_or_cosine(distribution, o, mirror_probability(o.z), u0, u1, u2, i);
        };
        return sample_in_frame(wo, sp.n, u, s, draw, [&](const vec3f& o, const vec3f& i) { return local_eval(o, i); },
                               [&](const vec3f& o, const vec3f& i) { return local_pdf(o, i); });
    }
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        return in_frame(sp.n, wo, wi, [&](const vec3f& o, const vec3f& i) { return local_eval(o, i); });
    }
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        return in_frame(sp.n, wo, wi, [&](const vec3f& o, const vec3f& i) { return local_pdf(o, i); });
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_density = true;
        return p;
    }
    float lobe_weight() const { return max_component(base_colour); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = true;
    void set_colour(const vec3f& c) { base_colour = c; }
    vec3f colour() const { return base_colour; }
    // Metallic and roughness, each clamped to [0, 1] (a texel times a factor may pass 1). The blend
    // has no mirror limit of its own (its coat and metal are microfacet lobes throughout): alpha
    // stops at smooth_alpha, a mirror to within a thousandth of a radian.
    void set_metallic_roughness(float m, float roughness) {
        metallic = fmin_inline(fmax_inline(m, 0.0f), 1.0f);
        const float a = fmax_inline(alpha_of_roughness(fmin_inline(fmax_inline(roughness, 0.0f), 1.0f)), smooth_alpha);
        distribution = {a, a};
    }

    // In the frame of microfacet_frame: f cos_i.
    vec3f local_eval(const vec3f& o, const vec3f& i) const {
        if (!(o.z > 0 && i.z > 0)) return {0, 0, 0};
        const vec3f h = normalize(o + i);
        const float c = fmin_inline(fmax_inline(dot(o, h), 0.0f), 1.0f), w = 1.0f - c, w5 = w * w * w * w * w;
        const float mirror = distribution.d(h) * distribution.g2(o, i) / (4.0f * o.z); // D G2 cos_i / (4 cos_o cos_i)
        const vec3f one{1, 1, 1};
        vec3f f{0, 0, 0};
        if (metallic < 1) {
            const ggx_albedo_table& table = ggx_albedo();
            const float a = alpha(), coat_avg = table.average(a, coat_f0);
            const float base = (1.0f - table.albedo(o.z, a, coat_f0)) * (1.0f - table.albedo(i.z, a, coat_f0)) *
                               i.z / (pi_f * (1.0f - coat_avg));
            const float coat = (coat_f0 + (1.0f - coat_f0) * w5) * mirror;
            f += (base_colour * base + one * coat) * (1.0f - metallic);
        }
        if (metallic > 0) {
            const vec3f metal = (base_colour + (one - base_colour) * w5) * mirror +
                                ggx_multiple_scattering(ggx_albedo().albedo(o.z, alpha()), ggx_albedo().albedo(i.z, alpha()),
                                                        i.z, ggx_albedo().average(alpha()), metal_fresnel_average());
            f += metal * metallic;
        }
        return f;
    }
    float local_pdf(const vec3f& o, const vec3f& i) const {
        if (!(o.z > 0 && i.z > 0)) return 0;
        return mirror_or_cosine_pdf(distribution, o, i, mirror_probability(o.z));
    }
    float alpha() const { return distribution.alpha_u; }
    // Schlick's mean over the hemisphere, 2 int F mu dmu = f0 + (1 - f0) / 21.
    vec3f metal_fresnel_average() const { return base_colour + (vec3f{1, 1, 1} - base_colour) * (1.0f / 21.0f); }
    // The probability of drawing from the mirror: the share of the mirrors in an estimate of what
    // the lobes return at cos_o (the mirrors: the metal's single scattering and the coat; the
    // cosine: the base under the coat and the metal's multiple scattering).
    float mirror_probability(float cos_o) const {
        const ggx_albedo_table& table = ggx_albedo();
        const float a = alpha();
        const float e = table.albedo(cos_o, a), coat = table.albedo(cos_o, a, coat_f0);
        const float mirror = metallic * e + (1.0f - metallic) * coat;
        const float diffuse = metallic * (1.0f - e) + (1.0f - metallic) * (1.0f - coat) * max_component(base_colour);
        return mirror + diffuse > 0 ? fmin_inline(fmax_inline(mirror / (mirror + diffuse), 0.05f), 1.0f) : 1.0f;
    }
};

} // namespace rt
