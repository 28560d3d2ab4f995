#pragma once
// The renderer's materials: a tagged table entry per material and one float kernel that
// samples the scattered direction. The kernels follow the book's materials exactly (same
// distributions, same absorption rule for fuzzy metal, the same Schlick choice for glass), so
// an image converges to what the book's code converges to. Two more materials use the exact
// Fresnel equations (fresnel.h): a smooth conductor, and glass that chooses reflection with the
// exact Fresnel probability and absorbs inside by Beer's law (applied by the path tracer, which
// knows the distance travelled: render.h, trace_path).

#include "fresnel.h"
#include "../material.h"
#include "rng.h"
#include "sampling.h"
#include "vec3f.h"

#include <cmath>
#include <cstdint>

namespace rt {

// exact_dielectric: dielectric(ior, absorption), exact Fresnel and Beer's law.
enum class material_kind : uint8_t { lambertian, metal, dielectric, custom, conductor, exact_dielectric };

struct material_desc {
    material_kind kind = material_kind::lambertian;
    vec3f albedo{0.5f, 0.5f, 0.5f};    // conductor: the tint
    float fuzz = 0;                    // metal
    float refraction_index = 1;        // dielectric, exact_dielectric
    vec3f absorption{0, 0, 0};         // exact_dielectric: per unit length inside
    vec3f eta{1, 1, 1}, k{0, 0, 0};    // conductor: complex index eta + ik per channel
    const material* custom = nullptr;  // a user's material subclass (virtual path)
};

// Schlick's approximation in float (see schlick_reflectance in material.h).
inline float schlick_reflectance_f(float cosine, float ri) {
    float r0 = (1 - ri) / (1 + ri);
    r0 = r0 * r0;
    float m = 1 - cosine;
    return r0 + (1 - r0) * (m * m * m * m * m);
}

// Refraction of unit `wi` through the unit normal `n` facing it, index ratio `ri` (book form).
inline vec3f refract_f(const vec3f& wi, const vec3f& n, float cos_theta, float ri) {
    vec3f perp = ri * (wi + cos_theta * n);
    vec3f parallel = -std::sqrt(std::fabs(1.0f - length_squared(perp))) * n;
    return perp + parallel;
}

inline vec3f reflect_f(const vec3f& v, const vec3f& n) { return v - 2.0f * dot(v, n) * n; }

// Beer-Lambert law: the fraction of light left after a distance d in a medium of absorption
// coefficient sigma, exp(-sigma d), per channel.
inline vec3f beer_transmittance(const vec3f& sigma, float d) {
    return {std::exp(-sigma.x * d), std::exp(-sigma.y * d), std::exp(-sigma.z * d)};
}

// Samples the direction a built-in material scatters the unit direction `wi` into, at a surface
// whose unit normal `n` faces the incoming ray. Returns false when the ray is absorbed. On
// success `dir` is a unit vector and `attenuation` the throughput weight.
inline bool scatter_builtin(const material_desc& m, const vec3f& wi, const vec3f& n, bool front_face, pcg32& rng,
                            vec3f& dir, vec3f& attenuation) {
    switch (m.kind) {
    case material_kind::lambertian: {
        float u1 = rng.next_float(), u2 = rng.next_float();
        dir = sample_cosine_direction(n, u1, u2);
        attenuation = m.albedo;
        return true;
    }
    case material_kind::metal: {
        vec3f d = reflect_f(wi, n);
        if (m.fuzz > 0) {
            float u1 = rng.next_float(), u2 = rng.next_float(), u3 = rng.next_float();
            d += m.fuzz * sample_unit_ball(u1, u2, u3);
        }
        // The book absorbs fuzzed directions that point below the surface.
        if (!(dot(d, n) > 0)) return false;
        dir = normalize(d);
        attenuation = m.albedo;
        return true;
    }
    case material_kind::dielectric: {
        float ri = front_face ? 1.0f / m.refraction_index : m.refraction_index;
        float cos_theta = std::fmin(-dot(wi, n), 1.0f);
        float sin_theta = std::sqrt(std::fmax(0.0f, 1.0f - cos_theta * cos_theta));
        bool cannot_refract = ri * sin_theta > 1.0f;
        if (cannot_refract || schlick_reflectance_f(cos_theta, ri) > rng.next_float())
            dir = reflect_f(wi, n);
        else
            dir = normalize(refract_f(wi, n, cos_theta, ri));
        attenuation = {1, 1, 1};
        return true;
    }
    case material_kind::conductor: {
        float cos_i = -dot(wi, n);
        dir = normalize(reflect_f(wi, n));
        vec3f fr{fresnel_conductor_f(cos_i, m.eta.x, m.k.x), fresnel_conductor_f(cos_i, m.eta.y, m.k.y),
                 fresnel_conductor_f(cos_i, m.eta.z, m.k.z)};
        attenuation = m.albedo * fr;
        return true;
    }
    case material_kind::exact_dielectric: {
        // Reflect with probability Fr exactly (Fr = 1 under total internal reflection), else
        // refract: the estimator's weight is 1 either way. Absorption is the caller's (Beer).
        float ri = front_face ? 1.0f / m.refraction_index : m.refraction_index; // n_i / n_t
        float eta = front_face ? m.refraction_index : 1.0f / m.refraction_index;
        float cos_theta = std::fmin(-dot(wi, n), 1.0f);
        float fr = fresnel_dielectric_f(cos_theta, eta);
        if (fr >= 1 || rng.next_float() < fr)
            dir = reflect_f(wi, n);
        else
            dir = normalize(refract_f(wi, n, cos_theta, ri));
        attenuation = {1, 1, 1};
        return true;
    }
    case material_kind::custom: break;
    }
    return false;
}

} // namespace rt
