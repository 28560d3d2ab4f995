// Adaptive sampling (camera::adaptive_error, rtweekend/measure/adaptive.h): pixels whose neighbourhood is
// calm stop at the minimum; noisy ones go on, in proportion to their noise (Neyman); the image
// stays unbiased and deterministic, and samples_saved counts what was not taken.
//
// Most tests drive render_samples with a synthetic sample function whose values have a known
// distribution (and so a known exact mean), and which counts the samples each pixel takes.

#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/camera.h>
#include <rtweekend/sphere.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

namespace test_adaptive {

using namespace rt;

namespace {

camera adaptive_camera(int w, int h, int spp, double error) {
    camera cam = test::test_camera(w, h, spp, 8);
    cam.settings.adaptive_error = error;
    cam.settings.adaptive_min_samples = 16;
    return cam;
}

// A synthetic render: `value(x, y, u)` -> the sample for uniform random u in [0, 1); one ray per
// sample. `counts` receives each pixel's number of samples (rounds are joined before the next
// starts, and within a round a pixel belongs to one job, so the plain increments are safe).
template <class Value>
render_result synthetic(const camera& cam, std::vector<int>& counts, Value value) {
    const camera_frame frame = cam.frame();
    counts.assign(size_t(frame.width) * size_t(frame.height), 0);
    return render_samples(frame.width, frame.height, cam.effective_settings(), [&](int x, int y, int, pcg32& rng, uint64_t& rays) {
        ++rays;
        ++counts[size_t(y) * size_t(frame.width) + size_t(x)];
        float v = value(x, y, rng.next_float());
        return vec3f{v, v, v};
    });
}

double mean_count(const std::vector<int>& counts, int w, int x0, int x1, int h) {
    double sum = 0;
    for (int y = 0; y < h; ++y)
        for (int x = x0; x < x1; ++x) sum += counts[size_t(y) * size_t(w) + size_t(x)];
    return sum / (double(x1 - x0) * h);
}

} // namespace

TEST_CASE("adaptive: a pixel whose samples are all equal stops at the minimum" * doctest::test_suite("threads")) {
    // An empty world under a constant background: every sample of every pixel is the same
    // colour, the variance is 0, so each pixel stops at exactly adaptive_min_samples.
    hittable_list world;
    camera cam = adaptive_camera(24, 16, 256, 0.01);
    cam.background = color(0.25, 0.5, 0.75);
    render_result r = render(cam, world);
    const uint64_t pixels = 24 * 16;
    CHECK(r.stats.samples == pixels * 16);
    CHECK(r.stats.samples_saved == pixels * (256 - 16));
    CHECK(r.stats.rays == pixels * 16); // one ray per sample
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x) CHECK(r.img.pixel(x, y).y() == doctest::Approx(0.5).epsilon(1e-6));

    // Off (error 0): every pixel takes every sample.
    cam.settings.adaptive_error = 0;
    render_result all = render(cam, world);
    CHECK(all.stats.samples == pixels * 256);
    CHECK(all.stats.samples_saved == 0);
}

TEST_CASE("adaptive: a constant region stops at the minimum, a noisy one takes more, in proportion to its noise"
          * doctest::test_suite("threads")) {
    // Three vertical bands of the same mean 0.5: constant; noise of standard deviation 0.05;
    // noise of 0.2 (uniform, light-tailed). Same value and cost everywhere, so Neyman's
    // allocation gives the noisy bands samples in proportion to their standard deviations: 4 to 1
    // (a rule that equalised the confidence intervals would give 16 to 1).
    const int w = 48, h = 8;
    camera cam = adaptive_camera(w, h, 4096, 0.01);
    std::vector<int> counts;
    render_result r = synthetic(cam, counts, [](int x, int, float u) {
        float sigma = x < 16 ? 0.0f : x < 32 ? 0.05f : 0.2f;
        return 0.5f + sigma * std::sqrt(12.0f) * (u - 0.5f);
    });
    // Away from the bands' borders (neighbours decide), each band's pixels agree.
    double constant = mean_count(counts, w, 0, 14, h);
    double low = mean_count(counts, w, 18, 30, h);
    double high = mean_count(counts, w, 34, 48, h);
    CHECK(constant == 16);
    // The stopping rule's count (measure/adaptive.h): 1.96 sigma sqrt(16) / (0.01 sqrt(0.5^2 + 0.3^2)),
    // about 67 and 269; rounds at most double a count and add at least a quarter, so a pixel
    // ends up to 25 % above its count.
    CHECK(low >= 67);
    CHECK(low <= 67 * 1.25 + 1);
    CHECK(high >= 269);
    CHECK(high <= 269 * 1.25 + 1);
    CHECK(high / low == doctest::Approx(4).epsilon(0.25));

    // samples and samples_saved are the counts the sample function saw.
    uint64_t taken = 0;
    for (int c : counts) taken += uint64_t(c);
    CHECK(r.stats.samples == taken);
    CHECK(r.stats.rays == taken);
    CHECK(r.stats.samples_saved == uint64_t(w) * h * 4096 - taken);
}

