// camera (rtweekend/camera.h): image size, the ray geometry of frame(), and validation.
//
// The expected directions are built here from the camera's definition (a viewport of height
// 2 tan(vfov/2) at unit distance along the view axis, spanned by the right-handed basis
// u = vup x w / |.|, v = w x u, w = (lookfrom - lookat)/|.|), written out independently of
// camera.h.

#include <rtweekend/camera.h>
#include <rtweekend/render/sampler.h>
#include <rtweekend/hittable_list.h>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace test_camera {

using namespace rt;

namespace {

constexpr double deg = 3.14159265358979323846 / 180.0;
const double nan_d = std::numeric_limits<double>::quiet_NaN();

struct basis {
    vec3 u, v, w;
};

// Camera basis, computed component by component.
basis camera_basis(const point3& from, const point3& at, const vec3& up) {
    auto norm = [](vec3 a) {
        double l = std::sqrt(a.x() * a.x() + a.y() * a.y() + a.z() * a.z());
        return vec3(a.x() / l, a.y() / l, a.z() / l);
    };
    auto crs = [](vec3 a, vec3 b) {
        return vec3(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
    };
    basis b;
    b.w = norm(vec3(from.x() - at.x(), from.y() - at.y(), from.z() - at.z()));
    b.u = norm(crs(up, b.w));
    b.v = crs(b.w, b.u);
    return b;
}


void check_dir(const vec3f& got, const vec3& expect, double eps = 2e-6) {
    CHECK(got.x == doctest::Approx(expect.x()).epsilon(eps));
    CHECK(got.y == doctest::Approx(expect.y()).epsilon(eps));
    CHECK(got.z == doctest::Approx(expect.z()).epsilon(eps));
}

camera general_camera() {
    camera cam;
    cam.image_width = 101;
    cam.image_height = 51;
    cam.vfov = 35;
    cam.lookfrom = point3(13, 2, 3);
    cam.lookat = point3(0, 0, 0);
    cam.vup = vec3(0, 1, 0);
    cam.focus_dist = 7.5;
    return cam;
}

} // namespace

TEST_CASE("camera: image height = int(width / aspect), at least 1, or as set") {
    camera cam;
    cam.image_width = 400;
    cam.aspect_ratio = 16.0 / 9.0;
    CHECK(cam.height() == 225); // 400 * 9 / 16 = 225
    cam.image_width = 1200;
    CHECK(cam.height() == 675); // 1200 * 9 / 16 = 675
    cam.image_width = 401;
    CHECK(cam.height() == 225); // 225.5625 truncated
    cam.image_width = 100;
    cam.aspect_ratio = 1.0;
    CHECK(cam.height() == 100);
    cam.aspect_ratio = 3.0;
    CHECK(cam.height() == 33); // 33.33 truncated
    cam.image_width = 10;
    cam.aspect_ratio = 100.0;
    CHECK(cam.height() == 1); // 0.1 -> 0, clamped to 1
    cam.image_width = 1;
    cam.aspect_ratio = 16.0 / 9.0;
    CHECK(cam.height() == 1);
    cam.image_height = 7; // explicit height wins
    CHECK(cam.height() == 7);

    camera c2;
    c2.image_width = 400;
    c2.aspect_ratio = 16.0 / 9.0;
    camera_frame f = c2.frame();
    CHECK(f.width == 400);
    CHECK(f.height == 225);
}

TEST_CASE("camera::frame: the centre pixel looks along lookat - lookfrom (odd sizes)") {
    camera cam = general_camera();
    camera_frame f = cam.frame();
    REQUIRE(f.width == 101);
    REQUIRE(f.height == 51);
    // Pixel (50, 25) is the centre: its centre is image position (50.5, 25.5).
    ray3f r = f.generate(50.5f, 25.5f);
    vec3 axis = unit_vector(cam.lookat - cam.lookfrom);
    check_dir(r.dir, axis);
    CHECK(length(r.dir) == doctest::Approx(1).epsilon(1e-6));
    // Pinhole: every ray starts at the camera (origin relative to lookfrom = 0).
    CHECK(r.origin.x == 0);
    CHECK(r.origin.y == 0);
    CHECK(r.origin.z == 0);
    CHECK_FALSE(f.thin_lens);

    // A different focus distance does not change pinhole directions.
    cam.focus_dist = 1.25;
    check_dir(cam.frame().generate(50.5f, 25.5f).dir, axis);
    check_dir(cam.frame().generate(3.5f, 40.5f).dir, f.generate(3.5f, 40.5f).dir.to_double(), 1e-5);
}

TEST_CASE("camera::frame: image corners lie at vfov/2 vertically from the view axis") {
    // Simple orientation first: looking down -z with y up, vfov = 60, 200x100 (aspect 2).
    // Viewport half-height tan(30) at unit distance, half-width 2 tan(30); corner (0,0) is the top
    // left: direction ~ (-2 tan30, tan30, -1).
    {
        camera cam;
        cam.image_width = 200;
        cam.image_height = 100;
        cam.vfov = 60;
        cam.lookfrom = point3(0, 0, 0);
        cam.lookat = point3(0, 0, -1);
        cam.focus_dist = 3;
        camera_frame f = cam.frame();
        const double t = std::tan(30 * deg);
        check_dir(f.generate(0, 0).dir, unit_vector(vec3(-2 * t, t, -1)));
        check_dir(f.generate(200, 100).dir, unit_vector(vec3(2 * t, -t, -1)));
        check_dir(f.generate(200, 0).dir, unit_vector(vec3(2 * t, t, -1)));
        // Top centre: exactly 30 degrees above the axis.
        ray3f top = f.generate(100, 0);
        CHECK(std::atan2(top.dir.y, -top.dir.z) == doctest::Approx(30 * deg).epsilon(1e-6));
        CHECK(std::fabs(top.dir.x) < 1e-6f);
    }
    // General orientation: the vertical angle (in the plane of v and the axis) is vfov/2 at the
    // top corners and -vfov/2 at the bottom ones; the horizontal one is atan(aspect tan(vfov/2)).
    for (double vfov : {20.0, 35.0, 90.0, 150.0}) {
        CAPTURE(vfov);
        camera cam = general_camera();
        cam.vfov = vfov;
        camera_frame f = cam.frame();
        basis b = camera_basis(cam.lookfrom, cam.lookat, cam.vup);
        const double half = vfov / 2 * deg, aspect = 101.0 / 51.0;
        const double horiz = std::atan(aspect * std::tan(half));
        struct corner {
            float x, y;
            double sv, su; // signs of the vertical and horizontal angles
        };
        for (corner c : {corner{0, 0, 1, -1}, corner{101, 0, 1, 1}, corner{0, 51, -1, -1}, corner{101, 51, -1, 1}}) {
            vec3 d = f.generate(c.x, c.y).dir.to_double();
            double fwd = -dot(d, b.w), up = dot(d, b.v), right = dot(d, b.u);
            CHECK(std::atan2(up, fwd) == doctest::Approx(c.sv * half).epsilon(2e-6));
            CHECK(std::atan2(right, fwd) == doctest::Approx(c.su * horiz).epsilon(2e-6));
        }
        // The ray through (0,0) is generate(0, 0), the image's corner, not a pixel centre.
        ray3f p00 = f.generate(0.5f, 0.5f);
        double up00 = dot(p00.dir.to_double(), b.v), fwd00 = -dot(p00.dir.to_double(), b.w);
        CHECK(std::atan2(up00, fwd00) < half);
    }
}

TEST_CASE("camera::frame: pixel spacing and the thin lens") {
    camera cam = general_camera();
    cam.defocus_angle = 10;
    cam.focus_dist = 4;
    camera_frame f = cam.frame();
    CHECK(f.thin_lens);
    basis b = camera_basis(cam.lookfrom, cam.lookat, cam.vup);
    // Pixel pitch at the focus plane: viewport height 2 tan(17.5 deg) * 4 over 51 rows, and the same
    // pitch across (square pixels: viewport width = height * 101/51).
    double pitch = 2 * std::tan(17.5 * deg) * 4 / 51;
    CHECK(length(f.pixel_delta_u) == doctest::Approx(pitch).epsilon(1e-6));
    CHECK(length(f.pixel_delta_v) == doctest::Approx(pitch).epsilon(1e-6));
    CHECK(dot(f.pixel_delta_u.to_double(), b.u) == doctest::Approx(pitch).epsilon(1e-6)); // rightwards
    CHECK(dot(f.pixel_delta_v.to_double(), b.v) == doctest::Approx(-pitch).epsilon(1e-6)); // downwards
    // Defocus disk radius: focus_dist * tan(defocus_angle / 2) = 4 tan 5 deg.
    double radius = 4 * std::tan(5 * deg);
    CHECK(length(f.defocus_disk_u) == doctest::Approx(radius).epsilon(1e-6));
    CHECK(length(f.defocus_disk_v) == doctest::Approx(radius).epsilon(1e-6));
    CHECK(std::fabs(dot(f.defocus_disk_u.to_double(), b.v)) < 1e-6);
    CHECK(std::fabs(dot(f.defocus_disk_u.to_double(), b.w)) < 1e-6);

    // All rays through one image position meet at the focus plane, whatever the lens position:
    // the centre-of-lens ray reaches the plane (distance 4 along -w) at P; every lens ray passes
    // through P.
    for (auto [x, y] : {std::pair<float, float>{10.5f, 7.5f}, {50.5f, 25.5f}, {100.0f, 0.0f}}) {
        ray3f c = f.generate(x, y);
        vec3 dc = c.dir.to_double();
        vec3 P = dc * (4 / -dot(dc, b.w));
        for (auto [lu, lv] : {std::pair<float, float>{1, 0}, {0, -1}, {0.6f, 0.8f}, {-0.3f, 0.2f}}) {
            ray3f r = f.generate(x, y, lu, lv);
            vec3 o = r.origin.to_double();
            CHECK(o.length() == doctest::Approx(radius * std::sqrt(lu * lu + lv * lv)).epsilon(1e-5));
            CHECK(std::fabs(dot(o, b.w)) < 1e-6); // the lens lies in the u-v plane
            CHECK(length(r.dir) == doctest::Approx(1).epsilon(1e-6));
            vec3 miss = cross(r.dir.to_double(), P - o);
            CHECK(miss.length() <= 1e-5 * P.length());
        }
    }
}

TEST_CASE("camera_frame::sample_rays: a batch's rays are each sample's own, through its pixel point from its lens point") {
    camera cam = general_camera();
    cam.defocus_angle = 10;
    cam.focus_dist = 4;
    for (sampler_kind kind : {sampler_kind::sobol, sampler_kind::stratified, sampler_kind::independent})
        for (bool with_time : {false, true}) {
            const camera_frame f = cam.frame();
            const int spp = 64;
            const sampler_plan plan(kind, 3, spp);
            constexpr int n = sample_lanes::capacity;
            int x[n], y[n], s[n];
            pcg32 pick(9, uint64_t(kind));
            std::vector<pcg32> streams, single_streams, check_streams;
            for (int k = 0; k < n; ++k) {
                x[k] = int(pick.next_u32() % uint32_t(f.width));
                y[k] = int(pick.next_u32() % uint32_t(f.height));
                s[k] = int(pick.next_u32() % uint32_t(spp));
                streams.push_back(sample_rng(1, uint64_t(y[k]) * 1000 + uint64_t(x[k]), uint64_t(s[k])));
            }
            single_streams = streams;
            check_streams = streams;
            std::vector<pixel_sampler> batch, single, check;
            batch.reserve(n);
            single.reserve(n);
            check.reserve(n);
            pixel_sampler* lanes[n];
            for (int k = 0; k < n; ++k) {
                lanes[k] = &batch.emplace_back(plan, x[k], y[k], s[k], streams[size_t(k)]);
                single.emplace_back(plan, x[k], y[k], s[k], single_streams[size_t(k)]);
                check.emplace_back(plan, x[k], y[k], s[k], check_streams[size_t(k)]);
            }
            ray3f rays[n];
            f.sample_rays(n, x, y, lanes, spp, with_time, rays);
            for (int k = 0; k < n; ++k) {
                // Bit for bit the ray of the sample taken alone.
                const ray3f one = f.sample_ray(x[k], y[k], spp, single[size_t(k)], with_time);
                CHECK(rays[k].origin.x == one.origin.x);
                CHECK(rays[k].origin.y == one.origin.y);
                CHECK(rays[k].origin.z == one.origin.z);
                CHECK(rays[k].dir.x == one.dir.x);
                CHECK(rays[k].dir.y == one.dir.y);
                CHECK(rays[k].dir.z == one.dir.z);
                CHECK(rays[k].time == one.time);
                // And the definition, in double: the sample's numbers in the order the camera
                // draws them (pixel point, lens point, time), the lens point at radius sqrt(u1)
                // and angle 2 pi u2 on the disk.
                const uniform2 jitter = check[size_t(k)].get2d(sample_dimension::camera_pixel);
                const uniform2 lens = check[size_t(k)].get2d(sample_dimension::camera_lens);
                const double t = with_time ? check[size_t(k)].get1d(sample_dimension::camera_time) : 0.0;
                const double radius = std::sqrt(double(lens.u1)), angle = 2 * 3.14159265358979323846 * double(lens.u2);
                const vec3 origin = radius * std::cos(angle) * f.defocus_disk_u.to_double() +
                                    radius * std::sin(angle) * f.defocus_disk_v.to_double();
                const vec3 target = f.pixel00.to_double() + (x[k] + double(jitter.u1) - 0.5) * f.pixel_delta_u.to_double() +
                                    (y[k] + double(jitter.u2) - 0.5) * f.pixel_delta_v.to_double();
                const vec3 dir = unit_vector(target - origin);
                CHECK((rays[k].origin.to_double() - origin).length() < 1e-6);
                CHECK((rays[k].dir.to_double() - dir).length() < 2e-6);
                CHECK(double(rays[k].time) == t);
            }
        }
}

namespace {

// check() (which checks frame(), settings() and sky()) must throw scene_error with a one-line message.
void check_rejected(const camera& cam, const char* what) {
    CAPTURE(what);
    bool threw = false;
    try {
        cam.check();
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(!msg.empty());
        CHECK(msg.find('\n') == std::string::npos);
        CHECK(msg.rfind("camera: ", 0) == 0);
    } catch (...) {
        FAIL_CHECK("threw something other than scene_error");
        threw = true;
    }
    CHECK(threw);
}

} // namespace

TEST_CASE("camera: the older books' (v3) cameras and get_ray(s, t), by hand") {
    auto near = [](const vec3& a, const vec3& b) { return (a - b).length() < 1e-12; };
    // Made by default: their first camera, 16:9 at focal length 1 from the origin down -z: the
    // viewport spans x in [-16/9, 16/9], y in [-1, 1] at z = -1.
    {
        camera cam;
        CHECK(near(cam.get_ray(0, 0).direction(), vec3(-16.0 / 9, -1, -1)));
        CHECK(near(cam.get_ray(1, 1).direction(), vec3(16.0 / 9, 1, -1)));
        CHECK(near(cam.get_ray(0.5, 0.5).direction(), vec3(0, 0, -1)));
        CHECK(near(cam.get_ray(0.25, 0.75).origin(), vec3(0, 0, 0)));
        cam.aspect_ratio = 2; // a set aspect ratio counts
        CHECK(near(cam.get_ray(1, 0).direction(), vec3(2, -1, -1)));
    }
    // camera(vfov, aspect): vfov 60 gives a half-height tan(30 deg) = 1 / sqrt(3).
    {
        camera cam(60, 1.5);
        const double h = 1 / std::sqrt(3.0);
        CHECK(near(cam.get_ray(1, 1).direction(), vec3(1.5 * h, h, -1)));
        CHECK(cam.vfov == 60);
        CHECK(cam.aspect_ratio == 1.5);
    }
    // camera(lookfrom, lookat, vup, vfov, aspect): from (3, 0, 0) towards the origin with vfov
    // 90 and aspect 2: w = +x, u = vup x w = (0, 0, -1), v = w x u = (0, 1, 0), horizontal = 4 u,
    // vertical = 2 v; the corner (s, t) = (0, 0) is at lookfrom - horizontal / 2 - vertical / 2 - w
    // = (3, 0, 0) + (0, 0, 2) - (0, 1, 0) - (1, 0, 0) = (2, -1, 2).
    {
        camera cam(point3(3, 0, 0), point3(0, 0, 0), vec3(0, 1, 0), 90, 2);
        const ray r = cam.get_ray(0, 0);
        CHECK(near(r.origin(), point3(3, 0, 0)));
        CHECK(near(r.direction(), vec3(-1, -1, 2)));
        CHECK(near(cam.get_ray(0.5, 0.5).direction(), vec3(-1, 0, 0)));
    }
    // With a lens: every ray leaves a point of the lens disk (radius aperture / 2, in the plane
    // across w) and passes through the viewport point at focus_dist, whatever the lens point.
    {
        const double aperture = 0.4, focus = 5;
        camera cam(point3(0, 0, 0), point3(0, 0, -1), vec3(0, 1, 0), 90, 1, aperture, focus, 0.25, 0.75);
        CHECK(cam.focus_dist == 5);
        CHECK(std::tan(cam.defocus_angle * deg / 2) * focus == doctest::Approx(aperture / 2)); // the renderer's lens
        bool moved = false;
        for (int i = 0; i < 200; ++i) {
            const ray r = cam.get_ray(0.75, 0.25);
            CHECK(r.origin().z() == 0);
            CHECK(r.origin().length() <= aperture / 2 + 1e-12);
            moved = moved || r.origin().length() > 0.01;
            // The viewport point: (s - 1/2, t - 1/2) of a 2 x 2 viewport, scaled to focus_dist.
            CHECK(near(r.origin() + r.direction(), point3(0.5 * focus, -0.5 * focus, -focus)));
            CHECK(r.time() >= 0.25);
            CHECK(r.time() < 0.75);
        }
        CHECK(moved);
    }
}

TEST_CASE("camera::check rejects invalid settings with scene_error") {
    const camera good = general_camera();
    CHECK_NOTHROW(good.check());

    camera c = good;
    c.image_width = 0;
    check_rejected(c, "width 0");
    c = good;
    c.image_width = -5;
    check_rejected(c, "negative width");
    c = good;
    c.image_width = 65536; // each side allowed, but 2^32 pixels are past the 2^26 limit of a render
    c.image_height = 65536;
    check_rejected(c, "65536 x 65536");
    c.image_height = 1025; // 2^26 + 65536 pixels
    check_rejected(c, "65536 x 1025");
    c.image_height = 1024; // 2^26 exactly: allowed
    CHECK_NOTHROW(c.check());
    c = good;
    c.samples_per_pixel = 0;
    check_rejected(c, "spp 0");
    c = good;
    c.max_depth = 0;
    check_rejected(c, "max_depth 0");
    c = good;
    c.vfov = nan_d;
    check_rejected(c, "NaN vfov");
    c = good;
    c.vfov = 0;
    check_rejected(c, "vfov 0");
    c = good;
    c.vfov = 180;
    check_rejected(c, "vfov 180");
    c = good;
    c.lookat = c.lookfrom;
    check_rejected(c, "lookfrom == lookat");
    c = good;
    c.vup = vec3(13, 2, 3); // parallel to the view direction (lookfrom - lookat)
    check_rejected(c, "vup parallel to view");
    c = good;
    c.vup = vec3(-26, -4, -6); // anti-parallel
    check_rejected(c, "vup anti-parallel to view");
    c = good;
    c.vup = vec3(0, 0, 0);
    check_rejected(c, "vup zero");
    c = good;
    c.defocus_angle = -0.5;
    check_rejected(c, "negative defocus_angle");
    c = good;
    c.focus_dist = 0;
    check_rejected(c, "focus_dist 0");
    c = good;
    c.focus_dist = nan_d;
    check_rejected(c, "focus_dist NaN");
    c = good;
    c.background = color(-0.1, 0, 0);
    check_rejected(c, "negative background");
    c = good;
    c.background = color(0, nan_d, 0);
    check_rejected(c, "NaN background");
    c = good;
    c.settings.threads = -1;
    check_rejected(c, "threads -1");
    c = good;
    c.lookfrom = point3(nan_d, 0, 0);
    check_rejected(c, "NaN lookfrom");
    c = good;
    c.image_height = 0;
    c.aspect_ratio = 0;
    check_rejected(c, "aspect 0");
    c = good;
    c.image_height = -1;
    check_rejected(c, "negative height");

    // Boundary values that are valid.
    c = good;
    c.background = color(0, 0, 0);
    c.settings.threads = 0;
    c.defocus_angle = 0;
    c.max_depth = 1;
    c.samples_per_pixel = 1;
    c.image_width = 1;
    CHECK_NOTHROW((void)c.frame());
}

TEST_CASE("camera::render_image reports invalid settings as scene_error too") {
    hittable_list world;
    camera c = general_camera();
    c.settings.quiet = true;
    c.image_width = 0;
    CHECK_THROWS_AS((void)c.render_image(world), scene_error);
    c = general_camera();
    c.settings.quiet = true;
    c.settings.threads = -1;
    CHECK_THROWS_AS((void)c.render_image(world), scene_error);
}

} // namespace test_camera
