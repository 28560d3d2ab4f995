// Caustics traced from the lights (render/caustic_paths.h) against answers derived by hand:
//   - camera_frame::connect inverts the camera: the point a pixel's ray meets is joined back to
//     that pixel;
//   - a Lambertian patch lit by a point light directly and through a mirror (the mirror's image of
//     the light): the image's mean is (A/pi) I (Omega_1 + Omega_2) / area, Omega_k the solid angle
//     the seen square subtends at the light and at its mirror image. Camera paths can never end on
//     a point, so without light tracing the mirror's share is missing;
//   - the power-heuristic weights between light tracing and the camera paths: the ratio of the
//     two strategies' densities worked out by hand for a point on the camera's axis;
//   - an area light seen in a mirror lights a Lambertian patch: the image's mean against the
//     integral of the mirror image's irradiance, with light tracing off, seen wide (light tracing
//     takes nearly all of the caustic) and zoomed in (both take a fair share);
//   - the same image at one and two threads with light tracing on.
// The estimators' agreement with it on the Cornell box is in test_lights.cpp.

#include <rtweekend/rtweekend.h>
#include <rtweekend/render/caustic_paths.h>

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
        camera cam = test::test_camera(32, 32, test::sanitized_share(64), 10);
        cam.lookfrom = point3(0, e, 0);
        cam.lookat = point3(0, 0, 0);
        cam.vup = vec3(1, 0, 0);
        cam.vfov = 90;
        cam.background = color(0, 0, 0);
        cam.settings.caustic_paths = caustic_paths;
        cam.settings.seed = seed;
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
    if (!test::sanitized_build) CHECK(standard_error < 0.01 * mirrored); // the bound above is a tight one
    // Without: the direct light alone (the camera paths cannot end on the point).
    const double without = mean_of(0, 1);
    INFO("without light tracing: " << without << ", direct light " << direct);
    CHECK(without == doctest::Approx(direct).epsilon(0.003));
}

TEST_CASE("light tracing and the camera paths weigh a caustic by the ratio of their densities") {
    // A one-sided quad light of area A_l, the only light (chosen with probability 1); a pinhole
    // camera of field of view theta, W x W pixels, looking along -z. At the point x on its axis at
    // distance d, facing it, a pixel covers the patch of side 2 d tan(theta / 2) / W: the camera
    // samples x with area density 1 / that squared per sample, light tracing the light's points
    // with N / A_l per sample. Their ratio r = N (2 d tan(theta/2) / W)^2 / A_l; the camera paths
    // keep 1 / (1 + r^2) of a caustic through x, light tracing r^2 / (1 + r^2) (power heuristic).
    // A two-sided light halves the density of each side.
    const double side_u = 0.4, side_v = 0.3, A_l = side_u * side_v, theta_deg = 30;
    const int W = 50;
    for (bool two_sided : {false, true}) {
        hittable_list world;
        auto glow = make_shared<diffuse_light>(color(4, 4, 4));
        if (two_sided) glow = make_shared<diffuse_light>(make_shared<solid_color>(color(4, 4, 4)), true);
        world.add(make_shared<quad>(point3(-0.2, 3, -5), vec3(side_u, 0, 0), vec3(0, 0, side_v), glow));
        world.add(make_shared<sphere>(point3(0, 1, -5), 0.5, make_shared<dielectric>(1.5)));
        camera cam = test::test_camera(W, W, 1, 10);
        cam.vfov = theta_deg;
        cam.lookfrom = point3(0, 0, 0);
        cam.lookat = point3(0, 0, -1);
        const camera_frame frame = cam.frame();
        const compiled_scene scene = compile_scene(world, frame.position);
        REQUIRE(scene.lights.lights.size() == 1);
        for (double N : {100.0, 2500.0}) {
            const caustic_splats splats(scene, frame, 10, 1, N);
            for (double d : {1.0, 4.0, 9.0}) {
                const double pixel_side = 2 * d * std::tan(theta_deg * pi_d / 360) / W;
                const double r = N * pixel_side * pixel_side / (A_l * (two_sided ? 2 : 1));
                const float density = splats.camera_density(vec3f{0, 0, -float(d)}, vec3f{0, 0, 0}, vec3f{0, 0, 1});
                INFO("N " << N << ", d " << d << ", two-sided " << two_sided << ": r = " << r);
                CHECK(splats.camera_path_weight(0, density) == doctest::Approx(1 / (1 + r * r)).epsilon(1e-4));
                CHECK(splats.light_path_weight(0, density) == doctest::Approx(r * r / (1 + r * r)).epsilon(1e-4));
            }
        }
        // Where the camera cannot be joined to x (behind it), light tracing cannot make the path.
        const caustic_splats splats(scene, frame, 10, 1, 100);
        const float behind = splats.camera_density(vec3f{0, 0, 2}, vec3f{0, 0, 0}, vec3f{0, 0, -1});
        CHECK(behind == 0.0f);
        CHECK(splats.camera_path_weight(0, behind) == 1.0f);
    }
}