TEST_CASE("adaptive: heavy-tailed samples stay unbiased" * doctest::test_suite("threads")) {
    // Each sample is 8 with probability 1/16, else 0: mean exactly 0.5, standard deviation 1.94,
    // and most pixels' first 16 samples are all 0. A rule that trusted a pixel's own samples
    // would see no variance there, stop, and leave the pixel at 0: a bias of -0.2 over the image.
    // The left half is a constant 0.5, so the right half's noise is all the planner has to go on.
    const int w = 32, h = 16;
    camera cam = adaptive_camera(w, h, 2048, 0.1);
    std::vector<int> counts;
    render_result r =
        synthetic(cam, counts, [](int x, int, float u) { return x < 16 ? 0.5f : (u < 1.0f / 16 ? 8.0f : 0.0f); });
    double sum = 0, variance_of_sum = 0;
    int zero_pixels = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 16; x < w; ++x) {
            double v = r.img.pixel(x, y).x();
            sum += v;
            variance_of_sum += 3.75 / counts[size_t(y) * w + size_t(x)]; // sigma^2 / n
            zero_pixels += v == 0;
        }
    const double n = 16.0 * h;
    double mean = sum / n, standard_error = std::sqrt(variance_of_sum) / n;
    CHECK(mean_count(counts, w, 18, w, h) > 16); // the noisy pixels went on
    CHECK(std::fabs(mean - 0.5) < 4 * standard_error);
    CHECK(standard_error < 0.02);
    CHECK(zero_pixels < 5);
    CHECK(mean_count(counts, w, 0, 14, h) == 16);
}

TEST_CASE("adaptive: the path tracer's furnace image stays unbiased" * doctest::test_suite("threads")) {
    // A Lambertian sphere (albedo 0.5) in a white furnace: a sample is exactly 0.5 (sphere) or
    // 1 (background). Pixels wholly on the sphere or wholly off it, and their neighbours, have
    // zero variance and stop at 16 samples; pixels near the outline keep sampling.
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = adaptive_camera(24, 16, 1024, 0.02);
    cam.vfov = 60;
    cam.background = color(1, 1, 1);
    render_result r = render(cam, world);
    const uint64_t pixels = 24 * 16;
    CHECK(r.stats.nonfinite_samples == 0);
    CHECK(r.stats.samples > pixels * 16);       // some pixels went on
    CHECK(r.stats.samples < pixels * 1024 / 4); // most stopped early
    CHECK(r.stats.samples + r.stats.samples_saved == pixels * 1024);

    // Against a uniform render with 1024 samples, the mean over the image agrees within a few
    // standard errors (an outline pixel's samples are 0.5 or 1: standard deviation at most 0.25).
    camera uniform = cam;
    uniform.settings.adaptive_error = 0;
    render_result u = render(uniform, world);
    double diff = 0, max_diff = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 24; ++x) {
            double d = r.img.pixel(x, y).x() - u.img.pixel(x, y).x();
            diff += d;
            max_diff = std::fmax(max_diff, std::fabs(d));
        }
    CHECK(std::fabs(diff / double(pixels)) < 0.005);
    CHECK(max_diff < 0.1);
}

TEST_CASE("adaptive: identical images at 1, 2 and 3 threads" * doctest::test_suite("threads")) {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, std::make_shared<metal>(color(0.8, 0.6, 0.4), 0.3)));
    world.add(std::make_shared<sphere>(point3(0, -101, -3), 100, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = adaptive_camera(24, 16, 128, 0.05);
    cam.settings.threads = 1;
    render_result one = render(cam, world);
    CHECK(one.stats.samples > 24 * 16 * 16);
    CHECK(one.stats.samples < 24 * 16 * 128);
    for (int threads : {2, 3}) {
        cam.settings.threads = threads;
        render_result other = render(cam, world);
        CHECK(one.stats.samples == other.stats.samples);
        CHECK(one.stats.rays == other.stats.rays);
        CHECK(std::memcmp(one.img.data().data(), other.img.data().data(), one.img.data().size() * sizeof(float)) == 0);
    }
}

TEST_CASE("adaptive: samples_per_pixel below the minimum, and a one-pixel image" * doctest::test_suite("threads")) {
    // The minimum is capped by samples_per_pixel; a lone pixel has no neighbours and uses its own
    // samples.
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = adaptive_camera(8, 8, 4, 0.01);
    render_result r = render(cam, world);
    CHECK(r.stats.samples == 8 * 8 * 4);
    CHECK(r.stats.samples_saved == 0);

    std::vector<int> counts;
    camera lone = adaptive_camera(1, 1, 512, 0.01);
    synthetic(lone, counts, [](int, int, float u) { return u; });
    CHECK(counts[0] > 16);
    CHECK(counts[0] <= 512);
}

TEST_CASE("adaptive: invalid settings are scene errors" * doctest::test_suite("threads")) {
    hittable_list world;
    camera cam = adaptive_camera(24, 16, 64, -0.1);
    CHECK_THROWS_AS(render(cam, world), scene_error);
    cam.settings.adaptive_error = std::nan("");
    CHECK_THROWS_AS(render(cam, world), scene_error);
    cam.settings.adaptive_error = 0.1;
    cam.settings.adaptive_min_samples = 1;
    CHECK_THROWS_AS(render(cam, world), scene_error);
}

} // namespace test_adaptive
