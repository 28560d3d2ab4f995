// The emitter scenes: each scene file in tests/data is the scene its milestone app builds in code
// (apps/light_scenes.h), and the text format's light directives mean what they say.

#include <rtweekend/io/scene_file.h>
#include <rtweekend/scene/compiled_scene.h>
#include <rtweekend/scene/scene_compiler.h>

#include <doctest/doctest.h>

#include "light_scenes.h"
#include "test_helpers.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

namespace test_light_scenes {

using namespace rt;

namespace {

// Renders a tiny version of both; they must agree bit for bit (same shapes in the same order,
// same materials, same camera, same seed). Both are built from the C library's rand() as a new
// program's first draws (a noise texture draws its tables from it).
template <class Make>
void check_same_scene(Make make, const std::string& file) {
    std::srand(1);
    light_scene code = make();
    std::srand(1);
    scene_description s = load_scene(std::string(RTWEEKEND_TEST_DATA) + "/" + file);
    for (camera* cam : {&code.cam, &s.cam}) {
        cam->image_width = 24;
        cam->samples_per_pixel = 4;
        cam->settings.quiet = true;
        cam->settings.threads = 2;
        cam->settings.seed = 7;
    }
    CHECK(code.cam.height() == s.cam.height());
    render_result a = render(code.cam, code.world), b = render(s.cam, s.world, s.point_lights);
    CHECK(test::same_bits(a.img, b.img));
    CHECK(a.stats.rays == b.stats.rays);
}

} // namespace

TEST_CASE("light scene files match the milestone apps' scenes") {
    SUBCASE("simple light") { check_same_scene(make_simple_light, "simple_light.txt"); }
    SUBCASE("empty Cornell box") { check_same_scene([] { return make_cornell_box(false); }, "cornell_empty.txt"); }
    SUBCASE("Cornell box with two boxes") { check_same_scene([] { return make_cornell_box(true); }, "cornell_box.txt"); }
    SUBCASE("book 3's final Cornell box") { check_same_scene(make_cornell_final, "cornell_final.txt"); }
    SUBCASE("sphere room") { check_same_scene(make_sphere_room, "sphere_room.txt"); }
}

TEST_CASE("scene file: quad, box, lights, transforms and background") {
    std::istringstream in("background 0.1 0.2 0.3\n"
                          "quad 0 0 0  1 0 0  0 1 0 diffuse_light 2 3 4 0 0\n"
                          "quad 0 0 0  1 0 0  0 1 0 two_sided_light 1 1 1 0 0 translate 0 0 -1\n"
                          "box 0 0 0  1 2 3 lambertian 0.5 0.5 0.5 0 0 rotate_y 90 translate 10 0 0\n"
                          "point_light 1 2 3  40 50 60\n"
                          "directional_light 0 -2 1  3 2 1\n");
    scene_description s = parse_scene(in, "t.txt");
    REQUIRE(s.cam.background.has_value());
    CHECK(s.cam.background->z() == doctest::Approx(0.3));
    REQUIRE(s.point_lights.size() == 1);
    CHECK(s.point_lights[0].position.y() == 2);
    CHECK(s.point_lights[0].intensity.z() == 60);
    REQUIRE(s.directional_lights.size() == 1);
    CHECK(s.directional_lights[0].direction.y() == -2);
    CHECK(s.directional_lights[0].irradiance.x() == 3);
    REQUIRE(s.world.objects.size() == 3);
    auto light = std::dynamic_pointer_cast<quad>(s.world.objects[0]);
    REQUIRE(light);
    auto emitter = std::dynamic_pointer_cast<diffuse_light>(light->mat());
    REQUIRE(emitter);
    CHECK_FALSE(emitter->two_sided());
    auto moved = std::dynamic_pointer_cast<translate>(s.world.objects[1]);
    REQUIRE(moved);
    CHECK(moved->offset().z() == -1);
    // The box, turned 90 degrees about y (x -> -z, z -> x) and moved by 10 in x: x in [10, 13],
    // z in [-1, 0] (each face's box padded by book 2's 1e-4 at most).
    aabb b = s.world.objects[2]->bounding_box();
    CHECK(std::fabs(b.x.min - 10) < 1e-4);
    CHECK(std::fabs(b.x.max - 13) < 1e-4);
    CHECK(std::fabs(b.z.min + 1) < 1e-4);
    CHECK(std::fabs(b.z.max - 0) < 1e-4);

    // The compiled scene: 2 + 6 quads, two lights on quads, one point light and one directional.
    compiled_scene c = compile_scene(s.world, point3(0, 0, 5), s.point_lights, s.directional_lights);
    CHECK(c.set<quad_set>().count == 8);
    CHECK(c.lights.lights.size() == 4);
}

} // namespace test_light_scenes
