// Triangles (rtweekend/triangle.h) on the teaching surface and in the compiled scene: hand-worked
// hits, watertightness on closed meshes and shared edges, and agreement of the BVH with a
// brute-force double-precision reference.

#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/mesh.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/core/sampling.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/sphere.h>
#include <rtweekend/triangle.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <vector>

namespace test_triangle {

using namespace rt;

namespace {

std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

ray3f make_ray(const compiled_scene& s, const point3& from, const vec3& dir, float tmin = 0,
               float tmax = std::numeric_limits<float>::infinity()) {
    ray3f r;
    r.origin = vec3f(from - s.origin);
    r.dir = vec3f(unit_vector(dir));
    r.tmin = tmin;
    r.tmax = tmax;
    return r;
}

// A regular icosahedron of circumradius `radius` about `centre`, subdivided `levels` times with
// every new vertex pushed onto the sphere: a closed, convex triangle mesh.
std::shared_ptr<triangle_mesh> icosphere(const point3& centre, double radius, int levels) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<vec3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (auto& p : v) p = unit_vector(p);
    std::vector<std::array<uint32_t, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                              {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                              {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                              {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back(unit_vector(v[a] + v[b]));
            return mid[key] = uint32_t(v.size() - 1);
        };
        std::vector<std::array<uint32_t, 3>> next;
        for (auto& t : f) {
            uint32_t a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
            next.push_back({t[0], a, c});
            next.push_back({t[1], b, a});
            next.push_back({t[2], c, b});
            next.push_back({a, b, c});
        }
        f = next;
    }
    std::vector<point3> positions;
    for (auto& p : v) positions.push_back(centre + radius * p);
    return std::make_shared<triangle_mesh>(positions, f, grey());
}

} // namespace

TEST_CASE("triangle: hand-worked hit, barycentrics, normal and both sides") {
    triangle tri(point3(0, 0, -1), point3(1, 0, -1), point3(0, 1, -1), grey());
    hit_record rec;
    // Towards (0.25, 0.25, -1): t = 1 for this unnormalised direction; the point's weights are
    // 1 - 0.25 - 0.25 = 0.5 for a, 0.25 for b and 0.25 for c.
    REQUIRE(tri.hit(ray(point3(0, 0, 0), vec3(0.25, 0.25, -1)), interval(0.001, infinity), rec));
    CHECK(rec.t == doctest::Approx(1.0));
    CHECK(rec.p.x() == doctest::Approx(0.25));
    CHECK(rec.p.y() == doctest::Approx(0.25));
    CHECK(rec.p.z() == doctest::Approx(-1.0));
    // Counter-clockwise a, b, c seen from +z: the outward normal is +z, facing the ray.
    CHECK(rec.front_face);
    CHECK(rec.normal.z() == doctest::Approx(1.0));

    double t, bary[3];
    REQUIRE(intersect_triangle(point3(0, 0, 0), vec3(0.25, 0.25, -1), tri.a(), tri.b(), tri.c(), 0, 10, t, bary));
    CHECK(bary[0] == doctest::Approx(0.5));
    CHECK(bary[1] == doctest::Approx(0.25));
    CHECK(bary[2] == doctest::Approx(0.25));

    // From behind: still hit (no culling), the normal flips to face the ray.
    REQUIRE(tri.hit(ray(point3(0.25, 0.25, -3), vec3(0, 0, 1)), interval(0.001, infinity), rec));
    CHECK(rec.t == doctest::Approx(2.0));
    CHECK_FALSE(rec.front_face);
    CHECK(rec.normal.z() == doctest::Approx(-1.0));

    // Outside the triangle (x + y > 1), out of range, and parallel to its plane: misses.
    CHECK_FALSE(tri.hit(ray(point3(0.6, 0.6, 0), vec3(0, 0, -1)), interval(0.001, infinity), rec));
    CHECK_FALSE(tri.hit(ray(point3(0.2, 0.2, 0), vec3(0, 0, -1)), interval(0.001, 0.99), rec));
    CHECK_FALSE(tri.hit(ray(point3(0.2, 0.2, -1), vec3(1, 0, 0)), interval(-1, infinity), rec));
}

TEST_CASE("triangle: compiled hit matches the hand-worked values, in float") {
    hittable_list world;
    world.add(std::make_shared<triangle>(point3(0, 0, -1), point3(1, 0, -1), point3(0, 1, -1), grey()));
    compiled_scene s = compile_scene(world, point3(0, 0, 0));
    CHECK(s.set<triangle_set>().count == 1);
    CHECK(s.set<sphere_set>().count == 0);
    surface_hit hit;
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0.25, 0.25, -1)), hit));
    CHECK(hit.t == doctest::Approx(std::sqrt(0.25 * 0.25 * 2 + 1)).epsilon(1e-6));
    CHECK(hit.p.z == -1.0f); // from the barycentric weights: exactly on the plane z = -1
    CHECK(hit.p.x == doctest::Approx(0.25).epsilon(1e-6));
    CHECK(hit.normal.z == 1.0f);
    CHECK(hit.front_face);
    CHECK(s.occluded(make_ray(s, point3(0, 0, 0), vec3(0.25, 0.25, -1))));
    // tmax just short of the plane: no hit, not occluded.
    float t_plane = std::sqrt(0.25f * 0.25f * 2 + 1);
    CHECK_FALSE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0.25, 0.25, -1), 0, t_plane * 0.999f), hit));
    CHECK_FALSE(s.occluded(make_ray(s, point3(0, 0, 0), vec3(0.25, 0.25, -1), 0, t_plane * 0.999f)));
    CHECK_FALSE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0.6, 0.6, -1)), hit));
}

