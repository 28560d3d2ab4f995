// Book 2's textures (rtweekend/texture.h, perlin.h, rtw_stb_image.h) and the engine's texture
// table (scene/texture_table.h, surface_coordinates.h): every expected value below is worked
// out by hand from the definitions (cell parity, pixel index arithmetic, the sRGB curve, Perlin's
// zero at lattice points), or compared between two independent routes through the renderer.

#include <rtweekend/camera.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/scene/surface_coordinates.h>
#include <rtweekend/scene/texture_table.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/material.h>
#include <rtweekend/mesh.h>
#include <rtweekend/perlin.h>
#include <rtweekend/quad.h>
#include <rtweekend/core/scene_error.h>
#include <rtweekend/sphere.h>
#include <rtweekend/texture.h>

#include <doctest/doctest.h>

// stb's writer for the Radiance HDR files these tests read (the library writes no HDR files, and
// a program that links the engine has none of stb's code in its own files).
#ifndef INCLUDE_STB_IMAGE_WRITE_H
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if __has_include(<stb_image_write.h>)
#include <stb_image_write.h>
#else
#include <stb/stb_image_write.h>
#endif
#endif

#include "test_helpers.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace test_texture {

using namespace rt;
using namespace test;

namespace {

const std::string texture_dir = RTWEEKEND_TEXTURE_DIR;

void check_color(const color& got, const color& want, double tol = 1e-6) {
    CAPTURE(got);
    CAPTURE(want);
    CHECK(std::fabs(got.x() - want.x()) <= tol);
    CHECK(std::fabs(got.y() - want.y()) <= tol);
    CHECK(std::fabs(got.z() - want.z()) <= tol);
}

// A texture class of the user's own: the engine calls it through value().
class stripes : public texture {
  public:
    color value(double u, double v, const point3& p) const override { return color(u, v, std::fabs(p.x()) < 0.5 ? 1 : 0); }
};

// What an image_texture of `path` reports, and what a render of a sphere wearing it throws.
std::string error_of(const char* path) { return image_texture(path).load_error(); }

std::string render_error_of(const char* path) {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -2), 1, std::make_shared<lambertian>(std::make_shared<image_texture>(path))));
    try {
        compile_scene(world, point3(0, 0, 0));
    } catch (const scene_error& e) {
        return e.what();
    }
    return "";
}

void append_bytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

} // namespace

TEST_CASE("checker_texture: parity of floor(p / scale) summed over x, y, z, negative cells included") {
    const color even(1, 0, 0), odd(0, 0, 1);
    checker_texture unit(1.0, even, odd);
    check_color(unit.value(0, 0, point3(0.5, 0.5, 0.5)), even);     // 0 + 0 + 0
    check_color(unit.value(0, 0, point3(1.5, 0.5, 0.5)), odd);      // 1
    check_color(unit.value(0, 0, point3(-0.5, 0.5, 0.5)), odd);     // -1
    check_color(unit.value(0, 0, point3(-0.5, -0.5, 0.5)), even);   // -2
    check_color(unit.value(0, 0, point3(-0.5, -0.5, -0.5)), odd);   // -3
    check_color(unit.value(0, 0, point3(-2.5, 7.25, 1.0)), odd);    // -3 + 7 + 1 = 5
    // The book's scale 0.32: cells 0.32 wide.
    checker_texture book(0.32, even, odd);
    check_color(book.value(0, 0, point3(0.31, 0, 0)), even);        // floor(0.97) = 0
    check_color(book.value(0, 0, point3(0.33, 0, 0)), odd);         // floor(1.03) = 1
    check_color(book.value(0, 0, point3(-0.01, -0.01, 0.65)), even); // -1 - 1 + 2 = 0
    // Children are textures: a checker of checkers.
    auto inner = std::make_shared<checker_texture>(0.5, color(0, 1, 0), color(1, 1, 1));
    checker_texture outer(2.0, inner, std::make_shared<solid_color>(0, 0, 0));
    check_color(outer.value(0, 0, point3(0.25, 0.25, 0.25)), color(0, 1, 0)); // outer even, inner 0
    check_color(outer.value(0, 0, point3(0.75, 0.25, 0.25)), color(1, 1, 1)); // outer even, inner 1
    check_color(outer.value(0, 0, point3(2.5, 0.25, 0.25)), color(0, 0, 0));  // outer odd
    CHECK_THROWS_AS(checker_texture(0.0, even, odd), scene_error);
}

