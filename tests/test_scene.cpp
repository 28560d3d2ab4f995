// compile_scene (rtweekend/scene/scene_compiler.h): what the renderer builds from the book's world, and the
// invalid input it must reject with scene_error.

#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/mesh.h>
#include <rtweekend/camera.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/core/sampling.h>
#include <rtweekend/sphere.h>
#include <rtweekend/triangle.h>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace test_scene {

using namespace rt;

namespace {

const double nan_d = std::numeric_limits<double>::quiet_NaN();
const double inf_d = std::numeric_limits<double>::infinity();

std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

// A hittable that is not a built-in shape.
class slab : public hittable {
  public:
    bool hit(const ray&, interval, hit_record&) const override { return false; }
};

class odd_material : public material {};

// compile_scene(world, origin) must throw scene_error with a one-line message containing `fragment`.
void check_rejected(const hittable& world, const std::string& fragment) {
    CAPTURE(fragment);
    bool threw = false;
    try {
        (void)compile_scene(world, point3(0, 0, 0));
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find(fragment) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
    CHECK(threw);
}

hittable_list with(std::shared_ptr<hittable> h) {
    hittable_list w;
    w.add(std::move(h));
    return w;
}

} // namespace

TEST_CASE("compile_scene: positions are relative to the origin, computed in double") {
    // Centre x = 1e8 + 0.5 with origin x = 1e8: the relative position 0.5 is exact in double, but
    // float cannot even represent 1e8 + 0.5 (float spacing at 1e8 is 8), so rounding first would
    // give 0 or 8.
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(1e8 + 0.5, -3, 2.25), 0.75, grey()));
    compiled_scene s = compile_scene(world, point3(1e8, 0, 0));
    REQUIRE(s.set<sphere_set>().count == 1);
    CHECK(s.set<sphere_set>().x[0] == 0.5f);
    CHECK(s.set<sphere_set>().y[0] == -3.0f);
    CHECK(s.set<sphere_set>().z[0] == 2.25f);
    CHECK(s.set<sphere_set>().r[0] == 0.75f);
    CHECK(s.set<sphere_set>().r2[0] == 0.5625f); // 0.75^2, exact
    CHECK(s.origin.x() == 1e8);

    // The hit is found where it should be: a ray from relative (0, -3, 2.25) along +x starts 0.5
    // from the centre, inside the sphere, and meets the far wall at x = 0.5 + 0.75 = 1.25.
    ray3f r;
    r.dir = {1, 0, 0};
    r.origin = {0, -3, 2.25};
    surface_hit hit;
    REQUIRE(s.intersect(r, hit));
    CHECK(hit.t == doctest::Approx(1.25).epsilon(1e-6));
    CHECK_FALSE(hit.front_face);
}