TEST_CASE("triangle: rays exactly through a shared edge or vertex are never lost") {
    // Two triangles sharing the edge (0,0,0)-(1,0,0), in the plane z = 0. Rays straight down
    // through points of that edge make its edge function exactly zero in both triangles.
    hittable_list world;
    auto m = grey();
    world.add(std::make_shared<triangle>(point3(0, 0, 0), point3(1, 0, 0), point3(0.5, 1, 0), m));
    world.add(std::make_shared<triangle>(point3(1, 0, 0), point3(0, 0, 0), point3(0.5, -1, 0), m));
    compiled_scene s = compile_scene(world, point3(0, 0, 0));
    pcg32 rng = sample_rng(7, 0, 0);
    surface_hit hit;
    int lost = 0;
    for (int i = 0; i < 2000; ++i) {
        double x = 0.001 + 0.998 * rng.next_float();
        if (!s.intersect(make_ray(s, point3(x, 0, 1), vec3(0, 0, -1)), hit)) ++lost;
        // And slanted rays aimed at the edge: the projected edge function is no longer exactly
        // zero, but the two triangles share it, so one of them must claim the ray.
        vec3 d = unit_vector(vec3(rng.next_float() - 0.5, rng.next_float() - 0.5, -1));
        point3 on_edge(x, 0, 0);
        if (!s.intersect(make_ray(s, on_edge - 2.0 * d, d), hit)) ++lost;
    }
    CHECK(lost == 0);

    // A fan of six triangles around the origin: rays through the shared centre vertex.
    hittable_list fan;
    for (int k = 0; k < 6; ++k) {
        double a0 = k * pi / 3, a1 = (k + 1) * pi / 3;
        fan.add(std::make_shared<triangle>(point3(0, 0, 0), point3(std::cos(a0), std::sin(a0), 0),
                                           point3(std::cos(a1), std::sin(a1), 0), m));
    }
    compiled_scene f = compile_scene(fan, point3(0.1, 0.2, 3));
    lost = 0;
    for (int i = 0; i < 500; ++i) {
        vec3 d = unit_vector(vec3(rng.next_float() - 0.5, rng.next_float() - 0.5, -1));
        if (!f.intersect(make_ray(f, point3(0, 0, 0) - 3.0 * d, d), hit)) ++lost;
    }
    CHECK(lost == 0);
}

