#pragma once
// The material contract: what every built-in material answers, once, for every integrator (the
// path tracer, the Whitted integrator, and light sampling to come), in the manner of pbrt's BxDFs
// (Pharr, Jakob, Humphreys, Physically Based Rendering, 4th ed., ch. 9) and Nori's BSDFs.
//
//   compiled_material m;                    a table entry (material_compiler.h makes them)
//   m.sample(wo, sp, u, s)                  draws a direction wi; s.value = f |cos| / pdf, s.pdf, s.lobe
//   m.eval(wo, wi, sp)                      f(wo, wi) |cos theta_i|       (0 on delta lobes)
//   m.pdf(wo, wi, sp)                       the solid-angle density sample() draws wi with
//   m.emitted(wo, sp)                       radiance the surface emits towards wo
//   m.transmittance(d)                      the fraction of light left after d inside (Beer's law)
//
// Directions are unit vectors pointing away from the surface: wo towards where the light goes
// (the previous vertex: minus the ray's direction), wi towards where it comes from (the scattered
// ray's direction). The shading point gives the unit normal on wo's side and which face was hit.
//
// Lobes. Glass, mirrors and smooth conductors scatter into single directions (delta lobes): their
// eval and pdf are 0 for every pair of directions, and sample() reports the lobe's discrete
// probability as s.pdf. Light sampling must treat them apart (pbrt, 4th ed., 9.1.3). sample() can
// be restricted to some lobes: the Whitted integrator follows the delta reflection and the delta
// transmission one after the other (as pbrt-v3's Whitted integrator does with BxDF type flags).
//
// The book's fuzzy metal (the mirror direction moved by fuzz times a uniform point of the unit
// ball) has a density in closed form, fuzzy_mirror_density below, so it is a glossy lobe with a
// real pdf, fit for multiple importance sampling, not a delta lobe. Below a fuzz of 1e-4 the lobe
// is narrower than float directions can resolve; it is then flagged delta (it still draws the
// book's offset, so images are unchanged).
//
// Material by material (kernels that follow the book's code exactly, so a render converges to what
// the book's code converges to):
//   lambertian            cosine-weighted: value = albedo, pdf = cos / pi
//   metal                 mirror plus fuzz in the ball; draws below the surface are absorbed (the
//                         book's rule); value = albedo
//   dielectric            the book's glass: reflect with Schlick's probability R, else refract
//   fresnel_dielectric    the same with the exact Fresnel reflectance; absorbs inside (Beer)
//   conductor             mirror weighted by tint * Fr(cos) per channel (exact, complex index)
//   diffuse_light         an emitter (book 2's diffuse_light): radiance `emission` towards every
//                         direction on the front side (both sides if two_sided); scatters nothing
//   isotropic             book 2's phase function of a constant_medium: uniform over the sphere,
//                         eval = albedo / (4 pi) with no cosine (see eval), pdf = 1 / (4 pi)
//   plastic               a Lambertian base under a smooth dielectric coat: the coat's mirror
//                         reflection (a delta lobe of weight F(cos_o)) and the base coupled to it
//                         (plastic_base_factor below); energy-conserving, reciprocal
//   blinn_phong           a Lambertian lobe plus a normalised Blinn-Phong glossy lobe
//                         (blinn_phong_lobe below), sampled by a mixture of the cosine and the
//                         half-vector densities
//   user                  a user's material subclass: the integrators call its virtual scatter()
//                         (user_material.h); it has no pdf and is treated like a delta lobe
// A material compiled from the CENG795 course's (whitted_material) may also carry a Lambertian
// base (`diffuse`) under its delta lobe; sample() picks the base or the lobe in proportion to
// their largest reflectances.

#include "constants.h"
#include "fresnel.h"
#include "rng.h"
#include "sampling.h"
#include "vec3f.h"

#include <cmath>
#include <cstdint>

