// Scene files (rtweekend/io/scene_file.h): the cover scene file, and one scene_error per kind of
// malformed line, each "name:LINE: problem".

#include <rtweekend/io/scene_file.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace test_scene_io {

using namespace rt;

namespace {

const std::string cover_path = std::string(RTWEEKEND_TEST_DATA) + "/rtiow_cover.txt";

scene_description parse(const std::string& text, const std::string& name = "test.txt") {
    std::istringstream in(text);
    return parse_scene(in, name);
}

// Parsing `text` must fail with a one-line scene_error starting "test.txt:<line>: " and
// containing each fragment.
void check_fails(const std::string& text, int line, std::initializer_list<std::string> fragments) {
    CAPTURE(text);
    bool threw = false;
    try {
        parse(text);
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        std::string prefix = "test.txt:" + std::to_string(line) + ": ";
        CHECK(msg.rfind(prefix, 0) == 0);
        CHECK(msg.find('\n') == std::string::npos);
        for (const std::string& f : fragments) {
            CAPTURE(f);
            CHECK(msg.find(f) != std::string::npos);
        }
    }
    CHECK(threw);
}

const sphere& sphere_at(const scene_description& s, size_t i) {
    auto p = std::dynamic_pointer_cast<sphere>(s.world.objects.at(i));
    REQUIRE(p);
    return *p;
}

const std::string good_sphere = "sphere 0 0 -1 0.5 lambertian 0.1 0.2 0.5 0 0";

} // namespace

TEST_CASE("load_scene: the book-1 cover scene file") {
    scene_description s = load_scene(cover_path);

    // The book's cover: ground + 22 x 22 grid minus the spheres too close to (4, 0.2, 0), + 3 big
    // ones = 487 spheres in this draw (counted in the file: 394 lambertian, 64 metal, 29 glass).
    REQUIRE(s.world.objects.size() == 487);
    int lambertians = 0, metals = 0, dielectrics = 0, others = 0;
    for (const auto& obj : s.world.objects) {
        auto sp = std::dynamic_pointer_cast<sphere>(obj);
        REQUIRE(sp);
        const material* m = sp->mat().get();
        if (dynamic_cast<const lambertian*>(m)) ++lambertians;
        else if (dynamic_cast<const metal*>(m)) ++metals;
        else if (dynamic_cast<const dielectric*>(m)) ++dielectrics;
        else ++others;
    }
    CHECK(lambertians == 394);
    CHECK(metals == 64);
    CHECK(dielectrics == 29);
    CHECK(others == 0);

    // The book's camera for the cover (section 14.1), at the file's 400 x 225.
    const camera& c = s.cam;
    CHECK(c.lookfrom.x() == 13);
    CHECK(c.lookfrom.y() == 2);
    CHECK(c.lookfrom.z() == 3);
    CHECK(c.lookat.x() == 0);
    CHECK(c.lookat.y() == 0);
    CHECK(c.lookat.z() == 0);
    CHECK(c.vup.y() == 1);
    CHECK(c.vfov == 20);
    CHECK(c.image_width == 400);
    CHECK(c.image_height == 225);
    CHECK(c.height() == 225);
    CHECK(c.aspect_ratio == 16.0 / 9.0); // 1.7777777777777777 is 16/9 rounded to 17 digits
    CHECK(c.defocus_angle == 0.6);       // 0.59999999999999998 is 0.6 printed to 17 digits
    CHECK(c.focus_dist == 10);
    CHECK(c.samples_per_pixel == 10);
    CHECK(c.max_depth == 50);
    CHECK_FALSE(c.background.has_value());
    CHECK_NOTHROW((void)c.frame());

    // The ground, and the three big spheres of the book's listing (last in the world list).
    const sphere& ground = sphere_at(s, 0);
    CHECK(ground.center().y() == -1000);
    CHECK(ground.radius() == 1000);
    auto* gm = dynamic_cast<const lambertian*>(ground.mat().get());
    REQUIRE(gm);
    CHECK(gm->albedo().x() == 0.5);

    const sphere& glass = sphere_at(s, 484);
    CHECK(glass.center().y() == 1);
    CHECK(glass.radius() == 1);
    auto* gl = dynamic_cast<const dielectric*>(glass.mat().get());
    REQUIRE(gl);
    CHECK(gl->refraction_index() == 1.5);

    const sphere& brown = sphere_at(s, 485);
    CHECK(brown.center().x() == -4);
    auto* br = dynamic_cast<const lambertian*>(brown.mat().get());
    REQUIRE(br);
    CHECK(br->albedo().x() == 0.4);
    CHECK(br->albedo().y() == 0.2);
    CHECK(br->albedo().z() == 0.1);

    const sphere& mirror = sphere_at(s, 486);
    CHECK(mirror.center().x() == 4);
    auto* mm = dynamic_cast<const metal*>(mirror.mat().get());
    REQUIRE(mm);
    CHECK(mm->albedo().x() == 0.7);
    CHECK(mm->albedo().y() == 0.6);
    CHECK(mm->albedo().z() == 0.5);
    CHECK(mm->fuzz() == 0);

    // Every small sphere has radius 0.2 at height 0.2, in the grid cell of its index:
    // centre x in [a, a + 0.9), z in [b, b + 0.9) for integers a, b in [-11, 10].
    for (size_t i = 1; i < 484; ++i) {
        const sphere& sp = sphere_at(s, i);
        CHECK(sp.radius() == 0.2);
        CHECK(sp.center().y() == 0.2);
        CHECK(sp.center().x() >= -11);
        CHECK(sp.center().x() < 10.9);
        CHECK(sp.center().x() - std::floor(sp.center().x()) < 0.9);
        CHECK(sp.center().z() - std::floor(sp.center().z()) < 0.9);
        // The book skips spheres within 0.9 of (4, 0.2, 0).
        CHECK((sp.center() - point3(4, 0.2, 0)).length() > 0.9);
    }
}