TEST_CASE("triangle: a closed mesh has no leaks, near and far from the origin") {
    // Every ray from inside a closed surface must hit it: a miss is a crack between triangles.
    for (double offset : {0.0, 1e4, 1e5}) {
        CAPTURE(offset);
        point3 centre(offset, -offset, 0.5 * offset);
        hittable_list world;
        world.add(icosphere(centre, 2.0, 3)); // 1280 triangles
        compiled_scene s = compile_scene(world, centre + vec3(0.3, -0.2, 0.1));
        CHECK(s.set<triangle_set>().distinct == 1280);
        CHECK_FALSE(s.bvh.nodes.empty());
        pcg32 rng = sample_rng(11, 0, 0);
        surface_hit hit;
        int lost = 0;
        for (int i = 0; i < 20000; ++i) {
            vec3f d = sample_unit_sphere(rng.next_float(), rng.next_float());
            ray3f r;
            r.origin = {0, 0, 0}; // the camera position, inside the mesh
            r.dir = d;
            if (!s.intersect(r, hit)) ++lost;
            else if (i % 97 == 0) {
                // The hit is on the mesh: between the inscribed and circumscribed radii.
                double dist = (hit.p.to_double() + s.origin - centre).length();
                CHECK(dist <= 2.0 * (1 + 1e-5));
                CHECK(dist >= 2.0 * 0.98);
                CHECK_FALSE(hit.front_face); // seen from inside
            }
        }
        CHECK(lost == 0);
    }
}

TEST_CASE("BVH: closest hits of spheres and triangles agree with brute force in double") {
    // A soup of random triangles and spheres, and random rays through it. The compiled scene
    // (float, BVH) must find the same closest primitive as a brute-force loop over the teaching
    // surface in double: the same hit or miss, and t within float precision. Rays that graze an
    // edge may legitimately differ; there must be only a handful.
    pcg32 rng = sample_rng(3, 0, 0);
    auto u = [&] { return double(rng.next_float()); };
    hittable_list world;
    auto m = grey();
    for (int i = 0; i < 3000; ++i) {
        point3 c(20 * u() - 10, 20 * u() - 10, 20 * u() - 10);
        vec3 e1(u() - 0.5, u() - 0.5, u() - 0.5), e2(u() - 0.5, u() - 0.5, u() - 0.5);
        world.add(std::make_shared<triangle>(c, c + 2.0 * e1, c + 2.0 * e2, m));
    }
    for (int i = 0; i < 300; ++i)
        world.add(std::make_shared<sphere>(point3(20 * u() - 10, 20 * u() - 10, 20 * u() - 10), 0.05 + 0.5 * u(), m));
    const point3 origin(1, 2, 3);
    compiled_scene s = compile_scene(world, origin);
    CHECK(s.set<triangle_set>().distinct == 3000);
    CHECK(s.set<sphere_set>().count == 300);
    CHECK(s.bvh.stats.depth >= 2);

    int disagree = 0, hits = 0;
    surface_hit hit;
    const int rays = test::sanitized_share(20000);
    for (int i = 0; i < rays; ++i) {
        point3 from(30 * u() - 15, 30 * u() - 15, 30 * u() - 15);
        vec3 d = unit_vector(vec3(u() - 0.5, u() - 0.5, u() - 0.5));
        ray3f r = make_ray(s, from, d);
        // Reference: the float ray's own origin and direction, in double.
        point3 o = origin + r.origin.to_double();
        vec3 dd = r.dir.to_double();
        hit_record rec;
        bool ref_hit = world.hit(ray(o, dd), interval(0, infinity), rec);
        bool got = s.intersect(r, hit);
        if (ref_hit) ++hits;
        if (got != ref_hit || (got && std::fabs(hit.t - rec.t) > 1e-4 * (1 + rec.t))) ++disagree;
        CHECK(s.occluded(r) == got);
    }
    CHECK(hits > rays / 10); // the test means something
    CHECK(disagree <= 3);
}

