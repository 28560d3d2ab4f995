#pragma once
// camera: the book's camera, a struct of public settings with defaults, plus render(world).
//
//   camera cam;
//   cam.image_width = 400;  ...
//   cam.render(world);                       // P3 PPM on stdout, progress on stderr
//   image img = cam.render_image(world);     // linear radiance, for programs and tests
//
// frame() turns the settings into the geometry that generates rays (camera_frame), in float and
// relative to lookfrom. The render loop itself lives in render.h, which this header includes at
// its end so that a book-style main needs only "camera.h".

#include "scene_error.h"
#include "hittable.h"
#include "io/image_write.h"
#include "engine/sampling.h"
#include "vec3.h"
#include "engine/vec3f.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace rt {

// The ray-generation geometry of a camera, relative to its position (lookfrom).
struct camera_frame {
    int width = 0, height = 0;
    vec3f pixel00;              // centre of the top-left pixel
    vec3f pixel_delta_u;        // offset to the pixel on the right
    vec3f pixel_delta_v;        // offset to the pixel below
    vec3f defocus_disk_u;       // defocus disk horizontal radius
    vec3f defocus_disk_v;       // defocus disk vertical radius
    bool thin_lens = false;     // defocus_angle > 0: rays start on the lens disk

    // The ray through image position (x, y), in pixels from the top-left corner of the image
    // ((i + 0.5, j + 0.5) is the centre of pixel (i, j)), starting at lens position (lu, lv) in
    // the unit disk. Direction normalised; origin relative to lookfrom.
    ray3f generate(float x, float y, float lu = 0, float lv = 0) const {
        vec3f target = pixel00 + (x - 0.5f) * pixel_delta_u + (y - 0.5f) * pixel_delta_v;
        vec3f origin = thin_lens ? lu * defocus_disk_u + lv * defocus_disk_v : vec3f{};
        return {origin, normalize(target - origin)};
    }
};

class camera {
  public:
    double aspect_ratio = 1.0;  // Ratio of image width over height
    int image_width = 100;      // Rendered image width in pixel count
    int image_height = 0;       // Rendered image height; 0 = image_width / aspect_ratio, as in the book
    int samples_per_pixel = 10; // Count of random samples for each pixel
    int max_depth = 10;         // Maximum number of ray bounces into scene

    double vfov = 90;                  // Vertical view angle (field of view)
    point3 lookfrom = point3(0, 0, 0); // Point camera is looking from
    point3 lookat = point3(0, 0, -1);  // Point camera is looking at
    vec3 vup = vec3(0, 1, 0);          // Camera-relative "up" direction

    double defocus_angle = 0; // Variation angle of rays through each pixel
    double focus_dist = 10;   // Distance from camera lookfrom point to plane of perfect focus

    // Adaptive sampling, off while adaptive_error is 0. Every pixel takes adaptive_min_samples
    // samples; then, in rounds over the image, a pixel takes more until the 95 % confidence
    // interval of its mean is narrower than adaptive_error times its value (its luminance, plus
    // 0.3 in quadrature so that dark pixels are not chased to zero), a target that loosens as
    // sqrt(n / adaptive_min_samples) and as the square root of the pixel's rays per sample
    // (against the image's mean): the allocation of samples that minimises the image's squared
    // error per ray traced. The samples' spread is estimated
    // from the pixel's neighbours (rtweekend/adaptive.h explains both). samples_per_pixel is the
    // most a pixel takes; render_stats::samples_saved counts the samples not taken.
    double adaptive_error = 0;
    int adaptive_min_samples = 16;

    std::optional<color> background; // Unset: the book's sky gradient; set: this constant colour
    uint64_t seed = 0;               // Random seed: the same seed gives the same image
    int threads = 0;                 // Worker threads; 0 = all cores
    bool quiet = false;              // No progress or statistics on stderr

    // Renders the world and writes a P3 PPM to stdout. On invalid input prints one error line
    // to stderr and exits with status 1 (book-style mains have no error handling of their own).
    void render(const hittable& world) const;

    // Renders the world and returns the linear-radiance image. Throws scene_error on bad input.
    image render_image(const hittable& world) const;

    // Renders with a user-supplied ray_color(const ray&, const hittable&) -> color instead of
    // the path tracer: the book's early chapters (background, flat sphere, normals) use this.
    template <class RayColor>
    image render_image(const hittable& world, RayColor ray_color) const;

    // The image size the settings give, after validation.
    int height() const {
        if (image_height > 0) return image_height;
        int h = static_cast<int>(image_width / aspect_ratio);
        return h < 1 ? 1 : h;
    }

