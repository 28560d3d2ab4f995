#pragma once
// camera_frame: the geometry that turns a pixel position into a ray, in float. The book's camera
// (camera.h) computes one from its settings. Rays start at `eye`, the camera's position relative to
// the origin of the compiled scene it looks at (placed_in): zero when the scene was compiled
// around the camera, as the book's camera::render compiles it, and the camera's offset from the
// scene's origin when several cameras share one compiled scene.

#include "../core/scene_error.h"
#include "../vec3.h"
#include "../core/force_inline.h"
#include "../core/rng.h"
#include "pixel_filter.h"
#include "sampler.h"
#include "../core/sampling.h"
#include "../core/simd.h"
#include "../core/vec3f.h"

#include <cmath>
#include <string>

namespace rt {

struct camera_frame {
    int width = 0, height = 0;
    point3 position;            // where rays start (lookfrom), in world coordinates
    vec3f pixel00;              // centre of the top-left pixel, relative to position
    vec3f pixel_delta_u;        // offset to the pixel on the right
    vec3f pixel_delta_v;        // offset to the pixel below
    vec3f defocus_disk_u;       // defocus disk horizontal radius
    vec3f defocus_disk_v;       // defocus disk vertical radius
    bool thin_lens = false;     // defocus_angle > 0: rays start on the lens disk
    vec3f eye{0, 0, 0};         // position relative to the scene origin (placed_in)
    bool eye_at_origin = true;  // eye is zero: nothing to add
    // How a pixel weighs the image around its centre (pixel_filter.h): the books' box by default.
    // Other filters draw each sample's offset from the filter and give it a weight (sample_rays).
    pixel_filter filter = pixel_filter::box();

    // This frame looking at a scene compiled around `origin`: rays start at position - origin.
    // Throws scene_error when that is beyond float's range for the scene (1e18).
    camera_frame placed_in(const point3& origin) const {
        camera_frame f = *this;
        const vec3 offset = position - origin;
        if (!(std::fabs(offset.x()) < 1e18 && std::fabs(offset.y()) < 1e18 && std::fabs(offset.z()) < 1e18))
            throw scene_error("camera position is out of single-precision range: it must be within 1e18 of the "
                              "scene's origin");
        f.eye = vec3f(offset);
        f.eye_at_origin = f.eye.x == 0 && f.eye.y == 0 && f.eye.z == 0;
        return f;
    }

    // The ray through image position (x, y), in pixels from the top-left corner of the image
    // ((i + 0.5, j + 0.5) is the centre of pixel (i, j)), starting at lens position (lu, lv) in
    // the unit disk. Direction normalised; origin relative to the scene origin (eye + the lens point).
    ray3f generate(float x, float y, float lu = 0, float lv = 0) const {
        vec3f target = pixel00 + (x - 0.5f) * pixel_delta_u + (y - 0.5f) * pixel_delta_v;
        vec3f origin = thin_lens ? lu * defocus_disk_u + lv * defocus_disk_v : vec3f{};
        ray3f r{origin, normalize(target - origin)};
        if (!eye_at_origin) r.origin = eye + r.origin;
        return r;
    }

