#pragma once
// The standard mesh workload of shared/formats/rays.md: three ray files generated from a mesh's
// bounding box and a closest-hit tracer, so that any two tracers can be timed on the same rays.
//
//   make_standard_workload(box_lo, box_hi, hit, resolution = 1024)  -> workload{primary, diffuse, shadow}
//
// `hit(const rt::ray3f&, float& t, rt::vec3f& geometric_normal) -> bool` is the closest hit
// between the ray's tmin and tmax; the normal may have any length and either orientation.
//
// The exact choices, so that another implementation can reproduce the files given the same
// tracer answers (all geometry in double, rounded to float only when a ray is stored). Bit for
// bit needs the same floating-point contraction too: with -march=native, GCC fuses multiply-adds
// by default (GNU mode), which moves the last bit of some coordinates.
//
//   c = (lo + hi) / 2, R = |hi - lo| / 2 (half the box diagonal).
//   Camera: eye = c + d * normalize(0.45, 0.35, 1), d = R / sin(20 deg), so the sphere of radius
//     R about c just fills the vertical field of view of 40 degrees. forward w = normalize(c - eye),
//     right u = normalize(cross(w, (0,1,0))), up v = cross(u, w). The image is square, N x N.
//   primary (kind closest): pixel (i, j), i = 0..N-1 left to right, j = 0..N-1 top to bottom,
//     pixel index j * N + i, in that order. x = (2 (i + 0.5) / N - 1) tan 20deg,
//     y = (1 - 2 (j + 0.5) / N) tan 20deg, direction normalize(w + x u + y v), origin eye,
//     tmin 0, tmax +inf.
//   For each primary ray that hits, in pixel order: p = o + t d (from the stored float ray),
//     n = normalize(geometric normal), flipped so that dot(n, d) < 0 (it faces the incoming ray),
//     q = p + 1e-4 R n, the origin of both secondary rays (stored as float).
//   diffuse (kind closest), one per primary hit: direction rt::sample_cosine_direction(n, u1, u2)
//     with u1 then u2 = next_float() of rt::sample_rng(0, pixel index, 0); origin q, tmin 0,
//     tmax +inf.
//   shadow (kind any), only where dot(n, L - p) > 0 (the light is above the surface):
//     L = c + 3 R normalize(-0.5, 1, 0.6); from the stored origin q towards L: direction
//     normalize(L - q), tmin 0, tmax = |L - q| (1 - 1e-4), just short of the light.
//
// A tracer answer that cannot be right (t outside the ray's range or not finite, a zero or
// non-finite normal) throws rt::scene_error rather than producing a subtly different workload.

#include <rtweekend/core/constants.h>
#include <rtweekend/io/ray_file.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/core/sampling.h>
#include <rtweekend/core/scene_error.h>
#include <rtweekend/vec3.h>
#include <rtweekend/core/vec3f.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

namespace app {

struct workload {
    rt::ray_batch primary, diffuse, shadow;
};

// The camera and light of the standard workload for one bounding box, in double.
struct standard_view {
    rt::vec3 centre;
    double radius = 0; // half the box diagonal
    rt::vec3 eye, forward, right, up;
    double tan_half_fov = 0;
    rt::vec3 light;
};

inline constexpr double standard_vfov_degrees = 40;
inline constexpr double standard_offset_scale = 1e-4;      // secondary origins move 1e-4 R off the surface
inline constexpr double standard_shadow_shortening = 1e-4; // shadow rays stop this fraction short of the light

inline standard_view make_standard_view(rt::vec3f box_lo, rt::vec3f box_hi) {
    rt::vec3 lo = box_lo.to_double(), hi = box_hi.to_double();
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]) || !(lo[k] <= hi[k]))
            throw rt::scene_error("standard workload: the bounding box is empty or not finite");
    standard_view v;
    v.centre = 0.5 * (lo + hi);
    v.radius = 0.5 * (hi - lo).length();
    if (!(v.radius > 0)) throw rt::scene_error("standard workload: the bounding box is a single point");
    double half_fov = rt::degrees_to_radians(0.5 * standard_vfov_degrees);
    v.tan_half_fov = std::tan(half_fov);
    v.eye = v.centre + (v.radius / std::sin(half_fov)) * rt::unit_vector(rt::vec3(0.45, 0.35, 1));
    v.forward = rt::unit_vector(v.centre - v.eye);
    v.right = rt::unit_vector(rt::cross(v.forward, rt::vec3(0, 1, 0)));
    v.up = rt::cross(v.right, v.forward);
    v.light = v.centre + 3 * v.radius * rt::unit_vector(rt::vec3(-0.5, 1, 0.6));
    return v;
}