TEST_CASE("an area light seen in a mirror lights a Lambertian patch, wide and zoomed in" * doctest::test_suite("heavy")) {
    // The patch (albedo A, half-width 0.3) at y = 0, a mirror facing down at y = h, and a square
    // light of side s and radiance Le at height d, centred at x = X0, facing up: it lights the
    // patch only through the mirror, as its image at height H = 2h - d facing down (centred at
    // X0, out of the real light's shadow). At a point p of the patch, parallel planes H apart:
    //     E(p) = Le * integral over the image of H^2 / |y - p|^4 dA_y,
    // and the camera, looking straight down from height e, sees a square of half-width
    // w = e tan(fov / 2) of radiance A E / pi, averaged over it (integrated numerically here).
    // Left out: light the patch sends to itself through the mirror, (A / pi) times its image's
    // solid angle 2h away, below 0.1 %.
    const double A = 0.5, Le = 20, h = 3, d = 1, s = 0.5, X0 = 1.5, H = 2 * h - d;
    hittable_list world;
    world.add(make_shared<quad>(point3(-0.3, 0, -0.3), vec3(0, 0, 0.6), vec3(0.6, 0, 0),
                                make_shared<lambertian>(color(A, A, A))));
    world.add(make_shared<quad>(point3(-5, h, -5), vec3(10, 0, 0), vec3(0, 0, 10), make_shared<metal>(color(1, 1, 1), 0.0)));
    // Normal u x v = +y: facing the mirror.
    world.add(make_shared<quad>(point3(X0 - s / 2, d, -s / 2), vec3(0, 0, s), vec3(s, 0, 0),
                                make_shared<diffuse_light>(color(Le, Le, Le))));
    auto expected = [&](double w) {
        const int np = 12, nl = 60;
        double sum = 0;
        for (int i = 0; i < np; ++i)
            for (int j = 0; j < np; ++j) {
                const double px = -w + (i + 0.5) * 2 * w / np, pz = -w + (j + 0.5) * 2 * w / np;
                double e = 0;
                for (int a = 0; a < nl; ++a)
                    for (int b = 0; b < nl; ++b) {
                        const double yx = X0 - s / 2 + (a + 0.5) * s / nl, yz = -s / 2 + (b + 0.5) * s / nl;
                        const double r2 = (yx - px) * (yx - px) + (yz - pz) * (yz - pz) + H * H;
                        e += H * H / (r2 * r2) * (s / nl) * (s / nl);
                    }
                sum += A / pi_d * Le * e;
            }
        return sum / (np * np);
    };
    auto render_mean = [&](double fov, double caustic_paths, uint64_t seed) {
        camera cam = test::test_camera(16, 16, test::sanitized_share(256), 10);
        cam.lookfrom = point3(0, 0.5, 0);
        cam.lookat = point3(0, 0, 0);
        cam.vup = vec3(1, 0, 0);
        cam.vfov = fov;
        cam.background = color(0, 0, 0);
        cam.settings.caustic_paths = caustic_paths;
        cam.settings.seed = seed;
        return image_mean(render(cam, world).img);
    };
    // 16 x 16 pixels and 16 light paths per pixel: N = 4096 per sample. Wide, w = 0.25: a pixel
    // covers (2w / 16)^2 of the patch and r = N (2w / 16)^2 / s^2 = 16, light tracing keeps
    // 1 - 1/(1 + r^2) = 99.6 % of the caustic. Zoomed in, w = 0.05: r = 0.64, the camera paths
    // keep 71 %. And the camera paths alone (no light paths) for the same view.
    struct view {
        double fov, caustic_paths;
    };
    for (view v : {view{2 * std::atan(0.5) * 180 / pi_d, 16.0}, view{2 * std::atan(0.1) * 180 / pi_d, 16.0},
                   view{2 * std::atan(0.1) * 180 / pi_d, 0.0}}) {
        const double w = 0.5 * std::tan(v.fov * pi_d / 360);
        const double want = expected(w);
        const int seeds = 8;
        std::vector<double> means;
        for (int seed = 1; seed <= seeds; ++seed) means.push_back(render_mean(v.fov, v.caustic_paths, uint64_t(seed)));
        double m = 0, var = 0;
        for (double x : means) m += x / seeds;
        for (double x : means) var += (x - m) * (x - m) / (seeds - 1);
        const double standard_error = std::sqrt(var / seeds);
        INFO("half-width " << w << ", light paths " << v.caustic_paths << ": " << m << " +- " << standard_error
                           << ", expected " << want);
        CHECK(std::fabs(m - want) <= 5 * standard_error + 0.003 * want);
        if (!test::sanitized_build) CHECK(standard_error < 0.05 * want); // the bound above is not a loose one
    }
}

