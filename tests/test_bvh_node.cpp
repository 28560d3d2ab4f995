// Book 2's bvh_node (rtweekend/bvh.h): its own hit() finds what a plain list finds, its box holds
// every object, and the renderer sees through it to the same image.
#include <doctest/doctest.h>

#include "test_helpers.h"

#include <rtweekend/bvh.h>
#include <rtweekend/camera.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/quad.h>
#include <rtweekend/sphere.h>

#include <memory>
#include <random>

namespace test_bvh_node {

using namespace rt;
using namespace test;

namespace {

hittable_list random_spheres(int n, std::mt19937& gen) {
    std::uniform_real_distribution<double> pos(-10, 10), rad(0.1, 1.5);
    auto mat = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    hittable_list list;
    for (int i = 0; i < n; ++i) list.add(std::make_shared<sphere>(point3(pos(gen), pos(gen), pos(gen)), rad(gen), mat));
    return list;
}

} // namespace

TEST_CASE("bvh_node: hit() finds the same nearest hit as the list it was built from") {
    std::mt19937 gen(7);
    for (int n : {1, 2, 3, 17, 200}) {
        hittable_list list = random_spheres(n, gen);
        bvh_node tree(list);
        std::uniform_real_distribution<double> pos(-15, 15), dir(-1, 1);
        int hits = 0;
        for (int i = 0; i < 2000; ++i) {
            // From anywhere towards a point near some object, so that many rays hit.
            const aabb box = list.objects[size_t(i) % size_t(n)]->bounding_box();
            const point3 near(box.x.min + dir(gen) + 1, box.y.min + dir(gen) + 1, box.z.min + dir(gen) + 1);
            const point3 o(pos(gen), pos(gen), pos(gen));
            ray r(o, i % 2 ? near - o : vec3(dir(gen), dir(gen), dir(gen)));
            hit_record a, b;
            bool in_list = list.hit(r, interval(0.001, infinity), a);
            bool in_tree = tree.hit(r, interval(0.001, infinity), b);
            REQUIRE(in_list == in_tree);
            if (in_list) {
                ++hits;
                CHECK(a.t == b.t);
                CHECK(a.p.x() == b.p.x());
            }
        }
        CHECK(hits > 0);
    }
}

TEST_CASE("bvh_node: the bounding box holds every object's box, and no more") {
    std::mt19937 gen(11);
    hittable_list list = random_spheres(50, gen);
    bvh_node tree(list);
    aabb box = tree.bounding_box();
    double lo = infinity, hi = -infinity;
    for (const auto& o : list.objects) {
        aabb b = o->bounding_box();
        CHECK(box.x.min <= b.x.min);
        CHECK(box.x.max >= b.x.max);
        CHECK(box.y.min <= b.y.min);
        CHECK(box.z.max >= b.z.max);
        lo = std::fmin(lo, b.x.min);
        hi = std::fmax(hi, b.x.max);
    }
    CHECK(box.x.min == lo);
    CHECK(box.x.max == hi);
}

TEST_CASE("bvh_node: the book's forms compile, and an empty list is a clear error") {
    std::mt19937 gen(3);
    hittable_list list = random_spheres(5, gen);
    auto a = std::make_shared<bvh_node>(list);
    auto b = std::make_shared<bvh_node>(list, 0.0, 1.0); // the book's older form with times
    auto c = std::make_shared<bvh_node>(list.objects, 0, list.objects.size());
    hittable_list world(a);
    CHECK(world.objects.size() == 1);
    CHECK(b->bounding_box().x.min == a->bounding_box().x.min);
    CHECK(c->bounding_box().y.max == a->bounding_box().y.max);
    CHECK_THROWS_AS(bvh_node{hittable_list{}}, scene_error);
}

TEST_CASE("bvh_node: the renderer sees through it: the same bits as the plain list") {
    std::mt19937 gen(5);
    hittable_list list = random_spheres(40, gen);
    auto light = std::make_shared<diffuse_light>(color(4, 4, 4));
    list.add(std::make_shared<quad>(point3(-3, 12, -3), vec3(6, 0, 0), vec3(0, 0, 6), light));
    hittable_list wrapped;
    wrapped.add(std::make_shared<bvh_node>(list));

    camera cam = test_camera(48, 32, 4, 6);
    cam.lookfrom = point3(0, 0, 30);
    cam.lookat = point3(0, 0, 0);
    cam.vfov = 50;
    CHECK(same_bits(render_checked(cam, list).img, render_checked(cam, wrapped).img));
}

TEST_CASE("bvh_node: a node over one object holds it on both sides, the renderer takes it once") {
    auto mat = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    hittable_list one(std::make_shared<sphere>(point3(0, 0, 0), 1, mat));
    hittable_list world(std::make_shared<bvh_node>(one));
    compiled_scene scene = compile_scene(world, point3(0, 0, 5));
    CHECK(scene.set<sphere_set>().count == 1);
    hittable_list three;
    for (int i = 0; i < 3; ++i) three.add(std::make_shared<sphere>(point3(3 * i, 0, 0), 1, mat));
    CHECK(compile_scene(hittable_list(std::make_shared<bvh_node>(three)), point3(0, 0, 5)).set<sphere_set>().count == 3);
}

} // namespace test_bvh_node