namespace detail {

// Rounds to float through volatile memory. GCC 12.2's SLP vectorizer folds the pair
// double(float(x)) back to x when it vectorizes both conversions (seen at -O2), which would let a
// ray's stored origin and the origin used to aim it differ by a rounding. The volatile store is
// opaque to that folding; it costs nothing measurable here.
inline rt::vec3f to_float(const rt::vec3& v) {
    volatile float x = float(v.x()), y = float(v.y()), z = float(v.z());
    return {x, y, z};
}

inline rt::vec3 to_double(const rt::vec3f& v) { return v.to_double(); }

} // namespace detail

// The primary ray through the centre of pixel (i, j) of an N x N image.
inline rt::ray3f standard_primary_ray(const standard_view& v, int i, int j, int resolution) {
    double n = resolution;
    double x = (2 * (i + 0.5) / n - 1) * v.tan_half_fov;
    double y = (1 - 2 * (j + 0.5) / n) * v.tan_half_fov;
    rt::ray3f r;
    r.origin = detail::to_float(v.eye);
    r.dir = detail::to_float(rt::unit_vector(v.forward + x * v.right + y * v.up));
    r.tmin = 0;
    r.tmax = std::numeric_limits<float>::infinity();
    return r;
}

template <class ClosestHit>
workload make_standard_workload(rt::vec3f box_lo, rt::vec3f box_hi, ClosestHit&& hit, int resolution = 1024) {
    if (resolution < 1 || resolution > (1 << 15))
        throw rt::scene_error("standard workload: resolution " + std::to_string(resolution) + " is out of range");
    const standard_view view = make_standard_view(box_lo, box_hi);
    const double offset = standard_offset_scale * view.radius;

    workload w;
    w.primary.kind = rt::ray_query::closest;
    w.diffuse.kind = rt::ray_query::closest;
    w.shadow.kind = rt::ray_query::any;
    w.primary.rays.reserve(size_t(resolution) * size_t(resolution));

    for (int j = 0; j < resolution; ++j) {
        for (int i = 0; i < resolution; ++i) {
            const size_t pixel = size_t(j) * size_t(resolution) + size_t(i);
            const rt::ray3f ray = standard_primary_ray(view, i, j, resolution);
            w.primary.rays.push_back(ray);

            float t = 0;
            rt::vec3f normal_f;
            if (!hit(ray, t, normal_f)) continue;
            if (!std::isfinite(t) || t < ray.tmin || t > ray.tmax)
                throw rt::scene_error("standard workload: the tracer returned t = " + std::to_string(t) +
                                      " for pixel " + std::to_string(pixel));
            rt::vec3 n = detail::to_double(normal_f);
            double n_len = n.length();
            if (!std::isfinite(n_len) || !(n_len > 0))
                throw rt::scene_error("standard workload: the tracer returned an unusable normal for pixel " +
                                      std::to_string(pixel));
            n = n / n_len;
            const rt::vec3 d = detail::to_double(ray.dir);
            if (rt::dot(n, d) > 0) n = -n;
            const rt::vec3 p = detail::to_double(ray.origin) + double(t) * d;
            const rt::vec3f q = detail::to_float(p + offset * n);

            rt::pcg32 rng = rt::sample_rng(0, pixel, 0);
            float u1 = rng.next_float();
            float u2 = rng.next_float();
            rt::ray3f diffuse;
            diffuse.origin = q;
            diffuse.dir = rt::sample_cosine_direction(detail::to_float(n), u1, u2);
            diffuse.tmin = 0;
            diffuse.tmax = std::numeric_limits<float>::infinity();
            w.diffuse.rays.push_back(diffuse);

            if (rt::dot(n, view.light - p) > 0) {
                rt::vec3 to_light = view.light - detail::to_double(q);
                double distance = to_light.length();
                rt::ray3f shadow;
                shadow.origin = q;
                shadow.dir = detail::to_float(to_light / distance);
                shadow.tmin = 0;
                shadow.tmax = float(distance * (1 - standard_shadow_shortening));
                w.shadow.rays.push_back(shadow);
            }
        }
    }
    return w;
}

} // namespace app
