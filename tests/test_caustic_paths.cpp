// Caustics traced from the lights (engine/caustic_paths.h) against answers derived by hand:
//   - camera_frame::connect inverts the camera: the point a pixel's ray meets is joined back to
//     that pixel;
//   - a Lambertian patch lit by a point light directly and through a mirror (the mirror's image of
//     the light): the image's mean is (A/pi) I (Omega_1 + Omega_2) / area, Omega_k the solid angle
//     the seen square subtends at the light and at its mirror image. Camera paths can never end on
//     a point, so without light tracing the mirror's share is missing;
//   - the same image at one and two threads with light tracing on.
// The estimators' agreement with it on the Cornell box is in test_lights.cpp.

#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include "light_scenes.h"
#include "test_helpers.h"

#include <cmath>
#include <vector>

namespace test_caustic_paths {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// The solid angle of a rectangle of half-widths a and b seen from a point at distance d on its
// axis: 4 asin(a b / sqrt((a^2 + d^2) (b^2 + d^2))).
double rectangle_solid_angle(double a, double b, double d) {
    return 4 * std::asin(a * b / std::sqrt((a * a + d * d) * (b * b + d * d)));
}

double image_mean(const image& img) {
    double sum = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) sum += img.pixel(x, y).x();
    return sum / double(img.width() * img.height());
}

} // namespace

TEST_CASE("camera_frame::connect joins the point a pixel's ray meets back to that pixel") {
    camera cam = test::test_camera(40, 30, 1, 5);
    cam.vfov = 50;
    cam.lookfrom = point3(1, 2, 3);
    cam.lookat = point3(-2, 0.5, -4);
    const camera_frame frame = cam.frame();
    pcg32 rng(7);
    for (int k = 0; k < 200; ++k) {
        const float fx = 40 * rng.next_float(), fy = 30 * rng.next_float();
        // The point at distance t along the ray through image position (fx, fy): the pixel centre
        // of pixel (x, y) is image position (x + 0.5, y + 0.5).
        const vec3f through = frame.pixel00 + (fx - 0.5f) * frame.pixel_delta_u + (fy - 0.5f) * frame.pixel_delta_v;
        const float t = 0.5f + 20 * rng.next_float();
        const vec3f x = t * through; // frame positions are relative to the camera
        camera_frame::connection c;
        REQUIRE(frame.connect(x, vec3f{0, 0, 0}, c));
        CHECK(c.px == doctest::Approx(fx).epsilon(1e-4));
        CHECK(c.py == doctest::Approx(fy).epsilon(1e-4));
        CHECK(c.distance == doctest::Approx(t * length(through)).epsilon(1e-5));
    }
    // Behind the camera: no pixel.
    camera_frame::connection c;
    CHECK_FALSE(frame.connect(-1.0f * (frame.pixel00 + 20.0f * frame.pixel_delta_u), vec3f{0, 0, 0}, c));
}

TEST_CASE("a point light seen in a mirror lights a Lambertian patch: (A/pi) I (Omega_1 + Omega_2) / area") {
    // The patch (albedo A) at y = 0, a mirror facing down at y = h, a point light of intensity I
    // at height d between them. A camera at height e looks straight down with a 90 degree field of
    // view: it sees the square of half-width w = e around the origin, and (image plane parallel to
    // the patch) every part of that square alike. The irradiance there is I cos / r^2 from the
    // light and again from its mirror image at height 2h - d (a perfect mirror); averaged over the
    // square, I Omega / (2w)^2 for each. Left out: light the patch sends to itself by way of the
    // mirror, below (A/pi) (solid angle of the patch's image, 2h away) = 0.2 % of the answer.
    const double A = 0.2, I = 10, d = 2.5, h = 3, e = 0.5, w = e;
    hittable_list world;
    world.add(make_shared<quad>(point3(-0.52, 0, -0.52), vec3(0, 0, 1.04), vec3(1.04, 0, 0),
                                make_shared<lambertian>(color(A, A, A))));
    world.add(make_shared<quad>(point3(-1, h, -1), vec3(2, 0, 0), vec3(0, 0, 2), make_shared<metal>(color(1, 1, 1), 0.0)));
    const std::vector<point_light> lights{{point3(0, d, 0), color(I, I, I)}};
    const double direct = A / pi_d * I * rectangle_solid_angle(w, w, d) / (4 * w * w);
    const double mirrored = A / pi_d * I * rectangle_solid_angle(w, w, 2 * h - d) / (4 * w * w);
    auto mean_of = [&](double caustic_paths, uint64_t seed) {
        camera cam = test::test_camera(32, 32, 64, 10);
        cam.lookfrom = point3(0, e, 0);
        cam.lookat = point3(0, 0, 0);
        cam.vup = vec3(1, 0, 0);
        cam.vfov = 90;
        cam.background = color(0, 0, 0);
        cam.caustic_paths = caustic_paths;
        cam.seed = seed;
        return image_mean(render(cam, world, lights).img);
    };
    // Light tracing: the mirror's share splatted by light paths (the noisy part; the direct light
    // has next to none). Eight seeds give the standard error.
    const int seeds = 8;
    std::vector<double> means;
    for (int seed = 1; seed <= seeds; ++seed) means.push_back(mean_of(64, uint64_t(seed)));
    double m = 0, v = 0;
    for (double x : means) m += x / seeds;
    for (double x : means) v += (x - m) * (x - m) / (seeds - 1);
    const double standard_error = std::sqrt(v / seeds);
    INFO("with light tracing: " << m << " +- " << standard_error << ", expected " << direct + mirrored << " (direct "
                                << direct << ", mirrored " << mirrored << ")");
    CHECK(std::fabs(m - (direct + mirrored)) <= 5 * standard_error + 0.003 * (direct + mirrored));
    CHECK(standard_error < 0.01 * mirrored); // the bound above is a tight one
    // Without: the direct light alone (the camera paths cannot end on the point).
    const double without = mean_of(0, 1);
    INFO("without light tracing: " << without << ", direct light " << direct);
    CHECK(without == doctest::Approx(direct).epsilon(0.003));
}

TEST_CASE("caustics traced from the lights: the same image at one and two threads") {
    light_scene s = make_cornell_final();
    camera cam = s.cam;
    cam.image_width = 24;
    cam.samples_per_pixel = 8;
    cam.quiet = true;
    cam.caustic_paths = 2;
    cam.threads = 1;
    const image one = render(cam, s.world).img;
    cam.threads = 2;
    const image two = render(cam, s.world).img;
    CHECK(one.data() == two.data());
    // And the light paths did add to it: the image differs from one without them.
    cam.caustic_paths = 0;
    CHECK(render(cam, s.world).img.data() != one.data());
}

} // namespace test_caustic_paths