TEST_CASE("image_texture: sRGB bytes decoded exactly: 0 -> 0, 255 -> 1, 128 -> 0.2158605") {
    image_texture t((texture_dir + "/srgb_2x2.png").c_str());
    REQUIRE(t.image().width() == 2);
    REQUIRE(t.image().height() == 2);
    // v = 1 is the top row: black, white; the bottom row: 128 grey, (255, 0, 64).
    check_color(t.value(0.25, 0.75, point3()), color(0, 0, 0));
    check_color(t.value(0.75, 0.75, point3()), color(1, 1, 1));
    check_color(t.value(0.25, 0.25, point3()), color(0.2158605, 0.2158605, 0.2158605));
    check_color(t.value(0.75, 0.25, point3()), color(1, 0, 0.0512695));
    // pixel_data: the file's bytes, (x, y) with y = 0 the top row.
    const unsigned char* px = t.image().pixel_data(0, 1);
    CHECK(int(px[0]) == 128);
    px = t.image().pixel_data(1, 1);
    CHECK(int(px[0]) == 255);
    CHECK(int(px[1]) == 0);
    CHECK(int(px[2]) == 64);
    // Out of range coordinates are clamped into the image.
    CHECK(int(t.image().pixel_data(-3, 9)[0]) == 128);
}

TEST_CASE("image_texture: nearest pixel i = int(u w), j = int((1 - v) h), clamped, rows top to bottom") {
    // Pixel (i, j) holds bytes (10 (i + 1), 100 + 50 j, 7), row 0 the top.
    image_texture t((texture_dir + "/rows_4x2.png").c_str());
    REQUIRE(t.image().width() == 4);
    REQUIRE(t.image().height() == 2);
    auto expect = [](int i, int j) {
        return color(srgb_to_linear(10 * (i + 1) / 255.0), srgb_to_linear((100 + 50 * j) / 255.0), srgb_to_linear(7 / 255.0));
    };
    struct probe {
        double u, v;
        int i, j;
    };
    const probe probes[] = {
        {0.0, 1.0, 0, 0},    // top-left corner
        {1.0, 1.0, 3, 0},    // top-right: u = 1 is the last column, not one past it
        {0.0, 0.0, 0, 1},    // bottom-left
        {1.0, 0.0, 3, 1},    // bottom-right
        {0.26, 0.9, 1, 0},   // int(1.04) = 1; int(0.2) = 0
        {0.2499, 0.9, 0, 0}, // int(0.9996) = 0
        {0.5, 0.5, 2, 1},    // int(2.0) = 2; int(1.0) = 1: v = 0.5 is the bottom row's top edge
        {0.5, 0.51, 2, 0},   // int(0.98) = 0
        {-4.0, 3.0, 0, 0},   // clamped to [0, 1] first
        {7.0, -2.0, 3, 1},
    };
    for (const probe& p : probes) {
        CAPTURE(p.u);
        CAPTURE(p.v);
        check_color(t.value(p.u, p.v, point3(9, 9, 9)), expect(p.i, p.j));
    }
}

