// The renderer (rtweekend/camera.h): determinism across thread counts, analytic "furnace" images,
// exact ray counts, user-written shapes and materials through the book's virtual interfaces, and
// the user shader path camera::render_image(world, ray_color).
//
// Furnace reasoning, used throughout: under a constant background B, a path that leaves the
// scene after bounces with attenuations a1..ak carries exactly a1*...*ak*B. A ray scattered
// outwards from a convex object (a sphere, or a plane from its open side) cannot hit that object
// again, so a camera ray that hits a lone convex object costs exactly 2 rays (the hit and the
// escape) and carries exactly attenuation * B, provided max_depth >= 2. With max_depth = 1 the
// hit uses up the only bounce and the path carries 0 (the book: no light past the bounce limit).
// All those products are of floats that are exact (1, 0.5, ...) or a single multiplication, and
// the pixel is the mean of spp identical values, so the expected pixels are exact.

#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_render {

using namespace rt;

namespace {

// Looking down -z from the origin at a sphere of radius 1 centred at (0,0,-2): its angular radius
// is asin(1/2) = 30 deg; with vfov 20 and a 20x12 image the view's corner half-diagonal is
// atan(tan(10 deg) * sqrt(1 + (20/12)^2)) = atan(0.3427) = 18.9 deg, so every camera ray hits it.
camera furnace_camera(int spp, int depth) {
    camera cam = test::test_camera(20, 12, spp, depth);
    cam.vfov = 20;
    cam.lookfrom = point3(0, 0, 0);
    cam.lookat = point3(0, 0, -1);
    cam.background = color(1, 1, 1);
    return cam;
}

hittable_list one_sphere(std::shared_ptr<material> m) {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -2), 1, std::move(m)));
    return world;
}

// Every pixel equals `expect` (per channel) to a relative 1e-6.
void check_uniform(const image& img, const color& expect) {
    long bad = 0;
    double sum[3] = {0, 0, 0};
    for (int y = 0; y < img.height(); ++y)
        for (int x = 0; x < img.width(); ++x) {
            color c = img.pixel(x, y);
            for (int k = 0; k < 3; ++k) {
                sum[k] += c[k];
                if (!(std::fabs(c[k] - expect[k]) <= 1e-6 * std::fabs(expect[k]) + 1e-12)) {
                    if (bad++ < 5) FAIL_CHECK("pixel (" << x << "," << y << ")[" << k << "] = " << c[k] << ", expected " << expect[k]);
                }
            }
        }
    CHECK(bad == 0);
    const double n = double(img.width()) * img.height();
    for (int k = 0; k < 3; ++k) CHECK(sum[k] / n == doctest::Approx(expect[k]).epsilon(1e-6));
}

// --- user code written against the book's interfaces -------------------------------------------

// An infinite plane through `point` with unit normal `normal`.
class plane : public hittable {
  public:
    plane(const point3& point, const vec3& normal, std::shared_ptr<material> m)
        : point_(point), normal_(unit_vector(normal)), mat_(std::move(m)) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        double denom = dot(r.direction(), normal_);
        if (denom == 0) return false;
        double t = dot(point_ - r.origin(), normal_) / denom;
        if (!ray_t.surrounds(t)) return false;
        rec.t = t;
        rec.p = r.at(t);
        rec.set_face_normal(r, normal_);
        rec.mat = mat_;
        return true;
    }

  private:
    point3 point_;
    vec3 normal_;
    std::shared_ptr<material> mat_;
};

