// make_cover_scene() (apps/cover_scene.h) against tests/data/rtiow_cover.txt, the scene exported
// from the book's own program (glibc rand(), unseeded = srand(1)). Matching it sphere for sphere
// shows that random_double() and vec3::random() reproduce the book's draws, in the book's order.

#include "cover_scene.h"

#include <rtweekend/io/scene_file.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

namespace test_cover_scene {

using namespace rt;

namespace {

// The file prints 17 significant digits, so a faithful reconstruction agrees to ~1e-16; allow 1e-12.
bool close(double a, double b) {
    return std::fabs(a - b) <= 1e-12 * std::max(std::fabs(a), std::fabs(b)) || a == b;
}

bool close3(const vec3& a, const vec3& b) { return close(a.x(), b.x()) && close(a.y(), b.y()) && close(a.z(), b.z()); }

std::string kind(const material* m) {
    if (dynamic_cast<const lambertian*>(m)) return "lambertian";
    if (dynamic_cast<const metal*>(m)) return "metal";
    if (dynamic_cast<const dielectric*>(m)) return "dielectric";
    return "other";
}

} // namespace

TEST_CASE("make_cover_scene reproduces the book's cover scene exactly (glibc rand, srand(1))") {
    scene_description file = load_scene(std::string(RTWEEKEND_TEST_DATA) + "/rtiow_cover.txt");

    std::srand(1);
    hittable_list world = make_cover_scene();

    REQUIRE(world.objects.size() == file.world.objects.size());
    REQUIRE(world.objects.size() == 487);

    int mismatches = 0;
    for (size_t i = 0; i < world.objects.size(); ++i) {
        CAPTURE(i);
        auto got = std::dynamic_pointer_cast<sphere>(world.objects[i]);
        auto want = std::dynamic_pointer_cast<sphere>(file.world.objects[i]);
        REQUIRE(got);
        REQUIRE(want);
        bool ok = close3(got->center(), want->center()) && close(got->radius(), want->radius());
        const material* gm = got->mat().get();
        const material* wm = want->mat().get();
        ok = ok && kind(gm) == kind(wm);
        if (ok && kind(gm) == "lambertian") {
            ok = close3(static_cast<const lambertian*>(gm)->albedo(), static_cast<const lambertian*>(wm)->albedo());
        } else if (ok && kind(gm) == "metal") {
            auto* g = static_cast<const metal*>(gm);
            auto* w = static_cast<const metal*>(wm);
            ok = close3(g->albedo(), w->albedo()) && close(g->fuzz(), w->fuzz());
        } else if (ok && kind(gm) == "dielectric") {
            ok = close(static_cast<const dielectric*>(gm)->refraction_index(),
                       static_cast<const dielectric*>(wm)->refraction_index());
        }
        if (!ok && mismatches++ < 5) {
            FAIL_CHECK("sphere " << i << ": got centre " << got->center() << " r " << got->radius() << " "
                                 << kind(gm) << ", file has " << want->center() << " r " << want->radius()
                                 << " " << kind(wm));
        }
    }
    CHECK(mismatches == 0);
}

TEST_CASE("make_cover_camera is the book's cover camera") {
    camera cam = make_cover_camera();
    CHECK(cam.lookfrom.x() == 13);
    CHECK(cam.lookfrom.y() == 2);
    CHECK(cam.lookfrom.z() == 3);
    CHECK(cam.vfov == 20);
    CHECK(cam.defocus_angle == 0.6);
    CHECK(cam.focus_dist == 10);
    CHECK(cam.image_width == 1200);
    CHECK(cam.height() == 675); // 1200 * 9 / 16
    CHECK(cam.max_depth == 50);
}

} // namespace test_cover_scene