TEST_CASE("image_texture: a Radiance HDR file stays linear and unclamped") {
    scratch_dir dir("texture");
    // RGBE stores (8, 2, 0.25) exactly: shared exponent 2^4, mantissas 128, 32 and 4 (of 256).
    const float pixels[] = {8.0f, 2.0f, 0.25f, 0.5f, 0.5f, 0.5f};
    std::string bytes;
    REQUIRE(stbi_write_hdr_to_func(append_bytes, &bytes, 2, 1, 3, pixels));
    const std::string path = dir.write("two.hdr", bytes);
    image_texture t(path.c_str());
    check_color(t.value(0.25, 0.5, point3()), color(8, 2, 0.25), 0);
    check_color(t.value(0.75, 0.5, point3()), color(0.5, 0.5, 0.5), 0);
    // Its bytes are its sRGB encoding, clamped: 8 -> 255, 0.25 -> 137 (0.537099 * 255 rounded).
    const unsigned char* px = t.image().pixel_data(0, 0);
    CHECK(int(px[0]) == 255);
    CHECK(int(px[2]) == 137);
}

TEST_CASE("image_texture: a missing or corrupt file is a scene_error naming it, at render time") {
    // Built without throwing, as the book's constructor goes on; the render refuses the scene.
    const std::string missing = error_of("no_such_texture_file.png");
    CHECK(missing.find("no_such_texture_file.png") != std::string::npos);
    CHECK(missing.find("not found") != std::string::npos);
    CHECK(render_error_of("no_such_texture_file.png") == missing);
    const std::string corrupt_path = texture_dir + "/corrupt.png";
    const std::string corrupt = error_of(corrupt_path.c_str());
    CHECK(corrupt.find(corrupt_path) != std::string::npos);
    CHECK(render_error_of(corrupt_path.c_str()) == corrupt);
    CHECK(error_of("") != "");
    CHECK(render_error_of("") == error_of(""));
    // A file that was read reports nothing and renders.
    const std::string good = texture_dir + "/rows_4x2.png";
    CHECK(error_of(good.c_str()).empty());
    CHECK(render_error_of(good.c_str()).empty());
    // Asked directly, the texture without pixels answers the book's cyan everywhere.
    const image_texture none("no_such_texture_file.png");
    check_color(none.value(0.3, 0.7, point3(1, 2, 3)), color(0, 1, 1), 0);
    check_color(none.value(-1, 2, point3()), color(0, 1, 1), 0);
}

TEST_CASE("perlin: 0 at lattice points, bounded by 1, continuous") {
    pcg32 g(42);
    detail::scoped_sample_rng guard(g);
    const perlin noise;
    pcg32 points(7);
    // At a lattice point every corner weight but one is 0, and that corner's offset is 0.
    for (int k = 0; k < 100; ++k) {
        const point3 p(std::floor(200 * points.next_double() - 100), std::floor(200 * points.next_double() - 100),
                       std::floor(200 * points.next_double() - 100));
        CHECK(noise.noise(p) == 0);
    }
    // |noise| <= sqrt(3) / 2 for unit gradients in 3-D (a gradient dotted with an offset of length
    // at most sqrt(3)/2 from the nearest corner bounds it); 1 is the brief's looser bound.
    double largest = 0, steepest = 0;
    for (int k = 0; k < 20000; ++k) {
        const point3 p(40 * points.next_double() - 20, 40 * points.next_double() - 20, 40 * points.next_double() - 20);
        const double n = noise.noise(p);
        largest = std::fmax(largest, std::fabs(n));
        const double h = 1e-6;
        steepest = std::fmax(steepest, std::fabs(noise.noise(p + vec3(h, -h, h)) - n) / h);
    }
    CHECK(largest <= 1.0);
    CHECK(largest > 0.3); // not flat
    // Smooth: its slope is bounded (by the gradients' length times a small constant).
    CHECK(steepest < 10);
    // turb is the absolute value of a weighted sum: non-negative, at most 2 (weights 1 + 1/2 + ...).
    for (int k = 0; k < 1000; ++k) {
        const point3 p(10 * points.next_double(), 10 * points.next_double(), 10 * points.next_double());
        const double t = noise.turb(p);
        CHECK(t >= 0);
        CHECK(t <= 2);
    }
}

