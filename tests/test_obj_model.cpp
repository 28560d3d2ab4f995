// OBJ models with their MTL materials (rtweekend/io/obj_model.h): small files written here, each
// MTL rule's material and parameters, faces grouped by material, and what renders: a face's Kd
// under a white sky, an emitter's Ke, a texture's texels, all exact; one warning for each thing
// not rendered as written, one error line for a malformed file; the scene file's `mesh ... mtl`.

#include <rtweekend/io/obj_model.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <memory>
#include <string>

namespace test_obj_model {

using namespace rt;

namespace {

// A square facing +z at z = 0, x and y in [x0, x0 + 2] x [-1, 1], two triangles, with texture
// coordinates (0, 0) to (1, 1) across it; `first` the number of vertices so far.
std::string square(double x0, int first, bool uv = false) {
    std::string s;
    for (auto [x, y] : {std::pair{0, 0}, {2, 0}, {2, 2}, {0, 2}})
        s += "v " + std::to_string(x0 + x) + " " + std::to_string(y - 1) + " 0\n";
    auto corner = [&](int k) {
        const std::string v = std::to_string(first + k - 1);
        return uv ? v + "/" + std::to_string(k) : v;
    };
    return s + "f " + corner(1) + " " + corner(2) + " " + corner(3) + "\nf " + corner(1) + " " + corner(3) + " " + corner(4) + "\n";
}

template <class M>
const M* material_of(const obj_model& m, size_t i) {
    const auto* mesh = dynamic_cast<const triangle_mesh*>(m.world.objects.at(i).get());
    REQUIRE(mesh);
    return dynamic_cast<const M*>(mesh->mat.get());
}

// A 2 x 1 PNG: red on the left, blue on the right.
std::string red_blue_png(const test::scratch_dir& dir) {
    return dir.write("rb.png", encode_8bit_image(dir.file("rb.png"), 2, 1, {255, 0, 0, 0, 0, 255}));
}

// Renders the model's square in front of the camera (every pixel on it), under `sky`.
image render_square(const obj_model& m, const color& sky) {
    camera cam = test::test_camera(16, 8, 16, 3);
    cam.lookfrom = point3(0, 0, 20);
    cam.lookat = point3(0, 0, 0);
    cam.vfov = 4; // half-height 20 tan 2 deg = 0.7 < 1, half-width 1.4 < 2: inside [-2, 2] x [-1, 1]
    cam.background = sky;
    hittable_list world;
    world.add(std::make_shared<hittable_list>(m.world));
    return test::render_checked(cam, world).img;
}

} // namespace

TEST_CASE("OBJ models: each MTL rule gives its material, faces grouped by material") {
    test::scratch_dir dir("obj_model");
    red_blue_png(dir);
    dir.write("m.mtl", "newmtl plain\nKd 0.2 0.4 0.6\n"
                       "newmtl glossy\nKd 0.5 0.4 0.3\nKs 0.3 0.3 0.3\nNs 50\n"
                       "newmtl glass\nKd 0 0 0\nNi 1.33\nillum 7\n"
                       "newmtl frosted\nd 0.5\nPr 0.4\n"
                       "newmtl copper\nKd 0.9 0.6 0.5\nPm 1\nPr 0.3\n"
                       "newmtl lamp\nKe 3 2 1\n"
                       "newmtl tiles\nKd 0.7 0.7 0.7\nmap_Kd rb.png\n");
    std::string obj = "mtllib m.mtl\n" + square(-10, 1);  // no material: grey
    const char* names[] = {"plain", "glossy", "glass", "frosted", "copper", "lamp", "tiles"};
    for (int k = 0; k < 7; ++k) obj += "usemtl " + std::string(names[k]) + "\n" + square(-8 + 2 * k, 5 + 4 * k, k == 6);
    obj = "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n" + obj;
    const obj_model m = load_obj_model(dir.write("m.obj", obj));
    CHECK(m.warnings.empty());
    REQUIRE(m.world.objects.size() == 8);
    for (const auto& o : m.world.objects) {
        const auto* mesh = dynamic_cast<const triangle_mesh*>(o.get());
        REQUIRE(mesh);
        CHECK(mesh->faces.size() == 2);
        CHECK(mesh->positions.size() == 4); // only its own vertices, renumbered
    }
    // In material order: none (-1) first, then the library's.
    CHECK(material_of<lambertian>(m, 0)->albedo().x() == 0.8);
    CHECK(material_of<lambertian>(m, 1)->albedo().z() == doctest::Approx(0.6));
    const auto* glossy = material_of<blinn_phong>(m, 2);
    REQUIRE(glossy);
    CHECK(glossy->specular().x() == doctest::Approx(0.3));
    CHECK(glossy->exponent() == 50);
    const auto* glass = material_of<dielectric>(m, 3);
    REQUIRE(glass);
    CHECK(glass->refraction_index() == doctest::Approx(1.33));
    CHECK(glass->exact_fresnel());
    const auto* frosted = material_of<rough_dielectric>(m, 4);
    REQUIRE(frosted);
    CHECK(frosted->refraction_index() == 1.5); // no Ni: 1.5
    CHECK(frosted->roughness_u() == doctest::Approx(0.4));
    const auto* copper = material_of<metal_roughness>(m, 5);
    REQUIRE(copper);
    CHECK(copper->metallic() == 1);
    CHECK(copper->roughness() == doctest::Approx(0.3));
    const auto* lamp = material_of<diffuse_light>(m, 6);
    REQUIRE(lamp);
    const auto* tiles = material_of<lambertian>(m, 7);
    REQUIRE(tiles);
    CHECK(dynamic_cast<const image_texture*>(tiles->tex().get()));
    CHECK(!dynamic_cast<const triangle_mesh*>(m.world.objects[7].get())->uvs.empty());
    CHECK(m.emits);
    CHECK(m.lo.x() == -10);
    CHECK(m.hi.x() == 6); // the last square, from x = 4
    CHECK(m.hi.y() == 1);
    REQUIRE(m.files.size() == 3); // the OBJ, the library, the texture
    CHECK(m.files[1] == dir.file("m.mtl"));
}

TEST_CASE("OBJ models: a face renders its Kd under a white sky, a lamp its Ke, a texture its texels") {
    test::scratch_dir dir("obj_render");
    red_blue_png(dir);
    dir.write("m.mtl", "newmtl blue\nKd 0.25 0.5 0.75\nnewmtl lamp\nKe 3 2 1\nnewmtl tiles\nKd 1 1 1\nmap_Kd rb.png\n");
    // A Lambertian square alone under a sky of radiance 1: every bounce leaves for the sky, so
    // each sample weighs exactly its albedo (the furnace of test_render.cpp).
    {
        const obj_model m = load_obj_model(dir.write("blue.obj", "mtllib m.mtl\nusemtl blue\n" + square(-2, 1) + square(0, 5)));
        const image img = render_square(m, color(1, 1, 1));
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < img.width(); ++x) {
                const color c = img.pixel(x, y);
                CHECK(c.x() == doctest::Approx(0.25).epsilon(1e-5));
                CHECK(c.y() == doctest::Approx(0.5).epsilon(1e-5));
                CHECK(c.z() == doctest::Approx(0.75).epsilon(1e-5));
            }
    }
    // An emitter in the dark: its radiance Ke, seen from either side (two-sided).
    {
        const obj_model m = load_obj_model(dir.write("lamp.obj", "mtllib m.mtl\nusemtl lamp\n" + square(-2, 1) + square(0, 5)));
        const image img = render_square(m, color(0, 0, 0));
        CHECK(img.pixel(8, 4).x() == doctest::Approx(3));
        CHECK(img.pixel(8, 4).y() == doctest::Approx(2));
        CHECK(img.pixel(8, 4).z() == doctest::Approx(1));
    }
    // One square across the view, (u, v) from (0, 0) to (1, 1): the texture's left texel (red)
    // on the left half of the picture, its right one (blue) on the right, each times the sky.
    {
        std::string obj = "mtllib m.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl tiles\n";
        obj += "v -2 -1 0\nv 2 -1 0\nv 2 1 0\nv -2 1 0\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
        const obj_model m = load_obj_model(dir.write("tex.obj", obj));
        const image img = render_square(m, color(1, 1, 1));
        const color left = img.pixel(3, 4), right = img.pixel(12, 4);
        CHECK(left.x() == doctest::Approx(1).epsilon(1e-5));
        CHECK(left.z() == doctest::Approx(0).epsilon(1e-5));
        CHECK(right.x() == doctest::Approx(0).epsilon(1e-5));
        CHECK(right.z() == doctest::Approx(1).epsilon(1e-5));
    }
}

