#pragma once
// camera: the book's camera, a struct of public settings with defaults, plus render(world).
//
//   camera cam;
//   cam.image_width = 400;  ...
//   cam.render(world);                       // P3 PPM on stdout, progress on stderr
//   image img = cam.render_image(world);     // linear radiance, for programs and tests
//
// The camera is the teaching surface over three engine pieces: frame() turns the view settings
// into the geometry that generates rays (render/camera_frame.h), `settings` holds what the books
// do not (seed, threads, estimator, sampler, ...: render/render_settings.h), and render() compiles
// the world and runs the path tracer (render/path_tracer.h) with them. To render one world from
// several cameras, compile it once (scene/scene_compiler.h) and give each camera the compiled
// scene: rt::render(cam, scene).

#include "core/constants.h"
#include "core/engine_linkage.h"
#include "render/camera_frame.h"
#include "render/environment.h"
#include "render/path_tracer.h"
#include "render/render_settings.h"
#include "core/rng.h"
#include "render/scheduler.h"
#include "core/vec3f.h"
#include "hittable.h"
#include "image/image_write.h"
#include "core/input_limits.h"
#include "directional_light.h"
#include "point_light.h"
#include "core/scene_error.h"
#include "vec3.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace rt {

class camera {
  public:
    camera() = default;

    // The older books' (v3) cameras, for their mains, which run their own pixel loop and ask
    // get_ray(s, t) for each sample (and may call render() as well):
    //   camera(vfov, aspect_ratio)                            looking down -z from the origin
    //   camera(lookfrom, lookat, vup, vfov, aspect_ratio)
    //   camera(lookfrom, lookat, vup, vfov, aspect_ratio, aperture, focus_dist[, time0, time1])
    // They set the settings above (the lens's diameter `aperture` as defocus_angle); without a
    // focus distance the viewport is at distance 1, those books' focal length.
    camera(double vfov_degrees, double aspect)
        : camera(point3(0, 0, 0), point3(0, 0, -1), vec3(0, 1, 0), vfov_degrees, aspect, 0, 1) {}
    camera(const point3& from, const point3& at, const vec3& up, double vfov_degrees, double aspect)
        : camera(from, at, up, vfov_degrees, aspect, 0, 1) {}
    camera(const point3& from, const point3& at, const vec3& up, double vfov_degrees, double aspect, double aperture,
           double focus_distance, double time0 = 0, double time1 = 0)
        : aspect_ratio(aspect), vfov(vfov_degrees), lookfrom(from), lookat(at), vup(up),
          defocus_angle(2 * std::atan(aperture / 2 / focus_distance) * 180 / pi), focus_dist(focus_distance),
          older_books_camera_(true), lens_radius_(aperture / 2), time0_(time0), time1_(time1) {}

    // The older books' ray for the point (s, t) of the viewport, s across from its left edge and
    // t up from its bottom, both in [0, 1]: from a random point of the lens (of diameter
    // `aperture`) through the point of the viewport at focus_dist, at a random time in
    // [time0, time1). The direction is not unit: to the viewport, as those books make it. A
    // camera made by default is their first one (section 7 of book 1): focal length 1, no lens,
    // and an aspect of 16:9 unless aspect_ratio was set.
    ray get_ray(double s, double t) const;

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

    std::optional<color> background; // Unset: the book's sky gradient; set: this constant colour
    // Beyond the book: a lat-long picture of the radiance from every direction (an HDR sky,
    // render/environment_map.h), which lights the scene and is light-sampled; it replaces the
    // background and the book's sky.
    std::shared_ptr<const environment_map> sky_map;
    // Beyond the book: the pixel reconstruction filter (render/pixel_filter.h): the book's box by
    // default, or pixel_filter::tent(), gaussian(), mitchell(), each sampled, never splatted.
    pixel_filter filter = pixel_filter::box();

    // Beyond the book: how the renderer samples (render/render_settings.h): seed (the same seed
    // gives the same image at any thread count), threads (0: one per processor this process may
    // use), quiet, adaptive sampling, the estimator (nee, bsdf or mixture), the sampler (sobol,
    // stratified, independent), caustic paths, and a stop flag. Its samples_per_pixel and
    // max_depth are the book's fields above, which a render copies in (effective_settings()).
    render_settings settings;

    // Renders the world and writes a P3 PPM to stdout. On invalid input prints one error line
    // to stderr and exits with status 1 (book-style mains have no error handling of their own).
    void render(const hittable& world) const;