namespace rt {

class material;

enum class material_kind : uint8_t {
    lambertian, metal, dielectric, fresnel_dielectric, conductor, diffuse_light, isotropic, plastic, blinn_phong, user
};

// Which lobes sample() may choose from: bit flags.
enum lobe : uint8_t {
    non_delta_lobe = 1,          // diffuse and glossy reflection, with a density
    delta_reflection = 2,        // a mirror direction
    delta_transmission = 4,      // a refracted direction
    all_lobes = 7,
};

// Where a material is asked: the unit normal on the side of wo (the geometric or the shading
// normal, as the integrator chooses) and whether the ray hit the front face (glass needs to
// know which index is on which side). A phase function (isotropic) ignores both: its point is
// inside a volume, and whatever normal the medium reports there means nothing.
struct shading_point {
    vec3f n;
    bool front_face = true;
};

struct material_sample {
    vec3f wi;                // unit direction the light arrives from: the scattered ray's direction
    vec3f value;             // f |cos theta_i| / pdf: what the path throughput is multiplied by
    float pdf = 0;           // solid-angle density; for a delta lobe, the probability of choosing it
    lobe sampled = non_delta_lobe;
    bool is_delta() const { return sampled != non_delta_lobe; }
};

// compiled_material::texture when the material has no texture.
inline constexpr uint32_t no_texture = UINT32_MAX;

// Below this fuzz a metal's lobe is flagged delta (see the top of the file).
inline constexpr float min_glossy_fuzz = 1e-4f;

struct compiled_material {
    material_kind kind = material_kind::lambertian;
    vec3f albedo{0.5f, 0.5f, 0.5f}; // lambertian, metal, isotropic; conductor: the tint; plastic,
                                    // blinn_phong: the diffuse reflectance
    float fuzz = 0;                 // metal
    float refraction_index = 1;     // dielectric, fresnel_dielectric; plastic: the coat's
    float coat_average = 0;         // plastic: the coat's mean Fresnel reflectance (fresnel_average)
    vec3f specular{0, 0, 0};        // blinn_phong: the glossy lobe's reflectance
    float exponent = 0;             // blinn_phong: the Phong exponent
    vec3f absorption{0, 0, 0};      // fresnel_dielectric: per unit length inside
    vec3f eta{1, 1, 1}, k{0, 0, 0}; // conductor: complex index eta + ik per channel
    vec3f diffuse{0, 0, 0};         // a Lambertian base under a delta lobe (course materials); 0: none
    vec3f emission{0, 0, 0};        // diffuse_light: emitted radiance
    bool two_sided = false;         // diffuse_light: emits from the back face too
    const material* source = nullptr; // what it was compiled from; a user material is called through it
    // A lambertian's albedo or a diffuse_light's emission looked up per hit in the compiled scene's
    // texture table (scene/texture_table.h); no_texture: the constant albedo / emission above.
    // The integrator then hands the contract a copy with that colour filled in.
    uint32_t texture = no_texture;

    // Draws wi for wo, restricted to `lobes`; false when the light is absorbed (or no lobe of
    // `lobes` exists). Draws its random numbers from `u`: a choice (lobe, Fresnel) from
    // u.next_float(), a direction's pair from draw_2d(u) (rng.h), each uniform in [0, 1).
    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes = all_lobes) const;
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const;
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const;
    // Radiance emitted towards wo: a diffuse_light's, from its front face (or either face when
    // two-sided, as book 2's diffuse_light is); zero for every other material.
    vec3f emitted(const vec3f& /*wo*/, const shading_point& sp) const {
        return sp.front_face || two_sided ? emission : vec3f{0, 0, 0};
    }
    bool emits() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }

    // Whether light travelling inside loses energy with distance (absorbing glass), and how much
    // is left after `distance`: exp(-absorption * distance) per channel (Beer-Lambert).
    bool absorbs_inside() const {
        return kind == material_kind::fresnel_dielectric && (absorption.x > 0 || absorption.y > 0 || absorption.z > 0);
    }
    vec3f transmittance(float distance) const;

    // Whether light can pass through the surface (its back face must never be culled).
    bool transmits() const {
        return kind == material_kind::dielectric || kind == material_kind::fresnel_dielectric ||
               kind == material_kind::isotropic || kind == material_kind::user;
    }
    // Whether it is a phase function, scattering to the whole sphere at a point inside a volume:
    // eval has no cosine, and light may arrive from any side.
    bool is_phase_function() const { return kind == material_kind::isotropic; }
    bool has_diffuse_base() const { return diffuse.x > 0 || diffuse.y > 0 || diffuse.z > 0; }
    bool is_glossy_metal() const { return kind == material_kind::metal && fuzz >= min_glossy_fuzz; }
    // Whether some lobe has a density (diffuse or glossy): light sampling can reach it.
    bool has_non_delta_lobe() const {
        return kind == material_kind::lambertian || is_glossy_metal() || has_diffuse_base() ||
               kind == material_kind::isotropic || kind == material_kind::plastic || kind == material_kind::blinn_phong;
    }
    // Whether some lobe is a delta lobe (glass, a mirror, a smooth coat): light leaving it can
    // form a caustic (caustic_paths.h).
    bool has_delta_lobe() const {
        switch (kind) {
        case material_kind::dielectric:
        case material_kind::fresnel_dielectric:
        case material_kind::conductor:
        case material_kind::plastic: return true;
        case material_kind::metal: return !is_glossy_metal();
        default: return false;
        }
    }

  private:
    template <class Uniform>
    bool sample_lobe(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const;
    // The probability sample() picks the diffuse base over the lobe.
    float base_probability() const;
    // plastic: the probability sample() picks the coat's mirror reflection, for cos_o = wo.n.
    float coat_probability(float cos_o) const;
    // blinn_phong: the probability sample() draws from the glossy lobe.
    float glossy_probability() const;
};

