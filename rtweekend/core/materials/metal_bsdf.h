#pragma once
// metal_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): the books' metal, mirror
// reflection with its direction moved by fuzz times a uniform point of the unit ball; draws below
// the surface are absorbed (the book's rule); value = albedo.
//
// The fuzzy lobe has a density in closed form (fuzzy_mirror_density below), so it is a glossy lobe
// with a real pdf, fit for multiple importance sampling, not a delta lobe. Below a fuzz of
// min_glossy_fuzz the lobe is narrower than float directions can resolve; it is then flagged delta
// (it still draws the book's offset, so images are unchanged).

#include "../bsdf.h"
#include "../constants.h"
#include "../rng.h"
#include "../sampling.h"
#include "../vec3f.h"

#include <cmath>

namespace rt {

// Below this fuzz a metal's lobe is flagged delta.
inline constexpr float min_glossy_fuzz = 1e-4f;

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

struct metal_bsdf {
    static constexpr const char* name = "metal";
    vec3f albedo{0.5f, 0.5f, 0.5f};
    float fuzz = 0;

    bool glossy() const { return fuzz >= min_glossy_fuzz; }

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        const vec3f d = -wo; // the incoming ray's direction
        const vec3f& n = sp.n;
        const bool is_glossy = glossy();
        if (!(lobes & (is_glossy ? non_delta_lobe : delta_reflection))) return false;
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
        s.pdf = is_glossy ? fuzzy_mirror_density(s.wi, mirror, fuzz) : 1.0f;
        s.sampled = is_glossy ? non_delta_lobe : delta_reflection;
        return true;
    }
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        if (!(dot(wi, sp.n) > 0) || !glossy()) return {0, 0, 0};
        return albedo * fuzzy_mirror_density(wi, reflect_f(-wo, sp.n), fuzz);
    }
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
        if (!(dot(wi, sp.n) > 0) || !glossy()) return 0;
        return fuzzy_mirror_density(wi, reflect_f(-wo, sp.n), fuzz);
    }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const {
        material_properties p;
        p.has_density = glossy();
        p.has_delta_lobe = !glossy();
        return p;
    }
    float lobe_weight() const { return max_component(albedo); }
    float reversal_ratio(const vec3f&, const vec3f&, bool, const material_sample&) const { return 1; }
    static constexpr bool takes_texture = false;
};

} // namespace rt