TEST_CASE("perlin: the book's tables from the random_double() sequence, in the book's order") {
    // The book's constructor drawn by hand: 256 vectors, three draws each (z, y, x; vec3.h), each
    // coordinate -1 + 2 r; then three Fisher-Yates shuffles with floor((i + 1) r) for i = 255..1.
    pcg32 reference(2024);
    vec3 gradient[256];
    for (vec3& v : gradient) {
        double z = -1 + 2 * reference.next_double(), y = -1 + 2 * reference.next_double(), x = -1 + 2 * reference.next_double();
        v = unit_vector(vec3(x, y, z));
    }
    int perm[3][256];
    for (auto& p : perm) {
        for (int i = 0; i < 256; ++i) p[i] = i;
        for (int i = 255; i > 0; --i) std::swap(p[i], p[int(std::floor((i + 1) * reference.next_double()))]);
    }
    // Noise at a point inside cell (0, 0, 0) near the corner (0, 0, 0): the smoothstep weights
    // of (u, v, w) = (0.25, 0.5, 0.75) are 0.15625, 0.5, 0.84375.
    const double u = 0.25, v = 0.5, w = 0.75;
    const double wu[2] = {1 - 0.15625, 0.15625}, wv[2] = {0.5, 0.5}, ww[2] = {1 - 0.84375, 0.84375};
    double expected = 0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k)
                expected += wu[i] * wv[j] * ww[k] *
                            dot(gradient[perm[0][i] ^ perm[1][j] ^ perm[2][k]], vec3(u - i, v - j, w - k));

    pcg32 g(2024);
    detail::scoped_sample_rng guard(g);
    const perlin noise;
    CHECK(noise.noise(point3(u, v, w)) == doctest::Approx(expected).epsilon(1e-12));
    // The same sequence gives the same noise; another gives another.
    pcg32 again(2024), other(2025);
    perlin a, b;
    {
        detail::scoped_sample_rng g2(again);
        a = perlin();
    }
    {
        detail::scoped_sample_rng g3(other);
        b = perlin();
    }
    const point3 p(3.7, -1.2, 8.9);
    CHECK(a.noise(p) == noise.noise(p));
    CHECK(b.noise(p) != noise.noise(p));
}

TEST_CASE("noise_texture: the book's marble 0.5 (1 + sin(scale z + 10 turb(p))), exact at lattice points") {
    pcg32 g(5);
    detail::scoped_sample_rng guard(g);
    noise_texture marble(4);
    // At (1, 2, 3) every octave's point is a lattice point: turb = 0, so 0.5 (1 + sin 12).
    check_color(marble.value(0, 0, point3(1, 2, 3)), color(0.2317135, 0.2317135, 0.2317135));
    const color c = marble.value(0, 0, point3(0.3, 0.6, 0.1));
    CHECK(c.x() >= 0);
    CHECK(c.x() <= 1);
    CHECK(c.x() == c.z());
}