// --- the pieces the materials share -------------------------------------------------------------

inline vec3f reflect_f(const vec3f& v, const vec3f& n) { return v - 2.0f * dot(v, n) * n; }

// Refraction of the unit direction `d` through the unit normal `n` facing it, for the index
// ratio ri = n_incident / n_transmitted and cos_theta = -d.n (the book's form: perpendicular and
// parallel parts).
inline vec3f refract_f(const vec3f& d, const vec3f& n, float cos_theta, float ri) {
    vec3f perp = ri * (d + cos_theta * n);
    vec3f parallel = -std::sqrt(std::fabs(1.0f - length_squared(perp))) * n;
    return perp + parallel;
}

// Beer-Lambert law: the fraction of light left after a distance d in a medium of absorption
// coefficient sigma, exp(-sigma d), per channel.
inline vec3f beer_transmittance(const vec3f& sigma, float d) {
    return {std::exp(-sigma.x * d), std::exp(-sigma.y * d), std::exp(-sigma.z * d)};
}

inline float max_component(const vec3f& v) { return fmax_inline(v.x, fmax_inline(v.y, v.z)); }

// The density of the directions of the book's fuzzy metal, w = normalize(m + f B) with m the unit
// mirror direction and B uniform in the unit ball, f <= 1. m + f B is uniform in the ball of
// radius f about m (volume 4 pi f^3 / 3); in spherical coordinates about the surface point
// (dV = r^2 dr dw) the density of w is the integral of r^2 along the chord r w that lies in the
// ball, over the volume:
//   p(w) = ((c + s)^3 - (c - s)^3) / 3 / (4 pi f^3 / 3) = s (3 c^2 + s^2) / (2 pi f^3),
// with c = w.m and s^2 = f^2 - |w x m|^2 the half chord squared; 0 outside the cone (s^2 <= 0).
// (For f = 1: p = 2 c^3 / pi.) sin^2 comes from the cross product, which keeps its digits when w
// is close to m.
inline float fuzzy_mirror_density(const vec3f& w, const vec3f& m, float f) {
    const float c = dot(w, m);
    const float s2 = f * f - length_squared(cross(w, m));
    if (!(c > 0 && s2 > 0)) return 0;
    const float s = std::sqrt(s2);
    return s * (3.0f * c * c + s2) / (2.0f * pi_f * f * f * f);
}

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

inline float compiled_material::coat_probability(float cos_o) const {
    // In proportion to what each lobe returns: F for the coat, albedo (1 - F) for the base.
    const float f = fresnel_dielectric_f(cos_o, refraction_index);
    const float total = f + (1.0f - f) * max_component(albedo);
    return total > 0 ? f / total : 1.0f;
}

inline float compiled_material::glossy_probability() const {
    const float s = max_component(specular), total = s + max_component(albedo);
    return total > 0 ? s / total : 0.0f;
}

inline float compiled_material::base_probability() const {
    const float base = max_component(diffuse);
    const float lobe_weight = kind == material_kind::dielectric || kind == material_kind::fresnel_dielectric
                                  ? 1.0f
                                  : max_component(albedo);
    return base / (base + lobe_weight);
}

