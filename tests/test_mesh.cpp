// Triangle meshes (rtweekend/mesh.h): OBJ loading with tinyobjloader, its errors, the scene
// format's `mesh` line, and rendering a mesh (furnace: no self-intersection, far from the origin).

#include <rtweekend/material.h>
#include <rtweekend/io/obj.h>
#include <rtweekend/mesh.h>
#include <rtweekend/camera.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/io/scene_file.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>

namespace test_mesh {

using namespace rt;

namespace {

const std::string mesh_dir = std::string(RTWEEKEND_TEST_DATA) + "/meshes";

// The unit cube [0,1]^3 as six quads, outward-facing, with one normal per face and UVs.
const std::string cube_obj = R"(# unit cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1/1 4/4/1 3/3/1 2/2/1
f 5/1/2 6/2/2 7/3/2 8/4/2
f 1/1/3 2/2/3 6/3/3 5/4/3
f 4/1/4 8/2/4 7/3/4 3/4/4
f 1/1/5 5/2/5 8/3/5 4/4/5
f 2/1/6 3/2/6 7/3/6 6/4/6
)";

void check_obj_error(const test::scratch_dir& dir, const std::string& text, const std::string& fragment) {
    CAPTURE(text);
    std::string path = dir.write("bad.obj", text);
    bool threw = false;
    try {
        load_obj(path, nullptr);
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.rfind(path, 0) == 0); // names the file first
        CHECK(msg.find(fragment) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
    CHECK(threw);
}

} // namespace

TEST_CASE("load_obj: quads become triangles, positions, normals and uvs are kept") {
    test::scratch_dir dir("cube");
    auto mat = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    auto mesh = load_obj(dir.write("cube.obj", cube_obj), mat);
    CHECK(mesh->triangle_count() == 12);
    CHECK(mesh->positions.size() == 8);
    CHECK(mesh->normals.size() == 6);
    CHECK(mesh->uvs.size() == 4);
    REQUIRE(mesh->face_normals.size() == 12);
    REQUIRE(mesh->face_uvs.size() == 12);
    CHECK(mesh->mat == mat);
    // The first quad 1 4 3 2 (0-based 0 3 2 1) becomes two triangles over its four corners
    // (tinyobjloader picks the diagonal), covering its area of 1, with the uv and normal of each
    // corner carried along (in this file every corner's uv index equals its vertex index, and
    // the face's normal is the first).
    std::set<uint32_t> corners;
    double area = 0;
    for (int t = 0; t < 2; ++t) {
        const auto& f = mesh->faces[size_t(t)];
        for (int k = 0; k < 3; ++k) {
            uint32_t v = f[size_t(k)];
            corners.insert(v);
            CHECK(v < 4);
            CHECK(mesh->face_uvs[size_t(t)][size_t(k)] == v);
            CHECK(mesh->face_normals[size_t(t)][size_t(k)] == 0);
        }
        area += 0.5 * cross(mesh->positions[f[1]] - mesh->positions[f[0]], mesh->positions[f[2]] - mesh->positions[f[0]]).length();
    }
    CHECK(corners == std::set<uint32_t>{0, 1, 2, 3});
    CHECK(area == doctest::Approx(1.0));
    CHECK(mesh->positions[6].x() == 1.0);
    CHECK(mesh->normals[5].x() == 1.0);
    CHECK(mesh->uvs[2][0] == 1.0);

    // Every triangle's winding gives an outward normal (the cube is centred at 0.5).
    for (const auto& f : mesh->faces) {
        vec3 a = mesh->positions[f[0]], b = mesh->positions[f[1]], c = mesh->positions[f[2]];
        vec3 n = cross(b - a, c - a);
        vec3 centre = (a + b + c) / 3 - vec3(0.5, 0.5, 0.5);
        CHECK(dot(n, centre) > 0);
    }

    // A mesh without normals or uvs has empty per-corner index lists.
    auto plain = load_obj(dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), mat);
    CHECK(plain->triangle_count() == 1);
    CHECK(plain->face_normals.empty());
    CHECK(plain->face_uvs.empty());
    // Negative indices count back from the latest vertex.
    auto relative = load_obj(dir.write("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"), mat);
    CHECK(relative->faces[0] == std::array<uint32_t, 3>{0, 1, 2});
}