    // A camera ray for pixel (x, y): jittered uniformly over the pixel (through its centre when
    // the pixel takes a single sample, as in the book's chapters before antialiasing), from a
    // uniform point of the lens disk when the camera has a thin lens, and `with_time`, at a time
    // uniform in the shutter interval [0, 1) (book 2's ray_time = random_double()). The time is
    // drawn last, and only when asked for: a scene where nothing depends on time draws the
    // random numbers it drew before motion blur existed.
    // `weight`, when given, receives the sample's filter weight (see sample_rays).
    ray3f sample_ray(int x, int y, int samples_per_pixel, pixel_sampler& ps, bool with_time = false,
                     float* weight = nullptr) const {
        pixel_sampler* const one[1] = {&ps};
        ray3f r[sample_lanes::capacity];
        float w[sample_lanes::capacity];
        sample_rays(1, &x, &y, one, samples_per_pixel, with_time, r, w);
        if (weight) *weight = w[0];
        return r[0];
    }
    // The same for n <= sample_lanes::capacity samples at once (the path tracer's batches): ray k
    // for pixel (x[k], y[k]) from samplers[k]; `out` holds sample_lanes::capacity rays. With a
    // filter other than the box, `weights` (when not null) receives each sample's filter weight,
    // by which its radiance is multiplied (1 for the box, and for a single sample through the
    // pixel's centre). Every step
    // works on all the lanes together (floatv, and sample_lanes' loops), one instruction for up to
    // sixteen samples where the path tracer spent a tenth of the cover scene's time on them one
    // at a time.
    void sample_rays(int n, const int* x, const int* y, pixel_sampler* const* samplers, int samples_per_pixel,
                     bool with_time, ray3f* out, float* weights = nullptr) const;
    // The other way round, for paths that start at the lights (caustic_paths.h): where the camera
    // sees the point x from the lens point `lens` (both relative to the scene origin, as rays are;
    // the lens point is eye for a pinhole). Fills the unit direction from the lens to x, the distance,
    // the image position in pixels (as generate() takes it) and the importance factor
    //   h^2 / (A_pixel cos^3 theta d^2),
    // with h the distance from the lens to the plane of pixel centres, A_pixel a pixel's area on
    // that plane, theta the angle between the direction and the plane's normal and d the distance:
    // a pixel's value is the mean radiance over the uniform points of its square on that plane,
    // and a patch dA of a surface at x facing the lens at angle theta_x covers
    // h^2 cos theta_x dA / (cos^3 theta d^2) of the plane (pbrt, 4th ed., 5.4.2, for a pinhole;
    // from each lens point alike). The caller multiplies in cos theta_x. False when x is behind
    // the lens or outside the image.
    struct connection {
        vec3f dir;
        float distance = 0;
        float px = 0, py = 0;
        float importance = 0;
    };
    bool connect(const vec3f& x_in_scene, const vec3f& lens_in_scene, connection& c) const {
        // In the camera's frame: relative to its position.
        const vec3f x = eye_at_origin ? x_in_scene : x_in_scene - eye;
        const vec3f lens = eye_at_origin ? lens_in_scene : lens_in_scene - eye;
        const vec3f across = cross(pixel_delta_u, pixel_delta_v);
        const float pixel_area = length(across);
        if (!(pixel_area > 0)) return false;
        vec3f normal = across / pixel_area;
        float h = dot(normal, pixel00 - lens);
        if (h < 0) {
            normal = -normal;
            h = -h;
        }
        const vec3f to = x - lens;
        const float d2 = length_squared(to);
        if (!(d2 > 0) || !(h > 0)) return false;
        c.distance = sqrt_f(d2);
        c.dir = to / c.distance;
        const float cos_theta = dot(normal, c.dir);
        if (!(cos_theta > 0)) return false;
        const vec3f on_plane = lens + (h / cos_theta) * c.dir - pixel00;
        c.px = dot(on_plane, pixel_delta_u) / length_squared(pixel_delta_u) + 0.5f;
        c.py = dot(on_plane, pixel_delta_v) / length_squared(pixel_delta_v) + 0.5f;
        // Inside the image, or (a filter wider than the pixel) within reach of its edge pixels.
        const float margin = filter.is_box() ? 0.0f : float(filter.radius()) - 0.5f;
        if (!(c.px >= -margin && c.px < float(width) + margin && c.py >= -margin && c.py < float(height) + margin))
            return false;
        c.importance = h * h / (pixel_area * cos_theta * cos_theta * cos_theta * d2);
        return std::isfinite(c.importance);
    }
    // The same with every number from `rng`, in the order above.
    ray3f sample_ray(int x, int y, int samples_per_pixel, pcg32& rng, bool with_time = false,
                     float* weight = nullptr) const {
        const sampler_plan independent;
        pixel_sampler ps(independent, x, y, 0, rng);
        return sample_ray(x, y, samples_per_pixel, ps, with_time, weight);
    }
};

inline void camera_frame::sample_rays(int n, const int* x, const int* y, pixel_sampler* const* samplers,
                                      int samples_per_pixel, bool with_time, ray3f* out, float* weights) const {
    constexpr int lanes = sample_lanes::capacity;
    constexpr int W = int(floatv::width);
    static_assert(lanes % W == 0, "a batch is a whole number of SIMD registers");
    sample_lanes numbers(samplers, n);
    alignas(64) float px[lanes] = {}, py[lanes] = {}, lu[lanes] = {}, lv[lanes] = {}, dir[3][lanes], org[3][lanes];
    // The point in the pixel: uniform over it, or its centre for a single sample.
    if (weights)
        for (int k = 0; k < n; ++k) weights[k] = 1;
    if (samples_per_pixel > 1) {
        numbers.get2d(sample_dimension::camera_pixel, px, py);
        if (!filter.is_box())
            for (int k = 0; k < n; ++k) {
                // The offset from the centre drawn from the filter, and the sample's weight.
                float wx = 1, wy = 1;
                px[k] = 0.5f + filter.sample(px[k], wx);
                py[k] = 0.5f + filter.sample(py[k], wy);
                if (weights) weights[k] = wx * wy;
            }
    } else {
        for (int k = 0; k < lanes; ++k) px[k] = py[k] = 0.5f;
    }
    for (int k = 0; k < n; ++k) {
        px[k] += float(x[k]);
        py[k] += float(y[k]);
    }
    // The point on the lens: uniform on the unit disk (sample_unit_disk, lane by lane).
    if (thin_lens) numbers.get2d(sample_dimension::camera_lens, lu, lv);
    for (int k = 0; k < lanes; k += W) {
        floatv lens_u(0.0f), lens_v(0.0f);
        if (thin_lens) {
            const floatv radius = sqrt(floatv::load(lu + k)), u = floatv::load(lv + k);
            // unit_circle(u) (sampling.h), its four quarter turns chosen by selects.
            const floatv quarter = round_nearest(floatv(4.0f) * u);
            const floatv a = (u - floatv(0.25f) * quarter) * floatv(2.0f * pi_f), a2 = a * a;
            const floatv sine = a * (floatv(1.0f) + a2 * (floatv(-1.0f / 6) + a2 * (floatv(1.0f / 120) + a2 * (floatv(-1.0f / 5040) + a2 * floatv(1.0f / 362880)))));
            const floatv cosine = floatv(1.0f) + a2 * (floatv(-1.0f / 2) + a2 * (floatv(1.0f / 24) + a2 * (floatv(-1.0f / 720) + a2 * floatv(1.0f / 40320))));
            const maskv odd = (quarter == floatv(1.0f)) | (quarter == floatv(3.0f));
            const maskv half = (quarter == floatv(2.0f)) | (quarter == floatv(3.0f));
            floatv cx = select(odd, -sine, cosine), cy = select(odd, cosine, sine);
            cx = select(half, -cx, cx);
            cy = select(half, -cy, cy);
            lens_u = radius * cx;
            lens_v = radius * cy;
        }
        // generate(): the pixel's point on the plane of pixel centres, seen from the lens point.
        const floatv sx = floatv::load(px + k) - floatv(0.5f), sy = floatv::load(py + k) - floatv(0.5f);
        floatv to[3];
        RTWEEKEND_UNROLL(3)
        for (int a = 0; a < 3; ++a) {
            const floatv target = floatv(pixel00[a]) + sx * floatv(pixel_delta_u[a]) + sy * floatv(pixel_delta_v[a]);
            const floatv origin = thin_lens ? lens_u * floatv(defocus_disk_u[a]) + lens_v * floatv(defocus_disk_v[a]) : floatv(0.0f);
            origin.store(org[a] + k);
            to[a] = target - origin;
        }
        const floatv inverse = floatv(1.0f) / sqrt(to[0] * to[0] + to[1] * to[1] + to[2] * to[2]);
        RTWEEKEND_UNROLL(3)
        for (int a = 0; a < 3; ++a) (to[a] * inverse).store(dir[a] + k);
    }
    alignas(64) float time[lanes] = {};
    if (with_time) numbers.get1d(sample_dimension::camera_time, time);
    for (int k = 0; k < n; ++k) {
        out[k] = ray3f{};
        out[k].origin = {org[0][k], org[1][k], org[2][k]};
        if (!eye_at_origin) out[k].origin = eye + out[k].origin;
        out[k].dir = {dir[0][k], dir[1][k], dir[2][k]};
        out[k].time = time[k];
    }
}

} // namespace rt
