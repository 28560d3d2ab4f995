#pragma once
// fresnel: the exact (unpolarised) Fresnel reflectance of smooth interfaces.
//
//   double fresnel_dielectric(double cos_i, double eta);     // eta = n_transmitted / n_incident
//   double fresnel_conductor(double cos_i, double n, double k); // index n + ik, seen from index 1
//   float  fresnel_dielectric_f(float cos_i, float eta);     // the same, for the float kernels
//   float  fresnel_conductor_f(float cos_i, float n, float k);
//   vec3f  fresnel_conductor_f(float cos_i, vec3f n, vec3f k); // per channel: coloured metals
//   T      schlick_reflectance(T cos_i, T ri);                 // Schlick's approximation
//
// cos_i is the cosine of the angle of incidence, measured on the incident side, in [0, 1]
// (values outside are clamped; NaN reads as grazing). The result is the reflected fraction of
// unpolarised light, the mean of the s- and p-polarised reflectances, in [0, 1]:
//   - fresnel_dielectric returns exactly 1 beyond the critical angle (total internal
//     reflection, possible when eta < 1) and at grazing incidence; eta must be positive.
//   - fresnel_conductor needs n > 0, k >= 0, both below 1e70 (the renderer stores them as float,
//     far inside that); with k = 0 it equals fresnel_dielectric(cos_i, n). At normal incidence it
//     is ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
//
// Schlick's approximation (C. Schlick, "An Inexpensive BRDF Model for Physically-based Rendering",
// 1994), which the book's glass uses: r0 + (1 - r0)(1 - cos)^5 with r0 = ((1 - ri)/(1 + ri))^2, for
// the ratio ri of refractive indices, in double and float.

#include "vec3f.h"

namespace rt {

double fresnel_dielectric(double cos_i, double eta);
double fresnel_conductor(double cos_i, double n, double k);
float fresnel_dielectric_f(float cos_i, float eta);
float fresnel_conductor_f(float cos_i, float n, float k);
vec3f fresnel_conductor_f(float cos_i, const vec3f& n, const vec3f& k);

template <class T>
T schlick_reflectance(T cosine, T ri) {
    T r0 = (1 - ri) / (1 + ri);
    r0 = r0 * r0;
    T m = 1 - cosine;
    return r0 + (1 - r0) * (m * m * m * m * m);
}

} // namespace rt

// --- IMPLEMENTATION -----------------------------------------------------------------------------

#include <cmath>

namespace rt {

namespace detail {

template <class T> T clamp_cosine(T c) { return fmin_inline(fmax_inline(c, T(0)), T(1)); } // NaN -> 0

// Fresnel's equations for a dielectric, divided through by n_incident (E. Hecht, Optics, 5th ed.,
// section 4.6.2, eqs. 4.42 and 4.43; M. Pharr, W. Jakob, G. Humphreys, Physically Based
// Rendering, 3rd ed., section 8.2.1, eq. 8.2):
//   r_s = (cos_i - eta cos_t) / (cos_i + eta cos_t),  r_p = (eta cos_i - cos_t) / (eta cos_i + cos_t)
// with cos_t from Snell's law, sin_t = sin_i / eta. R = (r_s^2 + r_p^2) / 2.
template <class T> T fresnel_dielectric_impl(T cos_i, T eta) {
    cos_i = clamp_cosine(cos_i);
    T sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1; // total internal reflection (and grazing incidence at eta = 1)
    T cos_t = std::sqrt(1 - sin2_t);
    T rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    T rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return (rs * rs + rp * rp) / 2;
}

} // namespace detail

inline double fresnel_dielectric(double cos_i, double eta) { return detail::fresnel_dielectric_impl(cos_i, eta); }

inline float fresnel_dielectric_f(float cos_i, float eta) { return detail::fresnel_dielectric_impl(cos_i, eta); }

// Fresnel's equations with the complex index n + ik, in the closed form of pbrt-v3's FrConductor
// (Pharr, Jakob, Humphreys, Physically Based Rendering, 3rd ed., section 8.2.1, following
// S. Lagarde, "Memo on Fresnel equations", 2013): with a + ib = sqrt((n + ik)^2 - sin_i^2),
//   R_s = (a^2 + b^2 + cos^2 - 2 a cos) / (a^2 + b^2 + cos^2 + 2 a cos)
//   R_p = R_s (cos^2 (a^2 + b^2) + sin^4 - 2 a cos sin^2) / (cos^2 (a^2 + b^2) + sin^4 + 2 a cos sin^2)
// and R = (R_s + R_p) / 2.
inline double fresnel_conductor(double cos_i, double n, double k) {
    double c = detail::clamp_cosine(cos_i), c2 = c * c, s2 = 1 - c2;
    double t0 = n * n - k * k - s2;                     // real part of a^2 - b^2 + 2iab
    double a2_plus_b2 = std::sqrt(t0 * t0 + 4 * n * n * k * k);
    // a = sqrt((|z| + Re z) / 2) loses every digit when Re z is large and negative (a metal's
    // k^2 >> n^2); there the imaginary part gives it without cancellation: a b = n k.
    double a = t0 >= 0 ? std::sqrt(0.5 * (a2_plus_b2 + t0)) : n * k / std::sqrt(0.5 * (a2_plus_b2 - t0));
    double t1 = a2_plus_b2 + c2, t2 = 2 * c * a;
    double rs = (t1 - t2) / (t1 + t2);
    double t3 = c2 * a2_plus_b2 + s2 * s2, t4 = t2 * s2;
    double rp = rs * (t3 - t4) / (t3 + t4);
    // t1 - t2 cancels where R is near 0 (n near 1, k near 0): keep rounding from going negative.
    return fmax_inline(0.0, 0.5 * (rs + rp));
}

// In double inside: k^2 of a good conductor squared again (t0 * t0) leaves float's range early.
inline float fresnel_conductor_f(float cos_i, float n, float k) {
    return static_cast<float>(fresnel_conductor(cos_i, n, k));
}

inline vec3f fresnel_conductor_f(float cos_i, const vec3f& n, const vec3f& k) {
    return {fresnel_conductor_f(cos_i, n.x, k.x), fresnel_conductor_f(cos_i, n.y, k.y), fresnel_conductor_f(cos_i, n.z, k.z)};
}

} // namespace rt