TEST_CASE("load_obj: the shared test meshes load with their documented triangle counts") {
    auto mat = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    CHECK(load_obj(mesh_dir + "/bunny_npm.obj", mat)->triangle_count() == 3674);
    CHECK(load_obj(mesh_dir + "/teapot_npm.obj", mat)->triangle_count() == 992);
    CHECK(load_obj(mesh_dir + "/bunny00_cgal.obj", mat)->triangle_count() == 75408);
}

TEST_CASE("load_obj: a missing or malformed file is one clear error naming it") {
    test::scratch_dir dir("errors");
    CHECK_THROWS_WITH_AS(load_obj((dir.path / "missing.obj").string(), nullptr),
                         doctest::Contains("missing.obj: cannot open OBJ file"), scene_error);
    CHECK_THROWS_WITH_AS(load_obj(dir.path.string(), nullptr), doctest::Contains("is a directory"), scene_error);
    check_obj_error(dir, "v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n", ":2: malformed OBJ file: 'x'");
    check_obj_error(dir, "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "'nan' in a 'v' line is not a finite number");
    check_obj_error(dir, "v 0 0\n", "needs 3 numbers");
    check_obj_error(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", ":4: malformed OBJ file: vertex index 4 is out of range");
    check_obj_error(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "vertex index -4 is out of range");
    check_obj_error(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "vertex index 0 is out of range");
    check_obj_error(dir, "v 0 0 0\nv 1 0 0\nf 1 2\n", "a face has 2 corners");
    check_obj_error(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 a\n", "face corner 'a'");
    check_obj_error(dir, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", "normal index 2 is out of range");
    check_obj_error(dir, "# nothing here\nv 0 0 0\n", "has no faces");
    check_obj_error(dir, "this is not an OBJ file\n", "has no faces");
}

TEST_CASE("scene files: 'mesh' and 'triangle' lines") {
    test::scratch_dir dir("scene");
    std::filesystem::create_directories(dir.path / "models");
    dir.write("models/cube.obj", cube_obj);
    // The OBJ path is relative to the scene file, not to the working directory.
    std::string scene_path = dir.write("scene.txt", "camera lookfrom 3 2 4\n"
                                                    "mesh models/cube.obj metal 0.8 0.7 0.6 0.1 0\n"
                                                    "triangle 0 0 0 1 0 0 0 1 0 lambertian 0.1 0.2 0.3 0 0\n");
    scene_description s = load_scene(scene_path);
    REQUIRE(s.world.objects.size() == 2);
    auto mesh = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[0]);
    REQUIRE(mesh);
    CHECK(mesh->triangle_count() == 12);
    auto m = std::dynamic_pointer_cast<metal>(mesh->mat);
    REQUIRE(m);
    CHECK(m->fuzz() == 0.1);
    auto tri = std::dynamic_pointer_cast<triangle>(s.world.objects[1]);
    REQUIRE(tri);
    CHECK(tri->b().x() == 1.0);

    // Errors carry the scene file and line, then the OBJ file's own message.
    auto fails = [&](const std::string& text, const std::string& fragment) {
        CAPTURE(text);
        std::string p = dir.write("bad.txt", text);
        bool threw = false;
        try {
            load_scene(p);
        } catch (const scene_error& e) {
            threw = true;
            std::string msg = e.what();
            CAPTURE(msg);
            CHECK(msg.rfind(p + ":2: ", 0) == 0);
            CHECK(msg.find(fragment) != std::string::npos);
        }
        CHECK(threw);
    };
    fails("# a missing mesh\nmesh nowhere.obj lambertian 1 1 1 0 0\n", "nowhere.obj: cannot open OBJ file");
    fails("\nmesh models/cube.obj lambertian 1 1 1 0\n", "expected ior");
    fails("\nmesh models/cube.obj velvet 1 1 1 0 0\n", "unknown material 'velvet'");
    fails("\ntriangle 0 0 0 1 1 1 2 2 2 lambertian 1 1 1 0 0\n", "zero area");
    fails("\ntriangle 0 0 0 1 0 0 0 1 0 lambertian 1 1 1 0\n", "expected ior");
}

TEST_CASE("scene files: a 'mesh' line reads a .ply file as PLY") {
    test::scratch_dir dir("scene_ply");
    // An ASCII PLY square (two triangles after the fan split), next to the scene file.
    dir.write("square.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    scene_description s = load_scene(dir.write("scene.txt", "mesh square.ply lambertian 0.5 0.5 0.5 0 0\n"));
    REQUIRE(s.world.objects.size() == 1);
    auto mesh = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[0]);
    REQUIRE(mesh);
    CHECK(mesh->triangle_count() == 2);
    CHECK(mesh->positions[2].x() == 1.0);
    CHECK(mesh->positions[2].y() == 1.0);
    CHECK_THROWS_WITH_AS(load_scene(dir.write("bad.txt", "mesh nowhere.ply lambertian 1 1 1 0 0\n")),
                         doctest::Contains("nowhere.ply"), scene_error);
}

TEST_CASE("render: a convex mesh in a white furnace renders its albedo exactly, near and far") {
    // A closed convex mesh (the cube) under a uniform white sky: a path leaving a Lambertian
    // face can never hit the cube again, so every sample that sees the cube is exactly the
    // albedo and every other sample exactly 1. A self-intersection (acne) would give a^2.
    test::scratch_dir dir("furnace");
    std::string path = dir.write("cube.obj", cube_obj);
    for (double offset : {0.0, 1e4, 1e5}) {
        CAPTURE(offset);
        auto mesh = load_obj(path, std::make_shared<lambertian>(color(0.5, 0.5, 0.5)));
        for (auto& p : mesh->positions) p += vec3(offset, offset, -offset);
        hittable_list world;
        world.add(mesh);
        camera cam;
        cam.image_width = 24;
        cam.aspect_ratio = 1;
        cam.samples_per_pixel = 4;
        cam.max_depth = 8;
        cam.vfov = 40;
        cam.lookfrom = point3(2.2, 1.9, 3.1) + vec3(offset, offset, -offset);
        cam.lookat = point3(0.5, 0.5, 0.5) + vec3(offset, offset, -offset);
        cam.background = color(1, 1, 1);
        cam.settings.quiet = true;
        render_result r = render(cam, world);
        CHECK(r.stats.nonfinite_samples == 0);
        int cube = 0, sky = 0, other = 0;
        for (int i = 0; i < r.img.width() * r.img.height(); ++i) {
            float v = r.img.data()[size_t(3 * i)];
            if (v == 0.5f) ++cube;
            else if (v == 1.0f) ++sky;
            else ++other; // a pixel on the cube's outline mixes the two: between 0.5 and 1
            CHECK(v >= 0.5f);
            CHECK(v <= 1.0f);
        }
        CHECK(cube > 100);
        CHECK(sky > 100);
        CHECK(other < 60); // outline pixels only
    }
}

TEST_CASE("render: the bunny renders without NaN, identically at 1 and 2 threads" * doctest::test_suite("threads")) {
    auto bunny = load_obj(mesh_dir + "/bunny_npm.obj", std::make_shared<metal>(color(0.8, 0.6, 0.4), 0.2));
    hittable_list world;
    world.add(bunny);
    world.add(std::make_shared<sphere>(point3(0, -1000, 0), 999.99, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam;
    cam.image_width = 32;
    cam.aspect_ratio = 1;
    cam.samples_per_pixel = 4;
    cam.lookfrom = point3(0, 6, 25); // the bunny spans x -5..5, y 0..9.7, z -3.7..3.8
    cam.lookat = point3(0, 4.5, 0);
    cam.settings.quiet = true;
    cam.settings.threads = 1;
    render_result one = render(cam, world);
    cam.settings.threads = 2;
    render_result two = render(cam, world);
    CHECK(one.stats.nonfinite_samples == 0);
    CHECK(one.img.data() == two.img.data());
}

} // namespace test_mesh