TEST_CASE("BVH with spatial splits: closest and any hits agree with brute force, an emitter split is one light") {
    // Small triangles and, one in ten, long thin ones across the scene, which the BVH splits by
    // planes through them (bvh.h): a split triangle is laid out once per leaf holding a part, and
    // must be found wherever a ray meets it, as the brute-force loop in double over the teaching
    // surface finds it.
    pcg32 rng = sample_rng(8, 0, 0);
    auto u = [&] { return double(rng.next_float()); };
    hittable_list world;
    auto m = grey();
    auto light = std::make_shared<diffuse_light>(color(4, 4, 4));
    int emitters = 0;
    for (int i = 0; i < 3000; ++i) {
        point3 c(20 * u() - 10, 20 * u() - 10, 20 * u() - 10);
        const double length = i % 10 == 0 ? 25 : 1;
        vec3 e1(length * (u() - 0.5), length * (u() - 0.5), length * (u() - 0.5)),
            e2(0.2 * (u() - 0.5), 0.2 * (u() - 0.5), 0.2 * (u() - 0.5));
        const bool emits = i % 20 == 0 || i % 7 == 0; // long ones and small ones
        emitters += emits;
        world.add(std::make_shared<triangle>(c, c + e1, c + e2, emits ? std::shared_ptr<material>(light) : m));
    }
    const point3 origin(-1, 2, 0.5);
    compiled_scene s = compile_scene(world, origin);
    CHECK(s.set<triangle_set>().distinct == 3000);
    CHECK(s.set<triangle_set>().count > s.set<triangle_set>().distinct); // some triangles were split
    // One light per emitting triangle, however many copies of it the leaves hold, and every copy
    // names its triangle's light.
    CHECK(s.lights.lights.size() == size_t(emitters));
    const auto& order = s.bvh.order[size_t(shape_id<triangle_set>)];
    std::map<uint32_t, uint32_t> light_of;
    for (size_t k = 0; k < s.set<triangle_set>().count; ++k) {
        const uint32_t l = s.lights.light_at(shape_id<triangle_set>, uint32_t(k));
        if (l == light_set::none) continue;
        const auto [it, is_new] = light_of.try_emplace(order[k], l);
        CHECK(it->second == l);
    }
    CHECK(light_of.size() == size_t(emitters));

    int disagree = 0, hits = 0;
    surface_hit hit;
    const int rays = test::sanitized_share(20000);
    for (int i = 0; i < rays; ++i) {
        // Towards the centroid of a triangle, so that many rays hit one.
        const auto& aim = static_cast<const triangle&>(*world.objects[size_t(rng.next_u32() % world.objects.size())]);
        point3 from(30 * u() - 15, 30 * u() - 15, 30 * u() - 15);
        vec3 d = unit_vector((aim.a() + aim.b() + aim.c()) / 3.0 - from);
        ray3f r = make_ray(s, from, d);
        hit_record rec;
        bool ref_hit = world.hit(ray(origin + r.origin.to_double(), r.dir.to_double()), interval(0, infinity), rec);
        bool got = s.intersect(r, hit);
        if (ref_hit) ++hits;
        if (got != ref_hit || (got && std::fabs(hit.t - rec.t) > 1e-4 * (1 + rec.t))) ++disagree;
        CHECK(s.occluded(r) == got);
    }
    CHECK(hits > rays / 10);
    CHECK(disagree <= 3); // rays that graze an edge may differ
}

TEST_CASE("triangle: invalid input is rejected, degenerate mesh triangles are skipped") {
    auto m = grey();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    {
        hittable_list w;
        w.add(std::make_shared<triangle>(point3(nan, 0, 0), point3(1, 0, 0), point3(0, 1, 0), m));
        CHECK_THROWS_AS(compile_scene(w, point3(0, 0, 5)), scene_error);
    }
    {
        hittable_list w;
        w.add(std::make_shared<triangle>(point3(0, 0, 0), point3(1, 1, 1), point3(2, 2, 2), m)); // collinear
        CHECK_THROWS_WITH_AS(compile_scene(w, point3(0, 0, 5)), doctest::Contains("zero area"), scene_error);
    }
    {
        hittable_list w;
        w.add(std::make_shared<triangle>(point3(0, 0, 0), point3(1, 0, 0), point3(0, 1, 0), nullptr));
        CHECK_THROWS_WITH_AS(compile_scene(w, point3(0, 0, 5)), doctest::Contains("no material"), scene_error);
    }
    {
        // A mesh: one good triangle, one with a repeated vertex (zero area): skipped, counted.
        hittable_list w;
        w.add(std::make_shared<triangle_mesh>(std::vector<point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                              std::vector<std::array<uint32_t, 3>>{{0, 1, 2}, {0, 1, 1}}, m));
        compiled_scene s = compile_scene(w, point3(0, 0, 5));
        CHECK(s.set<triangle_set>().count == 1);
        CHECK(s.set<triangle_set>().degenerate == 1);
    }
    {
        hittable_list w;
        w.add(std::make_shared<triangle_mesh>(std::vector<point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                              std::vector<std::array<uint32_t, 3>>{{0, 1, 3}}, m));
        CHECK_THROWS_WITH_AS(compile_scene(w, point3(0, 0, 5)), doctest::Contains("vertex 3"), scene_error);
    }
}

} // namespace test_triangle
