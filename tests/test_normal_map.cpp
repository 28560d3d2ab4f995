// Normal maps (material.h: normal_mapped; scene/surface_coordinates.h: shading_normal_at): a flat
// square with a constant tangent-space normal shades with that normal turned into the world by
// its dp/du, dp/dv and normal, worked by hand: as the guides see it, mirrored, scaled, inside a
// rotated instance, and as the light a point lamp gives it (albedo / pi I cos / d^2 with the
// mapped normal's cosine). A sphere (no texture frame) keeps its own normal. Bump maps
// (bump_mapped): a height ramp h = a u + b v displaced by `scale` tilts the square's normal to
// cross(dp/du + scale a N, dp/dv + scale b N), worked by hand.

#include <rtweekend/render/guides.h>
#include <rtweekend/rtweekend.h>
#include <rtweekend/scene/scene_compiler.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <memory>

namespace test_normal_map {

using namespace rt;

namespace {

// The square [-1, 1]^2 at z = 0 facing +z, u along +x (or -x when mirrored), v along +y.
std::shared_ptr<triangle_mesh> square(std::shared_ptr<material> mat, bool mirrored = false) {
    auto mesh = std::make_shared<triangle_mesh>();
    mesh->positions = {point3(-1, -1, 0), point3(1, -1, 0), point3(1, 1, 0), point3(-1, 1, 0)};
    const double u0 = mirrored ? 1 : 0, u1 = mirrored ? 0 : 1;
    mesh->uvs = {{u0, 0}, {u1, 0}, {u1, 1}, {u0, 1}};
    mesh->faces = {{0, 1, 2}, {0, 2, 3}};
    mesh->face_uvs = mesh->faces;
    mesh->mat = std::move(mat);
    return mesh;
}

// A texel whose normal is (sin 30, 0, cos 30): tilted 30 degrees towards +u.
std::shared_ptr<texture> tilted() { return std::make_shared<solid_color>(0.5 + 0.25, 0.5, 0.5 + 0.5 * std::sqrt(0.75)); }

// The normal guide of the pixel whose ray goes from `from` through `at` (a 5 x 5 image's centre).
color normal_seen(const hittable_list& world, const point3& from, const point3& at, double vfov) {
    camera cam = test::test_camera(5, 5, 1, 4); // pixel (2, 2): the ray through the centre
    cam.lookfrom = from;
    cam.lookat = at;
    cam.vfov = vfov;
    const camera_frame frame = cam.frame();
    const compiled_scene scene = compile_scene(world, frame.position, {});
    render_settings s;
    s.samples_per_pixel = 1;
    s.threads = 1;
    return render_guides(scene, frame, cam.sky(), s).normal.pixel(2, 2);
}

color centre_normal(const hittable_list& world) { return normal_seen(world, point3(0, 0, 10), point3(0, 0, 0), 5); }

} // namespace

TEST_CASE("normal maps: a constant texel turns a square's shading normal as worked by hand") {
    const auto grey = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    const double c30 = std::sqrt(0.75);
    { // T = +x, B = +y, N = +z: the texel's normal itself.
        hittable_list world;
        world.add(square(std::make_shared<normal_mapped>(grey, tilted())));
        const color n = centre_normal(world);
        CHECK(n.x() == doctest::Approx(0.5).epsilon(1e-5));
        CHECK(n.y() == doctest::Approx(0).epsilon(1e-5));
        CHECK(n.z() == doctest::Approx(c30).epsilon(1e-5));
    }
    { // u running along -x: the tilt turns with it.
        hittable_list world;
        world.add(square(std::make_shared<normal_mapped>(grey, tilted()), true));
        const color n = centre_normal(world);
        CHECK(n.x() == doctest::Approx(-0.5).epsilon(1e-5));
        CHECK(n.z() == doctest::Approx(c30).epsilon(1e-5));
    }
    { // scale 0: x and y of the texel go, the normal is the surface's.
        hittable_list world;
        world.add(square(std::make_shared<normal_mapped>(grey, tilted(), 0.0)));
        const color n = centre_normal(world);
        CHECK(n.x() == doctest::Approx(0).epsilon(1e-6));
        CHECK(n.z() == doctest::Approx(1));
    }
    { // Inside an instance turned 90 degrees about z (x -> y), placed twice: T = +y.
        auto mesh = square(std::make_shared<normal_mapped>(grey, tilted()));
        hittable_list world;
        world.add(std::make_shared<rotate>(mesh, vec3(0, 0, 1), 90));
        world.add(std::make_shared<translate>(std::make_shared<rotate>(mesh, vec3(0, 0, 1), 90), vec3(5, 0, 0)));
        const color n = centre_normal(world);
        CHECK(n.x() == doctest::Approx(0).epsilon(1e-5));
        CHECK(n.y() == doctest::Approx(0.5).epsilon(1e-5));
        CHECK(n.z() == doctest::Approx(c30).epsilon(1e-5));
    }
    { // A sphere has no texture frame here: its own normal, (0, 0, 1) where the camera looks.
        hittable_list world;
        world.add(std::make_shared<sphere>(point3(0, 0, 0), 1.0, std::make_shared<normal_mapped>(grey, tilted())));
        const color n = centre_normal(world);
        CHECK(n.z() == doctest::Approx(1).epsilon(1e-4));
    }
}

TEST_CASE("normal maps: a point lamp straight above lights the square by the mapped normal's cosine") {
    // Lambertian albedo 0.5, a lamp of intensity 4 at height 2 over the centre, no sky: the
    // radiance towards the camera is (0.5 / pi) 4 cos / 4 with cos = cos 30 deg for the mapped
    // normal, 1 for the plain square.
    const auto grey = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    auto radiance = [&](std::shared_ptr<material> m) {
        hittable_list world;
        world.add(square(std::move(m)));
        camera cam = test::test_camera(3, 3, 4, 2);
        cam.lookfrom = point3(0, 0.001, 30);
        cam.lookat = point3(0, 0, 0);
        cam.vfov = 0.05;
        cam.background = color(0, 0, 0);
        return render(cam, world, {point_light{point3(0, 0, 2), color(4, 4, 4)}}).img.pixel(1, 1).x();
    };
    CHECK(radiance(grey) == doctest::Approx(0.5 / pi).epsilon(1e-3));
    CHECK(radiance(std::make_shared<normal_mapped>(grey, tilted())) == doctest::Approx(0.5 / pi * std::sqrt(0.75)).epsilon(1e-3));
}

namespace {
// Heights h = a u + b v (a user texture: the renderer asks it at the (u, v) it chooses).
class ramp : public texture {
  public:
    ramp(double a, double b) : a_(a), b_(b) {}
    color value(double u, double v, const point3&) const override {
        const double h = a_ * u + b_ * v;
        return color(h, h, h);
    }