// The book's own sphere code (the textbook quadratic), as a user would type it.
class book_sphere : public hittable {
  public:
    book_sphere(const point3& center, double radius, std::shared_ptr<material> mat)
        : center(center), radius(radius), mat(std::move(mat)) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        vec3 oc = center - r.origin();
        auto a = r.direction().length_squared();
        auto h = dot(r.direction(), oc);
        auto c = oc.length_squared() - radius * radius;
        auto discriminant = h * h - a * c;
        if (discriminant < 0) return false;
        auto sqrtd = std::sqrt(discriminant);
        auto root = (h - sqrtd) / a;
        if (!ray_t.surrounds(root)) {
            root = (h + sqrtd) / a;
            if (!ray_t.surrounds(root)) return false;
        }
        rec.t = root;
        rec.p = r.at(rec.t);
        rec.set_face_normal(r, (rec.p - center) / radius);
        rec.mat = mat;
        return true;
    }

  private:
    point3 center;
    double radius;
    std::shared_ptr<material> mat;
};

// A mirror with a coloured tint.
class tinted_mirror : public material {
  public:
    explicit tinted_mirror(const color& tint) : tint_(tint) {}
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        scattered = ray(rec.p, reflect(unit_vector(r_in.direction()), rec.normal));
        attenuation = tint_;
        return true;
    }

  private:
    color tint_;
};

// A white mirror that absorbs with probability p, decided with the book's random_double().
class lossy_mirror : public material {
  public:
    explicit lossy_mirror(double p) : p_(p) {}
    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        double u = random_double();
        if (!(u >= 0 && u < 1)) throw std::logic_error("random_double() out of [0,1)");
        if (u < p_) return false;
        scattered = ray(rec.p, reflect(unit_vector(r_in.direction()), rec.normal));
        attenuation = color(1, 1, 1);
        return true;
    }

  private:
    double p_;
};

// A hittable whose hit() throws: errors in user code must reach the caller of render().
class throwing_hittable : public hittable {
  public:
    bool hit(const ray&, interval, hit_record&) const override { throw std::runtime_error("user hit failed"); }
};

// A small scene with all three built-in materials.
hittable_list mixed_scene() {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, -100.5, -1), 100, std::make_shared<lambertian>(color(0.8, 0.8, 0.0))));
    world.add(std::make_shared<sphere>(point3(0, 0, -1.2), 0.5, std::make_shared<lambertian>(color(0.1, 0.2, 0.5))));
    world.add(std::make_shared<sphere>(point3(-1, 0, -1), 0.5, std::make_shared<dielectric>(1.5)));
    world.add(std::make_shared<sphere>(point3(-1, 0, -1), 0.4, std::make_shared<dielectric>(1.0 / 1.5)));
    world.add(std::make_shared<sphere>(point3(1, 0, -1), 0.5, std::make_shared<metal>(color(0.8, 0.6, 0.2), 0.3)));
    return world;
}

camera mixed_camera() {
    camera cam = test::test_camera(40, 24, 4, 10);
    cam.vfov = 30;
    cam.lookfrom = point3(-2, 2, 1);
    cam.lookat = point3(0, 0, -1);
    cam.defocus_angle = 4;
    cam.focus_dist = 3.4;
    cam.settings.seed = 42;
    return cam;
}

} // namespace

TEST_CASE("render: bit-identical images at 1, 2 and 3 threads, and the seed matters" * doctest::test_suite("threads")) {
    const hittable_list world = mixed_scene();
    camera cam = mixed_camera();
    cam.settings.threads = 1;
    render_result r1 = render(cam, world);
    cam.settings.threads = 2;
    render_result r2 = render(cam, world);
    cam.settings.threads = 3;
    render_result r3 = render(cam, world);
    CHECK(test::same_bits(r1.img, r2.img));
    CHECK(test::same_bits(r1.img, r3.img));
    CHECK(r1.stats.rays == r2.stats.rays);
    CHECK(r1.stats.rays == r3.stats.rays);
    // 40x24 in 16x16 tiles is 3x2 = 6 tiles, so 3 threads really are used.
    CHECK(r3.stats.threads == 3);
    CHECK(r1.stats.threads == 1);

    // The same settings again: the same image (no hidden state between renders).
    cam.settings.threads = 2;
    CHECK(test::same_bits(render(cam, world).img, r1.img));

    // Another seed gives another image.
    cam.settings.seed = 43;
    render_result other = render(cam, world);
    CHECK_FALSE(test::same_bits(other.img, r1.img));

    // Sanity of the image itself: finite, non-negative, not black, nothing dropped.
    CHECK(r1.stats.nonfinite_samples == 0);
    CHECK(r1.stats.samples == test::sample_count(cam));
    // Every sample traces at least the camera ray and at most max_depth rays.
    CHECK(r1.stats.rays >= r1.stats.samples);
    CHECK(r1.stats.rays <= r1.stats.samples * uint64_t(cam.max_depth));
    double total = 0;
    for (float v : r1.img.data()) {
        CHECK(std::isfinite(v));
        CHECK(v >= 0);
        total += v;
    }
    CHECK(total > 0);
}

