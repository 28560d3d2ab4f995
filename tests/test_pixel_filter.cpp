// Pixel reconstruction filters (rtweekend/render/pixel_filter.h, camera::filter, render --filter):
// each filter's area against its closed form; filter importance sampling's weighted offsets against
// the filter's own moments (a deterministic sweep of u); a straight edge rendered through each
// filter against the edge's convolution with the filter (an integral of the closed-form profile,
// worked here by the trapezoid rule); a flat field stays flat; the same image at 1 and 2 threads;
// and the command line's filter names.

#include <rtweekend/camera.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/quad.h>
#include <rtweekend/render/pixel_filter.h>

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>

namespace test_pixel_filter {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// The profiles as the filters' definitions give them, written out here.
double tent_profile(double t, double r) { return std::fabs(t) < r ? 1 - std::fabs(t) / r : 0; }
double gaussian_profile(double t, double s, double r) {
    return std::fabs(t) < r ? std::exp(-t * t / (2 * s * s)) - std::exp(-r * r / (2 * s * s)) : 0;
}
double mitchell_profile(double t, double b, double c, double r) {
    const double x = 2 * std::fabs(t) / r;
    if (x >= 2) return 0;
    if (x < 1) return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6;
    return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6;
}

// The integral of g over [a, b] by the trapezoid rule on n steps.
double integrate(const std::function<double(double)>& g, double a, double b, int n = 200000) {
    const double h = (b - a) / n;
    double s = (g(a) + g(b)) / 2;
    for (int i = 1; i < n; ++i) s += g(a + i * h);
    return s * h;
}

// E[w g(t)] over u on a fine uniform grid (the filter's sampling as a quadrature rule).
double weighted_mean(const pixel_filter& f, const std::function<double(double)>& g, int n = 200000) {
    double s = 0;
    for (int i = 0; i < n; ++i) {
        float w = 0;
        const float t = f.sample(float((i + 0.5) / n), w);
        s += w * g(t);
    }
    return s / n;
}

struct named {
    const char* name;
    pixel_filter filter;
    std::function<double(double)> profile;
};

std::vector<named> filters() {
    return {{"tent", pixel_filter::tent(1.5), [](double t) { return tent_profile(t, 1.5); }},
            {"gaussian", pixel_filter::gaussian(0.5), [](double t) { return gaussian_profile(t, 0.5, 1.5); }},
            {"mitchell", pixel_filter::mitchell(), [](double t) { return mitchell_profile(t, 1.0 / 3, 1.0 / 3, 2); }},
            {"catmull-rom", pixel_filter::mitchell(0, 0.5), [](double t) { return mitchell_profile(t, 0, 0.5, 2); }}};
}

} // namespace

