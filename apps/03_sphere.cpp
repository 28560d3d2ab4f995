// 03_sphere: the first object, a sphere that is either hit or not (book section 5, "Adding a
// Sphere").
//
// A sphere of radius 0.5 sits one unit in front of the camera, at (0, 0, -1). Rays that hit it
// (at any t > 0) are coloured plain red; rays that miss see the sky of 02_rays_background. The
// result is a flat red disk in the middle of the sky: no shading yet, so it does not look round.
// (The sky is paler than in the book's figure: our writers apply gamma 2 to every image.)
//
// The book writes its own hit_sphere() here by solving the ray-sphere quadratic; we ask the
// library's sphere (rtweekend/sphere.h, which solves the same quadratic in a more precise form)
// through the hittable interface instead, so this app already uses the world that section 6
// builds up to.
//
//   03_sphere > sphere.ppm
//   03_sphere -o sphere.png

#include <rtweekend/rtweekend.h>

#include "app_options.h"

color ray_color(const ray& r, const hittable& world) {
    hit_record rec;
    if (world.hit(r, interval(0, infinity), rec)) return color(1, 0, 0);

    vec3 unit_direction = unit_vector(r.direction());
    auto a = 0.5 * (unit_direction.y() + 1.0);
    return (1.0 - a) * color(1.0, 1.0, 1.0) + a * color(0.5, 0.7, 1.0);
}

int main(int argc, char** argv) {
    const app::description d{"03_sphere", "Renders a red sphere against the sky: hit or miss, no shading.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        hittable_list world;
        // No material yet (materials arrive in section 10); ray_color only asks whether it is hit.
        world.add(make_shared<sphere>(point3(0, 0, -1), 0.5, nullptr));

        camera cam;
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 1;

        opt.apply(cam);
        // The image and its statistics: on Ctrl-C, write_output says how many samples it holds.
        app::write_output(opt, rt::render(cam, world, ray_color));
    });
}