TEST_CASE("texture_table: eval agrees with texture::value at random points, one entry per texture") {
    pcg32 g(11);
    detail::scoped_sample_rng guard(g);
    auto image = std::make_shared<image_texture>((texture_dir + "/rows_4x2.png").c_str());
    auto noise = std::make_shared<noise_texture>(3);
    auto user = std::make_shared<stripes>();
    auto nested = std::make_shared<checker_texture>(0.7, image, noise);
    auto top = std::make_shared<checker_texture>(1.3, nested, user);
    texture_table table;
    const uint32_t i_top = table.add(*top);
    CHECK(table.add(*top) == i_top);       // deduplicated by pointer
    CHECK(table.entries.size() == 5);      // top, nested, image, noise, user
    CHECK(table.calls_user_code());
    const texture* all[] = {top.get(), nested.get(), image.get(), noise.get(), user.get()};
    pcg32 r(3);
    for (const texture* t : all) {
        const uint32_t index = table.add(*t);
        for (int k = 0; k < 500; ++k) {
            const float u = r.next_float() * 1.2f - 0.1f, v = r.next_float() * 1.2f - 0.1f;
            const point3 p(8 * r.next_double() - 4, 8 * r.next_double() - 4, 8 * r.next_double() - 4);
            const vec3f got = table.eval(index, u, v, p);
            const color want = t->value(u, v, p);
            CAPTURE(index);
            CHECK(got.x == doctest::Approx(want.x()).epsilon(1e-6));
            CHECK(got.y == doctest::Approx(want.y()).epsilon(1e-6));
            CHECK(got.z == doctest::Approx(want.z()).epsilon(1e-6));
        }
    }
    // The means light selection uses: a solid colour's channels averaged, a checker half and half.
    texture_table means;
    checker_texture two(1.0, color(0.3, 0.6, 0.9), color(0, 0, 0));
    CHECK(means.average(means.add(two)) == doctest::Approx(0.3));
}

TEST_CASE("texture_table: reads_uv only for images, user textures and checkers holding one") {
    pcg32 g(12);
    detail::scoped_sample_rng guard(g);
    auto image = std::make_shared<image_texture>((texture_dir + "/rows_4x2.png").c_str());
    auto noise = std::make_shared<noise_texture>(3);
    auto user = std::make_shared<stripes>();
    auto plain = std::make_shared<solid_color>(color(0.2, 0.4, 0.6));
    checker_texture spatial(0.5, color(1, 0, 0), color(0, 1, 0));
    checker_texture marble_or_plain(0.5, noise, plain);
    checker_texture with_image(0.5, plain, image);
    checker_texture nested(0.5, std::make_shared<checker_texture>(0.25, noise, user), plain);
    texture_table table;
    CHECK_FALSE(table.reads_uv(table.add(*plain)));
    CHECK_FALSE(table.reads_uv(table.add(*noise)));
    CHECK_FALSE(table.reads_uv(table.add(spatial)));
    CHECK_FALSE(table.reads_uv(table.add(marble_or_plain)));
    CHECK(table.reads_uv(table.add(*image)));
    CHECK(table.reads_uv(table.add(*user)));
    CHECK(table.reads_uv(table.add(with_image)));
    CHECK(table.reads_uv(table.add(nested)));
    // A texture that ignores (u, v) gives the same colour whatever they are (what skipping them assumes).
    const uint32_t m = table.add(marble_or_plain);
    pcg32 r(4);
    for (int k = 0; k < 200; ++k) {
        const point3 p(8 * r.next_double() - 4, 8 * r.next_double() - 4, 8 * r.next_double() - 4);
        const vec3f a = table.eval(m, 0, 0, p), b = table.eval(m, r.next_float(), r.next_float(), p);
        CHECK(a.x == b.x);
        CHECK(a.y == b.y);
        CHECK(a.z == b.z);
    }
}