TEST_CASE("pixel filters: areas against closed forms, and the weighted samples' moments") {
    // Tent of radius r: area r. Gaussian: sqrt(2 pi) s erf(r / (s sqrt 2)) - 2 r exp(-r^2 / (2 s^2)).
    // Mitchell-Netravali: 1 over x in [-2, 2] for every B, C, so r / 2 in pixels.
    CHECK(pixel_filter::tent(1.5).integral() == doctest::Approx(1.5).epsilon(1e-9));
    const double s = 0.5, r = 1.5;
    CHECK(pixel_filter::gaussian(s).integral() ==
          doctest::Approx(std::sqrt(2 * pi_d) * s * std::erf(r / (s * std::sqrt(2.0))) - 2 * r * std::exp(-r * r / (2 * s * s)))
              .epsilon(1e-6));
    CHECK(pixel_filter::mitchell().integral() == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(pixel_filter::mitchell(0, 0.5, 3).integral() == doctest::Approx(1.5).epsilon(1e-9));
    CHECK(pixel_filter::box().integral() == 1);
    for (const named& f : filters()) {
        CAPTURE(f.name);
        CHECK(f.filter.eval(0.3) == doctest::Approx(f.profile(0.3)).epsilon(1e-6));
        CHECK(f.filter.eval(-1.1) == doctest::Approx(f.profile(-1.1)).epsilon(1e-6));
        // E[w] = 1, E[w t] = 0 and E[w t^2] = integral t^2 f / integral f.
        const double area = integrate(f.profile, -f.filter.radius(), f.filter.radius());
        const double second = integrate([&](double t) { return t * t * f.profile(t); }, -f.filter.radius(), f.filter.radius()) / area;
        CHECK(weighted_mean(f.filter, [](double) { return 1.0; }) == doctest::Approx(1).epsilon(1e-4));
        CHECK(std::fabs(weighted_mean(f.filter, [](double t) { return t; })) < 1e-4);
        CHECK(weighted_mean(f.filter, [](double t) { return t * t; }) == doctest::Approx(second).epsilon(1e-3));
        // Every offset within the radius.
        for (float u : {0.0f, 1e-7f, 0.5f, 0.9999999f}) {
            float w;
            CHECK(std::fabs(f.filter.sample(u, w)) <= f.filter.radius() + 1e-6);
        }
    }
    // Mitchell's negative lobes: samples there weigh less than 0.
    float w = 0;
    const pixel_filter m = pixel_filter::mitchell();
    const float t = m.sample(0.999f, w);
    CHECK(std::fabs(t) > 1.0f);
    CHECK(w < 0);
    // The box: the books' jitter, u - 1/2, weight 1.
    CHECK(pixel_filter::box().sample(0.25f, w) == -0.25f);
    CHECK(w == 1);
}

namespace {

// A 16 x 16 image of a plane facing the camera, white-emitting where x < 0 and black elsewhere:
// the edge falls on the boundary between columns 7 and 8.
image edge_image(const pixel_filter& filter, int spp, int threads = 2) {
    hittable_list world;
    auto light = std::make_shared<diffuse_light>(color(1, 1, 1));
    world.add(std::make_shared<quad>(point3(-50, -50, -1), vec3(50, 0, 0), vec3(0, 100, 0), light));
    camera cam;
    cam.image_width = 16;
    cam.image_height = 16;
    cam.vfov = 90;
    cam.lookfrom = point3(0, 0, 0);
    cam.lookat = point3(0, 0, -1);
    cam.samples_per_pixel = spp;
    cam.max_depth = 2;
    cam.background = color(0, 0, 0);
    cam.filter = filter;
    cam.settings.quiet = true;
    cam.settings.threads = threads;
    return cam.render_image(world);
}

} // namespace

TEST_CASE("pixel filters: a straight edge renders as its convolution with the filter") {
    // Column i's centre is 7.5 - i pixels left of the edge... at x = i + 0.5; the light covers
    // x < 8, so column i sees the share integral_{-r}^{7.5 - i} f / integral f of its filter.
    for (const named& f : filters()) {
        CAPTURE(f.name);
        const image img = edge_image(f.filter, 1024);
        const double area = integrate(f.profile, -f.filter.radius(), f.filter.radius());
        for (int i = 4; i < 12; ++i) {
            CAPTURE(i);
            const double upper = std::min(7.5 - i, f.filter.radius());
            const double expected = upper <= -f.filter.radius() ? 0 : integrate(f.profile, -f.filter.radius(), upper) / area;
            // The mean and spread of the column's 16 pixels (each an independent estimate).
            double sum = 0, sum2 = 0;
            for (int y = 0; y < 16; ++y) {
                const double v = img.pixel(i, y).x();
                sum += v;
                sum2 += v * v;
            }
            const double mean = sum / 16, error = std::sqrt(std::fmax(0.0, sum2 / 16 - mean * mean) / 15);
            INFO(mean << " +- " << error << ", expected " << expected);
            CHECK(std::fabs(mean - expected) <= 5 * error + 2e-3);
        }
    }
    // The box: the columns either side of the edge are exactly 1 and 0.
    const image box = edge_image(pixel_filter::box(), 16);
    CHECK(box.pixel(7, 3).x() == 1);
    CHECK(box.pixel(8, 3).x() == 0);
}

TEST_CASE("pixel filters: a flat field stays flat, and the image is the same at any thread count" * doctest::test_suite("threads")) {
    hittable_list world; // nothing: every ray sees the background
    for (const named& f : filters()) {
        CAPTURE(f.name);
        camera cam;
        cam.image_width = 8;
        cam.image_height = 8;
        cam.samples_per_pixel = 256;
        cam.background = color(0.5, 0.5, 0.5);
        cam.filter = f.filter;
        cam.settings.quiet = true;
        const image img = cam.render_image(world);
        double sum = 0;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                // Each pixel is 0.5 times the mean weight of its samples, E = 1; Owen-scrambled
                // Sobol points keep a pixel's mean weight within a few per cent of 1.
                CHECK(img.pixel(x, y).x() == doctest::Approx(0.5).epsilon(0.05));
                sum += img.pixel(x, y).x();
            }
        CHECK(sum / 64 == doctest::Approx(0.5).epsilon(0.01));
        const image one = edge_image(f.filter, 16, 1), two = edge_image(f.filter, 16, 2);
        CHECK(one.data() == two.data());
    }
}

TEST_CASE("pixel filters: the command line's names") {
    CHECK(parse_pixel_filter("box").is_box());
    CHECK(parse_pixel_filter("tent").radius() == 1);
    CHECK(parse_pixel_filter("tent:2.5").radius() == 2.5);
    CHECK(parse_pixel_filter("gaussian:0.5").radius() == doctest::Approx(1.5));
    CHECK(parse_pixel_filter("gaussian").name() == "gaussian:0.5");
    CHECK(parse_pixel_filter("mitchell:0,0.5").name() == "mitchell:0,0.5");
    CHECK(parse_pixel_filter("mitchell").radius() == 2);
    auto error_of = [](const std::string& text) -> std::string {
        try {
            parse_pixel_filter(text);
        } catch (const scene_error& e) {
            return e.what();
        }
        return "";
    };
    CHECK(error_of("blur").find("unknown filter 'blur'") != std::string::npos);
    CHECK(error_of("gaussian:-1").find("sigma must be positive") != std::string::npos);
    CHECK(error_of("tent:x").find("'x' is not a number") != std::string::npos);
    CHECK(error_of("tent:100").find("radius must be in (0, 16]") != std::string::npos);
    CHECK(error_of("mitchell:1").find("takes 2 numbers") != std::string::npos);
    CHECK(error_of("box:1").find("unknown filter") != std::string::npos);
}

} // namespace test_pixel_filter
