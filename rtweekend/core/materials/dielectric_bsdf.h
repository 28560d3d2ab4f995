#pragma once
// dielectric_bsdf: a material kind (core/bsdf.h; core/material_kinds.h): the books' glass. It
// reflects with Schlick's probability R and refracts otherwise, as the book's code draws; the
// weight is 1 either way. fresnel_glass_bsdf is the same with the exact Fresnel reflectance and
// Beer's law inside; both share detail::sample_glass below.

#include "../bsdf.h"
#include "../fresnel.h"
#include "../vec3f.h"

#include <cmath>

namespace rt {

namespace detail {

// A smooth dielectric of index `refraction_index` (inside over outside): reflect with probability
// R (Schlick's for the book's glass, the exact Fresnel reflectance otherwise; 1 under total
// internal reflection), else refract: the weight is 1 either way. Restricted to one lobe, that
// lobe's weight is R or 1 - R.
template <bool Schlick, class Uniform>
bool sample_glass(float refraction_index, const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s,
                  lobe lobes) {
    const vec3f d = -wo; // the incoming ray's direction
    const vec3f& n = sp.n;
    const float ri = sp.front_face ? 1.0f / refraction_index : refraction_index; // n_i / n_t
    const float cos_theta = fmin_inline(-dot(d, n), 1.0f);
    float r = 1.0f; // the reflected fraction
    bool cannot_refract;
    if (Schlick) {
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
        reflect = cannot_refract || (Schlick ? r > u.next_float() : u.next_float() < r);
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

// What a smooth dielectric is to the integrators: delta lobes both ways, a surface light crosses.
inline material_properties glass_properties() {
    material_properties p;
    p.has_delta_lobe = true;
    p.refracts = true;
    p.transmits = true;
    return p;
}

} // namespace detail

struct dielectric_bsdf {
    static constexpr const char* name = "dielectric";
    float refraction_index = 1; // inside over outside

    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        return detail::sample_glass<true>(refraction_index, wo, sp, u, s, lobes);
    }
    vec3f eval(const vec3f&, const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    float pdf(const vec3f&, const vec3f&, const shading_point&) const { return 0; }
    vec3f emitted(const vec3f&, const shading_point&) const { return {0, 0, 0}; }
    vec3f emission() const { return {0, 0, 0}; }
    vec3f transmittance(float) const { return {1, 1, 1}; }
    material_properties properties() const { return detail::glass_properties(); }
    float lobe_weight() const { return 1; }
    // Schlick's approximation takes the cosine on the side the path tracer arrives from, which
    // differs across a refraction: a light path refracting here is weighed by the ratio of the path
    // tracer's probability to its own, so that both estimate the same image, the book's. n: the
    // unit normal; wo: back along the arriving light path, on the side `front` says; s: the
    // refraction drawn.
    float reversal_ratio(const vec3f& n, const vec3f& wo, bool front, const material_sample& s) const {
        if (s.sampled != delta_transmission) return 1.0f;
        auto transmitted = [&](float cos_theta, bool front_face) {
            const float ri = front_face ? 1.0f / refraction_index : refraction_index;
            cos_theta = fmin_inline(cos_theta, 1.0f);
            const float sin_theta = sqrt_f(fmax_inline(0.0f, 1.0f - cos_theta * cos_theta));
            if (ri * sin_theta > 1.0f) return 0.0f;
            return 1.0f - schlick_reflectance(cos_theta, ri);
        };
        const float mine = transmitted(std::fabs(dot(wo, n)), front);
        const float theirs = transmitted(std::fabs(dot(s.wi, n)), !front);
        return mine > 0 ? theirs / mine : 0.0f;
    }
    static constexpr bool takes_texture = false;
};

} // namespace rt