    // Book 3's form: `lights` are the shapes its estimator aims rays at. This renderer finds the
    // emitters of `world` itself (every shape whose material is a diffuse_light) and samples them
    // all, so the image is the same whatever `lights` holds; `lights` is accepted for the book's
    // code and otherwise unused.
    void render(const hittable& world, const hittable& lights) const {
        (void)lights;
        render(world);
    }

    // Renders the world and returns the linear-radiance image. Throws scene_error on bad input.
    image render_image(const hittable& world) const;

    // Renders with a user-supplied ray_color(const ray&, const hittable&) -> color instead of
    // the path tracer: the book's early chapters (background, flat sphere, normals) use this.
    template <class RayColor>
    image render_image(const hittable& world, RayColor ray_color) const;

    // Throws scene_error "camera: ..." for any setting that cannot be rendered (frame(),
    // effective_settings() and sky() each check their own part).
    void check() const {
        (void)frame();
        (void)effective_settings();
        (void)sky();
    }

    // The settings a render takes: `settings` with the book's samples_per_pixel and max_depth,
    // checked.
    render_settings effective_settings() const {
        render_settings s = settings;
        s.samples_per_pixel = samples_per_pixel;
        s.max_depth = max_depth;
        s.check("camera");
        return s;
    }

    // What a ray that leaves the scene sees: the sky map, the book's sky, or the background colour
    // (checked).
    environment sky() const {
        if (sky_map) return environment::image_based(sky_map);
        if (!background) return environment::sky();
        // The renderer works in float: a background beyond float's range would be infinite there.
        constexpr double float_max = std::numeric_limits<float>::max();
        const color& c = *background;
        require(finite3(c) && c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && c.x() <= float_max && c.y() <= float_max &&
                    c.z() <= float_max,
                "background must be finite and non-negative (and at most 3.4e38, float's largest value)");
        return environment::uniform(vec3f(c));
    }

    // The image size the settings give, after validation.
    int height() const {
        if (image_height > 0) return image_height;
        int h = static_cast<int>(image_width / aspect_ratio);
        return h < 1 ? 1 : h;
    }

    // The ray-generation geometry of the view settings (checked).
    camera_frame frame() const;

  private:
    bool older_books_camera_ = false; // made by one of the v3 constructors (get_ray)
    double lens_radius_ = 0;
    double time0_ = 0, time1_ = 0;

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

    void check_view() const;

};