  private:
    double a_, b_;
};
} // namespace

TEST_CASE("bump maps: a height ramp tilts a square's normal as worked by hand") {
    // The square: dp/du = (2, 0, 0), dp/dv = (0, 2, 0), N = +z. Heights 2 u - v, scale 0.5: the
    // displaced tangents (2, 0, 1) and (0, 2, -0.5), whose cross product is (-2, 1, 4) / sqrt 21.
    const auto grey = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    const auto heights = std::make_shared<ramp>(2.0, -1.0);
    const double r = std::sqrt(21.0);
    {
        hittable_list world;
        world.add(square(std::make_shared<bump_mapped>(grey, heights, 0.5)));
        const color n = centre_normal(world);
        CHECK(n.x() == doctest::Approx(-2 / r).epsilon(1e-4));
        CHECK(n.y() == doctest::Approx(1 / r).epsilon(1e-4));
        CHECK(n.z() == doctest::Approx(4 / r).epsilon(1e-4));
    }
    { // u along -x: the heights rise towards -x, the normal leans to +x.
        hittable_list world;
        world.add(square(std::make_shared<bump_mapped>(grey, heights, 0.5), true));
        const color n = centre_normal(world);
        CHECK(n.x() == doctest::Approx(2 / r).epsilon(1e-4));
        CHECK(n.y() == doctest::Approx(1 / r).epsilon(1e-4));
        CHECK(n.z() == doctest::Approx(4 / r).epsilon(1e-4));
    }
    { // Constant heights, or scale 0: the surface's own normal.
        hittable_list world;
        world.add(square(std::make_shared<bump_mapped>(grey, std::make_shared<solid_color>(0.7, 0.7, 0.7), 3.0)));
        CHECK(centre_normal(world).z() == doctest::Approx(1));
        hittable_list flat;
        flat.add(square(std::make_shared<bump_mapped>(grey, heights, 0.0)));
        CHECK(centre_normal(flat).z() == doctest::Approx(1));
    }
    { // A lamp straight above: (0.5 / pi) I cos / d^2 with cos = 4 / sqrt 21.
        hittable_list world;
        world.add(square(std::make_shared<bump_mapped>(grey, heights, 0.5)));
        camera cam = test::test_camera(3, 3, 4, 2);
        cam.lookfrom = point3(0, 0.001, 30);
        cam.lookat = point3(0, 0, 0);
        cam.vfov = 0.05;
        cam.background = color(0, 0, 0);
        const double lit = render(cam, world, {point_light{point3(0, 0, 2), color(4, 4, 4)}}).img.pixel(1, 1).x();
        CHECK(lit == doctest::Approx(0.5 / pi * 4 / r).epsilon(1e-3));
    }
    // Refusals: one line each.
    hittable_list world;
    world.add(square(std::make_shared<bump_mapped>(grey, nullptr, 1.0)));
    camera cam = test::test_camera(2, 2, 1, 1);
    test::check_scene_error([&] { render(cam, world); }, {"bump_mapped material has no height map"});
}

TEST_CASE("normal maps on a smooth mesh: the frame turns smoothly across its triangles") {
    // The square [-1, 1]^2 facing +z in two triangles, smooth shading (normals +z), texture
    // coordinates (0, 0), (1, 0), (1, 1.5), (0, 1) at its corners (-1, -1), (1, -1), (1, 1),
    // (-1, 1): the lower triangle's dp/du is (2, 0, 0), the upper's (2, -1, 0). Averaged at the
    // corners (equal areas), the two shared corners' dp/du is (2, -0.5, 0), so on the diagonal
    // between them the frame's T is (2, -0.5, 0) / |...| from both sides, and the constant texel
    // tilted 30 degrees towards +u gives 0.5 T + cos 30 N there. Each triangle's own dp/du would
    // give (0.5, 0, 0.866) below the diagonal and (0.447, -0.224, 0.866) above it.
    auto mesh = std::make_shared<triangle_mesh>();
    mesh->positions = {point3(-1, -1, 0), point3(1, -1, 0), point3(1, 1, 0), point3(-1, 1, 0)};
    mesh->uvs = {{0, 0}, {1, 0}, {1, 1.5}, {0, 1}};
    mesh->normals = {vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1)};
    mesh->faces = {{0, 1, 2}, {0, 2, 3}};
    mesh->face_uvs = mesh->faces;
    mesh->face_normals = mesh->faces;
    mesh->smooth_shading = true;
    mesh->mat = std::make_shared<normal_mapped>(std::make_shared<lambertian>(color(0.5, 0.5, 0.5)), tilted());
    hittable_list world;
    world.add(mesh);
    auto normal_at = [&](double x, double y) { return normal_seen(world, point3(x, y, 10), point3(x, y, 0), 0.01); };
    const double len = std::sqrt(4.25), c30 = std::sqrt(0.75);
    for (const auto& [x, y] : {std::pair{0.01, -0.01}, std::pair{-0.01, 0.01}}) {
        CAPTURE(x);
        const color n = normal_at(x, y);
        CHECK(n.x() == doctest::Approx(0.5 * 2 / len).epsilon(0.01));
        CHECK(n.y() == doctest::Approx(0.5 * -0.5 / len).epsilon(0.03));
        CHECK(n.z() == doctest::Approx(c30).epsilon(1e-3));
    }
}

} // namespace test_normal_map
