// User-written hittables in the renderer (rtweekend/scene/user_shape_set.h): one that reports a
// bounding box (book 2's bounding_box()) goes into the BVH, one that does not (a book-1 class)
// is tested against every ray. Answers are checked against brute force over all shapes, in
// double, and against closed-form sphere hits.

#include <rtweekend/camera.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/sphere.h>
#include <rtweekend/triangle.h>

#include <doctest/doctest.h>

#include "test_helpers.h"
#include "user_sphere.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace test_user_shapes {

using namespace rt;

namespace {

const double inf_d = std::numeric_limits<double>::infinity();

using app::user_sphere;

// Counts the hit() calls of the user spheres that point at it.
std::atomic<long> hit_calls{0};

std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

// 10,000 spheres of radius 0.2 on a 100 x 100 grid of pitch 0.5 in the plane y = 0.
std::vector<std::shared_ptr<user_sphere>> grid(user_sphere::box_kind box = user_sphere::box_kind::exact) {
    std::vector<std::shared_ptr<user_sphere>> shapes;
    auto m = grey();
    for (int i = 0; i < 100; ++i)
        for (int j = 0; j < 100; ++j)
            shapes.push_back(std::make_shared<user_sphere>(point3(0.5 * i - 25, 0, 0.5 * j - 25), 0.2, m, box));
    for (auto& s : shapes) s->calls = &hit_calls;
    return shapes;
}

ray3f make_ray(const vec3& o, const vec3& d) {
    ray3f r;
    r.origin = vec3f(o);
    r.dir = vec3f(unit_vector(d));
    return r;
}

// The nearest of `shapes` along r (relative to the origin 0), in double, by brute force.
double brute_force_t(const std::vector<std::shared_ptr<user_sphere>>& shapes, const ray3f& r, size_t& which) {
    ray world(r.origin.to_double(), r.dir.to_double());
    double best = inf_d;
    which = SIZE_MAX;
    hit_record rec;
    for (size_t i = 0; i < shapes.size(); ++i)
        if (shapes[i]->hit(world, interval(r.tmin, best), rec)) {
            best = rec.t;
            which = i;
        }
    return best;
}

} // namespace

TEST_CASE("user shapes with a bounding box go into the BVH, those without one do not") {
    auto boxed = grid();
    hittable_list world;
    for (auto& s : boxed) world.add(s);
    auto unboxed = std::make_shared<user_sphere>(point3(0, 5, 0), 1, grey(), user_sphere::box_kind::none);
    world.add(unboxed);
    // An empty box, a box with a NaN and one beyond float's range cannot be placed: tested always.
    auto empty_box = std::make_shared<user_sphere>(point3(0, 9, 0), 1, grey(), user_sphere::box_kind::given, aabb());
    auto nan_box = std::make_shared<user_sphere>(point3(0, 9, 0), 1, grey(), user_sphere::box_kind::given,
                                                 aabb(interval(0, std::nan("")), interval(0, 1), interval(0, 1)));
    auto far_box = std::make_shared<user_sphere>(point3(0, 9, 0), 1, grey(), user_sphere::box_kind::given,
                                                 aabb(point3(0, 0, 0), point3(1e19, 1, 1)));
    world.add(empty_box);
    world.add(nan_box);
    world.add(far_box);
    compiled_scene s = compile_scene(world, point3(0, 0, 0));
    CHECK(s.set<user_shape_set>().shapes.size() == boxed.size());
    REQUIRE(s.unbounded_user_shapes.size() == 4);
    CHECK(s.unbounded_user_shapes[0] == unboxed.get());
    CHECK(s.bvh.stats.nodes > 10);
    CHECK(s.calls_user_code());
}

TEST_CASE("user shapes in the BVH: a ray asks only the few whose boxes it enters, and hits the right one") {
    auto shapes = grid();
    hittable_list world;
    for (auto& s : shapes) world.add(s);
    compiled_scene scene = compile_scene(world, point3(0, 0, 0));

    // Straight down onto the sphere at (0.5 * 52 - 25, 0, 0.5 * 47 - 25) = (1, 0, -1.5): it meets
    // the top of the sphere at y = 0.2, 9.8 below the origin.
    const size_t target = 52 * 100 + 47;
    ray3f r = make_ray(vec3(1, 10, -1.5), vec3(0, -1, 0));
    hit_calls = 0;
    surface_hit hit;
    REQUIRE(scene.intersect(r, hit));
    CHECK(hit.user_shape == shapes[target].get());
    CHECK(hit.t == doctest::Approx(9.8).epsilon(1e-6));
    CHECK(hit.normal.y == doctest::Approx(1).epsilon(1e-6));
    CHECK(hit.p.y == doctest::Approx(0.2).epsilon(1e-6));
    CHECK(hit.front_face);
    // Only the shapes of the leaves whose boxes the ray enters are asked (a leaf holds at most 16);
    // without the BVH all 10,000 would be.
    CHECK(hit_calls >= 1);
    CHECK(hit_calls <= 64);

    // A ray between the spheres (x = 1.25 and z = -1.25 lie halfway between rows, 0.05 outside
    // the nearest spheres' boxes) misses all of them, and asks few.
    hit_calls = 0;
    CHECK_FALSE(scene.intersect(make_ray(vec3(1.25, 10, -1.25), vec3(0, -1, 0)), hit));
    CHECK(hit_calls <= 64);

    // A shadow ray along the row z = -1.5 from far outside hits the first sphere of the row.
    CHECK(scene.occluded(make_ray(vec3(-40, 0, -1.5), vec3(1, 0, 0))));
    ray3f short_ray = make_ray(vec3(-40, 0, -1.5), vec3(1, 0, 0));
    short_ray.tmax = 14.7; // the first sphere (x = -25) starts at t = 14.8
    CHECK_FALSE(scene.occluded(short_ray));
}

