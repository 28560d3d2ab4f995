// Adaptive sampling (camera::adaptive_error, render.h): pixels whose samples agree stop at the
// minimum count; noisy ones go on; the image stays unbiased and deterministic.

#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/render.h>
#include <rtweekend/sphere.h>

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <memory>

using namespace rt;

namespace {

camera adaptive_camera(int spp, double error) {
    camera cam;
    cam.image_width = 24;
    cam.image_height = 16;
    cam.samples_per_pixel = spp;
    cam.max_depth = 8;
    cam.adaptive_error = error;
    cam.adaptive_min_samples = 16;
    cam.quiet = true;
    cam.threads = 2;
    return cam;
}

} // namespace

TEST_CASE("adaptive: a pixel whose samples are all equal stops at the minimum") {
    // An empty world under a constant background: every sample of every pixel is the same
    // colour, the variance is 0, so each pixel stops at exactly adaptive_min_samples.
    hittable_list world;
    camera cam = adaptive_camera(256, 0.01);
    cam.background = color(0.25, 0.5, 0.75);
    render_result r = render(cam, world);
    const uint64_t pixels = 24 * 16;
    CHECK(r.stats.samples == pixels * 16);
    CHECK(r.stats.samples_saved == pixels * (256 - 16));
    CHECK(r.stats.rays == pixels * 16); // one ray per sample
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x) CHECK(r.img.pixel(x, y).y() == doctest::Approx(0.5).epsilon(1e-6));

    // Off (error 0): every pixel takes every sample.
    cam.adaptive_error = 0;
    render_result all = render(cam, world);
    CHECK(all.stats.samples == pixels * 256);
    CHECK(all.stats.samples_saved == 0);
}

TEST_CASE("adaptive: silhouette pixels take more samples; the image stays unbiased") {
    // A Lambertian sphere (albedo 0.5) in a white furnace: a sample is exactly 0.5 (sphere) or
    // 1 (background). Pixels wholly on the sphere or wholly off it have zero variance and stop
    // at 16 samples; pixels on the outline mix the two values and keep sampling.
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = adaptive_camera(1024, 0.02);
    cam.vfov = 60;
    cam.background = color(1, 1, 1);
    render_result r = render(cam, world);
    const uint64_t pixels = 24 * 16;
    CHECK(r.stats.nonfinite_samples == 0);
    CHECK(r.stats.samples > pixels * 16);         // some pixels went on
    CHECK(r.stats.samples < pixels * 1024 / 4);   // most stopped early
    CHECK(r.stats.samples + r.stats.samples_saved == pixels * 1024);

    // Unbiased: against a uniform render with 1024 samples, the mean over the image agrees
    // within a few standard errors. Each outline pixel's error is bounded by the stopping rule
    // (95 % half-width <= 0.02 * |value|), the rest are exact.
    camera uniform = cam;
    uniform.adaptive_error = 0;
    render_result u = render(uniform, world);
    double diff = 0, max_diff = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x) {
            double d = r.img.pixel(x, y).x() - u.img.pixel(x, y).x();
            diff += d;
            max_diff = std::fmax(max_diff, std::fabs(d));
        }
    CHECK(std::fabs(diff / double(pixels)) < 0.005);
    CHECK(max_diff < 0.1); // a stopped pixel is within a few of its own half-widths (<= 0.02)
}

TEST_CASE("adaptive: identical images at 1 and 2 threads") {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, std::make_shared<metal>(color(0.8, 0.6, 0.4), 0.3)));
    world.add(std::make_shared<sphere>(point3(0, -101, -3), 100, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = adaptive_camera(128, 0.05);
    cam.threads = 1;
    render_result one = render(cam, world);
    cam.threads = 2;
    render_result two = render(cam, world);
    CHECK(one.stats.samples == two.stats.samples);
    CHECK(std::memcmp(one.img.data().data(), two.img.data().data(), one.img.data().size() * sizeof(float)) == 0);
}

TEST_CASE("adaptive: invalid settings are scene errors") {
    hittable_list world;
    camera cam = adaptive_camera(64, -0.1);
    CHECK_THROWS_AS(render(cam, world), scene_error);
    cam.adaptive_error = std::nan("");
    CHECK_THROWS_AS(render(cam, world), scene_error);
    cam.adaptive_error = 0.1;
    cam.adaptive_min_samples = 1;
    CHECK_THROWS_AS(render(cam, world), scene_error);
}
