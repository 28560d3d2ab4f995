// Environment maps (render/environment_map.h; camera::sky_map; the path tracer's light sampling
// of them in render/path_tracer.h): the texel each axis direction looks up, worked from the
// lat-long formula; the density integrating to one over the sphere and agreeing with what
// sample() returns; sampled texels in proportion to mean channel x sin(theta) (chi-square); a
// floor under a map with a small bright patch against the irradiance worked texel by texel, by
// next-event estimation with multiple importance sampling and by material sampling alone (the
// first with far less noise); a white furnace; the text scene's `sky_map` line (a PFM as it is,
// a PNG sRGB-decoded, times the scale); one-line refusals.

#include <rtweekend/image/image_write.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/io/sky_map_file.h>
#include <rtweekend/render/environment_map.h>
#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <memory>
#include <vector>

namespace test_environment_map {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// A w x h picture whose texel (x, y) is value(x, y) on every channel.
template <class F>
image picture(int w, int h, F value) {
    image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.set_pixel(x, y, color(value(x, y), value(x, y), value(x, y)));
    return img;
}

vec3f direction(double theta, double phi) {
    return vec3f(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)), float(-std::sin(theta) * std::cos(phi)));
}

// The mean of an image's red channel and its standard error, from the spread of its pixels.
struct pixel_mean {
    double mean = 0, error = 0;
};
pixel_mean mean_of(const image& img) {
    const int n = img.width() * img.height();
    double s = 0, s2 = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            s += img.pixel(x, y).x();
            s2 += img.pixel(x, y).x() * img.pixel(x, y).x();
        }
    const double mean = s / n;
    return {mean, std::sqrt(std::fmax(0.0, (s2 - n * mean * mean) / (n - 1)) / n)};
}

// A floor y = 0 of albedo 0.5 seen from straight above under the map, direct light only (the
// floor sees nothing but the sky): 8 x 8 pixels.
pixel_mean floor_under(const std::shared_ptr<const environment_map>& map, int spp, path_estimator estimator) {
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-50, 0, -50), vec3(0, 0, 100), vec3(100, 0, 0),
                                     std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = test::test_camera(8, 8, spp, 2);
    cam.lookfrom = point3(0, 1, 0);
    cam.lookat = point3(0, 0, 0);
    cam.vup = vec3(0, 0, -1);
    cam.vfov = 60;
    cam.sky_map = map;
    cam.settings.estimator = estimator;
    return mean_of(test::render_checked(cam, world).img);
}

} // namespace

TEST_CASE("environment map: each axis direction looks up the texel the lat-long formula gives") {
    // 8 x 4, texel (x, y) = 10 y + x. u = (1 + atan2(d_x, -d_z) / pi) / 2, v = acos(d_y) / pi.
    const environment_map m(picture(8, 4, [](int x, int y) { return 10.0 * y + x; }), 1);
    auto at = [&](const vec3f& d) { return m.radiance(d).x; };
    CHECK(at({0, 0, -1}) == 20 + 4);  // u = 1/2, v = 1/2: the middle, the row below the horizon's line
    CHECK(at({1, 0, 0}) == 20 + 6);   // u = 3/4
    CHECK(at({-1, 0, 0}) == 20 + 2);  // u = 1/4
    CHECK(at({0, 0, 1}) == 20 + 7);   // u = 1: the last column
    CHECK(at({0, 1, 0}) == 0 + 7);    // v = 0: the top row; atan2(0, -0) = pi, u = 1
    CHECK(at({0, -1, 0}) == 30 + 7);  // v = 1: the bottom row
    // theta = 60 deg, phi = 45 deg: v = 1/3 (row 1), u = (1 + 1/4) / 2 = 0.625 (column 5).
    CHECK(at(direction(pi_d / 3, pi_d / 4)) == 10 + 5);
}