TEST_CASE("parse_scene: comments, blank lines, inline comments and CRLF are ignored") {
    scene_description s = parse("# a scene\n"
                                "\n"
                                "   \t  \n"
                                "camera lookfrom 1 2 3   # where we stand\n"
                                "camera vfov 45\n"
                                "# sphere 0 0 0 1 lambertian 1 1 1 0 0  (commented out)\n"
                                "sphere 0 0 -1 0.5 metal 0.8 0.6 0.2 0.25 0 # a metal ball\r\n"
                                "camera image_width 64\r\n"
                                "camera seed 17\n"
                                "camera sampler stratified\n"
                                "camera filter gaussian:0.4\n"
                                "camera estimator mixture\n"
                                "camera background 0.1 0.2 0.3\n");
    REQUIRE(s.world.objects.size() == 1);
    CHECK(s.cam.lookfrom.z() == 3);
    CHECK(s.cam.vfov == 45);
    CHECK(s.cam.image_width == 64);
    CHECK(s.cam.settings.seed == 17);
    CHECK(s.cam.settings.sampler == sampler_kind::stratified);
    CHECK(s.cam.filter.name() == "gaussian:0.4");
    CHECK(s.cam.filter.radius() == doctest::Approx(1.2)); // 3 sigma
    CHECK(s.cam.settings.estimator == path_estimator::mixture);
    REQUIRE(s.cam.background.has_value());
    CHECK(s.cam.background->y() == 0.2);
    const sphere& sp = sphere_at(s, 0);
    CHECK(sp.center().z() == -1);
    CHECK(sp.radius() == 0.5);
    auto* m = dynamic_cast<const metal*>(sp.mat().get());
    REQUIRE(m);
    CHECK(m->fuzz() == 0.25);
    CHECK(m->albedo().x() == 0.8);

}

TEST_CASE("parse_scene: text without a directive is refused as load_scene refuses an empty file") {
    // Nothing, blank lines, comments, CRLF: one error line naming the stream, with the words of
    // load_scene's error (tests/test_fuzz_inputs.cpp checks the file path says the same).
    for (const char* text : {"", "\n\n   \t \n", "# nothing\n\n# here\n", "# a comment\r\n\r\n", "   # indented\n"}) {
        CAPTURE(text);
        std::istringstream in(text);
        bool threw = false;
        try {
            parse_scene(in, "inline.txt");
        } catch (const scene_error& e) {
            threw = true;
            CHECK(std::string(e.what()) == "inline.txt: scene file is empty (no directives)");
        }
        CHECK(threw);
    }
    // One directive is enough to parse (an empty world is load_scene's own error, not the stream's).
    scene_description camera_only = parse("# a camera and nothing else\ncamera image_width 64\n");
    CHECK(camera_only.world.objects.empty());
    CHECK(camera_only.cam.image_width == 64);
}