    // Validates the settings and derives the ray-generation geometry.
    camera_frame frame() const {
        check_settings();
        camera_frame f;
        f.width = image_width;
        f.height = height();

        // Determine viewport dimensions.
        double theta = degrees_to_radians(vfov);
        double h = std::tan(theta / 2);
        double viewport_height = 2 * h * focus_dist;
        double viewport_width = viewport_height * (double(f.width) / f.height);

        // Calculate the u,v,w unit basis vectors for the camera coordinate frame. Only the
        // directions of lookfrom - lookat and vup matter: they are rescaled first, so that very
        // long or very short vectors do not overflow or underflow when squared.
        vec3 w = unit_vector(rescaled(lookfrom - lookat));
        vec3 u = unit_vector(cross(rescaled(vup), w));
        vec3 v = cross(w, u);

        // Vectors across the horizontal and down the vertical viewport edges.
        vec3 viewport_u = viewport_width * u;
        vec3 viewport_v = viewport_height * -v;
        vec3 delta_u = viewport_u / f.width;
        vec3 delta_v = viewport_v / f.height;

        // Location of the upper left pixel, relative to the camera centre.
        vec3 viewport_upper_left = -(focus_dist * w) - viewport_u / 2 - viewport_v / 2;
        f.pixel00 = vec3f(viewport_upper_left + 0.5 * (delta_u + delta_v));
        f.pixel_delta_u = vec3f(delta_u);
        f.pixel_delta_v = vec3f(delta_v);

        // Calculate the camera defocus disk basis vectors.
        double defocus_radius = focus_dist * std::tan(degrees_to_radians(defocus_angle / 2));

        // Rays are generated in float as normalize(target - origin), with the target on the focus
        // plane and the origin on the lens. Its squared length must neither overflow (the farthest
        // target, a viewport corner, plus the lens radius) nor fall below float's normal range
        // (the nearest, at focus_dist along the axis, a third of it in one component at least).
        double reach = viewport_upper_left.length() + defocus_radius;
        require(reach < 1e18 && focus_dist > 1e-18,
                "focus_dist, vfov and defocus_angle put the viewport outside the float range rays are made in "
                "(focus_dist must exceed 1e-18 and the viewport corners lie within 1e18 of lookfrom)");
        f.defocus_disk_u = vec3f(u * defocus_radius);
        f.defocus_disk_v = vec3f(v * defocus_radius);
        f.thin_lens = defocus_angle > 0;
        return f;
    }

  private:
    static bool finite3(const vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

    // v divided by its largest absolute component: the same direction, a length in [1, sqrt(3)]
    // (v itself if it is zero).
    static vec3 rescaled(const vec3& v) {
        double m = std::fmax(std::fabs(v.x()), std::fmax(std::fabs(v.y()), std::fabs(v.z())));
        return m > 0 ? v / m : v;
    }

    static void require(bool ok, const std::string& message) {
        if (!ok) throw scene_error("camera: " + message);
    }

    void check_settings() const {
        constexpr int max_size = 1 << 16;
        require(image_width >= 1 && image_width <= max_size,
                "image_width must be between 1 and " + std::to_string(max_size) + ", got " + std::to_string(image_width));
        require(image_height >= 0 && image_height <= max_size,
                "image_height must be between 0 (derived) and " + std::to_string(max_size) + ", got " +
                    std::to_string(image_height));
        require(image_height > 0 || (std::isfinite(aspect_ratio) && aspect_ratio > 0),
                "aspect_ratio must be positive and finite, got " + std::to_string(aspect_ratio));
        require(image_height > 0 || image_width / aspect_ratio <= max_size, "aspect_ratio gives an image taller than " +
                                                                                std::to_string(max_size) + " pixels");
        require(samples_per_pixel >= 1, "samples_per_pixel must be at least 1, got " + std::to_string(samples_per_pixel));
        require(max_depth >= 1, "max_depth must be at least 1, got " + std::to_string(max_depth));
        require(std::isfinite(vfov) && vfov > 0 && vfov < 180,
                "vfov must be between 0 and 180 degrees (exclusive), got " + std::to_string(vfov));
        require(finite3(lookfrom) && finite3(lookat) && finite3(vup), "lookfrom, lookat and vup must be finite");
        const vec3 view = lookfrom - lookat;
        require(view.x() != 0 || view.y() != 0 || view.z() != 0, "lookfrom and lookat must differ");
        require(finite3(view), "lookfrom - lookat overflows: the points are too far apart");
        require(vup.x() != 0 || vup.y() != 0 || vup.z() != 0, "vup must be non-zero");
        // sin^2 of the angle between vup and the view direction, scale-free.
        require(cross(unit_vector(rescaled(vup)), unit_vector(rescaled(view))).length_squared() > 1e-20,
                "vup must not be parallel to the view direction");
        require(std::isfinite(defocus_angle) && defocus_angle >= 0 && defocus_angle < 180,
                "defocus_angle must be in [0, 180) degrees, got " + std::to_string(defocus_angle));
        require(std::isfinite(focus_dist) && focus_dist > 0,
                "focus_dist must be positive and finite, got " + std::to_string(focus_dist));
        // The renderer works in float: a background beyond float's range would be infinite there.
        constexpr double float_max = std::numeric_limits<float>::max();
        require(!background || (finite3(*background) && background->x() >= 0 && background->y() >= 0 &&
                                background->z() >= 0 && background->x() <= float_max &&
                                background->y() <= float_max && background->z() <= float_max),
                "background must be finite and non-negative (and at most 3.4e38, float's largest value)");
        require(threads >= 0, "threads must be 0 (all cores) or more, got " + std::to_string(threads));
        require(std::isfinite(adaptive_error) && adaptive_error >= 0,
                "adaptive_error must be 0 (off) or positive, got " + std::to_string(adaptive_error));
        require(adaptive_min_samples >= 2,
                "adaptive_min_samples must be at least 2 (a variance needs two samples), got " +
                    std::to_string(adaptive_min_samples));
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::camera;
#endif

// The render loop and camera::render's definitions (render.h includes this header first).
#include "engine/path_tracer.h"
