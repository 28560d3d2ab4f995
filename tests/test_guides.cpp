// Denoiser guides (rtweekend/render/guides.h): a textured Lambertian square's albedo is its
// texture, texel for texel; a sphere's normals are the analytic ones; depth and position of a
// plane at a known distance; a mirror shows the albedo of what it reflects; the sky's pixels; the
// same guides at any thread count.

#include <rtweekend/render/guides.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/rtweekend.h>
#include <rtweekend/scene/scene_compiler.h>

#include <doctest/doctest.h>

#include "aov_sheet.h"
#include "test_helpers.h"

#include <cmath>
#include <limits>
#include <memory>

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
#include <rtweekend/core/file.h>
#include <rtweekend/image/exr.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#endif

namespace test_guides {

using namespace rt;

namespace {

render_settings guide_settings(int spp, int threads = 2) {
    render_settings s;
    s.samples_per_pixel = spp;
    s.threads = threads;
    s.quiet = true;
    s.seed = 7;
    return s;
}

camera front_camera(int w, int h) {
    camera cam = test::test_camera(w, h, 1, 4);
    cam.lookfrom = point3(0, 0, 10);
    cam.lookat = point3(0, 0, 0);
    cam.vfov = 10; // half-height 10 tan 5 deg = 0.87: inside the square [-1, 1]^2
    cam.background = color(0.25, 0.5, 2.0);
    return cam;
}

guide_images guides_of(const hittable_list& world, const camera& cam, const render_settings& s) {
    const camera_frame frame = cam.frame();
    const compiled_scene scene = compile_scene(world, frame.position, {});
    return render_guides(scene, frame, cam.sky(), s);
}

} // namespace

TEST_CASE("guides: a textured Lambertian square, its albedo the texture, depth, position and normal of the plane") {
    // A 2 x 2 picture over the square [-1, 1]^2 at z = 0, seen head-on from z = 10.
    const std::string png = encode_8bit_image("g.png", 2, 2, {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255});
    rtw_image picture;
    picture.decode(png, "g.png");
    auto tex = std::make_shared<image_texture>(picture, image_sampling{});
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-1, -1, 0), vec3(2, 0, 0), vec3(0, 2, 0), std::make_shared<lambertian>(tex)));
    const camera cam = front_camera(8, 8);
    const guide_images g = guides_of(world, cam, guide_settings(4));
    // Quarters of the view: top left red, top right green, bottom left blue, bottom right white.
    const color expect[2][2] = {{color(1, 0, 0), color(0, 1, 0)}, {color(0, 0, 1), color(1, 1, 1)}};
    for (int y : {1, 6})
        for (int x : {1, 6}) {
            const color a = g.albedo.pixel(x, y), e = expect[y / 4][x / 4];
            CAPTURE(x);
            CAPTURE(y);
            CHECK(a.x() == doctest::Approx(e.x()).epsilon(1e-6));
            CHECK(a.y() == doctest::Approx(e.y()).epsilon(1e-6));
            CHECK(a.z() == doctest::Approx(e.z()).epsilon(1e-6));
            const color n = g.normal.pixel(x, y);
            CHECK(n.z() == doctest::Approx(1));
            // The plane z = 0 seen from (0, 0, 10): each ray's depth is its point's distance from
            // the camera. Means of 4 rays a pixel: the mean depth is at least the mean point's
            // distance, and within 1e-4 of it over a pixel this narrow.
            const color p = g.position.pixel(x, y);
            CHECK(std::fabs(p.z()) < 1e-5);
            const double d = g.depth.pixel(x, y).x(), mean_distance = std::sqrt(p.x() * p.x() + p.y() * p.y() + 100);
            CHECK(d >= mean_distance * (1 - 1e-6));
            CHECK(d == doctest::Approx(mean_distance).epsilon(1e-4));
        }
}

TEST_CASE("guides: a sphere with the analytic normals, and the sky pixels") {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, 0), 1.0, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    camera cam = front_camera(24, 24);
    cam.vfov = 14; // the sphere and some sky
    // One sample a pixel: the ray through the pixel's centre.
    const guide_images g = guides_of(world, cam, guide_settings(1));
    int sphere_pixels = 0, sky_pixels = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            const color n = g.normal.pixel(x, y);
            if (std::isinf(g.depth.pixel(x, y).x())) {
                ++sky_pixels;
                CHECK(n.length() == 0);
                CHECK(g.albedo.pixel(x, y).x() == doctest::Approx(0.25)); // the sky, clamped to [0, 1]
                CHECK(g.albedo.pixel(x, y).z() == doctest::Approx(1.0));
                continue;
            }
            ++sphere_pixels;
            // The unit sphere at the origin: the normal at a point is the point itself.
            const color p = g.position.pixel(x, y);
            CHECK(n.x() == doctest::Approx(p.x()).epsilon(1e-4));
            CHECK(n.y() == doctest::Approx(p.y()).epsilon(1e-4));
            CHECK(n.z() == doctest::Approx(p.z()).epsilon(1e-4));
            CHECK(p.length() == doctest::Approx(1).epsilon(1e-5));
            CHECK(g.albedo.pixel(x, y).x() == doctest::Approx(0.5));
        }
    CHECK(sphere_pixels > 100);
    CHECK(sky_pixels > 100);
}

