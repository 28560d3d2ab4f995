// Metallic-roughness maps (material.h: metal_roughness with a map; scene/surface_coordinates.h:
// textured): the map's blue channel times the metallic factor and its green times the roughness
// factor, per hit. A constant map renders bit for bit what the material with those products as
// its factors renders; a map that changes across a square renders each half as the constant
// material of that half does; the book interface's scatter() follows the map too.

#include <rtweekend/rtweekend.h>
#include <rtweekend/scene/scene_compiler.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <memory>

namespace test_metallic_roughness_map {

using namespace rt;

namespace {

// A square facing +z under a white sky, filling the view, seen from slightly above so that its
// mirror-like parts reflect sky and nothing else.
image render_square(const std::vector<std::shared_ptr<hittable>>& shapes) {
    hittable_list world;
    for (const auto& s : shapes) world.add(s);
    camera cam = test::test_camera(24, 12, 16, 3);
    cam.lookfrom = point3(0, -1, 4);
    cam.lookat = point3(0, 0.5, 0);
    cam.vup = vec3(0, 1, 0);
    cam.vfov = 20;
    return render(cam, world).img;
}

double mean(const image& img, int x0, int x1) {
    double s = 0;
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
        for (int x = x0; x < x1; ++x) {
            const color c = img.pixel(x, y);
            s += c.x() + c.y() + c.z();
            ++n;
        }
    return s / n;
}

} // namespace

TEST_CASE("metallic-roughness map: a constant map is the material with the products as its factors") {
    // Blue 1 (metallic 0.8 x 1), green 0.5 (roughness 0.6 x 0.5 = 0.3).
    auto mapped = std::make_shared<metal_roughness>(std::make_shared<solid_color>(color(0.9, 0.6, 0.3)), 0.8, 0.6,
                                                    std::make_shared<solid_color>(color(0.25, 0.5, 1.0)));
    auto plain = std::make_shared<metal_roughness>(color(0.9, 0.6, 0.3), 0.8, 0.3);
    const image a = render_square({std::make_shared<quad>(point3(-4, -4, 0), vec3(8, 0, 0), vec3(0, 8, 0), mapped)});
    const image b = render_square({std::make_shared<quad>(point3(-4, -4, 0), vec3(8, 0, 0), vec3(0, 8, 0), plain)});
    CHECK(test::same_bits(a, b));
    // The compiled scene keeps the map beside the material, whose base colour became a texture.
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-4, -4, 0), vec3(8, 0, 0), vec3(0, 8, 0), mapped));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 5));
    REQUIRE(scene.metallic_roughness_maps.size() == 1);
    CHECK(scene.metallic_roughness_maps[0].metallic == doctest::Approx(0.8));
    CHECK(scene.metallic_roughness_maps[0].roughness == doctest::Approx(0.6));
    CHECK(scene.materials[0].texture != no_texture);
}

TEST_CASE("metallic-roughness map: two mapped materials of constant colours keep their own colours") {
    // The compiler gives each a constant texture of its base colour (so that textured() reads the
    // map); the second must not be handed the first's.
    auto map = std::make_shared<solid_color>(color(0, 1, 1));
    auto red = std::make_shared<metal_roughness>(std::make_shared<solid_color>(color(0.9, 0.1, 0.1)), 1.0, 0.5, map);
    auto blue = std::make_shared<metal_roughness>(std::make_shared<solid_color>(color(0.1, 0.1, 0.9)), 1.0, 0.5, map);
    hittable_list world;
    world.add(std::make_shared<quad>(point3(-4, -4, 0), vec3(4, 0, 0), vec3(0, 8, 0), red));
    world.add(std::make_shared<quad>(point3(0, -4, 0), vec3(4, 0, 0), vec3(0, 8, 0), blue));
    const compiled_scene scene = compile_scene(world, point3(0, 0, 5));
    REQUIRE(scene.materials.size() == 2);
    const vec3f first = scene.textures.eval(scene.materials[0].texture, 0, 0, vec3(0, 0, 0));
    const vec3f second = scene.textures.eval(scene.materials[1].texture, 0, 0, vec3(0, 0, 0));
    CHECK(first.x + second.x == doctest::Approx(1.0f));
    CHECK(first.z + second.z == doctest::Approx(1.0f));
    CHECK(std::fabs(first.x - second.x) == doctest::Approx(0.8f));
}