TEST_CASE("caustics seen indirectly: light tracing and the camera paths alone give the same image" * doctest::test_suite("heavy")) {
    // A room lit only through a mirror: the light faces up into a mirror ceiling, so that every
    // path that reaches it ends ... -> mirror -> light, and the whole image is light that light
    // tracing also finds: seen directly (camera -> wall -> mirror -> light), past an inner
    // Lambertian vertex (camera -> wall -> mirror -> floor -> mirror -> light) and past the first
    // vertex (camera -> wall -> floor -> mirror -> light, joined to the sample's own light path).
    // Without light paths the camera paths find all of it by themselves (no shadow ray reaches
    // the light's emitting side), so the two images must have the same mean, at any max_depth,
    // which the joins must respect as the camera paths do.
    hittable_list world;
    auto white = make_shared<lambertian>(color(0.7, 0.7, 0.7));
    world.add(make_shared<quad>(point3(-2, 0, -2), vec3(0, 0, 4), vec3(4, 0, 0), white));                // floor
    world.add(make_shared<quad>(point3(-2, 0, -2), vec3(0, 3, 0), vec3(0, 0, 4),
                                make_shared<lambertian>(color(0.5, 0.6, 0.4))));                           // wall
    world.add(make_shared<quad>(point3(-3, 3, -3), vec3(6, 0, 0), vec3(0, 0, 6), make_shared<metal>(color(0.9, 0.9, 0.9), 0.0)));
    // Normal u x v = +y: facing the mirror; its back is dark and blocks.
    world.add(make_shared<quad>(point3(-0.2, 2, -0.75), vec3(0, 0, 1.5), vec3(1.5, 0, 0),
                                make_shared<diffuse_light>(color(4, 4, 4))));
    auto image_mean_all = [](const image& img) {
        double sum = 0;
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < img.width(); ++x) {
                const color c = img.pixel(x, y);
                sum += c.x() + c.y() + c.z();
            }
        return sum / double(3 * img.width() * img.height());
    };
    for (int depth : {3, 4, 6, 12}) {
        double mean[2], standard_error[2];
        for (int traced = 0; traced < 2; ++traced) {
            const int seeds = 8;
            std::vector<double> means;
            for (int seed = 1; seed <= seeds; ++seed) {
                // The camera paths alone are the noisier: more samples for them.
                camera cam = test::test_camera(24, 24, test::sanitized_share(traced ? 64 : 256), depth);
                cam.lookfrom = point3(3.5, 1.6, 0.8);
                cam.lookat = point3(-2, 0.8, 0);
                cam.vfov = 60;
                cam.background = color(0, 0, 0);
                cam.settings.caustic_paths = traced ? 1.0 : 0.0;
                cam.settings.seed = uint64_t(seed + 100 * traced);
                means.push_back(image_mean_all(render(cam, world).img));
            }
            double m = 0, var = 0;
            for (double x : means) m += x / seeds;
            for (double x : means) var += (x - m) * (x - m) / (seeds - 1);
            mean[traced] = m;
            standard_error[traced] = std::sqrt(var / seeds);
        }
        const double both = std::sqrt(standard_error[0] * standard_error[0] + standard_error[1] * standard_error[1]);
        INFO("max_depth " << depth << ": camera paths alone " << mean[0] << " +- " << standard_error[0]
                          << ", with light tracing " << mean[1] << " +- " << standard_error[1]);
        CHECK(mean[0] > 0.01);
        CHECK(std::fabs(mean[1] - mean[0]) <= 4.5 * both);
        if (!test::sanitized_build) CHECK(both < 0.01 * mean[0]); // the bound above is not a loose one
    }
}

TEST_CASE("caustics traced from the lights: the same image at one and two threads") {
    light_scene s = make_cornell_final();
    camera cam = s.cam;
    cam.image_width = 24;
    cam.samples_per_pixel = 8;
    cam.settings.quiet = true;
    cam.settings.caustic_paths = 2;
    cam.settings.threads = 1;
    const image one = render(cam, s.world).img;
    cam.settings.threads = 2;
    const image two = render(cam, s.world).img;
    CHECK(one.data() == two.data());
    // And the light paths did add to it: the image differs from one without them.
    cam.settings.caustic_paths = 0;
    CHECK(render(cam, s.world).img.data() != one.data());
}

} // namespace test_caustic_paths
