#pragma once
// Light sampling: directions from a shading point p towards a point y on an emitting sphere,
// quad or triangle, with their solid-angle densities, and the density each sampler would have
// given a direction found otherwise (a material-sampled ray that hit the light), for multiple
// importance sampling. Pure functions of float vectors and explicit uniforms.
//
//   sample_sphere_light / sphere_light_pdf      the cone of directions the sphere subtends from
//                                               outside; uniform by area from inside
//   sample_quad_light / quad_light_pdf          spherical rectangles or area, chosen alike by both
//     sample_quad_area / quad_area_pdf          uniform by area
//     sample_quad_solid_angle /                 uniform by solid angle over a rectangle: Urena,
//     quad_solid_angle_pdf, quad_solid_angle    Fajardo and King, "An Area-Preserving
//                                               Parametrization for Spherical Rectangles", EGSR 2013
//   sample_triangle_light / triangle_light_pdf  uniform by area: Heitz, "A Low-Distortion Map
//                                               Between Triangle and Square", 2019
//   area_to_solid_angle                         p_A d^2 / |cos theta_y|
//   power_heuristic                             Veach, "Robust Monte Carlo Methods for Light
//                                               Transport Simulation", PhD thesis, 1997, ch. 9
//
// The sphere's cone, with the sampled point placed by its angle at the centre, follows Pharr,
// Jakob and Humphreys, Physically Based Rendering, 4th ed. (spheres, chapter 6); the solid-angle
// limits of the quad's choice are that book's (triangles and bilinear patches, chapter 6), and its
// conditioning limit was measured for this header (quad_max_condition). A sampler samples the
// whole shape: whether the side it sees emits is the caller's business. Each returns false when
// nothing can be sampled from p (p on the light's plane, degenerate geometry, a density float
// cannot hold).

#include "../core/constants.h"
#include "../core/sampling.h"
#include "../core/vec3f.h"

#include <cmath>