TEST_CASE("metallic-roughness map: each half of a square as the material of that half") {
    // Book 2's checker, cell size 1, on the square z = 0.5 that spans x in [-1, 1] and y in
    // [0.1, 0.9]: cells by the parity of floor(x) + floor(y) + floor(z), so x < 0 is an odd cell,
    // black here (metallic 0, roughness 0: the coat a mirror over the diffuse base), and x >= 0 an
    // even one, (0, 1, 1) (metallic 1, roughness 1: a rough metal).
    auto map = std::make_shared<checker_texture>(1.0, color(0, 1, 1), color(0, 0, 0));
    const color base(0.7, 0.5, 0.3);
    CHECK(map->value(0, 0, point3(-0.5, 0.5, 0.5)).z() == 0);
    CHECK(map->value(0, 0, point3(0.5, 0.5, 0.5)).z() == 1);
    auto mapped = std::make_shared<metal_roughness>(std::make_shared<solid_color>(base), 1.0, 1.0, map);
    const image a = render_square({std::make_shared<quad>(point3(-1, 0.1, 0.5), vec3(2, 0, 0), vec3(0, 0.8, 0), mapped)});
    const image b = render_square(
        {std::make_shared<quad>(point3(-1, 0.1, 0.5), vec3(1, 0, 0), vec3(0, 0.8, 0), std::make_shared<metal_roughness>(base, 0.0, 0.0)),
         std::make_shared<quad>(point3(0, 0.1, 0.5), vec3(1, 0, 0), vec3(0, 0.8, 0), std::make_shared<metal_roughness>(base, 1.0, 1.0))});
    // Both halves, away from the seam, agree within 1e-4.
    const int w = a.width();
    CHECK(mean(a, 0, w / 2 - 1) == doctest::Approx(mean(b, 0, w / 2 - 1)).epsilon(1e-4));
    CHECK(mean(a, w / 2 + 1, w) == doctest::Approx(mean(b, w / 2 + 1, w)).epsilon(1e-4));
    // And the halves differ: the map is read per hit, not once per material.
    CHECK(std::fabs(mean(a, 0, w / 2 - 1) - mean(a, w / 2 + 1, w)) > 0.05);
}

TEST_CASE("metallic-roughness map: the book interface's scatter() follows the map") {
    // Metallic 1 and roughness 0 where the map says so (blue 1, green 0): nearly every scattered
    // ray is the mirror reflection (a few are drawn from the lobe for the metal's multiple
    // scattering); with the factors alone, roughness 1, few are.
    auto map = std::make_shared<solid_color>(color(0, 0, 1));
    auto mapped = std::make_shared<metal_roughness>(std::make_shared<solid_color>(color(1, 1, 1)), 1.0, 1.0, map);
    auto unmapped = std::make_shared<metal_roughness>(color(1, 1, 1), 1.0, 1.0);
    auto mirror_like = [](const std::shared_ptr<material>& m) {
        hit_record rec;
        rec.p = point3(0, 0, 0);
        rec.normal = vec3(0, 0, 1);
        rec.front_face = true;
        rec.mat = m;
        const ray in(point3(-1, 0, 1), vec3(1, 0, -1));
        int count = 0;
        for (int i = 0; i < 256; ++i) {
            color attenuation;
            ray scattered;
            if (m->scatter(in, rec, attenuation, scattered) &&
                dot(unit_vector(scattered.direction()), unit_vector(vec3(1, 0, 1))) > 0.999)
                ++count;
        }
        return count;
    };
    CHECK(mirror_like(mapped) >= 240);
    CHECK(mirror_like(unmapped) <= 32);
}

} // namespace test_metallic_roughness_map
