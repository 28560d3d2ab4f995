// Motion blur (book 2): a moving sphere on the teaching surface and in the engine, rays that carry
// a time, and renders that average over the shutter interval.
//
// The sphere used throughout moves from (0, 0, -5) at time 0 to (1, 0, -5) at time 1, radius 1,
// and the ray starts at (0.5, 0, 0) going along -z. By hand: at time 0 the centre is 0.5 to the
// ray's left, so the ray meets the sphere where z = -5 + sqrt(1 - 0.25): t = 5 - sqrt(3)/2,
// outward normal (0.5, 0, sqrt(3)/2); at time 0.5 the centre is on the ray: t = 4, normal
// (0, 0, 1); at time 1 it is 0.5 to the right: t = 5 - sqrt(3)/2, normal (-0.5, 0, sqrt(3)/2).

#include "test_helpers.h"

#include <rtweekend/render/path_tracer.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <random>

namespace test_motion {

using namespace rt;

namespace {

std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

const double half_sqrt3 = std::sqrt(3.0) / 2;

struct expected_hit {
    double time, t;
    vec3 normal;
};
const expected_hit expected[] = {
    {0.0, 5 - half_sqrt3, vec3(0.5, 0, half_sqrt3)},
    {0.5, 4.0, vec3(0, 0, 1)},
    {1.0, 5 - half_sqrt3, vec3(-0.5, 0, half_sqrt3)},
};

std::shared_ptr<sphere> moving_test_sphere() {
    return std::make_shared<sphere>(point3(0, 0, -5), point3(1, 0, -5), 1.0, grey());
}

ray3f engine_ray(const vec3& origin, const vec3& dir, float time) {
    ray3f r;
    r.origin = vec3f(origin);
    r.dir = vec3f(unit_vector(dir));
    r.time = time;
    return r;
}

} // namespace

TEST_CASE("motion: a moving sphere's hit() at times 0, 0.5 and 1 is where its centre is then") {
    auto s = moving_test_sphere();
    CHECK(s->is_moving());
    for (const expected_hit& e : expected) {
        CAPTURE(e.time);
        hit_record rec;
        REQUIRE(s->hit(ray(point3(0.5, 0, 0), vec3(0, 0, -1), e.time), interval(0.001, infinity), rec));
        CHECK(rec.t == doctest::Approx(e.t).epsilon(1e-12));
        CHECK(rec.front_face);
        for (int c = 0; c < 3; ++c) CHECK(rec.normal[c] == doctest::Approx(e.normal[c]).epsilon(1e-12));
        CHECK((rec.p - point3(0.5, 0, -e.t)).length() < 1e-12);
    }
    // Centre at time 0.25: (0.25, 0, -5).
    const point3 c = s->center(0.25);
    CHECK(c.x() == doctest::Approx(0.25));
    CHECK(c.z() == doctest::Approx(-5));
    // A still sphere does not move: the two-centre constructor with equal centres is one too.
    CHECK_FALSE(sphere(point3(1, 2, 3), 1, grey()).is_moving());
    CHECK_FALSE(sphere(point3(1, 2, 3), point3(1, 2, 3), 1, grey()).is_moving());
}

TEST_CASE("motion: a moving sphere's bounding box is the box around its boxes at both ends") {
    sphere s(point3(0, 0, -5), point3(1, 2, -5), 1.0, grey());
    const aabb box = s.bounding_box();
    CHECK(box.x.min == doctest::Approx(-1));
    CHECK(box.x.max == doctest::Approx(2));
    CHECK(box.y.min == doctest::Approx(-1));
    CHECK(box.y.max == doctest::Approx(3));
    CHECK(box.z.min == doctest::Approx(-6));
    CHECK(box.z.max == doctest::Approx(-4));
}

TEST_CASE("motion: the engine hits a moving sphere where it is at the ray's time") {
    hittable_list world;
    world.add(moving_test_sphere());
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    CHECK(scene.set<sphere_set>().count == 0);
    CHECK(scene.set<moving_sphere_set>().count == 1);
    CHECK(scene.has_motion);
    CHECK(scene.uses_time());
    for (const expected_hit& e : expected) {
        CAPTURE(e.time);
        surface_hit hit;
        REQUIRE(scene.intersect(engine_ray(vec3(0.5, 0, 0), vec3(0, 0, -1), float(e.time)), hit));
        CHECK(hit.kind == shape_id<moving_sphere_set>);
        CHECK(hit.t == doctest::Approx(e.t).epsilon(1e-5));
        CHECK(hit.front_face);
        CHECK(hit.time == float(e.time)); // spawned rays keep it
        for (int c = 0; c < 3; ++c) CHECK(hit.normal[c] == doctest::Approx(e.normal[c]).epsilon(1e-5));
        CHECK(hit.p.x == doctest::Approx(0.5).epsilon(1e-5));
        CHECK(hit.p.z == doctest::Approx(-e.t).epsilon(1e-5));
        CHECK(scene.occluded(engine_ray(vec3(0.5, 0, 0), vec3(0, 0, -1), float(e.time))));
        // A ray spawned from the hit carries the path's time.
        const ray3f next = detail::spawn_ray(hit, vec3f(0, 0, 1), 100.0f);
        CHECK(next.time == float(e.time));
    }
    // The ray x = 1.6: at time 0 the centre is 1.6 away (a miss), at time 1 only 0.6 (a hit).
    CHECK_FALSE(scene.occluded(engine_ray(vec3(1.6, 0, 0), vec3(0, 0, -1), 0.0f)));
    CHECK(scene.occluded(engine_ray(vec3(1.6, 0, 0), vec3(0, 0, -1), 1.0f)));
}

TEST_CASE("motion: any object under moving() is hit where it is at the ray's time, as an instance") {
    // The same motion as the moving sphere above, given to a still sphere, to a mesh that shares its
    // triangles with a still copy, and (through the teaching surface's hit()) checked against the
    // expected hits: the engine traces it as an instance whose place shifts with the time.
    hittable_list world;
    world.add(std::make_shared<moving>(std::make_shared<sphere>(point3(0, 0, -5), 1.0, grey()), vec3(1, 0, 0)));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    CHECK(scene.set<instance_set>().count() == 1);
    CHECK(scene.has_motion);
    for (const expected_hit& e : expected) {
        CAPTURE(e.time);
        surface_hit hit;
        REQUIRE(scene.intersect(engine_ray(vec3(0.5, 0, 0), vec3(0, 0, -1), float(e.time)), hit));
        CHECK(hit.t == doctest::Approx(e.t).epsilon(1e-5));
        for (int c = 0; c < 3; ++c) CHECK(hit.normal[c] == doctest::Approx(e.normal[c]).epsilon(1e-5));
        CHECK(hit.p.x == doctest::Approx(0.5).epsilon(1e-5));
        CHECK(hit.p.z == doctest::Approx(-e.t).epsilon(1e-5));
        // The book's own hit() agrees.
        hit_record rec;
        REQUIRE(world.hit(ray(point3(0.5, 0, 0), vec3(0, 0, -1), e.time), interval(0.001, infinity), rec));
        CHECK(rec.t == doctest::Approx(e.t).epsilon(1e-9));
    }
    CHECK_FALSE(scene.occluded(engine_ray(vec3(1.6, 0, 0), vec3(0, 0, -1), 0.0f)));
    CHECK(scene.occluded(engine_ray(vec3(1.6, 0, 0), vec3(0, 0, -1), 1.0f)));

    // A triangle at z = -5 spanning x in [-1, 1], placed twice: still, and moving by (0, 10, 0).
    auto tri = std::make_shared<triangle_mesh>();
    tri->positions = {point3(-1, -1, -5), point3(1, -1, -5), point3(0, 1, -5)};
    tri->faces = {{0, 1, 2}};
    tri->mat = grey();
    hittable_list two;
    two.add(tri);
    two.add(std::make_shared<moving>(std::make_shared<translate>(tri, vec3(0, 0, -1)), vec3(0, 10, 0)));
    const compiled_scene both = compile_scene(two, point3(0, 0, 0));
    // Through (0, 0): the still one at z = -5 at any time.
    for (float time : {0.0f, 0.5f, 1.0f}) {
        surface_hit hit;
        REQUIRE(both.intersect(engine_ray(vec3(0, 0, 0), vec3(0, 0, -1), time), hit));
        CHECK(hit.t == doctest::Approx(5).epsilon(1e-6));
    }
    // Through (0, 10): the moving one (z = -6) only at time 1, when it has moved up by 10.
    surface_hit hit;
    CHECK_FALSE(both.intersect(engine_ray(vec3(0, 10, 0), vec3(0, 0, -1), 0.0f), hit));
    CHECK_FALSE(both.intersect(engine_ray(vec3(0, 10, 0), vec3(0, 0, -1), 0.5f), hit));
    REQUIRE(both.intersect(engine_ray(vec3(0, 10, 0), vec3(0, 0, -1), 1.0f), hit));
    CHECK(hit.t == doctest::Approx(6).epsilon(1e-6));
    CHECK(hit.p.y == doctest::Approx(10).epsilon(1e-6));
}

TEST_CASE("motion: a still scene uses no time and no moving-sphere kind") {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -5), 1.0, grey()));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    CHECK(scene.set<sphere_set>().count == 1);
    CHECK(scene.set<moving_sphere_set>().count == 0);
    CHECK_FALSE(scene.has_motion);
    CHECK_FALSE(scene.uses_time());
    CHECK(scene.single_kind == shape_id<sphere_set>);
}