TEST_CASE("compile_scene: padding, nested lists, material table") {
    auto shared = grey();
    hittable_list inner;
    inner.add(std::make_shared<sphere>(point3(0, 0, -5), 1, shared));
    inner.add(std::make_shared<sphere>(point3(2, 0, -5), 1, shared));
    hittable_list world;
    world.add(std::make_shared<hittable_list>(inner));
    world.add(std::make_shared<sphere>(point3(-2, 0, -5), 1, std::make_shared<metal>(color(0.1, 0.2, 0.3), 0.4)));
    world.add(std::make_shared<sphere>(point3(-4, 0, -5), 1, std::make_shared<dielectric>(1.33)));
    world.add(std::make_shared<sphere>(point3(4, 0, -5), 1, shared));
    compiled_scene s = compile_scene(world, point3(0, 0, 0));

    CHECK(s.set<sphere_set>().count == 5);
    // Five spheres need no BVH: the root is one leaf holding all of them, in input order.
    CHECK(s.bvh.nodes.empty());
    CHECK(bvh_ref::is_leaf(s.bvh.root));
    CHECK(bvh_ref::count(s.bvh.root) == 5);
    // Arrays padded by one SIMD width (leaf loads read that far), padding spheres unhittable
    // (negative squared radius).
    CHECK(s.set<sphere_set>().x.size() == 5 + floatv::width);
    CHECK(s.set<sphere_set>().r2.size() == 5 + floatv::width);
    for (size_t i = 5; i < s.set<sphere_set>().r2.size(); ++i) CHECK(s.set<sphere_set>().r2[i] < 0);
    CHECK(s.unbounded_user_shapes.empty());
    CHECK_FALSE(s.has_user_materials);

    // One table entry per distinct material, shared by pointer.
    REQUIRE(s.materials.size() == 3);
    CHECK(s.set<sphere_set>().material[0] == s.set<sphere_set>().material[1]);
    CHECK(s.set<sphere_set>().material[0] == s.set<sphere_set>().material[4]);
    const compiled_material& lam = s.materials[s.set<sphere_set>().material[0]];
    CHECK(lam.is<lambertian_bsdf>());
    CHECK(lam.as<lambertian_bsdf>().albedo.x == 0.5f);
    const compiled_material& met = s.materials[s.set<sphere_set>().material[2]];
    CHECK(met.is<metal_bsdf>());
    CHECK(met.as<metal_bsdf>().fuzz == 0.4f);
    CHECK(met.as<metal_bsdf>().albedo.z == 0.3f);
    const compiled_material& gl = s.materials[s.set<sphere_set>().material[3]];
    CHECK(gl.is<dielectric_bsdf>());
    CHECK(gl.as<dielectric_bsdf>().refraction_index == 1.33f);

    // 17 spheres in a row get a BVH (more than one leaf's worth).
    hittable_list many;
    for (int i = 0; i < 17; ++i) many.add(std::make_shared<sphere>(point3(i, 0, -5), 0.1, shared));
    compiled_scene m = compile_scene(many, point3(0, 0, 0));
    CHECK(m.set<sphere_set>().count == 17);
    CHECK(m.set<sphere_set>().x.size() == 17 + floatv::width);
    CHECK_FALSE(m.bvh.nodes.empty());

    // Empty world: nothing to hit.
    hittable_list none;
    compiled_scene e = compile_scene(none, point3(0, 0, 0));
    CHECK(e.set<sphere_set>().count == 0);
    ray3f r;
    r.dir = {0, 0, -1};
    surface_hit hit;
    CHECK_FALSE(e.intersect(r, hit));
}

TEST_CASE("compile_scene: user shapes and materials are kept for the virtual path") {
    hittable_list world;
    auto user_shape = std::make_shared<slab>();
    world.add(user_shape);
    world.add(std::make_shared<sphere>(point3(0, 0, -5), 1, std::make_shared<odd_material>()));
    compiled_scene s = compile_scene(world, point3(0, 0, 0));
    REQUIRE(s.unbounded_user_shapes.size() == 1);
    CHECK(s.unbounded_user_shapes[0] == user_shape.get());
    CHECK(s.has_user_materials);
    REQUIRE(s.materials.size() == 1);
    CHECK(s.materials[0].is<user_bsdf>());
    CHECK(s.materials[0].source != nullptr);
}

TEST_CASE("compile_scene rejects invalid spheres and materials") {
    check_rejected(with(std::make_shared<sphere>(point3(nan_d, 0, 0), 1, grey())), "centre");
    check_rejected(with(std::make_shared<sphere>(point3(0, inf_d, 0), 1, grey())), "centre");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 0, grey())), "radius");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), -0.0, grey())), "radius");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), nan_d, grey())), "radius");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), inf_d, grey())), "radius");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, nullptr)), "material");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<lambertian>(color(-0.1, 0, 0)))),
                   "albedo");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<lambertian>(color(0, nan_d, 0)))),
                   "albedo");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<metal>(color(1, 1, -1), 0))),
                   "albedo");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<metal>(color(1, 1, 1), -0.5))),
                   "fuzz");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<dielectric>(0))), "refraction");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<dielectric>(-1.5))), "refraction");
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<dielectric>(nan_d))),
                   "refraction");
    hittable_list holes;
    holes.add(nullptr);
    check_rejected(holes, "null");

    // A non-finite camera position.
    hittable_list ok = with(std::make_shared<sphere>(point3(0, 0, 0), 1, grey()));
    CHECK_THROWS_AS((void)compile_scene(ok, point3(0, nan_d, 0)), scene_error);

    // render() reports the same errors (nothing is rendered from bad input).
    camera cam;
    cam.image_width = 8;
    cam.settings.quiet = true;
    hittable_list bad = with(std::make_shared<sphere>(point3(0, 0, -2), 0, grey()));
    CHECK_THROWS_AS((void)render(cam, bad), scene_error);
}