TEST_CASE("parse_scene: every malformed line is 'name:LINE: problem'") {
    // Line numbers count every physical line, comments and blank lines included.
    check_fails("# header\n\nplane 0 1 0\n", 3, {"unknown directive", "'plane'"});
    check_fails("camera zoom 3\n", 1, {"unknown camera key", "'zoom'"});
    check_fails("camera\n", 1, {"camera"});

    // Wrong field counts.
    check_fails(good_sphere + "\nsphere 0 0 -1 0.5 lambertian 0.1 0.2 0.5 0\n", 2, {"expected ior"});
    check_fails("sphere 0 0 -1 0.5 lambertian 0.1 0.2 0.5 0 0 7\n", 1, {"unexpected '7'"});
    check_fails("sphere 0 0 -1 0.5 lambertian 0.1 0.2 0.5 0\n", 1, {"expected ior"});
    check_fails("sphere 0 0 -1 0.5 lambertian 0.1 0.2 0.5 0 0 rotate_y\n", 1, {"rotate_y needs an angle"});
    check_fails("sphere 0 0 -1 0.5 lambertian 0.1 0.2 0.5 0 0 translate 1 2\n", 1, {"translate needs x y z"});
    check_fails("quad 0 0 0 1 0 0 2 0 0 lambertian 0.5 0.5 0.5 0 0\n", 1, {"quad has zero area"});
    check_fails("box 0 0 0 1 0 1 lambertian 0.5 0.5 0.5 0 0\n", 1, {"box corners must differ"});
    check_fails("point_light 0 1 0 1 1\n", 1, {"point_light x y z r g b"});
    check_fails("directional_light 0 -1 0 1 1\n", 1, {"directional_light dx dy dz r g b"});
    check_fails("directional_light 0 0 0 1 1 1\n", 1, {"directional light direction must not be zero"});
    check_fails("directional_light 1e300 1e300 0 1 1 1\n", 1, {"too long"});
    check_fails("directional_light 0 -1 0 1 -1 1\n", 1, {"irradiance must be non-negative"});
    check_fails("point_light 0 1 0 1 -1 1\n", 1, {"intensity must be non-negative"});
    check_fails("background 0 -1 0\n", 1, {"background must be non-negative"});
    check_fails("sphere 0 0 -1 0.5 light 1 1 1 0 0\n", 1, {"unknown material 'light'"});
    check_fails("camera lookfrom 1 2\n", 1, {"lookfrom", "got 4"});
    check_fails("camera vfov 20 30\n", 1, {"vfov", "got 4"});
    check_fails("camera image_width\n", 1, {"image_width", "got 2"});

    // Non-numeric fields.
    check_fails("sphere 0 abc -1 0.5 lambertian 0.1 0.2 0.5 0 0\n", 1, {"'abc'", "not a number"});
    check_fails("sphere 0 0 -1 0.5x lambertian 0.1 0.2 0.5 0 0\n", 1, {"'0.5x'", "not a number"});
    check_fails("camera lookat 0 zero 0\n", 1, {"'zero'", "not a number"});
    check_fails("camera image_width 4x0\n", 1, {"'4x0'", "not an integer"});
    check_fails("camera samples_per_pixel 2.5\n", 1, {"'2.5'", "not an integer"});

    // NaN and infinite fields.
    check_fails("sphere nan 0 -1 0.5 lambertian 0.1 0.2 0.5 0 0\n", 1, {"'nan'", "finite"});
    check_fails("sphere 0 0 -1 inf lambertian 0.1 0.2 0.5 0 0\n", 1, {"'inf'", "finite"});
    check_fails("sphere 0 0 -1 0.5 lambertian 0.1 -infinity 0.5 0 0\n", 1, {"'-infinity'", "finite"});
    check_fails("sphere 0 0 1e999 0.5 lambertian 0.1 0.2 0.5 0 0\n", 1, {"'1e999'", "beyond the range of a double"});
    check_fails("camera focus_dist NaN\n", 1, {"'NaN'", "finite"});

    // A token quoted in an error is cut to 40 characters and its length given: a 100,000-digit
    // "number" gave a 100,000-character line.
    const std::string long_token = std::string(100000, '7') + "x";
    check_fails("sphere 0 0 -1 " + long_token + " lambertian 0.1 0.2 0.5 0 0\n", 1,
                {"'7777777777777777777777777777777777777777... (100001 characters)' is not a number"});
    try {
        parse("sphere 0 0 -1 " + long_token + " lambertian 0.1 0.2 0.5 0 0\n");
    } catch (const scene_error& e) {
        CHECK(std::string(e.what()).size() < 150);
    }
    // Numbers in messages: nine significant digits, not std::to_string's six decimals (1e308 came
    // out as 309 digits and ".000000"; 1e-7 as "0.000000").
    CHECK(number_text(1e308) == "1e+308");
    CHECK(number_text(1e-7) == "1e-07");
    CHECK(number_text(-2.5) == "-2.5");
    CHECK(number_text(0.1) == "0.1");
    CHECK(number_text(1.0 / 3.0) == "0.333333333");
    // An underflow is a number: 1e-320 rounds to a subnormal double, not "not a finite number".
    CHECK_NOTHROW(parse("sphere 0 0 -1 0.5 lambertian 1e-320 0.2 0.5 0 0\n"));

    // Radii.
    check_fails("sphere 0 0 -1 -0.5 lambertian 0.1 0.2 0.5 0 0\n", 1, {"radius", "positive", "-0.5"});
    check_fails("sphere 0 0 -1 0 lambertian 0.1 0.2 0.5 0 0\n", 1, {"radius", "positive"});

    // Materials.
    check_fails("sphere 0 0 -1 0.5 velvet 0.1 0.2 0.5 0 0\n", 1, {"unknown material", "'velvet'"});
    check_fails("sphere 0 0 -1 0.5 lambertian 0.1 -0.2 0.5 0 0\n", 1, {"albedo", "non-negative"});
    check_fails("sphere 0 0 -1 0.5 metal -0.1 0.2 0.5 0 0\n", 1, {"albedo", "non-negative"});
    check_fails("sphere 0 0 -1 0.5 metal 0.1 0.2 0.5 -0.3 0\n", 1, {"fuzz", "non-negative", "-0.3"});
    check_fails("sphere 0 0 -1 0.5 dielectric 1 1 1 0 0\n", 1, {"ior", "positive"});
    check_fails("sphere 0 0 -1 0.5 dielectric 1 1 1 0 -1.5\n", 1, {"ior", "positive", "-1.5"});

    // Camera values out of range.
    check_fails("camera vfov 0\n", 1, {"vfov"});
    check_fails("camera vfov_deg 180\n", 1, {"vfov"});
    check_fails("camera focus_dist 0\n", 1, {"focus_dist", "positive"});
    check_fails("camera defocus_angle -1\n", 1, {"defocus_angle"});
    check_fails("camera aspect_ratio -1.5\n", 1, {"aspect_ratio", "positive"});
    check_fails("camera image_width 0\n", 1, {"image_width", "out of range"});
    check_fails("camera max_depth -3\n", 1, {"max_depth", "out of range"});
    check_fails("camera seed -1\n", 1, {"seed", "out of range"});
    check_fails("camera background 0.1 -0.2 0.3\n", 1, {"background", "non-negative"});
    check_fails("camera sampler halton\n", 1, {"sampler", "'halton'"});
    check_fails("camera filter lanczos\n", 1, {"unknown filter 'lanczos'"});
    check_fails("camera estimator\n", 1, {"camera estimator"});

    // The error names the right line when it comes after valid content.
    check_fails(good_sphere + "\n" + good_sphere + "\n# c\n" + "sphere 0 0 -1 0.5 velvet 0.1 0.2 0.5 0 0\n", 4,
                {"'velvet'"});
}