TEST_CASE("guides: a mirror shows the albedo and normal of what it reflects, the same at any thread count") {
    // A mirror square facing +z at z = 0; a green Lambertian floor-wall behind the camera, at
    // z = 20 facing -z, which the mirror reflects back into the camera.
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-1, -1, 0), vec3(2, 0, 0), vec3(0, 2, 0), std::make_shared<metal>(color(1, 1, 1), 0.0)));
    world.add(std::make_shared<quad>(point3(-5, -5, 20), vec3(0, 10, 0), vec3(10, 0, 0), std::make_shared<lambertian>(color(0.1, 0.7, 0.2))));
    const camera cam = front_camera(8, 8);
    const guide_images g = guides_of(world, cam, guide_settings(4, 1));
    const color a = g.albedo.pixel(4, 4), n = g.normal.pixel(4, 4);
    CHECK(a.x() == doctest::Approx(0.1).epsilon(1e-5));
    CHECK(a.y() == doctest::Approx(0.7).epsilon(1e-5));
    CHECK(n.z() == doctest::Approx(-1).epsilon(1e-3)); // the wall's normal, facing the reflected ray
    CHECK(g.depth.pixel(4, 4).x() == doctest::Approx(10).epsilon(1e-3)); // the mirror, the first surface
    const guide_images two = guides_of(world, cam, guide_settings(4, 2));
    CHECK(test::same_bits(g.albedo, two.albedo));
    CHECK(test::same_bits(g.normal, two.normal));
    CHECK(test::same_bits(g.depth, two.depth));
    CHECK(test::same_bits(g.position, two.position));
}

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
TEST_CASE("guides: an EXR of several images holds each channel under its name") {
    // Three 2 x 1 images with known values; the file read back by OpenEXR's own reader.
    image beauty(2, 1), albedo(2, 1), depth(2, 1);
    beauty.set_pixel(0, 0, color(1, 2, 3));
    beauty.set_pixel(1, 0, color(4, 5, 6));
    albedo.set_pixel(1, 0, color(0.25, 0.5, 0.75));
    depth.set_pixel(0, 0, color(7, 7, 7));
    depth.set_pixel(1, 0, color(8, 8, 8));
    test::scratch_dir dir("exr_channels");
    const std::string path = dir.file("g.exr");
    write_file_atomically(path, encode_exr({{&beauty, {"R", "G", "B"}}, {&albedo, {"albedo.R", "albedo.G", "albedo.B"}}, {&depth, {"Z"}}}, path));
    Imf::InputFile file(path.c_str());
    std::vector<std::string> names;
    for (auto c = file.header().channels().begin(); c != file.header().channels().end(); ++c) names.push_back(c.name());
    CHECK(names == std::vector<std::string>{"B", "G", "R", "Z", "albedo.B", "albedo.G", "albedo.R"}); // EXR sorts them
    float g[2] = {0, 0}, z[2] = {0, 0}, a[2] = {0, 0};
    Imf::FrameBuffer fb;
    fb.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g), sizeof(float), 2 * sizeof(float)));
    fb.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(z), sizeof(float), 2 * sizeof(float)));
    fb.insert("albedo.B", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(a), sizeof(float), 2 * sizeof(float)));
    file.setFrameBuffer(fb);
    file.readPixels(0, 0);
    CHECK(g[0] == 2);
    CHECK(g[1] == 5);
    CHECK(z[0] == 7);
    CHECK(z[1] == 8);
    CHECK(a[1] == 0.75f);
    // Images of different sizes are refused in one line.
    const image small(1, 1);
    test::check_scene_error([&] { encode_exr({{&beauty, {"R", "G", "B"}}, {&small, {"Z"}}}, "bad.exr"); }, {"bad.exr", "differ in size"});
}
#endif

TEST_CASE("aov_sheet: the four panels, each value mapped as the app's help says") {
    // Two pixels: one sees a surface at distance 2 (albedo 0.25, normal (0, 0, 1)), the other
    // one at distance 8 (normal (-1, 0, 0)); a third sees nothing. Shown through the book's gamma 2,
    // each panel value v is stored as v^2.
    image render(3, 1), albedo(3, 1), normal(3, 1), depth(3, 1), position(3, 1);
    render.set_pixel(0, 0, color(0.5, 0.25, 1));
    albedo.set_pixel(0, 0, color(0.25, 0.25, 0.25));
    normal.set_pixel(0, 0, color(0, 0, 1));
    normal.set_pixel(1, 0, color(-1, 0, 0));
    depth.set_pixel(0, 0, color(2, 2, 2));
    depth.set_pixel(1, 0, color(8, 8, 8));
    const double inf = std::numeric_limits<double>::infinity();
    depth.set_pixel(2, 0, color(inf, inf, inf));
    const image sheet = app::aov_sheet_image(render, guide_images{albedo, normal, depth, position});
    REQUIRE(sheet.width() == 6);
    REQUIRE(sheet.height() == 2);
    CHECK(sheet.pixel(0, 0).y() == doctest::Approx(0.25)); // the render, as it is
    CHECK(sheet.pixel(3, 0).x() == doctest::Approx(0.25)); // the albedo, as it is
    // The normal as 0.5 + 0.5 n: (0.5, 0.5, 1) and (0, 0.5, 0.5), squared; black where no hit.
    CHECK(sheet.pixel(0, 1).x() == doctest::Approx(0.25));
    CHECK(sheet.pixel(0, 1).z() == doctest::Approx(1));
    CHECK(sheet.pixel(1, 1).x() == doctest::Approx(0));
    CHECK(sheet.pixel(1, 1).y() == doctest::Approx(0.25));
    CHECK(sheet.pixel(2, 1).y() == 0);
    // The inverse depth, nearest / depth: 1 and 1/4, squared; black where nothing was hit.
    CHECK(sheet.pixel(3, 1).x() == doctest::Approx(1));
    CHECK(sheet.pixel(4, 1).x() == doctest::Approx(1.0 / 16));
    CHECK(sheet.pixel(5, 1).x() == 0);
}

} // namespace test_guides