TEST_CASE("OBJ models: one warning for what is not rendered as written, one error line for a malformed file") {
    test::scratch_dir dir("obj_warn");
    red_blue_png(dir);
    auto contains = [](const std::vector<std::string>& lines, const std::string& fragment) {
        for (const std::string& l : lines)
            if (l.find(fragment) != std::string::npos && l.find('\n') == std::string::npos) return true;
        return false;
    };
    dir.write("w.mtl", "newmtl a\nKd 0.5 0.5 0.5\nbump b.png\nmap_Ks s.png\n"
                       "newmtl b\nKd 0.3 0.2 0.1\nmap_Kd missing.png\n"
                       "newmtl c\nKd 1 1 1\nKs 0.5 0.5 0.5\nmap_Kd rb.png\n");
    const obj_model m = load_obj_model(dir.write("w.obj", "mtllib w.mtl\nusemtl a\n" + square(0, 1) + "usemtl b\n" + square(2, 5) +
                                                              "usemtl c\n" + square(4, 9)));
    CHECK(m.warnings.size() == 4);
    CHECK(contains(m.warnings, "w.mtl: material 'a': bump map 'b.png' not found; the faces are flat"));
    CHECK(contains(m.warnings, "w.mtl: material 'a': map_Ks 's.png' is not supported yet and is ignored"));
    CHECK(contains(m.warnings, "w.mtl: material 'b': "));
    CHECK(contains(m.warnings, "missing.png"));
    CHECK(contains(m.warnings, "the faces keep Kd"));
    CHECK(contains(m.warnings, "w.mtl: material 'c': Ks is ignored: a textured material is Lambertian"));
    CHECK(material_of<lambertian>(m, 1)->albedo().x() == doctest::Approx(0.3)); // kept Kd

    // A library that cannot be read: the model renders grey, said once.
    const obj_model grey = load_obj_model(dir.write("g.obj", "mtllib nowhere.mtl\nusemtl a\n" + square(0, 1)));
    CHECK(contains(grey.warnings, "nowhere.mtl"));
    CHECK(contains(grey.warnings, "every face is grey"));
    CHECK(material_of<lambertian>(grey, 0)->albedo().y() == 0.8);

    // Malformed: one error line naming the file (and line).
    auto fails = [&](const std::string& mtl, const std::string& fragment) {
        dir.write("bad.mtl", mtl);
        test::check_scene_error([&] { load_obj_model(dir.write("bad.obj", "mtllib bad.mtl\nusemtl a\n" + square(0, 1))); },
                                    {fragment});
    };
    fails("newmtl a\nKd -1 0 0\n", "bad.mtl: material 'a': Kd must be finite and non-negative");
    fails("newmtl a\nKd 1e999 0 0\n", "bad.mtl:2: malformed MTL file");
    fails(std::string("newmtl a\nKd 1 1", 16) + std::string(1, '\0') + "\n", "bad.mtl:2: malformed MTL file: a NUL byte");
    fails("newmtl a\nillum 99999999999\n", "bad.mtl:2: malformed MTL file");
}