TEST_CASE("compile_scene rejects a metal with NaN fuzz (documented: 'NaN fuzz ... throws')") {
    // material_compiler.h lists "NaN fuzz" among the invalid input that compile_scene rejects. A NaN fuzz is
    // an error in the caller's scene and must not render silently as some other material.
    check_rejected(with(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<metal>(color(1, 1, 1), nan_d))),
                   "fuzz");
}

// Back-face culling: two parallel squares facing +z at z = -2 and z = -4 (each two triangles,
// counter-clockwise seen from +z), and rays along -z and +z.
namespace {

std::shared_ptr<triangle_mesh> square_at(double z, std::shared_ptr<material> m) {
    std::vector<point3> p = {point3(-1, -1, z), point3(1, -1, z), point3(1, 1, z), point3(-1, 1, z)};
    std::vector<std::array<uint32_t, 3>> f = {{0, 1, 2}, {0, 2, 3}};
    return std::make_shared<triangle_mesh>(p, f, m);
}

ray3f axis_ray(float z0, float dz) {
    ray3f r;
    r.origin = {0.25f, 0.1f, z0};
    r.dir = {0, 0, dz};
    r.tmin = 0;
    r.tmax = std::numeric_limits<float>::infinity();
    return r;
}

} // namespace

TEST_CASE("compile_scene: back-face culling skips back faces of the marked materials only") {
    auto opaque = grey();
    auto glass = std::make_shared<dielectric>(1.5);
    hittable_list world;
    world.add(square_at(-2, opaque));
    world.add(square_at(-4, glass));
    compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    const uint32_t opaque_index = scene.materials[0].is<lambertian_bsdf>() ? 0 : 1;
    scene.set_back_face_culling([&](uint32_t m) { return m == opaque_index; });

    surface_hit hit;
    // From +z looking down -z: the opaque square's front face, 2 away; culling changes nothing.
    REQUIRE(scene.intersect_culling_back_faces(axis_ray(0, -1), hit));
    CHECK(hit.t == doctest::Approx(2));
    // From z = -6 looking up +z: the glass square's back face at distance 2 is kept (not marked),
    REQUIRE(scene.intersect_culling_back_faces(axis_ray(-6, 1), hit));
    CHECK(hit.t == doctest::Approx(2));
    CHECK_FALSE(hit.front_face);
    // and from z = -3 looking up +z, the opaque square's back face at distance 1 is skipped: the
    // ray escapes, while the unculled query finds it.
    CHECK_FALSE(scene.intersect_culling_back_faces(axis_ray(-3, 1), hit));
    REQUIRE(scene.intersect(axis_ray(-3, 1), hit));
    CHECK(hit.t == doctest::Approx(1));
    // Shadow queries never cull.
    CHECK(scene.occluded(axis_ray(-3, 1)));
}

TEST_CASE("compile_scene: back-face culling of spheres skips the exit point of a ray from inside") {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -5), 1, grey()));
    compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    scene.set_back_face_culling([](uint32_t) { return true; });
    surface_hit hit;
    // The rays run parallel to the axis at (0.25, 0.1): the sphere's half-chord there is h.
    const double h = std::sqrt(1 - 0.25 * 0.25 - 0.1 * 0.1);
    REQUIRE(scene.intersect_culling_back_faces(axis_ray(0, -1), hit)); // from outside: the front
    CHECK(hit.t == doctest::Approx(5 - h).epsilon(1e-6));
    CHECK_FALSE(scene.intersect_culling_back_faces(axis_ray(-5, -1), hit)); // from the centre: culled
    REQUIRE(scene.intersect(axis_ray(-5, -1), hit));
    CHECK(hit.t == doctest::Approx(h).epsilon(1e-6));
}