TEST_CASE("render: threads larger than the number of tiles are capped" * doctest::test_suite("threads")) {
    hittable_list world;
    camera cam = test::test_camera(16, 16, 1, 2); // exactly one 16x16 tile
    cam.settings.threads = 8;
    render_result r = render(cam, world);
    CHECK(r.stats.threads == 1);
    CHECK(r.stats.width == 16);
    CHECK(r.stats.height == 16);
    CHECK(r.stats.samples_per_pixel == 1);
}

TEST_CASE("render: empty world shows the background, one ray per sample") {
    hittable_list world;
    SUBCASE("constant background") {
        camera cam = test::test_camera(20, 12, 3, 5);
        cam.background = color(0.25, 0.5, 0.75);
        render_result r = render(cam, world);
        check_uniform(r.img, color(0.25, 0.5, 0.75));
        CHECK(r.stats.rays == test::sample_count(cam)); // 20 * 12 * 3 = 720
        CHECK(r.stats.rays == 720);
        CHECK(r.stats.samples == 720);
        CHECK(r.stats.nonfinite_samples == 0);
    }
    SUBCASE("the book's sky gradient, from pixel-centre rays (spp = 1)") {
        // Camera at the origin looking down -z, vfov 90, 8x6: the ray through pixel (x, y) has
        // direction ((2 (x + 0.5)/8 - 1) * 8/6, 1 - 2 (y + 0.5)/6, -1) (viewport half-height
        // tan 45 = 1 at unit distance). The sky is (1 - a) white + a (0.5, 0.7, 1), a = (dir_y + 1)/2.
        camera cam = test::test_camera(8, 6, 1, 5);
        cam.vfov = 90;
        render_result r = render(cam, world);
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 8; ++x) {
                vec3 d = unit_vector(vec3((2 * (x + 0.5) / 8 - 1) * 8.0 / 6.0, 1 - 2 * (y + 0.5) / 6, -1));
                double a = 0.5 * (d.y() + 1);
                color expect = (1 - a) * color(1, 1, 1) + a * color(0.5, 0.7, 1.0);
                color got = r.img.pixel(x, y);
                CAPTURE(x);
                CAPTURE(y);
                CHECK(got.x() == doctest::Approx(expect.x()).epsilon(1e-5));
                CHECK(got.y() == doctest::Approx(expect.y()).epsilon(1e-5));
                CHECK(got.z() == doctest::Approx(expect.z()).epsilon(1e-5));
            }
        CHECK(r.stats.rays == 48);
    }
}