TEST_CASE("environment map: the density integrates to one and agrees with what sample() returns") {
    // A sky with a bright patch (texels (5, 1) and (6, 1): 1000) over a dim one (1), and a black row.
    const environment_map m(picture(16, 8, [](int x, int y) { return y == 7 ? 0.0 : (y == 1 && (x == 5 || x == 6)) ? 1000.0 : 1.0; }), 2);
    // The integral of pdf over the sphere, by the midpoint rule on a grid fine within each texel.
    const int n_theta = 512, n_phi = 1024;
    double integral = 0;
    for (int i = 0; i < n_theta; ++i)
        for (int j = 0; j < n_phi; ++j) {
            const double theta = pi_d * (i + 0.5) / n_theta, phi = -pi_d + 2 * pi_d * (j + 0.5) / n_phi;
            integral += m.pdf(direction(theta, phi)) * std::sin(theta) * (pi_d / n_theta) * (2 * pi_d / n_phi);
        }
    CHECK(integral == doctest::Approx(1).epsilon(2e-3));
    // Each texel's probability is its mean channel x sin(row centre) over the sum: counted from
    // 200,000 samples against the expected counts (chi-square, 16 x 7 cells with mass).
    std::vector<double> weight(16 * 8, 0.0);
    double total = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const double v = y == 7 ? 0.0 : (y == 1 && (x == 5 || x == 6)) ? 1000.0 : 1.0;
            weight[size_t(y * 16 + x)] = 2 * v * std::sin(pi_d * (y + 0.5) / 8);
            total += weight[size_t(y * 16 + x)];
        }
    std::vector<double> count(16 * 8, 0.0);
    pcg32 rng(7);
    const int samples = 200000;
    int mismatched = 0;
    for (int k = 0; k < samples; ++k) {
        vec3f wi, le;
        float pdf = 0;
        REQUIRE(m.sample(rng.next_float(), rng.next_float(), wi, pdf, le));
        if (!(std::fabs(pdf - m.pdf(wi)) <= 1e-6f * pdf) || !(le.x == m.radiance(wi).x)) ++mismatched;
        const double u = (1 + std::atan2(double(wi.x), -double(wi.z)) / pi_d) / 2, v = std::acos(double(wi.y)) / pi_d;
        const int x = std::min(15, int(u * 16)), y = std::min(7, int(v * 8));
        count[size_t(y * 16 + x)] += 1;
    }
    CHECK(mismatched == 0);
    double chi2 = 0;
    int cells = 0;
    for (size_t i = 0; i < count.size(); ++i) {
        if (weight[i] == 0) {
            CHECK(count[i] == 0);
            continue;
        }
        const double expected = samples * weight[i] / total;
        chi2 += (count[i] - expected) * (count[i] - expected) / expected;
        ++cells;
    }
    // 111 degrees of freedom: the 0.999 quantile is about 163.
    CHECK(cells == 112);
    CHECK(chi2 < 163);
}

TEST_CASE("environment map: a floor under a bright patch, by light sampling and by material sampling") {
    // 16 x 8: a patch of 5000 at texels (3..4, 1) (theta between 22.5 and 45 degrees) over 1
    // elsewhere above the horizon, 100 below it (which the floor, facing +y, must not see). The
    // irradiance from texel rows [theta0, theta1] spanning dphi is L dphi (sin^2 theta1 - sin^2
    // theta0) / 2; the floor of albedo 0.5 shows 0.5 / pi of it.
    auto value = [](int x, int y) { return y >= 4 ? 100.0 : (y == 1 && (x == 3 || x == 4)) ? 5000.0 : 1.0; };
    const auto map = std::make_shared<const environment_map>(picture(16, 8, value), 1);
    double irradiance = 0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 16; ++x) {
            const double t0 = pi_d * y / 8, t1 = pi_d * (y + 1) / 8;
            irradiance += value(x, y) * (2 * pi_d / 16) * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) / 2;
        }
    const double expected = 0.5 / pi_d * irradiance;
    const pixel_mean nee = floor_under(map, 256, path_estimator::nee);
    const pixel_mean bsdf = floor_under(map, 256, path_estimator::bsdf);
    INFO("expected " << expected << ", light sampling " << nee.mean << " +- " << nee.error << ", material sampling "
                     << bsdf.mean << " +- " << bsdf.error);
    CHECK(std::fabs(nee.mean - expected) <= 5 * nee.error + 1e-4 * expected);
    CHECK(std::fabs(bsdf.mean - expected) <= 5 * bsdf.error + 1e-4 * expected);
    CHECK(nee.error < 0.01 * expected);
    CHECK(nee.error < bsdf.error / 3);
}