TEST_CASE("surface_coordinates: spheres by the book's get_sphere_uv, quads by their edges, meshes by their uv") {
    hittable_list world;
    auto grey = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    world.add(std::make_shared<sphere>(point3(0, 0, -10), 1, grey));
    world.add(std::make_shared<quad>(point3(10, -1, -5), vec3(4, 0, 0), vec3(0, 2, 0), grey));
    auto mesh = std::make_shared<triangle_mesh>(
        std::vector<point3>{point3(-10, 0, -5), point3(-9, 0, -5), point3(-10, 1, -5)},
        std::vector<std::array<uint32_t, 3>>{{0, 1, 2}}, grey);
    mesh->uvs = {{0.2, 0.4}, {0.6, 0.4}, {0.2, 0.9}};
    mesh->face_uvs = {{0, 1, 2}};
    world.add(mesh);
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    auto uv_along = [&](const vec3& dir, double& u, double& v) {
        ray3f r;
        r.dir = vec3f(unit_vector(dir));
        surface_hit hit;
        REQUIRE(scene.intersect(r, hit));
        surface_coordinates(scene, hit, u, v);
    };
    double u, v;
    // The sphere seen from +z: its point (0, 0, 1) from the centre, which the book maps to (0.25, 0.5).
    uv_along(vec3(0, 0, -1), u, v);
    CHECK(u == doctest::Approx(0.25).epsilon(1e-6));
    CHECK(v == doctest::Approx(0.5).epsilon(1e-6));
    // The quad Q + a (4, 0, 0) + b (0, 2, 0): its point (11, 0.5, -5) is a = 0.25, b = 0.75.
    uv_along(vec3(11, 0.5, -5), u, v);
    CHECK(u == doctest::Approx(0.25).epsilon(1e-5));
    CHECK(v == doctest::Approx(0.75).epsilon(1e-5));
    // The triangle's point (-9.75, 0.5, -5): barycentric (0.25, 0.25, 0.5) on (a, b, c), so
    // u = 0.25 * 0.2 + 0.25 * 0.6 + 0.5 * 0.2 = 0.3 and v = 0.25 * 0.4 + 0.25 * 0.4 + 0.5 * 0.9 = 0.65.
    uv_along(vec3(-9.75, 0.5, -5), u, v);
    CHECK(u == doctest::Approx(0.3).epsilon(1e-5));
    CHECK(v == doctest::Approx(0.65).epsilon(1e-5));
    // The mesh's own hit() (world.hit, not the engine) agrees.
    hit_record rec;
    REQUIRE(mesh->hit(ray(point3(0, 0, 0), vec3(-9.75, 0.5, -5)), interval(0.001, infinity), rec));
    CHECK(rec.u == doctest::Approx(0.3).epsilon(1e-9));
    CHECK(rec.v == doctest::Approx(0.65).epsilon(1e-9));
}

namespace {
// A camera at (0, 0, 0.2) looking down -z with a 90 degree view, 8x8: at the plane z = -0.8
// (distance 1) the picture spans [-1, 1] in x and y, a pixel 0.25 wide.
rt::camera straight_on(int spp) {
    rt::camera cam = test_camera(8, 8, spp, 10);
    cam.vfov = 90;
    cam.lookfrom = point3(0, 0, 0.2);
    cam.lookat = point3(0, 0, -0.8);
    cam.vup = vec3(0, 1, 0);
    cam.defocus_angle = 0;
    return cam;
}

// The checker's colour at pixel (i, j)'s part of the plane z = -0.8, cells 0.5 wide: every
// pixel lies inside one cell, and floor(-0.8 / 0.5) = -2 is even.
color cell_colour(int i, int j, const color& even, const color& odd) {
    const double x = -1 + 0.25 * (i + 0.5), y = 1 - 0.25 * (j + 0.5);
    const double sum = std::floor(x / 0.5) + std::floor(y / 0.5) - 2;
    return std::fmod(sum, 2.0) == 0 ? even : odd;
}
} // namespace

TEST_CASE("render: a checker emitter seen directly shows its texture colour in every pixel") {
    const color even(0.9, 0.2, 0.1), odd(0.1, 0.3, 0.8);
    auto checker = std::make_shared<checker_texture>(0.5, even, odd);
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-2, -2, -0.8), vec3(4, 0, 0), vec3(0, 4, 0),
                                     std::make_shared<diffuse_light>(checker)));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 0));
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].is<emitter_bsdf>()); // not the virtual fallback
    CHECK(scene.materials[0].texture != no_texture);
    CHECK_FALSE(scene.calls_user_code());
    rt::camera cam = straight_on(4);
    cam.background = color(0, 0, 0);
    const render_result r = render_checked(cam, world);
    int evens = 0;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            const color want = cell_colour(i, j, even, odd);
            evens += want.x() == even.x();
            CAPTURE(i);
            CAPTURE(j);
            check_color(r.img.pixel(i, j), want, 1e-6);
        }
    CHECK(evens == 32); // half the pixels each colour
}