TEST_CASE("motion: many moving spheres in a BVH agree with the teaching surface at random times") {
    // Boxes must cover each sphere's whole motion: the engine's closest hit, at any time, is the
    // one the double-precision hit() of every sphere finds.
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> u(-1, 1);
    hittable_list world;
    for (int i = 0; i < 300; ++i) {
        const point3 c(10 * u(gen), 10 * u(gen), -20 + 5 * u(gen));
        const vec3 motion(3 * u(gen), 3 * u(gen), u(gen));
        if (i % 3 == 0)
            world.add(std::make_shared<sphere>(c, 0.3 + 0.2 * u(gen), grey())); // a mixed scene
        else
            world.add(std::make_shared<sphere>(c, c + motion, 0.5 + 0.2 * u(gen), grey()));
    }
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    REQUIRE(scene.bvh.stats.nodes > 0);
    int hits = 0;
    for (int k = 0; k < 3000; ++k) {
        const vec3 dir = unit_vector(vec3(0.5 * u(gen), 0.5 * u(gen), -1));
        const double time = 0.5 * (u(gen) + 1);
        hit_record rec;
        const bool expect = world.hit(ray(point3(0, 0, 0), dir, time), interval(1e-6, infinity), rec);
        surface_hit hit;
        const bool found = scene.intersect(engine_ray(vec3(0, 0, 0), dir, float(time)), hit);
        CHECK(found == expect);
        if (found && expect) {
            ++hits;
            CHECK(hit.t == doctest::Approx(rec.t).epsilon(1e-4));
            CHECK(dot(hit.normal.to_double(), rec.normal) > 0.9999);
        }
    }
    CHECK(hits > 300);
}