TEST_CASE("render: white furnace, lambertian sphere renders its albedo exactly") {
    for (double a : {0.5, 1.0, 0.3}) {
        for (int depth : {2, 3, 50}) {
            CAPTURE(a);
            CAPTURE(depth);
            camera cam = furnace_camera(8, depth);
            hittable_list world = one_sphere(std::make_shared<lambertian>(color(a, a, a)));
            render_result r = render(cam, world);
            // Exactly float(a): e.g. 0.3 renders 0.3f, the float the kernel multiplies by.
            check_uniform(r.img, color(double(float(a)), double(float(a)), double(float(a))));
            // Every camera ray hits, scatters once and escapes: 2 rays per sample.
            CHECK(r.stats.rays == 2 * test::sample_count(cam)); // 2 * 20 * 12 * 8 = 3840
            CHECK(r.stats.nonfinite_samples == 0);
        }
    }
    // Albedo 1: every value is exactly 1.
    {
        camera cam = furnace_camera(8, 2);
        hittable_list world = one_sphere(std::make_shared<lambertian>(color(1, 1, 1)));
        render_result r = render(cam, world);
        for (float v : r.img.data()) CHECK(v == 1.0f);
    }
    // A coloured albedo: per channel.
    {
        camera cam = furnace_camera(4, 4);
        hittable_list world = one_sphere(std::make_shared<lambertian>(color(0.25, 0.5, 0.75)));
        check_uniform(render(cam, world).img, color(0.25, 0.5, 0.75));
    }
    // Background 0.5 instead of 1: radiance a * B = 0.5 * 0.5 = 0.25.
    {
        camera cam = furnace_camera(4, 4);
        cam.background = color(0.5, 0.5, 0.5);
        hittable_list world = one_sphere(std::make_shared<lambertian>(color(0.5, 0.5, 0.5)));
        check_uniform(render(cam, world).img, color(0.25, 0.25, 0.25));
    }
    // max_depth = 1: the hit uses the only bounce, every pixel is 0, one ray per sample.
    {
        camera cam = furnace_camera(4, 1);
        hittable_list world = one_sphere(std::make_shared<lambertian>(color(0.5, 0.5, 0.5)));
        render_result r = render(cam, world);
        for (float v : r.img.data()) CHECK(v == 0.0f);
        CHECK(r.stats.rays == test::sample_count(cam));
    }
}

TEST_CASE("render: furnace with a mirror and a glass sphere") {
    // Mirror (fuzz 0) on a convex sphere: one reflection, then escape: albedo exactly, 2 rays each.
    {
        camera cam = furnace_camera(8, 3);
        hittable_list world = one_sphere(std::make_shared<metal>(color(0.8, 0.6, 0.4), 0.0));
        render_result r = render(cam, world);
        check_uniform(r.img, color(double(0.8f), double(0.6f), double(0.4f)));
        CHECK(r.stats.rays == 2 * test::sample_count(cam));
    }
    // Glass: every scattering has attenuation 1, so every path that escapes carries exactly 1.
    // Inside a sphere the internal angle equals the refraction angle, below critical, so there is
    // no total internal reflection; Schlick's internal reflectance is at most
    // 0.04 + 0.96 (1 - cos)^5 with cos >= sqrt(1 - 1/1.5^2) = 0.745, i.e. <= 0.041, so reaching
    // max_depth = 50 needs ~48 internal reflections in a row: probability < 1e-60.
    {
        camera cam = furnace_camera(8, 50);
        hittable_list world = one_sphere(std::make_shared<dielectric>(1.5));
        render_result r = render(cam, world);
        check_uniform(r.img, color(1, 1, 1));
        CHECK(r.stats.nonfinite_samples == 0);
        // At least the entry and the exit (or an outward reflection: 2 rays).
        CHECK(r.stats.rays >= 2 * test::sample_count(cam));
    }
}