TEST_CASE("render: a checker albedo under a uniform sky reflects exactly its albedo") {
    // A flat surface under a background of radiance 1 receives irradiance pi from the hemisphere,
    // none from itself: out goes albedo * 1, whatever direction each bounce takes.
    const color even(0.8, 0.5, 0.2), odd(0.25, 0.25, 0.75);
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-2, -2, -0.8), vec3(4, 0, 0), vec3(0, 4, 0),
                                     std::make_shared<lambertian>(std::make_shared<checker_texture>(0.5, even, odd))));
    rt::camera cam = straight_on(4);
    cam.background = color(1, 1, 1);
    const render_result r = render_checked(cam, world);
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            CAPTURE(i);
            CAPTURE(j);
            check_color(r.img.pixel(i, j), cell_colour(i, j, even, odd), 1e-6);
        }
}

TEST_CASE("render: a textured light is sampled with its texture at the sampled point") {
    // A white floor under a ceiling light in the dark. (1) A checker light whose cells are both
    // the same colour c renders bit for bit as diffuse_light(c): the same power, the same draws,
    // the same radiance at every sampled point. (2) A two-colour checker light, found by light
    // sampling (nee) and by bsdf sampling alone (which only ever sees the texture where a ray
    // hits it), gives the same image within the noise.
    auto scene_with = [](std::shared_ptr<material> light) {
        hittable_list world;
        world.add(std::make_shared<quad>(point3(-3, 0, -3), vec3(6, 0, 0), vec3(0, 0, 6),
                                         std::make_shared<lambertian>(color(0.8, 0.8, 0.8))));
        // Edges (2, 0, 0) then (0, 0, 2): the normal, cross(u, v), points down at the floor.
        world.add(std::make_shared<quad>(point3(-1, 2, -1), vec3(2, 0, 0), vec3(0, 0, 2), light));
        return world;
    };
    auto camera = [](int spp) {
        rt::camera cam = test_camera(12, 12, spp, 4);
        cam.vfov = 60;
        cam.lookfrom = point3(0, 1, 4);
        cam.lookat = point3(0, 0, 0);
        cam.vup = vec3(0, 1, 0);
        cam.defocus_angle = 0;
        cam.background = color(0, 0, 0);
        return cam;
    };
    const color c(3, 2, 1);
    const hittable_list plain = scene_with(std::make_shared<diffuse_light>(c));
    const hittable_list same = scene_with(std::make_shared<diffuse_light>(std::make_shared<checker_texture>(0.4, c, c)));
    const image plain_img = render_checked(camera(8), plain).img;
    CHECK(plain_img.pixel(6, 8).x() > 0); // the floor in front of the camera is lit
    CHECK(same_bits(plain_img, render_checked(camera(8), same).img));

    const hittable_list two = scene_with(
        std::make_shared<diffuse_light>(std::make_shared<checker_texture>(0.4, color(6, 4, 2), color(0, 0, 0))));
    rt::camera nee = camera(256), bsdf = camera(256);
    nee.settings.estimator = path_estimator::nee;
    bsdf.settings.estimator = path_estimator::bsdf;
    const image a = render_checked(nee, two).img, b = render_checked(bsdf, two).img;
    // The floor's mean radiance, over the whole image: the two estimators' means differ by
    // their noise only (bsdf sampling of a small light is noisy; 10 % is several of its sigmas).
    double sum_a = 0, sum_b = 0;
    for (size_t k = 0; k < a.data().size(); ++k) {
        sum_a += a.data()[k];
        sum_b += b.data()[k];
    }
    CHECK(sum_a > 0);
    CHECK(sum_a == doctest::Approx(sum_b).epsilon(0.1));
}

} // namespace test_texture
