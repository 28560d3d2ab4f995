// Smooth shading in the path tracer (render/vertex_material.h): a direction below
// the triangle is mirrored back above it, so a material under tilted shading normals reflects
// exactly what it reflects without them, and no facet turns black.
#include <doctest/doctest.h>

#include "test_helpers.h"

#include <rtweekend/camera.h>
#include <rtweekend/render/path_tracer.h>
#include <rtweekend/render/vertex_material.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/mesh.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

namespace test_smooth_shading {

using namespace rt;

namespace {

// An octahedron of radius 1 about the origin, its vertex normals pointing out from the centre:
// each differs from its faces' normals by 54.7 degrees, as far as shading normals ever tilt in
// a closed mesh this coarse.
std::shared_ptr<triangle_mesh> smooth_octahedron(std::shared_ptr<material> mat) {
    std::vector<point3> p = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::vector<std::array<uint32_t, 3>> f = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                              {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    auto mesh = std::make_shared<triangle_mesh>(p, f, std::move(mat));
    mesh->compute_vertex_normals();
    return mesh;
}

} // namespace

TEST_CASE("smooth shading: compute_vertex_normals gives a symmetric solid its radial normals") {
    auto mesh = smooth_octahedron(std::make_shared<lambertian>(color(0.5, 0.5, 0.5)));
    REQUIRE(mesh->normals.size() == 6);
    // Each vertex of the octahedron is shared by four faces whose normals average to the vertex
    // direction itself.
    for (size_t v = 0; v < 6; ++v) {
        CHECK(mesh->normals[v].x() == doctest::Approx(mesh->positions[v].x()));
        CHECK(mesh->normals[v].y() == doctest::Approx(mesh->positions[v].y()));
        CHECK(mesh->normals[v].z() == doctest::Approx(mesh->positions[v].z()));
    }
    CHECK(mesh->smooth_shading);
}

TEST_CASE("smooth shading: a convex smooth mesh in a white sky reflects exactly its albedo") {
    // Every ray leaving a convex object's outside escapes, so a pixel on it sees albedo x 1 in
    // every sample: exact, if no energy is lost or gained where the shading normals tilt.
    hittable_list world(smooth_octahedron(std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = test::test_camera(32, 32, 16, 8);
    cam.lookfrom = point3(2.2, 1.7, 3.1);
    cam.lookat = point3(0, 0, 0);
    cam.vfov = 40;
    cam.background = color(1, 1, 1);
    render_result r = test::render_checked(cam, world);
    int object = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            color c = r.img.pixel(x, y);
            // A pixel is part sky (1) and part object (0.5): its mean lies in [0.5, 1]; a pixel
            // entirely on the object is 0.5 exactly.
            CHECK(c.x() >= 0.5 - 1e-5);
            CHECK(c.x() <= 1 + 1e-5);
            if (std::fabs(c.x() - 0.5) < 1e-5) ++object;
        }
    CHECK(object > 100);
}

TEST_CASE("smooth shading: the folded Lambertian weighs every sample by its albedo, eval/pdf agree") {
    compiled_material m = lambertian(color(0.6, 0.6, 0.6)).compiled();
    const vec3f ng(0, 0, 1);
    const vec3f ns = normalize(vec3f(0.7f, 0, 1)); // tilted 35 degrees
    const vec3f wo = normalize(vec3f(-0.2f, 0.1f, 1));
    detail::vertex_material<false> vm{m, shading_point{ns, true}, wo, nullptr, ng, true};
    pcg32 rng(3);
    double pdf_integral = 0;
    const int n = 200000;
    int failed = 0, below = 0, off_albedo = 0;
    for (int i = 0; i < n; ++i) {
        material_sample s;
        if (!vm.sample(rng, s)) ++failed;
        else if (!(dot(s.wi, ng) > 0)) ++below; // never below the triangle
        else if (std::fabs(s.value.x - 0.6f) > 1e-4f) ++off_albedo;
        // Uniform directions over the upper hemisphere estimate the integral of pdf' (must be 1).
        const float u1 = rng.next_float(), u2 = rng.next_float();
        const float z = u1, r = std::sqrt(std::fmax(0.0f, 1 - z * z)), phi = 2 * pi_f * u2;
        pdf_integral += vm.pdf(vec3f(r * std::cos(phi), r * std::sin(phi), z)) * (2 * pi);
    }
    CHECK(failed == 0);
    CHECK(below == 0);
    CHECK(off_albedo == 0);
    CHECK(pdf_integral / n == doctest::Approx(1.0).epsilon(0.01));
}

TEST_CASE("smooth shading: a scene file's `smooth` turns it on, with computed normals when the file has none") {
    const std::string dir = std::string(RTWEEKEND_TEST_DATA) + "/scene.txt";
    std::istringstream flat("mesh meshes/bunny_npm.obj lambertian 0.5 0.5 0.5 0 0\n");
    std::istringstream smooth("mesh meshes/bunny_npm.obj lambertian 0.5 0.5 0.5 0 0 smooth translate 1 0 0\n");
    scene_description a = parse_scene(flat, dir), b = parse_scene(smooth, dir);
    auto* flat_mesh = dynamic_cast<const triangle_mesh*>(a.world.objects.at(0).get());
    REQUIRE(flat_mesh);
    CHECK(!flat_mesh->smooth_shading);
    auto* moved = dynamic_cast<const translate*>(b.world.objects.at(0).get());
    REQUIRE(moved);
    auto* smooth_mesh = dynamic_cast<const triangle_mesh*>(moved->object().get());
    REQUIRE(smooth_mesh);
    CHECK(smooth_mesh->smooth_shading);
    CHECK(smooth_mesh->normals.size() > 0);
    CHECK(smooth_mesh->face_normals.size() == smooth_mesh->faces.size());
}

} // namespace test_smooth_shading