namespace rt {

struct light_sample {
    vec3f wi;            // unit direction from p towards the sampled point y
    float distance = 0;  // |y - p|
    vec3f y;             // the sampled point on the light
    vec3f n;             // the light's unit geometric normal at y: outward for spheres,
                         // cross(u, v) normalised for quads, cross(b - a, c - a) for triangles
    float pdf = 0;       // solid-angle density of wi at p (> 0 when the sampler returns true)
};

// How sample_quad_light and quad_light_pdf sample a quad. automatic: by solid angle when the quad
// looks large from p (quad_solid_angle_worth) and is a rectangle whose solid angle from p lies in
// [quad_min_solid_angle, quad_max_solid_angle] and which float can warp accurately from p
// (quad_max_condition), by area otherwise. area: always by area. solid_angle: by solid angle
// whenever the quad is a rectangle not seen edge-on, the thresholds ignored (for measurements).
enum class quad_sampling { automatic, area, solid_angle };

// Below 3e-4 sr the light is so small or far that the area-to-solid-angle factor varies little
// over it, so area sampling is about as good, and it stays exact where the spherical rectangle's
// float arithmetic starts to lose precision. Above 6.22 sr (within 0.063 of a hemisphere) p is
// nearly on the quad's plane, where the warp's divisions degenerate. These are pbrt-v4's
// MinSphericalSampleArea and MaxSphericalSampleArea.
inline constexpr float quad_min_solid_angle = 3e-4f;
inline constexpr float quad_max_solid_angle = 6.22f;
// Solid-angle sampling costs four arc tangents, a sine, a cosine and ten square roots per sample
// and as much again per density; area sampling, a few multiplications. The two differ in noise only
// where the factor d^2 / cos theta_y varies much over the quad, that is, where the quad looks large
// from p. So `automatic` builds the spherical rectangle only when a cheap estimate of the solid
// angle, A |cos theta_c| / d_c^2 at the quad's centre c, reaches this. Measured with nee at 64 spp,
// 300 wide, on 2 threads (BENCHMARKS.md, section 6), against solid angle wherever it applies:
// book 3's Cornell box, the same error in 0.71x the time; book 2's Cornell box, 1.01x the error
// in 0.69x the time; book 2's simple light (a 2x2 light a few units from the objects), 1.02x the
// error in the same time. Thresholds of 0.05, 0.2 and 0.5 traded the one against the other.
inline constexpr float quad_solid_angle_worth = 0.1f;
// Between those, the warp in float is still distorted where the rectangle is seen at a grazing
// angle or far off to the side (measured against the same warp in double over random rectangles:
// cells of 1/16 of the unit square carried up to 2.2 times their share of solid angle). Two
// condition numbers bound the rounding error's growth, and area sampling is used when either
// exceeds quad_max_condition (which kept the measured distortion below 0.4 %):
//   x:  x_far (x_far^2 + z0^2) / (z0^2 (x1 - x0)), the same in y, with (x, y, z0) the rectangle
//       in a frame at p with z across it: the warp finds x as z0 cu / sqrt(1 - cu^2), whose
//       relative error grows as (x^2 + z0^2) / z0^2, and the error counts against a cell's width;
//   sum |delta_i| / solid angle: the solid angle is a sum of four angles delta_i that cancel when
//       the rectangle is far off the axis (make_spherical_rectangle below).
inline constexpr float quad_max_condition = 1e3f;
// A quad counts as a rectangle when |cos| of the angle between its edges is at most this: edges
// made perpendicular in double and rounded to float are within 1e-7. The rectangle sampled is the
// one spanned by u and v's part across u, which differs from the quad by this fraction of |v|.
inline constexpr float quad_rectangle_tolerance = 1e-4f;

// The solid-angle density at p of the point y (unit normal ny) of a light sampled with area density
// area_pdf: area_pdf d^2 / |cos theta_y|. 0 when y is edge-on from p or is p (the density is
// unbounded there, on a set of directions of measure zero) or when the result overflows.
float area_to_solid_angle(float area_pdf, const vec3f& p, const vec3f& y, const vec3f& ny);

// Veach's power heuristic with beta = 2: pdf_a^2 / (pdf_a^2 + pdf_b^2), for a sample drawn by
// strategy a. A density that is not positive (0, negative, NaN) counts as 0: the weight is 0 when
// pdf_a is, 1 when only pdf_b is; an infinite density beats a finite one; two infinite give 1/2.
float power_heuristic(float pdf_a, float pdf_b);

// A uniform point of a triangle (by area) from two uniforms, as barycentric weights of its
// corners a, b, c (Heitz, "A Low-Distortion Map Between Triangle and Square", 2019).
struct barycentric {
    float b0 = 0, b1 = 0, b2 = 0;
};
barycentric uniform_triangle_point(float u1, float u2);

// The sphere of centre c and radius r. From outside: uniform over the cone of directions it
// subtends, y the near point where the direction meets it, pdf 1 / (cone solid angle). From inside
// or on it: y uniform by area, pdf converted to solid angle.
bool sample_sphere_light(const vec3f& p, const vec3f& c, float r, float u1, float u2, light_sample& s);
// The density sample_sphere_light gives the direction from p to the point y (normal ny) of the
// sphere; y must be a point p sees (from outside, any point of the near side: the density is
// constant over the cone).
float sphere_light_pdf(const vec3f& p, const vec3f& c, float r, const vec3f& y, const vec3f& ny);

// The parallelogram Q + a u + b v, a, b in [0, 1] (book 2's quad), uniform by area.
bool sample_quad_area(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, float u1, float u2,
                      light_sample& s);
float quad_area_pdf(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, const vec3f& y,
                    const vec3f& ny);

// The rectangle Q + a u + b v (u perpendicular to v) uniform by the solid angle it subtends at p.
// False (and density 0) when the quad is not a rectangle or p is on its plane.
bool sample_quad_solid_angle(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, float u1, float u2,
                             light_sample& s);
// 1 / the solid angle; the caller guarantees the direction meets the quad.
float quad_solid_angle_pdf(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v);
// The solid angle the rectangle subtends at p, as the sampler computes it (0: not a rectangle, or
// p on its plane).
float quad_solid_angle(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v);

// The quad by the strategy `strategy` chooses for it from p; sampling and density always choose
// alike.
bool sample_quad_light(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, float u1, float u2,
                       light_sample& s, quad_sampling strategy = quad_sampling::automatic);
float quad_light_pdf(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, const vec3f& y,
                     const vec3f& ny, quad_sampling strategy = quad_sampling::automatic);

// The triangle (a, b, c), uniform by area.
bool sample_triangle_light(const vec3f& p, const vec3f& a, const vec3f& b, const vec3f& c, float u1, float u2,
                           light_sample& s);
float triangle_light_pdf(const vec3f& p, const vec3f& a, const vec3f& b, const vec3f& c, const vec3f& y,
                         const vec3f& ny);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// Fills s for the point y (normal n) drawn with area density area_pdf; the density is the one the
// matching *_pdf function computes, by the same expression.
inline bool finish_area_sample(const vec3f& p, const vec3f& y, const vec3f& n, float area_pdf, light_sample& s) {
    const vec3f to = y - p;
    const float d2 = length_squared(to);
    if (!(d2 > 0)) return false;
    s.distance = sqrt_f(d2);
    s.wi = to / s.distance;
    s.y = y;
    s.n = n;
    s.pdf = area_to_solid_angle(area_pdf, p, y, n);
    return s.pdf > 0;
}

// 1 - cos(theta_max) of the cone a sphere of radius r subtends at distance sqrt(d2) > r, as
// sin^2 / (1 + cos): no cancellation when the cone is narrow (1 - cos would round to 0 below
// theta_max ~ 3e-4 rad in float).
inline float sphere_cone_one_minus_cos(float d2, float r) {
    const float sin2_max = r * r / d2;
    return sin2_max / (1.0f + sqrt_f(fmax_inline(0.0f, 1.0f - sin2_max)));
}

// 1 / x when that is a finite positive density, else 0.
inline float density_from_measure(float measure) {
    const float pdf = 1.0f / measure;
    return measure > 0 && std::isfinite(pdf) ? pdf : 0.0f;
}

// Urena, Fajardo and King's spherical rectangle, in a frame with x along u, y along v's part
// across u, and z the normal turned away from p, so that the rectangle is the plane z = z0 < 0
// seen from p at the origin, spanning [x0, x1] x [y0, y1].
struct spherical_rectangle {
    vec3f ex, ey, ez;
    float x0 = 0, x1 = 0, y0 = 0, y1 = 0, z0 = 0;
    float b0 = 0, b1 = 0;   // z of the unit normals of the planes through p and the edges y = y0, y1
    float delta01 = 0;      // delta0 + delta1 (see make_spherical_rectangle)
    float delta23 = 0;      // delta2 + delta3
    float solid_angle = 0;  // 0: not a rectangle, or p on its plane
    bool accurate = false;  // float warps it accurately (the condition numbers of quad_max_condition)