template <class Uniform>
bool compiled_material::sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s,
                               lobe lobes) const {
    if (!has_diffuse_base() || !(lobes & non_delta_lobe)) return sample_lobe(wo, sp, u, s, lobes);
    // A diffuse base under a delta lobe: choose one in proportion to their reflectances (or
    // the base alone, when the lobe is not asked for).
    const bool lobe_allowed = (lobes & ~non_delta_lobe) != 0;
    const float p_base = lobe_allowed ? base_probability() : 1.0f;
    if (p_base >= 1.0f || u.next_float() < p_base) {
        const auto [u1, u2] = draw_2d(u);
        s.wi = sample_cosine_direction(sp.n, u1, u2);
        s.value = diffuse * (1.0f / p_base);
        s.pdf = p_base * fmax_inline(dot(s.wi, sp.n), 0.0f) * (1.0f / pi_f);
        s.sampled = non_delta_lobe;
        return true;
    }
    if (!sample_lobe(wo, sp, u, s, lobes)) return false;
    s.value *= 1.0f / (1.0f - p_base);
    s.pdf *= 1.0f - p_base;
    return true;
}

template <class Uniform>
bool compiled_material::sample_lobe(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s,
                                    lobe lobes) const {
    const vec3f d = -wo; // the incoming ray's direction
    const vec3f& n = sp.n;
    switch (kind) {
    case material_kind::lambertian: {
        if (!(lobes & non_delta_lobe)) return false;
        const auto [u1, u2] = draw_2d(u);
        s.wi = sample_cosine_direction(n, u1, u2);
        s.value = albedo;
        s.pdf = fmax_inline(dot(s.wi, n), 0.0f) * (1.0f / pi_f);
        s.sampled = non_delta_lobe;
        return true;
    }
    case material_kind::metal: {
        const bool glossy = is_glossy_metal();
        if (!(lobes & (glossy ? non_delta_lobe : delta_reflection))) return false;
        const vec3f mirror = reflect_f(d, n);
        vec3f dir = mirror;
        if (fuzz > 0) {
            const auto [u1, u2] = draw_2d(u);
            const float u3 = u.next_float();
            dir += fuzz * sample_unit_ball(u1, u2, u3);
        }
        // The book absorbs fuzzed directions that point below the surface.
        if (!(dot(dir, n) > 0)) return false;
        s.wi = normalize(dir);
        s.value = albedo;
        s.pdf = glossy ? fuzzy_mirror_density(s.wi, mirror, fuzz) : 1.0f;
        s.sampled = glossy ? non_delta_lobe : delta_reflection;
        return true;
    }
    case material_kind::dielectric:
    case material_kind::fresnel_dielectric: {
        // Reflect with probability R (Schlick's for the book's glass, the exact Fresnel
        // reflectance otherwise; 1 under total internal reflection), else refract: the weight is
        // 1 either way. Restricted to one lobe, that lobe's weight is R or 1 - R.
        const bool schlick = kind == material_kind::dielectric;
        const float ri = sp.front_face ? 1.0f / refraction_index : refraction_index; // n_i / n_t
        const float cos_theta = fmin_inline(-dot(d, n), 1.0f);
        float r = 1.0f; // the reflected fraction
        bool cannot_refract;
        if (schlick) {
            const float sin_theta = std::sqrt(fmax_inline(0.0f, 1.0f - cos_theta * cos_theta));
            cannot_refract = ri * sin_theta > 1.0f;
            if (!cannot_refract) r = schlick_reflectance(cos_theta, ri);
        } else {
            const float eta = sp.front_face ? refraction_index : 1.0f / refraction_index; // n_t / n_i
            r = fresnel_dielectric_f(cos_theta, eta);
            cannot_refract = r >= 1.0f;
        }
        bool reflect;
        if ((lobes & delta_reflection) && (lobes & delta_transmission)) {
            // The draws of the book's code: none when the ray cannot refract.
            reflect = cannot_refract || (schlick ? r > u.next_float() : u.next_float() < r);
            s.value = {1, 1, 1};
            s.pdf = reflect ? r : 1.0f - r;
        } else if (lobes & delta_reflection) {
            reflect = true;
            s.value = {r, r, r};
            s.pdf = 1;
        } else if ((lobes & delta_transmission) && !cannot_refract) {
            reflect = false;
            s.value = {1.0f - r, 1.0f - r, 1.0f - r};
            s.pdf = 1;
        } else {
            return false;
        }
        s.wi = reflect ? reflect_f(d, n) : normalize(refract_f(d, n, cos_theta, ri));
        s.sampled = reflect ? delta_reflection : delta_transmission;
        return true;
    }
    case material_kind::conductor: {
        if (!(lobes & delta_reflection)) return false;
        s.wi = normalize(reflect_f(d, n));
        s.value = albedo * fresnel_conductor_f(-dot(d, n), eta, k);
        s.pdf = 1;
        s.sampled = delta_reflection;
        return true;
    }
    case material_kind::isotropic: {
        if (!(lobes & non_delta_lobe)) return false;
        const auto [u1, u2] = draw_2d(u);
        s.wi = sample_unit_sphere(u1, u2);
        s.value = albedo;
        s.pdf = 1.0f / (4.0f * pi_f);
        s.sampled = non_delta_lobe;
        return true;
    }
    case material_kind::plastic: {
        // The coat's mirror with probability q (delta), else the base, cosine-weighted.
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
    case material_kind::blinn_phong: {
        // One-sample mixture of the cosine density and the half-vector density; the weight is
        // eval over the mixture's pdf.
        if (!(lobes & non_delta_lobe)) return false;
        const float ps = glossy_probability();
        const float u0 = u.next_float();
        const auto [u1, u2] = draw_2d(u);
        if (u0 < ps) {
            // cos theta_h = u^(1 / (n + 1)) has density (n + 1) cos^n theta_h sin theta_h d theta.
            const float cos_h = std::pow(u1, 1.0f / (exponent + 1.0f));
            const float sin_h = std::sqrt(fmax_inline(0.0f, 1.0f - cos_h * cos_h));
            vec3f e1, e2;
            frame_across(n, e1, e2);
            const vec3f c = unit_circle(u2);
            const vec3f h = (sin_h * c.x) * e1 + (sin_h * c.y) * e2 + cos_h * n;
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
    case material_kind::diffuse_light: break; // absorbs what reaches it
    case material_kind::user: break; // the integrators call the user's scatter() (user_material.h)
    }
    return false;
}

inline vec3f compiled_material::eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
    // A phase function p(wo, wi) takes the place of f |cos theta_i|: radiance scattered in a
    // volume has no surface to be foreshortened by (pbrt, 4th ed., 11.3).
    if (kind == material_kind::isotropic) return albedo * (1.0f / (4.0f * pi_f));
    const float cos_i = dot(wi, sp.n);
    if (!(cos_i > 0)) return {0, 0, 0}; // every density lobe here reflects
    vec3f f{0, 0, 0};
    if (kind == material_kind::lambertian) f = albedo * (cos_i * (1.0f / pi_f));
    if (has_diffuse_base()) f += diffuse * (cos_i * (1.0f / pi_f));
    if (is_glossy_metal()) f += albedo * fuzzy_mirror_density(wi, reflect_f(-wo, sp.n), fuzz);
    if (kind == material_kind::plastic) {
        const float cos_o = fmin_inline(fmax_inline(dot(wo, sp.n), 0.0f), 1.0f);
        f = albedo * (plastic_base_factor(cos_i, cos_o, refraction_index, coat_average) * cos_i * (1.0f / pi_f));
    }
    if (kind == material_kind::blinn_phong)
        f = albedo * (cos_i * (1.0f / pi_f)) + specular * blinn_phong_lobe(wo, wi, sp.n, exponent);
    return f;
}

inline float compiled_material::pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
    if (kind == material_kind::isotropic) return 1.0f / (4.0f * pi_f);
    const float cos_i = dot(wi, sp.n);
    if (!(cos_i > 0)) return 0;
    if (kind == material_kind::plastic) {
        const float cos_o = fmin_inline(fmax_inline(dot(wo, sp.n), 0.0f), 1.0f);
        return (1.0f - coat_probability(cos_o)) * cos_i * (1.0f / pi_f); // the coat is a delta lobe
    }
    if (kind == material_kind::blinn_phong) {
        const float ps = glossy_probability();
        return (1.0f - ps) * cos_i * (1.0f / pi_f) + ps * blinn_phong_lobe_pdf(wo, wi, sp.n, exponent);
    }
    if (kind == material_kind::lambertian) return cos_i * (1.0f / pi_f);
    if (has_diffuse_base()) return base_probability() * cos_i * (1.0f / pi_f); // the lobe is a delta one
    if (is_glossy_metal()) return fuzzy_mirror_density(wi, reflect_f(-wo, sp.n), fuzz);
    return 0;
}

inline vec3f compiled_material::transmittance(float distance) const {
    if (!absorbs_inside()) return {1, 1, 1};
    return beer_transmittance(absorption, distance);
}

} // namespace rt