TEST_CASE("load_scene: a missing file is a scene_error naming it") {
    const std::string missing = std::string(RTWEEKEND_TEST_DATA) + "/no-such-scene.txt";
    bool threw = false;
    try {
        load_scene(missing);
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.rfind(missing + ":", 0) == 0);
        CHECK(msg.find("cannot open") != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
    CHECK(threw);
}

TEST_CASE("load_scene: errors in a file carry the file's path and line") {
    test::scratch_dir dir("scene_io");
    const std::string path = dir.write("scene.txt", "camera vfov 20\n"
                                                    "sphere 0 0 0 -1 lambertian 1 1 1 0 0\n");
    bool threw = false;
    try {
        load_scene(path);
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.rfind(path + ":2: ", 0) == 0);
        CHECK(msg.find("radius") != std::string::npos);
    }
    CHECK(threw);
}

TEST_CASE("parse_scene: conductor and glass materials (exact Fresnel)") {
    scene_description s = parse("sphere 0 0 -1 0.5 conductor 1 0.8 0.5 0.2 3.5\n"
                                "sphere 1 0 -1 0.5 glass 0 0.5 2 0 1.5\n"
                                "triangle 0 0 0 1 0 0 0 1 0 conductor 1 1 1 1.5 0\n"
                                "sphere 2 0 -1 0.5 dielectric 1 1 1 0 1.5\n");
    REQUIRE(s.world.objects.size() == 4);
    auto same = [](const color& a, const color& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); };
    auto gold = std::dynamic_pointer_cast<conductor>(sphere_at(s, 0).mat());
    REQUIRE(gold);
    CHECK(same(gold->n(), color(0.2, 0.2, 0.2)));
    CHECK(same(gold->k(), color(3.5, 3.5, 3.5)));
    CHECK(same(gold->tint(), color(1, 0.8, 0.5)));
    auto glass = std::dynamic_pointer_cast<dielectric>(sphere_at(s, 1).mat());
    REQUIRE(glass);
    CHECK(glass->exact_fresnel());
    CHECK(glass->refraction_index() == 1.5);
    CHECK(same(glass->absorption(), color(0, 0.5, 2)));
    auto tri = std::dynamic_pointer_cast<triangle>(s.world.objects.at(2));
    REQUIRE(tri);
    REQUIRE(std::dynamic_pointer_cast<conductor>(tri->mat()));
    // The book's dielectric keeps its meaning: Schlick, rgb ignored.
    auto book = std::dynamic_pointer_cast<dielectric>(sphere_at(s, 3).mat());
    REQUIRE(book);
    CHECK(!book->exact_fresnel());
}

