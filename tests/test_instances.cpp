// General transforms (rotate about any axis, non-uniform scale, any affine map) on the teaching
// surface, and the engine's instances: an object compiled once, traced in its own frame wherever
// it is placed. Expected values are derived by hand (Rodrigues' formula, the ellipsoid's
// gradient) or from the same geometry transformed by hand and traced without instancing.

#include "test_helpers.h"

#include <rtweekend/render/path_tracer.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <random>
#include <sstream>

namespace test_instances {

using namespace rt;

namespace {

std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

ray3f engine_ray(const compiled_scene& s, const point3& from, const vec3& dir, float time = 0) {
    ray3f r;
    r.origin = vec3f(from - s.origin);
    r.dir = vec3f(unit_vector(dir));
    r.time = time;
    return r;
}

void check_vec(const vec3& a, const vec3& b, double tol) {
    for (int c = 0; c < 3; ++c) CHECK(a[c] == doctest::Approx(b[c]).epsilon(tol).scale(1));
}

// A closed mesh of 2 n (n - 1) triangles approximating the unit sphere (a UV sphere).
std::shared_ptr<triangle_mesh> uv_sphere_mesh(int n) {
    auto mesh = std::make_shared<triangle_mesh>();
    mesh->mat = grey();
    const int rings = n, segments = 2 * n;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double theta = pi * i / rings, phi = 2 * pi * j / segments;
            mesh->positions.push_back(point3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
        }
    auto at = [&](int i, int j) { return uint32_t(i * segments + (j % segments)); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            if (i > 0) mesh->faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
            if (i < rings - 1) mesh->faces.push_back({at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
        }
    return mesh;
}

// The same mesh with every vertex mapped by x -> m x + t: the transform done by hand.
std::shared_ptr<triangle_mesh> mapped(const triangle_mesh& in, const mat3& m, const vec3& t) {
    auto out = std::make_shared<triangle_mesh>(in);
    for (point3& p : out->positions) p = m * p + t;
    return out;
}

} // namespace

TEST_CASE("instances: mat3::rotation matches Rodrigues' formula at hand-chosen points") {
    // 120 degrees about (1, 1, 1) permutes the axes: x -> y -> z -> x.
    const mat3 r120 = mat3::rotation(vec3(1, 1, 1), 120);
    check_vec(r120 * vec3(1, 0, 0), vec3(0, 1, 0), 1e-12);
    check_vec(r120 * vec3(0, 1, 0), vec3(0, 0, 1), 1e-12);
    check_vec(r120 * vec3(0, 0, 1), vec3(1, 0, 0), 1e-12);
    // 180 degrees about k = (1, 1, 0)/sqrt 2: v -> 2 (k.v) k - v.
    const mat3 r180 = mat3::rotation(vec3(2, 2, 0), 180);
    check_vec(r180 * vec3(1, 0, 0), vec3(0, 1, 0), 1e-12);
    check_vec(r180 * vec3(0, 0, 1), vec3(0, 0, -1), 1e-12);
    // 90 degrees about the same axis, v = z perpendicular to it: v -> k x v = (1, -1, 0)/sqrt 2.
    check_vec(mat3::rotation(vec3(1, 1, 0), 90) * vec3(0, 0, 1), vec3(1, -1, 0) / std::sqrt(2.0), 1e-12);
    // About y it is rotate_y's rotation: +x turns towards -z.
    check_vec(mat3::rotation(vec3(0, 1, 0), 90) * vec3(1, 0, 0), vec3(0, 0, -1), 1e-12);
    // The inverse undoes it.
    const mat3 m(vec3(2, 1, 0), vec3(0, 3, 1), vec3(1, 0, 1));
    const mat3 id = m * m.inverse();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) CHECK(id(i, j) == doctest::Approx(i == j ? 1.0 : 0.0).scale(1));
}

TEST_CASE("instances: rotate about an axis moves a triangle where Rodrigues puts it, in hit() and in the engine") {
    // The triangle (1,0,0) (0,1,0) (0,0,1) turned 120 degrees about (1,1,1) is itself, with its
    // vertices permuted; turned 180 degrees about z it is (-1,0,0) (0,-1,0) (0,0,1). A ray from
    // far along -(1,1,1) towards the origin meets the latter at (-1/3,-1/3,1/3).
    auto tri = std::make_shared<triangle>(point3(1, 0, 0), point3(0, 1, 0), point3(0, 0, 1), grey());
    hittable_list world;
    world.add(std::make_shared<rotate>(tri, vec3(0, 0, 1), 180));
    const point3 target(-1.0 / 3, -1.0 / 3, 1.0 / 3), from = target + vec3(0, 0, 10);
    hit_record rec;
    REQUIRE(world.hit(ray(from, vec3(0, 0, -1)), interval(0.001, infinity), rec));
    CHECK(rec.t == doctest::Approx(10));
    check_vec(rec.p, target, 1e-12);
    check_vec(rec.normal, vec3(-1, -1, 1) / std::sqrt(3.0), 1e-9); // the plane -x - y + z = 1, facing the ray
    const compiled_scene scene = compile_scene(world, point3(0, 0, 5));
    CHECK(scene.set<triangle_set>().count == 1); // a rigid map over one triangle: flattened
    surface_hit hit;
    REQUIRE(scene.intersect(engine_ray(scene, from, vec3(0, 0, -1)), hit));
    CHECK(hit.t == doctest::Approx(10).epsilon(1e-5));
    check_vec((scene.origin + hit.p.to_double()), target, 1e-5);
}

TEST_CASE("instances: a sphere scaled by (2, 1, 1) is the ellipsoid x^2/4 + y^2 + z^2 = 1, normals by its gradient") {
    // The point (sqrt 2, 1/2, 1/2) is on it (2/4 + 1/4 + 1/4 = 1); a ray down -z from z = 5 meets
    // it there at t = 4.5. The gradient of x^2/4 + y^2 + z^2 there is 2 (sqrt2/4, 1/2, 1/2).
    auto ball = std::make_shared<sphere>(point3(0, 0, 0), 1.0, grey());
    hittable_list world;
    world.add(std::make_shared<scale>(ball, vec3(2, 1, 1)));
    const point3 p(std::sqrt(2.0), 0.5, 0.5), from(p.x(), p.y(), 5);
    const vec3 gradient = unit_vector(vec3(std::sqrt(2.0) / 4, 0.5, 0.5));

    hit_record rec;
    REQUIRE(world.hit(ray(from, vec3(0, 0, -1)), interval(0.001, infinity), rec));
    CHECK(rec.t == doctest::Approx(4.5).epsilon(1e-12));
    check_vec(rec.p, p, 1e-12);
    check_vec(rec.normal, gradient, 1e-12);
    CHECK(rec.front_face);

    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    CHECK(scene.set<sphere_set>().count == 0); // no longer a sphere: an instance
    CHECK(scene.set<instance_set>().count() == 1);
    surface_hit hit;
    REQUIRE(scene.intersect(engine_ray(scene, from, vec3(0, 0, -1)), hit));
    CHECK(hit.kind == shape_id<instance_set>);
    CHECK(hit.t == doctest::Approx(4.5).epsilon(1e-5));
    check_vec(hit.p.to_double(), p, 1e-5);
    check_vec(hit.normal.to_double(), gradient, 1e-5);
    CHECK(hit.front_face);
    // From inside, the far side: the normal faces the ray (inwards), front_face false.
    REQUIRE(scene.intersect(engine_ray(scene, point3(0, 0, 0), vec3(1, 0, 0)), hit));
    CHECK(hit.t == doctest::Approx(2).epsilon(1e-5));
    check_vec(hit.normal.to_double(), vec3(-1, 0, 0), 1e-5);
    CHECK_FALSE(hit.front_face);
}

TEST_CASE("instances: an instanced mesh is hit exactly where the same mesh transformed by hand is") {
    // Two placements of one mesh (so it becomes an instance) under a rotation, a non-uniform
    // scale and a translation; the reference is each placement's mesh with its vertices mapped
    // by hand, compiled flat. Same t and normal for random rays.
    auto mesh = uv_sphere_mesh(8); // 224 triangles
    const mat3 a = mat3::rotation(vec3(1, 2, 3), 40) * mat3::diagonal(vec3(2, 0.5, 1));
    const mat3 b = mat3::rotation(vec3(0, 1, 1), -70) * mat3::diagonal(vec3(0.7, 1.5, 1.2));
    const vec3 ta(2, 0, -6), tb(-2, 1, -7);
    hittable_list instanced, by_hand;
    instanced.add(std::make_shared<transform>(mesh, a, ta));
    instanced.add(std::make_shared<translate>(std::make_shared<transform>(mesh, b), tb));
    by_hand.add(mapped(*mesh, a, ta));
    by_hand.add(mapped(*mesh, b, tb));

    const compiled_scene inst = compile_scene(instanced, point3(0, 0, 0));
    const compiled_scene flat = compile_scene(by_hand, point3(0, 0, 0));
    CHECK(inst.set<instance_set>().count() == 2);
    REQUIRE(inst.objects.size() == 1);
    CHECK(inst.objects[0]->set<triangle_set>().distinct == mesh->faces.size());
    CHECK(inst.set<triangle_set>().count == 0);
    CHECK(flat.set<triangle_set>().distinct == 2 * mesh->faces.size());

    std::mt19937 gen(11);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
        const point3 from(4 * u(gen), 4 * u(gen), 2);
        const vec3 dir = unit_vector(point3(3 * u(gen), 2 * u(gen), -6.5) - from);
        surface_hit hi, hf;
        const bool fi = inst.intersect(engine_ray(inst, from, dir), hi);
        const bool ff = flat.intersect(engine_ray(flat, from, dir), hf);
        hit_record rec;
        const bool fd = instanced.hit(ray(from, dir), interval(1e-9, infinity), rec); // teaching surface, double
        CHECK(fi == ff);
        CHECK(fi == fd);
        if (!(fi && ff && fd)) continue;
        ++hits;
        CHECK(hi.t == doctest::Approx(hf.t).epsilon(1e-4));
        CHECK(hi.t == doctest::Approx(rec.t).epsilon(1e-4));
        CHECK(dot(hi.normal, hf.normal) > 0.9999f);
        CHECK(length(hi.p - hf.p) < 1e-3f);
        CHECK(hi.front_face == hf.front_face);
    }
    CHECK(hits > 300);
}

TEST_CASE("instances: a mesh placed 1000 times is stored once") {
    auto mesh = uv_sphere_mesh(6); // 120 triangles
    hittable_list world;
    for (int i = 0; i < 1000; ++i)
        world.add(std::make_shared<translate>(mesh, vec3(3.0 * (i % 10), 3.0 * ((i / 10) % 10), -3.0 * (i / 100) - 5)));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    CHECK(scene.set<instance_set>().count() == 1000);
    REQUIRE(scene.objects.size() == 1);
    CHECK(scene.objects[0]->set<triangle_set>().distinct == mesh->faces.size());
    CHECK(scene.set<triangle_set>().count == 0);
    // Each placement is where its translation puts it: straight down -z onto the sphere of
    // instance (i, j) in the front layer, whose top point is at z = -5 + 1.
    for (int i : {0, 3, 9})
        for (int j : {0, 5, 9}) {
            surface_hit hit;
            const point3 from(3.0 * i, 3.0 * j, 10);
            REQUIRE(scene.intersect(engine_ray(scene, from, vec3(0, 0, -1)), hit));
            CHECK(hit.t == doctest::Approx(14).epsilon(1e-5)); // the mesh's pole vertex is exact
        }
    // Used once, the same mesh is copied (flattened): today's behaviour, the fastest to trace.
    hittable_list once;
    once.add(std::make_shared<translate>(mesh, vec3(0, 0, -5)));
    const compiled_scene single = compile_scene(once, point3(0, 0, 0));
    CHECK(single.set<instance_set>().count() == 0);
    CHECK(single.set<triangle_set>().distinct == mesh->faces.size());
}

TEST_CASE("instances: small subtrees are copied, spheres under a similarity stay spheres") {
    auto b = box(point3(0, 0, 0), point3(1, 1, 1), grey());
    auto ball = std::make_shared<sphere>(point3(1, 0, 0), 0.5, grey());
    hittable_list world;
    for (int i = 0; i < 5; ++i) world.add(std::make_shared<translate>(b, vec3(2.0 * i, 0, -5)));
    // Uniform scale 3 after a turn: the sphere of radius 1.5 about 3 R (1, 0, 0) = (0, 0, -3)
    // (90 degrees about y takes +x to -z).
    world.add(std::make_shared<scale>(std::make_shared<rotate>(ball, vec3(0, 1, 0), 90), 3.0));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    CHECK(scene.set<instance_set>().count() == 0);
    CHECK(scene.set<quad_set>().count == 30);
    REQUIRE(scene.set<sphere_set>().count == 1);
    CHECK(scene.set<sphere_set>().r[0] == doctest::Approx(1.5));
    CHECK(scene.set<sphere_set>().z[0] == doctest::Approx(-3));
    CHECK(std::fabs(scene.set<sphere_set>().x[0]) < 1e-6);
}

namespace {
// Shoots rays at `target_of(k)` from `from_of(k)` and, from every hit, a ray in a random direction
// on the side the ray came from; returns how many of those hit the scene again (none may, for a
// convex surface) and counts the hits in `tested`.
template <class Target, class From>
int spawned_rays_hitting_again(const compiled_scene& scene, Target target_of, From from_of, int& tested) {
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int again = 0;
    tested = 0;
    for (int k = 0; k < 4000; ++k) {
        const point3 target = target_of(gen), from = from_of(gen, target);
        surface_hit hit;
        if (!scene.intersect(engine_ray(scene, from, target - from), hit)) continue;
        vec3 d(u(gen), u(gen), u(gen));
        if (d.length_squared() < 1e-6) continue;
        if (dot(d, hit.normal.to_double()) < 0) d = -d;
        ++tested;
        if (scene.occluded(detail::spawn_ray(hit, vec3f(unit_vector(d)), std::numeric_limits<float>::infinity())))
            ++again;
    }
    return again;
}
} // namespace

TEST_CASE("instances: rays spawned from instanced convex shapes never hit them again") {
    // A ray leaving a convex surface outwards meets it nowhere. The offsets must cover the error
    // of carrying points out of the object's frame and rays back into it.
    std::uniform_real_distribution<double> u(-1, 1);
    SUBCASE("a strongly stretched ellipsoid far from the origin") {
        auto ball = std::make_shared<sphere>(point3(0, 0, 0), 1.0, grey());
        hittable_list world;
        world.add(std::make_shared<translate>(std::make_shared<scale>(ball, vec3(300, 1, 0.02)), vec3(1000, 20, -30)));
        const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
        REQUIRE(scene.set<instance_set>().count() == 1);
        int tested = 0;
        const int again = spawned_rays_hitting_again(
            scene, [&](std::mt19937& g) { return point3(1000 + 250 * u(g), 20 + 0.8 * u(g), -30); },
            [&](std::mt19937& g, const point3& t) { return t + vec3(50 * u(g), 5 * u(g), 40); }, tested);
        CHECK(tested > 1000);
        CHECK(again == 0);
    }
    SUBCASE("a mesh far from its own origin, brought back near the scene's: the map cancels") {
        // Object coordinates about 500 in size, world coordinates about 1: the point carried out
        // of the object's frame is only as good as a few ulps of 1000, far more than the ray
        // offset of a point near the origin covers by itself.
        auto mesh = mapped(*uv_sphere_mesh(8), mat3(), vec3(-500, 0, 0));
        hittable_list world;
        for (double y : {0.0, 50.0})
            world.add(std::make_shared<translate>(std::make_shared<scale>(mesh, vec3(2, 1, 1)), vec3(1000, y, -3)));
        const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
        REQUIRE(scene.set<instance_set>().count() == 2);
        int tested = 0;
        const int again = spawned_rays_hitting_again(
            scene, [&](std::mt19937& g) { return point3(1.8 * u(g), 0.9 * u(g), -3); },
            [&](std::mt19937& g, const point3& t) { return t + vec3(3 * u(g), 3 * u(g), 5); }, tested);
        CHECK(tested > 1000);
        CHECK(again == 0);
    }
}

TEST_CASE("instances: a moving sphere inside an instance moves with the ray's time, and renders are deterministic"
          * doctest::test_suite("threads")) {
    auto mover = std::make_shared<sphere>(point3(0, 0, 0), point3(1, 0, 0), 0.5, grey());
    hittable_list world;
    world.add(std::make_shared<scale>(mover, vec3(2, 1, 1))); // centre (0,0,0) -> (2,0,0), an ellipsoid
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    REQUIRE(scene.set<instance_set>().count() == 1);
    CHECK(scene.has_motion);
    surface_hit hit;
    // Down -z through x = 2: the ellipsoid's centre is there only at time 1.
    CHECK_FALSE(scene.intersect(engine_ray(scene, point3(2, 0, 5), vec3(0, 0, -1), 0.0f), hit));
    REQUIRE(scene.intersect(engine_ray(scene, point3(2, 0, 5), vec3(0, 0, -1), 1.0f), hit));
    CHECK(hit.t == doctest::Approx(4.5).epsilon(1e-5));

    hittable_list room;
    room.add(std::make_shared<sphere>(point3(0, -100.5, -1), 100, grey()));
    auto mesh = uv_sphere_mesh(5);
    for (int i = 0; i < 3; ++i)
        room.add(std::make_shared<translate>(std::make_shared<scale>(mesh, vec3(0.3, 0.2, 0.3)), vec3(0.7 * (i - 1), 0, -1.5)));
    room.add(std::make_shared<translate>(world.objects[0], vec3(0, 0.2, -2)));
    camera cam = test::test_camera(20, 12, 4, 5);
    cam.settings.threads = 1;
    const render_result one = test::render_checked(cam, room);
    cam.settings.threads = 2;
    CHECK(test::same_bits(one.img, test::render_checked(cam, room).img));
}

TEST_CASE("instances: the scene format's rotate and scale words") {
    // The unit sphere stretched to x^2/4 + y^2 + z^2 = 1, turned 90 degrees about z (its long
    // axis now along y), moved to z = -5: a ray down -z at (0, 1.2, 0) meets it where
    // y^2/4 + z'^2 = 1, z' = 0.8, at t = 5 - 0.8.
    std::istringstream text("sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0 scale 2 1 1 rotate 0 0 1 90 translate 0 0 -5\n");
    const scene_description scene_text = parse_scene(text, "inline.txt");
    const compiled_scene scene = compile_scene(scene_text.world, point3(0, 0, 0));
    CHECK(scene.set<instance_set>().count() == 1);
    surface_hit hit;
    REQUIRE(scene.intersect(engine_ray(scene, point3(0, 1.2, 0), vec3(0, 0, -1)), hit));
    CHECK(hit.t == doctest::Approx(4.2).epsilon(1e-5));
    // Its gradient there, (x, y/4, z) with (0, 1.2, 0.8) relative to the centre.
    check_vec(hit.normal.to_double(), unit_vector(vec3(0, 0.3, 0.8)), 1e-5);

    auto fails = [](const std::string& line) {
        std::istringstream in(line + "\n");
        CHECK_THROWS_AS(parse_scene(in, "bad.txt"), scene_error);
    };
    fails("sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0 rotate 0 0 0 30");
    fails("sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0 rotate 0 1 0");
    fails("sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0 scale 1 0 1");
    fails("sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0 scale 1 1");
}

TEST_CASE("instances: a textured shape inside an instance has the (u, v) of its own frame") {
    // A unit sphere stretched to (2, 1, 1) (an instance: no longer a sphere). Its (u, v) are book
    // 2's get_sphere_uv of the object's own normal: at the object's (0, 0, 1), u = 1/4, v = 1/2;
    // at (1, 0, 0), u = 1/2, v = 1/2; at (0, 1, 0), v = 1.
    auto tex = std::make_shared<checker_texture>(0.5, color(1, 1, 1), color(0, 0, 0));
    auto ball = std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<lambertian>(tex));
    hittable_list world(std::make_shared<scale>(ball, vec3(2, 1, 1)));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    struct probe {
        vec3 from, dir;
        double u, v;
    };
    for (const probe& p : {probe{vec3(0, 0, 10), vec3(0, 0, -1), 0.25, 0.5}, probe{vec3(10, 0, 0), vec3(-1, 0, 0), 0.5, 0.5},
                           probe{vec3(0, 10, 0), vec3(0, -1, 0), -1, 1.0}}) {
        surface_hit hit;
        REQUIRE(scene.intersect(engine_ray(scene, p.from, p.dir), hit));
        CHECK(hit.kind == shape_id<instance_set>);
        double u, v;
        surface_coordinates(scene, hit, u, v);
        if (p.u >= 0) CHECK(u == doctest::Approx(p.u).epsilon(1e-5));
        CHECK(v == doctest::Approx(p.v).epsilon(1e-5));
    }
}

} // namespace test_instances