TEST_CASE("environment map: a white furnace, a convex diffuse ball is its albedo") {
    const auto white = std::make_shared<const environment_map>(picture(8, 4, [](int, int) { return 1.0; }), 1);
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<lambertian>(color(0.8, 0.8, 0.8))));
    camera cam = test::test_camera(6, 6, 256, 4);
    cam.lookfrom = point3(0, 0, 10);
    cam.lookat = point3(0, 0, 0);
    cam.vfov = 5; // the ball fills the view
    cam.sky_map = white;
    const pixel_mean m = mean_of(test::render_checked(cam, world).img);
    INFO(m.mean << " +- " << m.error);
    CHECK(m.mean == doctest::Approx(0.8).epsilon(2e-3));
}

TEST_CASE("environment map: one line for a picture it cannot take") {
    test::check_scene_error([] { environment_map(image(), 1); }, {"environment map has no pixels"});
    test::check_scene_error([] { environment_map(picture(2, 1, [](int, int) { return 1.0; }), -1); },
                            {"environment map scale must be finite and at least 0"});
    test::check_scene_error([] { environment_map(picture(2, 1, [](int x, int) { return x == 1 ? -1.0 : 1.0; }), 1); },
                            {"environment map texel (1, 0) must be finite and at least 0"});
    // A black map: looked up, never sampled.
    const environment_map black(picture(2, 1, [](int, int) { return 0.0; }), 1);
    vec3f wi, le;
    float pdf;
    CHECK_FALSE(black.sample(0.5f, 0.5f, wi, pdf, le));
    CHECK(black.pdf(vec3f(0, 1, 0)) == 0);
}

TEST_CASE("environment map: the text scene's sky_map line, HDR as it is and 8-bit sRGB-decoded, times its scale") {
    test::scratch_dir dir("sky_map_line");
    std::string pfm = "PF\n2 1\n-1\n";
    for (float v : {1.5f, 2.5f, 3.5f, 0.25f, 0.5f, 0.75f}) pfm += std::string(reinterpret_cast<const char*>(&v), 4);
    dir.write("sky.pfm", pfm);
    dir.write("sky.png", encode_8bit_image(dir.file("sky.png"), 1, 1, {128, 0, 255}));
    const std::string ball = "sphere 0 0 -1 0.5 lambertian 0.5 0.5 0.5 0 0\n";
    // A PFM's rows run bottom first: (1.5, 2.5, 3.5) is the bottom-left texel, read as it is;
    // scale 2. Left column: u < 1/2, e.g. -x.
    const scene_description a = load_scene(dir.write("a.txt", "sky_map sky.pfm 2\n" + ball));
    REQUIRE(a.cam.sky_map);
    CHECK(a.cam.sky_map->radiance(vec3f(-1, 0, 0)).x == doctest::Approx(3.0f));
    CHECK(a.cam.sky_map->radiance(vec3f(-1, 0, 0)).z == doctest::Approx(7.0f));
    // 8-bit codes sRGB-decoded: 128 is 0.2158605, 255 is 1; scale 1 by default.
    const scene_description b = load_scene(dir.write("b.txt", "sky_map sky.png\n" + ball));
    REQUIRE(b.cam.sky_map);
    CHECK(b.cam.sky_map->radiance(vec3f(0, 1, 0)).x == doctest::Approx(0.2158605f).epsilon(1e-5));
    CHECK(b.cam.sky_map->radiance(vec3f(0, 1, 0)).y == 0);
    CHECK(b.cam.sky_map->radiance(vec3f(0, 1, 0)).z == doctest::Approx(1.0f));
    CHECK(b.cam.sky().map == b.cam.sky_map); // what the renderer sees
    // One line naming the file and line: a missing picture, a negative scale, a wrong count.
    test::check_scene_error([&] { load_scene(dir.write("c.txt", ball + "sky_map nowhere.hdr\n")); }, {"c.txt:2:", "nowhere.hdr"});
    test::check_scene_error([&] { load_scene(dir.write("d.txt", "sky_map sky.pfm -1\n" + ball)); },
                            {"d.txt:1:", "sky_map scale must be at least 0"});
    test::check_scene_error([&] { load_scene(dir.write("e.txt", "sky_map\n" + ball)); }, {"e.txt:1:", "expected: sky_map file [scale]"});
}

} // namespace test_environment_map