    bool valid() const { return solid_angle > 0; }
};

// Whether float warps the rectangle accurately from p: both condition numbers of
// quad_max_condition within it, written without divisions (an overflow reads as ill-conditioned).
inline bool well_conditioned(const spherical_rectangle& r, float delta_abs_sum) {
    const float z2 = r.z0 * r.z0, k = quad_max_condition;
    const float xf = fmax_inline(std::fabs(r.x0), std::fabs(r.x1)), yf = fmax_inline(std::fabs(r.y0), std::fabs(r.y1));
    return xf * (xf * xf + z2) <= k * z2 * (r.x1 - r.x0) && yf * (yf * yf + z2) <= k * z2 * (r.y1 - r.y0) &&
           delta_abs_sum <= k * r.solid_angle;
}

// atan(y / x) for x > 0, to within 3 float ulps (2.1e-7 relative; std::atan2 gives 1.2e-7),
// without a call: the make-up of Cephes' atanf (Moshier, "Methods and Programs for Mathematical
// Functions", 1989), whose range reduction to |t| <= tan(pi / 8) (t = y / x, or (y - x) / (y + x)
// plus pi / 4, or -x / y plus pi / 2) and degree-9 odd polynomial are used here with one division
// and no branches. The four angles of a spherical rectangle then cost less than one call did.
inline float atan_of_ratio(float y, float x) {
    const float ay = std::fabs(y);
    const bool beyond_3pi_8 = ay > 2.414213562373095f * x, beyond_pi_8 = ay > 0.4142135623730950f * x;
    const float num = beyond_3pi_8 ? -x : beyond_pi_8 ? ay - x : ay;
    const float den = beyond_3pi_8 ? ay : beyond_pi_8 ? ay + x : x;
    const float base = beyond_3pi_8 ? 1.570796326794897f : beyond_pi_8 ? 0.7853981633974483f : 0.0f;
    const float t = num / den, z = t * t;
    const float odd = (((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) * z;
    return std::copysign(base + (odd * t + t), y);
}

// The set-up of the paper's algorithm 1. The interior angle of the spherical rectangle at the
// corner (x, y, z0) is gamma = atan2(|z0| |corner|, +-x y): a closed form of the angle between the
// normals of the planes through p and the two edges meeting there. Writing gamma_i = pi/2 - delta_i
// with delta_i = atan2(+-x y, |z0| |corner|), the solid angle gamma_0 + ... + gamma_3 - 2 pi is
// -(delta_0 + ... + delta_3): the 2 pi that would cancel against four angles near pi/2 is never
// formed, and each delta is precise to its own size.
// Kept out of line, with the accuracy test inside: the sampler and the pdf function then get
// bit-identical set-ups (inlined, a compiler may fuse multiply-adds differently at the two call
// sites, and the solid angle, a sum of cancelling angles, would differ in its last digits), so
// both make the same choice of strategy even at its thresholds, and report the same density.
#if defined(__GNUC__)
__attribute__((noinline))
#endif
inline spherical_rectangle make_spherical_rectangle(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v) {
    spherical_rectangle r;
    const float uu = length_squared(u), vv = length_squared(v), uv = dot(u, v);
    if (!(uu > 0 && vv > 0)) return r;
    if (!(uv * uv <= quad_rectangle_tolerance * quad_rectangle_tolerance * uu * vv)) return r;
    const vec3f normal = cross(u, v);
    const float normal_length = length(normal);
    if (!(normal_length > 0) || !std::isfinite(normal_length)) return r;
    const float u_length = sqrt_f(uu);
    r.ex = u / u_length;
    r.ez = normal / normal_length;
    r.ey = cross(r.ez, r.ex);
    const vec3f d = Q - p;
    r.x0 = dot(d, r.ex);
    r.y0 = dot(d, r.ey);
    r.z0 = dot(d, r.ez);
    if (r.z0 > 0) {
        r.z0 = -r.z0;
        r.ez = -r.ez;
    }
    if (!(r.z0 < 0)) return r; // p on the plane: no spherical rectangle
    r.x1 = r.x0 + u_length;
    r.y1 = r.y0 + dot(v, r.ey);
    const float z0 = r.z0, z2 = z0 * z0, az = -z0;
    const float x0 = r.x0, x1 = r.x1, y0 = r.y0, y1 = r.y1;
    // |corner| for the four corners (x0|x1, y0|y1, z0).
    const float c00 = sqrt_f(x0 * x0 + y0 * y0 + z2), c10 = sqrt_f(x1 * x1 + y0 * y0 + z2);
    const float c11 = sqrt_f(x1 * x1 + y1 * y1 + z2), c01 = sqrt_f(x0 * x0 + y1 * y1 + z2);
    // The corners in the order of the paper's angles g0..g3: (x1, y0), (x1, y1), (x0, y1), (x0, y0).
    const float delta0 = atan_of_ratio(x1 * y0, az * c10);
    const float delta1 = atan_of_ratio(-x1 * y1, az * c11);
    const float delta2 = atan_of_ratio(x0 * y1, az * c01);
    const float delta3 = atan_of_ratio(-x0 * y0, az * c00);
    r.delta01 = delta0 + delta1;
    r.delta23 = delta2 + delta3;
    r.b0 = -y0 / sqrt_f(y0 * y0 + z2);
    r.b1 = y1 / sqrt_f(y1 * y1 + z2);
    const float omega = -(r.delta01 + r.delta23);
    r.solid_angle = omega > 0 && std::isfinite(omega) ? omega : 0.0f;
    r.accurate = well_conditioned(r, std::fabs(delta0) + std::fabs(delta1) + std::fabs(delta2) + std::fabs(delta3));
    return r;
}

// The paper's algorithm 2, for (u1, u2) in [0, 1)^2: the point of the rectangle, as its offsets
// (a, b) along ex and ey from the corner Q. The angle a_u = u1 S + k (k = 2 pi - g2 - g3) is
// pi + beta with beta = (1 - u1)(delta2 + delta3) - u1 (delta0 + delta1), so cos and sin of a_u are
// -cos beta and -sin beta, taken of the small beta itself rather than of pi + beta rounded.
inline void sample_spherical_rectangle(const spherical_rectangle& r, float u1, float u2, float& a, float& b) {
    const float beta = (1.0f - u1) * r.delta23 - u1 * r.delta01;
    const float fu = (std::cos(beta) * r.b0 + r.b1) / std::sin(beta);
    // cu: the cosine of the angle of the plane through p that splits off the fraction u1.
    float cu = std::copysign(1.0f, fu) / sqrt_f(fu * fu + r.b0 * r.b0);
    cu = fmin_inline(fmax_inline(cu, -1.0f), 1.0f);
    float xu = -(cu * r.z0) / sqrt_f(fmax_inline(0.0f, 1.0f - cu * cu));
    if (!(xu >= r.x0)) xu = r.x0; // also catches the NaN of cu = +-1
    if (xu > r.x1) xu = r.x1;
    // Along that line the solid angle is uniform in the sine of the elevation h.
    const float dd = sqrt_f(xu * xu + r.z0 * r.z0);
    const float h0 = r.y0 / sqrt_f(dd * dd + r.y0 * r.y0);
    const float h1 = r.y1 / sqrt_f(dd * dd + r.y1 * r.y1);
    const float hv = h0 + u2 * (h1 - h0), hv2 = hv * hv;
    const float yv = hv2 < 1.0f - 1e-6f ? hv * dd / sqrt_f(1.0f - hv2) : r.y1;
    a = fmin_inline(fmax_inline(xu - r.x0, 0.0f), r.x1 - r.x0);
    b = fmin_inline(fmax_inline(yv - r.y0, 0.0f), r.y1 - r.y0);
}

// Whether the quad looks large enough from p for solid-angle sampling to pay (quad_solid_angle_worth).
// Out of line for the reason make_spherical_rectangle is: the sampler and the density must agree.
#if defined(__GNUC__)
__attribute__((noinline))
#endif
inline bool quad_looks_large(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v) {
    const vec3f normal = cross(u, v);
    const vec3f to = Q + 0.5f * (u + v) - p;
    const float d2 = length_squared(to);
    // |normal| = A, so |normal . to| = A d_c |cos theta_c|.
    return std::fabs(dot(normal, to)) >= quad_solid_angle_worth * d2 * sqrt_f(d2);
}

// The choice sample_quad_light and quad_light_pdf both make: true (and r the spherical rectangle)
// when `strategy` samples the quad by solid angle from p. `automatic` first asks the cheap
// quad_looks_large and builds the rectangle only if it does.
inline bool quad_by_solid_angle(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, quad_sampling strategy,
                                spherical_rectangle& r) {
    if (strategy == quad_sampling::area || (strategy == quad_sampling::automatic && !quad_looks_large(p, Q, u, v)))
        return false;
    r = make_spherical_rectangle(p, Q, u, v);
    if (!r.valid()) return false;
    if (strategy == quad_sampling::solid_angle) return true;
    // Comparisons only, of values made out of line: the same answer for the sampler and the pdf.
    return r.solid_angle >= quad_min_solid_angle && r.solid_angle <= quad_max_solid_angle && r.accurate;
}

inline bool sample_rectangle(const spherical_rectangle& r, const vec3f& p, const vec3f& Q, const vec3f& u,
                             const vec3f& v, float u1, float u2, light_sample& s) {
    float a, b;
    sample_spherical_rectangle(r, u1, u2, a, b);
    // From the corner along the edges, so y lies on the quad's plane whatever p's distance.
    const vec3f y = Q + a * r.ex + b * r.ey;
    const vec3f to = y - p;
    const float d2 = length_squared(to);
    if (!(d2 > 0) || !is_finite(y)) return false;
    s.distance = sqrt_f(d2);
    s.wi = to / s.distance;
    s.y = y;
    s.n = normalize(cross(u, v));
    s.pdf = density_from_measure(r.solid_angle);
    return s.pdf > 0;
}

} // namespace detail

inline barycentric uniform_triangle_point(float u1, float u2) {
    // Heitz's map: the square is cut along its diagonal and each half mapped linearly onto the
    // triangle (one coordinate halved, the other sheared), which keeps areas (uniform) with no
    // square root and less distortion than the sqrt(u1) warp.
    barycentric w;
    if (u1 < u2) {
        w.b0 = 0.5f * u1;
        w.b1 = u2 - w.b0;
    } else {
        w.b1 = 0.5f * u2;
        w.b0 = u1 - w.b1;
    }
    w.b2 = 1.0f - w.b0 - w.b1;
    return w;
}

inline float area_to_solid_angle(float area_pdf, const vec3f& p, const vec3f& y, const vec3f& ny) {
    const vec3f to = y - p;
    const float d2 = length_squared(to);
    const float cos_y = std::fabs(dot(ny, to)) / sqrt_f(d2);
    const float pdf = area_pdf * d2 / cos_y;
    return cos_y > 0 && std::isfinite(pdf) ? pdf : 0.0f;
}

inline float power_heuristic(float pdf_a, float pdf_b) {
    if (!(pdf_a > 0)) return 0.0f;
    if (!(pdf_b > 0)) return 1.0f;
    // As 1 / (1 + (b/a)^2): squares that would overflow or underflow on their own are never formed.
    const float ratio = pdf_b / pdf_a;
    if (std::isnan(ratio)) return 0.5f; // both infinite
    return 1.0f / (1.0f + ratio * ratio);
}

inline bool sample_sphere_light(const vec3f& p, const vec3f& c, float r, float u1, float u2, light_sample& s) {
    if (!(r > 0)) return false;
    const vec3f to_centre = c - p;
    const float d2 = length_squared(to_centre);
    if (d2 <= r * r) {
        // Inside or on the sphere every point of it is seen: uniform by area.
        const vec3f n = sample_unit_sphere(u1, u2);
        return detail::finish_area_sample(p, c + r * n, n, 1.0f / (4.0f * pi_f * r * r), s);
    }
    const float one_minus_cos_max = detail::sphere_cone_one_minus_cos(d2, r);
    const float pdf = detail::density_from_measure(2.0f * pi_f * one_minus_cos_max);
    if (!(pdf > 0)) return false; // too small or far for float to see
    const float d = sqrt_f(d2);
    const vec3f w = to_centre / d;
    const float sin_max = r / d, sin2_max = sin_max * sin_max;
    // theta uniform in cos over [cos theta_max, 1], kept as t = 1 - cos theta (exact for narrow
    // cones), sin^2 theta = t (2 - t).
    const float t = u1 * one_minus_cos_max;
    const float cos_theta = 1.0f - t;
    const float sin2_theta = t * (2.0f - t);
    const float sin_theta = sqrt_f(sin2_theta);
    // The point is placed by the angle alpha at the centre between p and y, rather than by
    // intersecting the ray, so it lies on the sphere even when the sphere is tiny beside d. In the
    // triangle (p, c, y) the angle at y has sine sin theta / sin theta_max (law of sines) and is
    // obtuse at the near point; with B = its |cosine|:
    //   cos alpha = sin^2 theta / sin theta_max + cos theta B
    //   sin alpha = sin theta cos^2 theta_max / (sin theta_max (cos theta + sin theta_max B)),
    // the second being sin theta (cos theta / sin theta_max - B) with the difference multiplied
    // out: every term is positive, so neither cancels.
    const float B = sqrt_f(fmax_inline(0.0f, 1.0f - fmin_inline(1.0f, sin2_theta / sin2_max)));
    const float cos_alpha = sin2_theta / sin_max + cos_theta * B;
    const float sin_alpha = sin_theta * (1.0f - sin2_max) / (sin_max * (cos_theta + sin_max * B));
    vec3f e1, e2;
    frame_across(w, e1, e2);
    const vec3f circle = unit_circle(u2);
    const vec3f n = normalize(-cos_alpha * w + (sin_alpha * circle.x) * e1 + (sin_alpha * circle.y) * e2);
    const vec3f y = c + r * n;
    const vec3f to = y - p;
    const float dist2 = length_squared(to);
    if (!(dist2 > 0) || !is_finite(y)) return false;
    s.distance = sqrt_f(dist2);
    s.wi = to / s.distance;
    s.y = y;
    s.n = n;
    s.pdf = pdf;
    return true;
}

inline float sphere_light_pdf(const vec3f& p, const vec3f& c, float r, const vec3f& y, const vec3f& ny) {
    if (!(r > 0)) return 0.0f;
    const vec3f to_centre = c - p;
    const float d2 = length_squared(to_centre);
    if (d2 <= r * r) return area_to_solid_angle(1.0f / (4.0f * pi_f * r * r), p, y, ny);
    return detail::density_from_measure(2.0f * pi_f * detail::sphere_cone_one_minus_cos(d2, r));
}

inline bool sample_quad_area(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, float u1, float u2,
                             light_sample& s) {
    const vec3f normal = cross(u, v);
    const float area = length(normal);
    if (!(area > 0)) return false;
    return detail::finish_area_sample(p, Q + u1 * u + u2 * v, normal / area, 1.0f / area, s);
}

inline float quad_area_pdf(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, const vec3f& y,
                           const vec3f& ny) {
    (void)Q;
    const float area = length(cross(u, v));
    if (!(area > 0)) return 0.0f;
    return area_to_solid_angle(1.0f / area, p, y, ny);
}

inline bool sample_quad_solid_angle(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, float u1,
                                    float u2, light_sample& s) {
    const detail::spherical_rectangle r = detail::make_spherical_rectangle(p, Q, u, v);
    return r.valid() && detail::sample_rectangle(r, p, Q, u, v, u1, u2, s);
}

inline float quad_solid_angle(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v) {
    return detail::make_spherical_rectangle(p, Q, u, v).solid_angle;
}

inline float quad_solid_angle_pdf(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v) {
    return detail::density_from_measure(quad_solid_angle(p, Q, u, v));
}

inline bool sample_quad_light(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, float u1, float u2,
                              light_sample& s, quad_sampling strategy) {
    detail::spherical_rectangle r;
    if (detail::quad_by_solid_angle(p, Q, u, v, strategy, r)) return detail::sample_rectangle(r, p, Q, u, v, u1, u2, s);
    return sample_quad_area(p, Q, u, v, u1, u2, s);
}

inline float quad_light_pdf(const vec3f& p, const vec3f& Q, const vec3f& u, const vec3f& v, const vec3f& y,
                            const vec3f& ny, quad_sampling strategy) {
    detail::spherical_rectangle r;
    if (detail::quad_by_solid_angle(p, Q, u, v, strategy, r)) return detail::density_from_measure(r.solid_angle);
    return quad_area_pdf(p, Q, u, v, y, ny);
}

inline bool sample_triangle_light(const vec3f& p, const vec3f& a, const vec3f& b, const vec3f& c, float u1,
                                  float u2, light_sample& s) {
    const vec3f normal = cross(b - a, c - a);
    const float twice_area = length(normal);
    if (!(twice_area > 0)) return false;
    const barycentric w = uniform_triangle_point(u1, u2);
    return detail::finish_area_sample(p, w.b0 * a + w.b1 * b + w.b2 * c, normal / twice_area, 2.0f / twice_area, s);
}

inline float triangle_light_pdf(const vec3f& p, const vec3f& a, const vec3f& b, const vec3f& c, const vec3f& y,
                                const vec3f& ny) {
    const float twice_area = length(cross(b - a, c - a));
    if (!(twice_area > 0)) return 0.0f;
    return area_to_solid_angle(2.0f / twice_area, p, y, ny);
}

} // namespace rt