TEST_CASE("scene files: mesh file.obj mtl keeps the model's materials") {
    test::scratch_dir dir("obj_scene");
    dir.write("m.mtl", "newmtl red\nKd 0.9 0.1 0.1\nnewmtl lamp\nKe 4 4 4\nbump b.png\n");
    dir.write("m.obj", "mtllib m.mtl\nusemtl red\n" + square(0, 1) + "usemtl lamp\n" + square(2, 5));
    const scene_description s = load_scene(dir.write("s.txt", "mesh m.obj mtl translate 0 0 -3\n"));
    REQUIRE(s.world.objects.size() == 1); // the model, placed as one
    REQUIRE(s.warnings.size() == 1);
    CHECK(s.warnings[0].find("bump map 'b.png'") != std::string::npos);
    CHECK(s.files.size() == 3); // the scene, the OBJ, its library
    test::check_scene_error([&] { load_scene(dir.write("p.txt", "mesh m.ply mtl\n")); },
                                {"p.txt:1: ", "a PLY mesh has no material library"});
}

} // namespace test_obj_model

namespace test_obj_model {

TEST_CASE("OBJ models: a norm normal map makes the material normal_mapped, a missing one warns") {
    test::scratch_dir dir("obj_norm");
    dir.write("n.png", rt::encode_8bit_image(dir.file("n.png"), 1, 1, {128, 191, 237}));
    dir.write("n.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnorm n.png\nnewmtl b\nKd 0.5 0.5 0.5\nnorm gone.png\n");
    const rt::obj_model m = rt::load_obj_model(dir.write("n.obj", "mtllib n.mtl\nusemtl a\n" + square(0, 1) + "usemtl b\n" + square(2, 5)));
    const auto* mapped = material_of<rt::normal_mapped>(m, 0);
    REQUIRE(mapped);
    CHECK(dynamic_cast<const rt::lambertian*>(mapped->base().get()));
    // Read as data: green 191 is 191 / 255, not sRGB-decoded.
    CHECK(mapped->normals()->value(0.5, 0.5, rt::point3(0, 0, 0)).y() == doctest::Approx(191 / 255.0).epsilon(1e-6));
    CHECK(material_of<rt::lambertian>(m, 1));
    bool warned = false;
    for (const std::string& w : m.warnings) warned = warned || w.find("normal map 'gone.png' not found; the faces are flat") != std::string::npos;
    CHECK(warned);
}

TEST_CASE("OBJ models: a bump map makes the material bump_mapped, its -bm the scale") {
    test::scratch_dir dir("obj_bump");
    dir.write("h.png", rt::encode_8bit_image(dir.file("h.png"), 2, 1, {0, 0, 0, 255, 255, 255}));
    dir.write("b.mtl", "newmtl a\nKd 0.5 0.5 0.5\nbump -bm 0.25 h.png\nnewmtl b\nKd 0.5 0.5 0.5\nmap_Bump h.png\n"
                       "newmtl c\nKd 0.5 0.5 0.5\nnorm h.png\nbump h.png\n");
    const rt::obj_model m = rt::load_obj_model(
        dir.write("b.obj", "mtllib b.mtl\nusemtl a\n" + square(0, 1) + "usemtl b\n" + square(2, 5) + "usemtl c\n" + square(4, 9)));
    const auto* a = material_of<rt::normal_mapped>(m, 0);
    REQUIRE(a);
    CHECK(a->holds_heights());
    CHECK(a->scale() == doctest::Approx(0.25));
    // Read as data: white is 1, black 0.
    CHECK(a->normals()->value(0.75, 0.5, rt::point3(0, 0, 0)).x() == doctest::Approx(1).epsilon(1e-6));
    const auto* b = material_of<rt::normal_mapped>(m, 1);
    REQUIRE(b);
    CHECK(b->holds_heights());
    CHECK(b->scale() == 1); // map_Bump, -bm's default
    const auto* c = material_of<rt::normal_mapped>(m, 2);
    REQUIRE(c);
    CHECK_FALSE(c->holds_heights()); // the normal map wins, said once
    bool warned = false;
    for (const std::string& w : m.warnings) warned = warned || w.find("the normal map is used, the bump map 'h.png' is ignored") != std::string::npos;
    CHECK(warned);
}

} // namespace test_obj_model