TEST_CASE("parse_scene: malformed conductor and glass lines are 'name:LINE: problem'") {
    check_fails("sphere 0 0 -1 0.5 conductor 1 1 1 0 3\n", 1, {"conductor n", "positive", "got 0"});
    check_fails("sphere 0 0 -1 0.5 conductor 1 1 1 -0.2 3\n", 1, {"conductor n", "positive", "-0.2"});
    check_fails("sphere 0 0 -1 0.5 conductor 1 1 1 0.2 -3\n", 1, {"conductor k", "non-negative", "-3"});
    check_fails("sphere 0 0 -1 0.5 conductor 1 -1 1 0.2 3\n", 1, {"conductor tint", "non-negative"});
    check_fails("sphere 0 0 -1 0.5 conductor 1 1 1 n 3\n", 1, {"conductor n", "'n'", "not a number"});
    check_fails("sphere 0 0 -1 0.5 conductor 1 1 1 0.2\n", 1, {"expected conductor k"});
    check_fails("sphere 0 0 -1 0.5 glass 0 0 0 0 0\n", 1, {"glass ior", "positive"});
    check_fails("sphere 0 0 -1 0.5 glass 0 -0.5 0 0 1.5\n", 1, {"glass absorption", "non-negative"});
    check_fails("sphere 0 0 -1 0.5 glass 0 0 inf 0 1.5\n", 1, {"'inf'", "finite"});
    check_fails("sphere 0 0 -1 0.5 velvet 0.1 0.2 0.5 0 0\n", 1, {"glass", "conductor"});
}

} // namespace test_scene_io