// Left out of a program that links the engine (core/engine_linkage.h): each is long, and a main
// compiled them again.
#if RTWEEKEND_ENGINE_BODIES
RTWEEKEND_ENGINE_FUNCTION camera_frame camera::frame() const {
    check_view();
    camera_frame f;
    f.position = lookfrom;
    f.width = image_width;
    f.height = height();
    f.filter = filter;

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


RTWEEKEND_ENGINE_FUNCTION void camera::check_view() const {
    constexpr int max_size = 1 << 16;
    require(image_width >= 1 && image_width <= max_size,
            "image_width must be between 1 and " + std::to_string(max_size) + ", got " + std::to_string(image_width));
    require(image_height >= 0 && image_height <= max_size,
            "image_height must be between 0 (derived) and " + std::to_string(max_size) + ", got " +
                std::to_string(image_height));
    require(image_height > 0 || (std::isfinite(aspect_ratio) && aspect_ratio > 0),
            "aspect_ratio must be positive and finite, got " + number_text(aspect_ratio));
    require(image_height > 0 || image_width / aspect_ratio <= max_size, "aspect_ratio gives an image taller than " +
                                                                            std::to_string(max_size) + " pixels");
    // Each side may be 65536, but not both: the framebuffer is checked before it is allocated.
    const uint64_t rows = uint64_t(height());
    require(uint64_t(image_width) * rows <= max_render_pixels,
            "the image is " + std::to_string(image_width) + "x" + std::to_string(rows) +
                " pixels, more than the limit of 67108864 (2^26) for a render");
    require(std::isfinite(vfov) && vfov > 0 && vfov < 180,
            "vfov must be between 0 and 180 degrees (exclusive), got " + number_text(vfov));
    require(finite3(lookfrom) && finite3(lookat) && finite3(vup), "lookfrom, lookat and vup must be finite");
    const vec3 view = lookfrom - lookat;
    require(view.x() != 0 || view.y() != 0 || view.z() != 0, "lookfrom and lookat must differ");
    require(finite3(view), "lookfrom - lookat overflows: the points are too far apart");
    require(vup.x() != 0 || vup.y() != 0 || vup.z() != 0, "vup must be non-zero");
    // sin^2 of the angle between vup and the view direction, scale-free.
    require(cross(unit_vector(rescaled(vup)), unit_vector(rescaled(view))).length_squared() > 1e-20,
            "vup must not be parallel to the view direction");
    require(std::isfinite(defocus_angle) && defocus_angle >= 0 && defocus_angle < 180,
            "defocus_angle must be in [0, 180) degrees, got " + number_text(defocus_angle));
    require(std::isfinite(focus_dist) && focus_dist > 0,
            "focus_dist must be positive and finite, got " + number_text(focus_dist));
}
#endif // RTWEEKEND_ENGINE_BODIES

inline ray camera::get_ray(double s, double t) const {
    const double aspect = older_books_camera_ || aspect_ratio != 1.0 ? aspect_ratio : 16.0 / 9.0;
    const double focus = older_books_camera_ ? focus_dist : 1.0;
    const double viewport_height = 2 * std::tan(degrees_to_radians(vfov) / 2), viewport_width = aspect * viewport_height;
    const vec3 w = unit_vector(lookfrom - lookat), u = unit_vector(cross(vup, w)), v = cross(w, u);
    const vec3 horizontal = focus * viewport_width * u, vertical = focus * viewport_height * v;
    const point3 lower_left_corner = lookfrom - horizontal / 2 - vertical / 2 - focus * w;
    vec3 offset(0, 0, 0);
    if (older_books_camera_ && lens_radius_ > 0) {
        const vec3 rd = lens_radius_ * random_in_unit_disk();
        offset = u * rd.x() + v * rd.y();
    }
    const double time = time1_ > time0_ ? time0_ + (time1_ - time0_) * random_double() : time0_;
    return ray(lookfrom + offset, lower_left_corner + s * horizontal + t * vertical - lookfrom - offset, time);
}

// Renders `world` as `cam` sees it, with the path tracer (and point and directional lights
// besides the world's emitters): the image and the statistics. The world is compiled around the
// camera.
inline render_result render(const camera& cam, const hittable& world, const std::vector<point_light>& point_lights = {},
                            const std::vector<directional_light>& directional_lights = {}) {
    return path_trace(world, cam.frame(), cam.sky(), cam.effective_settings(), point_lights, directional_lights);
}

// Renders a scene compiled once (compile_scene, scene/scene_compiler.h) as `cam` sees it: one
// compiled scene serves any number of cameras.
inline render_result render(const camera& cam, const compiled_scene& scene) {
    return path_trace(scene, cam.frame(), cam.sky(), cam.effective_settings());
}

// Renders with a user-supplied ray_color(const ray&, const hittable&) -> color instead of the
// path tracer, as camera::render_image(world, ray_color) does, and returns the statistics too:
// samples and rays taken and, when cam.stop ended the render early, how far it got.
template <class RayColor, class = std::enable_if_t<std::is_invocable_r_v<color, RayColor&, const ray&, const hittable&>>>
render_result render(const camera& cam, const hittable& world, RayColor ray_color);

inline image camera::render_image(const hittable& world) const { return rt::render(*this, world).img; }

template <class RayColor, class>
render_result render(const camera& cam, const hittable& world, RayColor ray_color) {
    auto start = std::chrono::steady_clock::now();
    const camera_frame f = cam.frame();
    const render_settings s = cam.effective_settings();
    return render_samples(
        f.width, f.height, s,
        [&](int x, int y, int, pcg32& rng, uint64_t& rays) {
            // Every ray has a time, as in book 2: the shader's world may move.
            float weight = 1; // the camera's filter's (pixel_filter.h)
            ray3f r = f.sample_ray(x, y, s.samples_per_pixel, rng, /*with_time=*/true, &weight);
            ++rays;
            detail::scoped_sample_rng guard(rng); // ray_color may call random_double()
            color c = ray_color(ray(f.position + r.origin.to_double(), r.dir.to_double(), r.time), world);
            return weight * vec3f(c);
        },
        start);
}

template <class RayColor>
image camera::render_image(const hittable& world, RayColor ray_color) const {
    return rt::render(*this, world, ray_color).img;
}

inline void camera::render(const hittable& world) const {
    try {
        write_ppm(std::cout, render_image(world));
        std::cout.flush();
    } catch (const scene_error& e) {
        std::cerr << "rtweekend: error: " << e.what() << '\n';
        std::exit(1);
    }
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::camera;
#endif
