// Book 2's scenes: each scene file in tests/data is the scene its milestone app builds in code
// (apps/next_week_scenes.h), and the text format's book-2 directives (textures, moving spheres,
// media, groups and instances) mean what they say.

#include <rtweekend/io/scene_file.h>

#include <doctest/doctest.h>

#include "next_week_scenes.h"
#include "test_helpers.h"

#include <cstdlib>
#include <sstream>
#include <string>

namespace test_next_week_scenes {

using namespace rt;

namespace {

void tiny(camera& cam) {
    cam.image_width = 24;
    cam.samples_per_pixel = 4;
    cam.max_depth = 6;
    cam.settings.quiet = true;
    cam.settings.threads = 2;
    cam.settings.seed = 7;
}

// Renders a tiny version of both; they must agree bit for bit. Both are built from the C
// library's rand() as a new program's first draws, after `skip` draws for the file (what the app
// drew before its first noise texture, which the file builds as it reads it).
template <class Make>
void check_same_scene(Make make, const std::string& file, int skip = 0) {
    std::srand(1);
    next_week_scene code = make();
    std::srand(1);
    for (int i = 0; i < skip; ++i) random_double();
    scene_description s = load_scene(std::string(RTWEEKEND_TEST_DATA) + "/" + file);
    tiny(code.cam);
    tiny(s.cam);
    CHECK(code.cam.height() == s.cam.height());
    render_result a = render(code.cam, code.world), b = render(s.cam, s.world, s.point_lights);
    CHECK(test::same_bits(a.img, b.img));
    CHECK(a.stats.rays == b.stats.rays);
}

scene_description parse(const std::string& text) {
    std::istringstream in(text);
    return parse_scene(in, std::string(RTWEEKEND_TEST_DATA) + "/inline.txt");
}

} // namespace

TEST_CASE("book 2 scene files match the milestone apps' scenes") {
    SUBCASE("bouncing spheres") { check_same_scene([] { return make_bouncing_spheres(); }, "bouncing_spheres.txt"); }
    SUBCASE("checkered spheres") { check_same_scene(make_checkered_spheres, "checkered_spheres.txt"); }
    SUBCASE("earth") { check_same_scene(make_earth, "earth.txt"); }
    SUBCASE("Perlin spheres") { check_same_scene(make_perlin_spheres, "perlin_spheres.txt"); }
    SUBCASE("quads") { check_same_scene(make_quads, "quads.txt"); }
    SUBCASE("Cornell smoke") { check_same_scene(make_cornell_smoke, "cornell_smoke.txt"); }
    SUBCASE("final scene") { check_same_scene([] { return make_next_week_final(); }, "next_week_final.txt", 400); }
}

TEST_CASE("scene files: textures are named once and used as @name where a colour may vary") {
    scene_description s = parse("texture c checker 2 1 0 0 0 0 1\n"
                                "texture m checker 1 @c 0.5 0.5 0.5\n"
                                "sphere 0 0 0 1 lambertian @m 0 0\n");
    CHECK(s.world.objects.size() == 1);
    CHECK_THROWS_WITH_AS(parse("sphere 0 0 0 1 lambertian @nope 0 0\n"), doctest::Contains("no texture named 'nope'"),
                         scene_error);
    CHECK_THROWS_WITH_AS(parse("texture a solid 1 1 1\ntexture a solid 1 1 1\n"), doctest::Contains("already defined"),
                         scene_error);
    CHECK_THROWS_WITH_AS(parse("texture t solid 1 1 1\nsphere 0 0 0 1 metal @t 0 0\n"),
                         doctest::Contains("not a texture"), scene_error);
    CHECK_THROWS_WITH_AS(parse("texture e image no_such_file.png\n"), doctest::Contains("no_such_file.png"), scene_error);
    CHECK_THROWS_WITH_AS(parse("texture n noise -1\n"), doctest::Contains("noise scale"), scene_error);
}

TEST_CASE("scene files: a checker texture seen head-on shows its two colours in the right cells") {
    // An emitter textured with a checker of cell 1, filling the view: each pixel is exactly the
    // colour of the cell its centre sees (one sample per pixel through the pixel centre is not
    // what the camera does, so use cells much larger than pixels and look at cell centres).
    scene_description s = parse("texture c checker 1 1 0 0 0 0 1\n"
                                "quad -2 -2 0  4 0 0  0 4 0 diffuse_light @c 0 0\n"
                                "background 0 0 0\n"
                                "camera lookfrom 0 0 10\ncamera lookat 0 0 0\ncamera vfov 22.619864948040426\n"
                                "camera aspect_ratio 1\n");
    s.cam.image_width = 40;
    s.cam.samples_per_pixel = 4;
    s.cam.settings.quiet = true;
    s.cam.settings.threads = 2;
    render_result r = render(s.cam, s.world);
    // The view spans [-2, 2] in x and y (tan(vfov/2) * 10 = 2): pixel (5, 5) looks at about
    // (-1.5, 1.5, 0); floor sums -2 + 1 + 0 = -1: odd, blue. Pixel (15, 5) at (-0.5, 1.5):
    // -1 + 1 + 0 = 0, even, red.
    auto px = [&](int x, int y) { return r.img.pixel(x, y); };
    CHECK(px(5, 5).z() == doctest::Approx(1));
    CHECK(px(5, 5).x() == doctest::Approx(0));
    CHECK(px(15, 5).x() == doctest::Approx(1));
    CHECK(px(15, 5).z() == doctest::Approx(0));
}

TEST_CASE("scene files: media, moving spheres, groups and instances") {
    scene_description s = parse("group g\n"
                                "sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0\n"
                                "end\n"
                                "instance g translate 3 0 0\n"
                                "instance g translate -3 0 0\n"
                                "moving_sphere 0 0 0  0 1 0  0.5 lambertian 1 1 1 0 0\n"
                                "medium 0.5 1 1 1 box 0 0 0 1 1 1 lambertian 1 1 1 0 0\n");
    CHECK(s.world.objects.size() == 4); // two instances, the moving sphere, the medium
    CHECK_THROWS_WITH_AS(parse("group g\nsphere 0 0 0 1 lambertian 1 1 1 0 0\n"), doctest::Contains("no 'end'"),
                         scene_error);
    CHECK_THROWS_WITH_AS(parse("end\n"), doctest::Contains("without a group"), scene_error);
    CHECK_THROWS_WITH_AS(parse("instance q\n"), doctest::Contains("no group named 'q'"), scene_error);
    CHECK_THROWS_WITH_AS(parse("medium 0 1 1 1 sphere 0 0 0 1 lambertian 1 1 1 0 0\n"),
                         doctest::Contains("density must be positive"), scene_error);
    CHECK_THROWS_WITH_AS(parse("moving_sphere 0 0 0 1 1 1 -1 lambertian 1 1 1 0 0\n"),
                         doctest::Contains("radius must be positive"), scene_error);
}

} // namespace test_next_week_scenes