TEST_CASE("user shapes in the BVH agree with brute force, mixed with built-in spheres and triangles") {
    auto shapes = grid();
    hittable_list world;
    for (auto& s : shapes) world.add(s);
    // Built-in shapes among them, touching none of the user spheres: a sphere just above the
    // grid's centre and a triangle above half of it.
    auto m = grey();
    world.add(std::make_shared<sphere>(point3(0.25, 0.5, 0.25), 0.2, m));
    world.add(std::make_shared<triangle>(point3(-30, 2, -30), point3(30, 2, -30), point3(-30, 2, 30), m));
    compiled_scene scene = compile_scene(world, point3(0, 0, 0));

    pcg32 rng(2024);
    long user_hits = 0, builtin_hits = 0, misses = 0;
    for (int k = 0; k < 3000; ++k) {
        // From above the grid towards a random point of it.
        vec3 o(-30 + 60 * rng.next_double(), 3 + 5 * rng.next_double(), -30 + 60 * rng.next_double());
        vec3 target(-26 + 52 * rng.next_double(), 0, -26 + 52 * rng.next_double());
        ray3f r = make_ray(o, target - o);
        size_t which;
        double t_user = brute_force_t(shapes, r, which);
        // The built-in shapes, in double: the triangle's plane y = 2, the sphere.
        double t_builtin = inf_d;
        {
            ray world_ray(r.origin.to_double(), r.dir.to_double());
            hit_record rec;
            if (sphere(point3(0.25, 0.5, 0.25), 0.2, m).hit(world_ray, interval(0, inf_d), rec)) t_builtin = rec.t;
            if (triangle(point3(-30, 2, -30), point3(30, 2, -30), point3(-30, 2, 30), m)
                    .hit(world_ray, interval(0, t_builtin), rec))
                t_builtin = rec.t;
        }
        surface_hit hit;
        bool found = scene.intersect(r, hit);
        CAPTURE(k);
        if (t_user == inf_d && t_builtin == inf_d) {
            CHECK_FALSE(found);
            ++misses;
            continue;
        }
        REQUIRE(found);
        if (t_user < t_builtin) {
            CHECK(hit.user_shape == shapes[which].get());
            CHECK(hit.t == doctest::Approx(t_user).epsilon(1e-5));
            ++user_hits;
        } else {
            CHECK(hit.user_shape == nullptr);
            CHECK(hit.t == doctest::Approx(t_builtin).epsilon(1e-5));
            ++builtin_hits;
        }
    }
    // Every case occurred often enough to mean something.
    CHECK(user_hits > 500);
    CHECK(builtin_hits > 50);
    CHECK(misses > 50);
}

TEST_CASE("a user shape is found through its box: a box elsewhere hides it, as the book's bvh_node would") {
    // The sphere is at (0, 0, -5) but claims to be near (100, 100, 100): the BVH never sends a ray
    // towards (0, 0, -5) to it. The same sphere without a box is found.
    auto m = grey();
    hittable_list lying, honest;
    lying.add(std::make_shared<user_sphere>(point3(0, 0, -5), 1, m, user_sphere::box_kind::given,
                                            aabb(point3(99, 99, 99), point3(101, 101, 101))));
    lying.add(std::make_shared<sphere>(point3(100, 100, 100), 1, m)); // a second shape: the BVH has a real box to test
    honest.add(std::make_shared<user_sphere>(point3(0, 0, -5), 1, m, user_sphere::box_kind::none));
    const ray3f r = make_ray(vec3(0, 0, 0), vec3(0, 0, -1));
    surface_hit hit;
    CHECK_FALSE(compile_scene(lying, point3(0, 0, 0)).intersect(r, hit));
    REQUIRE(compile_scene(honest, point3(0, 0, 0)).intersect(r, hit));
    CHECK(hit.t == doctest::Approx(4).epsilon(1e-6));
}

TEST_CASE("render: user spheres with and without bounding boxes give the same image" * doctest::test_suite("threads")) {
    // A small grid of user spheres on a built-in ground under the sky: the BVH changes which
    // shapes are asked, never which hit is nearest, so the images agree bit for bit.
    auto render_grid = [](user_sphere::box_kind box) {
        hittable_list world;
        world.add(std::make_shared<sphere>(point3(0, -1000, 0), 999.8, grey()));
        auto m = std::make_shared<metal>(color(0.8, 0.7, 0.6), 0.3);
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j)
                world.add(std::make_shared<user_sphere>(point3(0.5 * i - 2, 0, 0.5 * j - 4), 0.2, m, box));
        camera cam = test::test_camera(32, 18, 4, 6);
        cam.lookfrom = point3(0, 3, 4);
        cam.lookat = point3(0, 0, -2);
        cam.vfov = 50;
        return render(cam, world);
    };
    render_result with_box = render_grid(user_sphere::box_kind::exact);
    render_result without = render_grid(user_sphere::box_kind::none);
    CHECK(test::same_bits(with_box.img, without.img));
    CHECK(with_box.stats.rays == without.stats.rays);
    CHECK(with_box.stats.nonfinite_samples == 0);
}

} // namespace test_user_shapes