TEST_CASE("motion: a pixel the moving emitter covers for a quarter of the shutter gets a quarter of its light") {
    // A one-pixel camera looking along -z with a tiny field of view; the emitter (radius 1,
    // radiance 1) moves from centre x = 0 to x = 4 at z = -5: the pixel's ray meets it while
    // |4 time| < 1, a quarter of [0, 1). Moving emitters are not light-sampled: counted when hit.
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -5), point3(4, 0, -5), 1.0,
                                       std::make_shared<diffuse_light>(color(1, 1, 1))));
    camera cam = test::test_camera(1, 1, 4096, 4);
    cam.vfov = 0.1;
    cam.background = color(0, 0, 0);
    const render_result r = test::render_checked(cam, world);
    const double expected_value = 0.25, sigma = std::sqrt(0.25 * 0.75 / 4096);
    CHECK(std::fabs(r.img.pixel(0, 0).x() - expected_value) < 4 * sigma);
}

TEST_CASE("motion: a motion-blurred render is bit-identical at 1 and 2 threads, and differs from a still one"
          * doctest::test_suite("threads")) {
    auto scene_with = [](bool moving) {
        hittable_list world;
        world.add(std::make_shared<sphere>(point3(0, -100.5, -1), 100, grey()));
        auto m = std::make_shared<metal>(color(0.8, 0.6, 0.2), 0.2);
        for (int i = 0; i < 5; ++i) {
            const point3 c(-1 + 0.5 * i, 0, -1.5);
            if (moving)
                world.add(std::make_shared<sphere>(c, c + vec3(0, 0.3, 0), 0.2, i % 2 ? m : grey()));
            else
                world.add(std::make_shared<sphere>(c, 0.2, i % 2 ? m : grey()));
        }
        return world;
    };
    const hittable_list moving = scene_with(true), still = scene_with(false);
    camera cam = test::test_camera(24, 16, 8, 6);
    cam.settings.threads = 1;
    const render_result one = test::render_checked(cam, moving);
    cam.settings.threads = 2;
    const render_result two = test::render_checked(cam, moving);
    CHECK(test::same_bits(one.img, two.img));
    CHECK_FALSE(test::same_bits(one.img, test::render_checked(cam, still).img));
}

} // namespace test_motion