TEST_CASE("render: a user-written hittable (a plane) renders through the book interface") {
    // Looking straight down at the plane y = 0 from (0,5,0): every camera ray hits it (vfov 60),
    // and rays scattered upward can never come back to a plane.
    camera cam = test::test_camera(12, 12, 4, 5);
    cam.vfov = 60;
    cam.lookfrom = point3(0, 5, 0);
    cam.lookat = point3(0, 0, 0);
    cam.vup = vec3(0, 0, -1);
    cam.background = color(1, 1, 1);

    SUBCASE("with a built-in lambertian material") {
        hittable_list world;
        world.add(std::make_shared<plane>(point3(0, 0, 0), vec3(0, 1, 0),
                                          std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
        render_result r = render(cam, world);
        check_uniform(r.img, color(0.5, 0.5, 0.5));
        CHECK(r.stats.rays == 2 * test::sample_count(cam));
        CHECK(r.stats.nonfinite_samples == 0);
    }
    SUBCASE("with a user-written material (tinted mirror)") {
        hittable_list world;
        world.add(std::make_shared<plane>(point3(0, 0, 0), vec3(0, 1, 0),
                                          std::make_shared<tinted_mirror>(color(0.9, 0.5, 0.25))));
        render_result r = render(cam, world);
        check_uniform(r.img, color(double(0.9f), 0.5, 0.25));
        CHECK(r.stats.rays == 2 * test::sample_count(cam));
    }
    SUBCASE("far from the world origin (plane at y = 1e4, camera 5 above)") {
        camera far = cam;
        far.lookfrom = point3(1e4, 1e4 + 5, -1e4);
        far.lookat = point3(1e4, 1e4, -1e4);
        hittable_list world;
        world.add(std::make_shared<plane>(point3(0, 1e4, 0), vec3(0, 1, 0),
                                          std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
        render_result r = render(far, world);
        check_uniform(r.img, color(0.5, 0.5, 0.5));
        CHECK(r.stats.rays == 2 * test::sample_count(far));
    }
}

TEST_CASE("render: the book's own sphere code as a user hittable (furnace)") {
    camera cam = furnace_camera(8, 4);
    hittable_list world;
    world.add(std::make_shared<book_sphere>(point3(0, 0, -2), 1, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    render_result r = render(cam, world);
    check_uniform(r.img, color(0.5, 0.5, 0.5));
    CHECK(r.stats.rays == 2 * test::sample_count(cam));

    // User and built-in spheres together (a built-in sphere behind the user one, which scattered
    // rays can reach): the image is still bit-identical at any thread count.
    world.add(std::make_shared<sphere>(point3(0, 0, -10), 3, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    cam.settings.threads = 1;
    image a = render(cam, world).img;
    cam.settings.threads = 3;
    CHECK(test::same_bits(a, render(cam, world).img));
}

TEST_CASE("render: a user-written material on a built-in sphere") {
    camera cam = furnace_camera(8, 4);
    hittable_list world = one_sphere(std::make_shared<tinted_mirror>(color(0.9, 0.5, 0.25)));
    render_result r = render(cam, world);
    check_uniform(r.img, color(double(0.9f), 0.5, 0.25));
    CHECK(r.stats.rays == 2 * test::sample_count(cam));
    cam.settings.threads = 1;
    CHECK(test::same_bits(r.img, render(cam, world).img));
}

TEST_CASE("render: a user material that calls random_double() is deterministic and unbiased"
          * doctest::test_suite("threads")) {
    // Each sample survives with probability 1 - p = 0.7 (value 1) or is absorbed (value 0), so a
    // pixel is k / spp, and the image mean over N = 20*12*16 = 3840 samples is 0.7 within
    // 5 sqrt(0.7 * 0.3 / N) = 0.037.
    const double p = 0.3;
    camera cam = furnace_camera(16, 4);
    hittable_list world = one_sphere(std::make_shared<lossy_mirror>(p));

    std::srand(5);
    cam.settings.threads = 1;
    render_result r1 = render(cam, world);
    int after = std::rand();
    std::srand(5);
    CHECK(after == std::rand()); // the render did not draw from the C library's rand()

    cam.settings.threads = 2;
    render_result r2 = render(cam, world);
    cam.settings.threads = 3;
    render_result r3 = render(cam, world);
    CHECK(test::same_bits(r1.img, r2.img));
    CHECK(test::same_bits(r1.img, r3.img));

    const double spp = cam.samples_per_pixel;
    double survivors = 0;
    for (int y = 0; y < r1.img.height(); ++y)
        for (int x = 0; x < r1.img.width(); ++x) {
            color c = r1.img.pixel(x, y);
            double k = c.x() * spp;
            CHECK(k == std::round(k)); // k / 16 is exact in float
            CHECK(c.y() == c.x());
            CHECK(c.z() == c.x());
            survivors += k;
        }
    const double N = double(test::sample_count(cam));
    CHECK(std::fabs(survivors / N - (1 - p)) <= 5 * std::sqrt(p * (1 - p) / N));
    // Absorbed samples cost 1 ray, survivors 2.
    CHECK(double(r1.stats.rays) == N + survivors);

    cam.settings.seed = 1;
    CHECK_FALSE(test::same_bits(render(cam, world).img, r1.img));
}

TEST_CASE("render: exceptions thrown by user code reach the caller" * doctest::test_suite("threads")) {
    camera cam = test::test_camera(40, 40, 1, 2);
    cam.settings.threads = 3;
    hittable_list world;
    world.add(std::make_shared<throwing_hittable>());
    CHECK_THROWS_AS((void)render(cam, world), std::runtime_error);
}

TEST_CASE("render: stats_line() is one line with the counts") {
    camera cam = furnace_camera(2, 2);
    hittable_list world = one_sphere(std::make_shared<lambertian>(color(0.5, 0.5, 0.5)));
    render_result r = render(cam, world);
    std::string line = stats_line(r.stats);
    CHECK(line.find('\n') == std::string::npos);
    CHECK(line.find("20x12") != std::string::npos);
    CHECK(line.find(std::to_string(2 * 20 * 12 * 2) + " rays") != std::string::npos); // 960 rays
}

TEST_CASE("camera::render_image(world) equals render(cam, world).img") {
    const hittable_list world = mixed_scene();
    camera cam = mixed_camera();
    CHECK(test::same_bits(cam.render_image(world), render(cam, world).img));
}

TEST_CASE("camera::render_image(world, ray_color): the shader sees the frame's rays") {
    // Camera at (1,2,3) looking down -z (lookat (1,2,2)), vfov 90, 8x4, spp 1: the ray through
    // pixel (x, y) starts at lookfrom and has direction
    // ((2 (x + 0.5)/8 - 1) * 2, 1 - 2 (y + 0.5)/4, -1), normalised (aspect 8/4 = 2).
    camera cam = test::test_camera(8, 4, 1, 1);
    cam.vfov = 90;
    cam.lookfrom = point3(1, 2, 3);
    cam.lookat = point3(1, 2, 2);
    cam.settings.threads = 1;
    hittable_list world;

    std::vector<ray> seen;
    const hittable* seen_world = nullptr;
    image img = cam.render_image(world, [&](const ray& r, const hittable& w) {
        seen.push_back(r);
        seen_world = &w;
        return color(r.direction());
    });
    CHECK(seen.size() == 32);
    CHECK(seen_world == &world);
    for (const ray& r : seen) {
        CHECK(r.origin().x() == 1);
        CHECK(r.origin().y() == 2);
        CHECK(r.origin().z() == 3);
        CHECK(r.direction().length() == doctest::Approx(1).epsilon(1e-6));
    }
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            vec3 d = unit_vector(vec3((2 * (x + 0.5) / 8 - 1) * 2, 1 - 2 * (y + 0.5) / 4, -1));
            color got = img.pixel(x, y);
            CAPTURE(x);
            CAPTURE(y);
            CHECK(got.x() == doctest::Approx(d.x()).epsilon(1e-6));
            CHECK(got.y() == doctest::Approx(d.y()).epsilon(1e-6));
            CHECK(got.z() == doctest::Approx(d.z()).epsilon(1e-6));
        }
}

TEST_CASE("camera::render_image(world, ray_color): random_double() in a shader is deterministic"
          * doctest::test_suite("threads")) {
    camera cam = test::test_camera(24, 20, 4, 1);
    hittable_list world;
    auto noise = [](const ray&, const hittable&) {
        double a = random_double(), b = random_double(), c = random_double();
        return color(a, b, c);
    };
    cam.settings.threads = 1;
    image a = cam.render_image(world, noise);
    cam.settings.threads = 2;
    image b = cam.render_image(world, noise);
    CHECK(test::same_bits(a, b));
    // The values are means of 4 uniforms on [0, 1): in [0, 1), varying, mean 0.5 within
    // 5 sigma: Var = 1/12 per uniform, N = 24 * 20 * 4 * 3 uniforms -> 5 sqrt(1/12/N) = 0.019.
    double sum = 0, lo = 1, hi = 0;
    for (float v : a.data()) {
        CHECK(v >= 0);
        CHECK(v < 1);
        sum += v;
        lo = std::fmin(lo, v);
        hi = std::fmax(hi, v);
    }
    const double N = 24.0 * 20 * 4 * 3;
    CHECK(std::fabs(sum / a.data().size() - 0.5) <= 5 * std::sqrt(1.0 / 12 / N));
    CHECK(hi - lo > 0.5);
}

TEST_CASE("camera samples: thin-lens rays start on the lens disk and pass through their pixel") {
    // Camera at the origin looking down -z (u = +x, v = +y, w = +z), vfov 90, focus_dist 2,
    // defocus_angle 40: the focus plane is z = -2, where the viewport is 2 tan(45) * 2 = 4 units
    // tall and wide (4x4 image), so image position (X, Y) is the point (X - 2, 2 - Y, -2). The lens
    // radius is 2 tan(20 deg) = 0.72794. A ray (o, d) meets the focus plane at o + d (-2 - o.z)/d.z.
    // Lens points are uniform on the disk: E[|o|^2] = R^2 / 2 with Var = R^4 / 12.
    // Pixel samples are uniform over the pixel: the mean of X over spp samples of pixel (x, y) is
    // x + 1/2 with standard error sqrt(1/12/spp).
    camera cam = test::test_camera(4, 4, 64, 1);
    cam.vfov = 90;
    cam.focus_dist = 2;
    cam.defocus_angle = 40;
    cam.settings.threads = 1;
    const double R = 2 * std::tan(20 * 3.14159265358979323846 / 180);
    hittable_list world;

    std::vector<ray> rays;
    image img = cam.render_image(world, [&](const ray& r, const hittable&) {
        rays.push_back(r);
        const vec3& o = r.origin();
        const vec3& d = r.direction();
        double t = (-2 - o.z()) / d.z();
        vec3 P = o + t * d;
        return color(P.x() + 2, 2 - P.y(), o.length_squared());
    });
    REQUIRE(rays.size() == 4 * 4 * 64);

    double sum_r2 = 0;
    for (const ray& r : rays) {
        const vec3& o = r.origin();
        if (std::fabs(o.z()) > 1e-6) FAIL_CHECK("lens point off the lens plane: " << o);
        if (o.length() > R * (1 + 1e-6)) FAIL_CHECK("lens point outside the lens: " << o);
        vec3 P = o + ((-2 - o.z()) / r.direction().z()) * r.direction();
        double X = P.x() + 2, Y = 2 - P.y();
        if (!(X >= -1e-5 && X <= 4 + 1e-5 && Y >= -1e-5 && Y <= 4 + 1e-5))
            FAIL_CHECK("ray misses the image on the focus plane: " << X << " " << Y);
        sum_r2 += o.length_squared();
    }
    const double N = double(rays.size());
    CHECK(std::fabs(sum_r2 / N - R * R / 2) <= 5 * std::sqrt(R * R * R * R / 12 / N));

    const double se = std::sqrt(1.0 / 12 / 64);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            color c = img.pixel(x, y);
            CAPTURE(x);
            CAPTURE(y);
            CHECK(std::fabs(c.x() - (x + 0.5)) <= 5 * se);
            CHECK(std::fabs(c.y() - (y + 0.5)) <= 5 * se);
        }
}

} // namespace test_render
