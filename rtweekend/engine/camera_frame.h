#pragma once
// camera_frame: the geometry that turns a pixel position into a ray, in float and relative to the
// camera's position (the compiled scene is stored relative to the same point). The book's camera
// (camera.h) computes one from its settings.

#include "../scene_error.h"
#include "../vec3.h"
#include "../whitted_scene.h"
#include "rng.h"
#include "sampler.h"
#include "sampling.h"
#include "vec3f.h"

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

    // The ray through image position (x, y), in pixels from the top-left corner of the image
    // ((i + 0.5, j + 0.5) is the centre of pixel (i, j)), starting at lens position (lu, lv) in
    // the unit disk. Direction normalised; origin relative to `position`.
    ray3f generate(float x, float y, float lu = 0, float lv = 0) const {
        vec3f target = pixel00 + (x - 0.5f) * pixel_delta_u + (y - 0.5f) * pixel_delta_v;
        vec3f origin = thin_lens ? lu * defocus_disk_u + lv * defocus_disk_v : vec3f{};
        return {origin, normalize(target - origin)};
    }

    // A camera ray for pixel (x, y): jittered uniformly over the pixel (through its centre when
    // the pixel takes a single sample, as in the book's chapters before antialiasing), from a
    // uniform point of the lens disk when the camera has a thin lens, and `with_time`, at a time
    // uniform in the shutter interval [0, 1) (book 2's ray_time = random_double()). The time is
    // drawn last, and only when asked for: a scene where nothing depends on time draws the
    // random numbers it drew before motion blur existed.
    ray3f sample_ray(int x, int y, int samples_per_pixel, pixel_sampler& ps, bool with_time = false) const {
        float jx = 0.5f, jy = 0.5f;
        if (samples_per_pixel > 1) {
            const uniform2 j = ps.get2d(sample_dimension::camera_pixel);
            jx = j.u1;
            jy = j.u2;
        }
        float lu = 0, lv = 0;
        if (thin_lens) {
            const uniform2 l = ps.get2d(sample_dimension::camera_lens);
            vec3f d = sample_unit_disk(l.u1, l.u2);
            lu = d.x;
            lv = d.y;
        }
        ray3f r = generate(float(x) + jx, float(y) + jy, lu, lv);
        if (with_time) r.time = ps.get1d(sample_dimension::camera_time);
        return r;
    }
    // The other way round, for paths that start at the lights (caustic_paths.h): where the camera
    // sees the point x (relative to `position`) from the lens point `lens` (relative to
    // `position`; zero for a pinhole). Fills the unit direction from the lens to x, the distance,
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
    bool connect(const vec3f& x, const vec3f& lens, connection& c) const {
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
        c.distance = std::sqrt(d2);
        c.dir = to / c.distance;
        const float cos_theta = dot(normal, c.dir);
        if (!(cos_theta > 0)) return false;
        const vec3f on_plane = lens + (h / cos_theta) * c.dir - pixel00;
        c.px = dot(on_plane, pixel_delta_u) / length_squared(pixel_delta_u) + 0.5f;
        c.py = dot(on_plane, pixel_delta_v) / length_squared(pixel_delta_v) + 0.5f;
        if (!(c.px >= 0 && c.px < float(width) && c.py >= 0 && c.py < float(height))) return false;
        c.importance = h * h / (pixel_area * cos_theta * cos_theta * cos_theta * d2);
        return std::isfinite(c.importance);
    }
    // The same with every number from `rng`, in the order above.
    ray3f sample_ray(int x, int y, int samples_per_pixel, pcg32& rng, bool with_time = false) const {
        const sampler_plan independent;
        pixel_sampler ps(independent, x, y, 0, rng);
        return sample_ray(x, y, samples_per_pixel, ps, with_time);
    }
};

// The frame of a CENG795 course camera (whitted_scene.h): the image plane at near_distance along
// the gaze, spanning [left, right] x [bottom, top]; pixel (i, j), j = 0 the top row, centred at
// e - d w + (l + (i + 0.5)(r - l)/nx) u + (t - (j + 0.5)(t - b)/ny) v, with w = -gaze,
// u = unit(up x w), v = w x u. Throws scene_error for settings that make no image.
inline camera_frame view_camera_frame(const view_camera& c) {
    auto finite = [](const vec3& a) { return std::isfinite(a.x()) && std::isfinite(a.y()) && std::isfinite(a.z()); };
    if (c.width <= 0 || c.height <= 0 || c.width > (1 << 16) || c.height > (1 << 16))
        throw scene_error("image resolution must be between 1 and 65536, got " + std::to_string(c.width) + "x" +
                          std::to_string(c.height));
    if (!finite(c.position) || !finite(c.gaze) || !finite(c.up) ||
        !std::isfinite(c.left + c.right + c.bottom + c.top + c.near_distance))
        throw scene_error("camera settings must be finite numbers");
    const vec3 w = -unit_vector(c.gaze);
    const vec3 u = unit_vector(cross(c.up, w));
    const vec3 v = cross(w, u);
    if (!finite(u) || !finite(w)) throw scene_error("camera gaze and up must be non-zero and not parallel");
    const vec3 du = (c.right - c.left) / c.width * u, dv = -(c.top - c.bottom) / c.height * v;
    camera_frame f;
    f.width = c.width;
    f.height = c.height;
    f.position = c.position;
    f.pixel00 = vec3f(-c.near_distance * w + c.left * u + c.top * v + 0.5 * (du + dv));
    f.pixel_delta_u = vec3f(du);
    f.pixel_delta_v = vec3f(dv);
    return f;
}

} // namespace rt