TEST_CASE("compile_scene: smooth meshes interpolate their vertex normals barycentrically") {
    // One triangle in the plane z = -2 with normals tilted differently at each corner.
    auto mesh = std::make_shared<triangle_mesh>();
    mesh->positions = {point3(-1, -1, -2), point3(3, -1, -2), point3(-1, 3, -2)};
    mesh->faces = {{0, 1, 2}};
    mesh->normals = {vec3(0, 0, 1), vec3(1, 0, 1), vec3(0, 1, 1)}; // unnormalised on purpose
    mesh->face_normals = {{0, 1, 2}};
    mesh->mat = grey();

    hittable_list world;
    world.add(mesh);
    // Flat unless asked: the shading normal is the geometric one.
    surface_hit hit;
    ray3f r = axis_ray(0, -1); // hits (0.25, 0.1, -2)
    REQUIRE(compile_scene(world, point3(0, 0, 0)).intersect(r, hit));
    CHECK(hit.shading_normal.x == doctest::Approx(0));
    CHECK(hit.shading_normal.z == doctest::Approx(1));

    mesh->smooth_shading = true;
    compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    REQUIRE(scene.intersect(r, hit));
    // Barycentric weights of (0.25, 0.1) in the triangle (-1,-1), (3,-1), (-1,3):
    // p = a + b1 (b - a) + b2 (c - a) gives b1 = (x + 1) / 4, b2 = (y + 1) / 4.
    const double b1 = 1.25 / 4, b2 = 1.1 / 4, b0 = 1 - b1 - b2;
    // Unit corner normals: (0,0,1), (1,0,1)/sqrt2, (0,1,1)/sqrt2, weighted and normalised.
    const double s = 1 / std::sqrt(2.0);
    double nx = b1 * s, ny = b2 * s, nz = b0 + b1 * s + b2 * s;
    double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    CHECK(hit.shading_normal.x == doctest::Approx(nx / len).epsilon(1e-5));
    CHECK(hit.shading_normal.y == doctest::Approx(ny / len).epsilon(1e-5));
    CHECK(hit.shading_normal.z == doctest::Approx(nz / len).epsilon(1e-5));
    CHECK(hit.normal.z == doctest::Approx(1)); // the geometric normal is unchanged
    // Seen from behind, both normals face the ray.
    REQUIRE(scene.intersect(axis_ray(-3, 1), hit));
    CHECK(hit.normal.z == doctest::Approx(-1));
    CHECK(hit.shading_normal.z == doctest::Approx(-nz / len).epsilon(1e-5));
}

TEST_CASE("compile_scene: a scene of one shape kind is walked by that kind's kernel alone, with the same hits") {
    // 300 random spheres; the same with a triangle far away added (a mixed scene, whose walk asks
    // every leaf its kind). Both walks must find the same sphere at the same distance, bit for bit.
    pcg32 rng(99);
    hittable_list spheres_only, mixed;
    auto m = grey();
    for (int i = 0; i < 300; ++i) {
        auto s = std::make_shared<sphere>(point3(20 * rng.next_double() - 10, 20 * rng.next_double() - 10,
                                                 20 * rng.next_double() - 10),
                                          0.1 + 0.5 * rng.next_double(), m);
        spheres_only.add(s);
        mixed.add(s);
    }
    mixed.add(std::make_shared<triangle>(point3(500, 500, 500), point3(501, 500, 500), point3(500, 501, 500), m));
    const compiled_scene a = compile_scene(spheres_only, point3(0, 0, 0));
    const compiled_scene b = compile_scene(mixed, point3(0, 0, 0));
    REQUIRE(a.single_kind.has_value());
    CHECK(*a.single_kind == shape_id<sphere_set>);
    CHECK_FALSE(b.single_kind.has_value());
    REQUIRE(a.bvh.stats.nodes > 0);

    hittable_list triangles_only;
    triangles_only.add(std::make_shared<triangle>(point3(0, 0, -1), point3(1, 0, -1), point3(0, 1, -1), m));
    const compiled_scene t = compile_scene(triangles_only, point3(0, 0, 0));
    REQUIRE(t.single_kind.has_value());
    CHECK(*t.single_kind == shape_id<triangle_set>);
    CHECK_FALSE(compile_scene(hittable_list(), point3(0, 0, 0)).single_kind.has_value());

    long hits = 0;
    for (int k = 0; k < 5000; ++k) {
        ray3f r;
        r.origin = {float(30 * rng.next_double() - 15), float(30 * rng.next_double() - 15), float(30 * rng.next_double() - 15)};
        r.dir = sample_unit_sphere(rng.next_float(), rng.next_float());
        surface_hit ha, hb;
        bool fa = a.intersect(r, ha), fb = b.intersect(r, hb);
        REQUIRE(fa == fb);
        CHECK(a.occluded(r) == fa);
        CHECK(b.occluded(r) == fb);
        if (!fa) continue;
        ++hits;
        CHECK(ha.t == hb.t);
        CHECK(ha.p.x == hb.p.x);
        CHECK(ha.normal.z == hb.normal.z);
    }
    CHECK(hits > 200); // about 7 % of random rays meet a sphere here
}

} // namespace test_scene
