// 11_defocus_blur: depth of field (book section 13, "Defocus Blur").
//
// The view of 10_camera through a thin lens instead of a pinhole. Rays no longer all start at
// lookfrom: each starts at a random point of a disk around it (the lens) and passes through
// the same point of the focus plane, focus_dist away. Objects on that plane stay sharp; the
// further something is from it, the more its rays spread and the blurrier it looks.
//   defocus_angle  10 degrees: the cone a pixel's rays span, apex on the focus plane (lens size)
//   focus_dist     3.4: the distance from lookfrom to the centre sphere, which stays in focus
// Compare with 10_camera, where defocus_angle is 0 and everything is sharp.
//
//   11_defocus_blur > blur.ppm
//   11_defocus_blur -o blur.png

#include <rtweekend/rtweekend.h>

#include "app_options.h"

int main(int argc, char** argv) {
    const app::description d{"11_defocus_blur", "Path traces 10's view through a thin lens.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        auto material_ground = make_shared<lambertian>(color(0.8, 0.8, 0.0));
        auto material_center = make_shared<lambertian>(color(0.1, 0.2, 0.5));
        auto material_left = make_shared<dielectric>(1.50);
        auto material_bubble = make_shared<dielectric>(1.00 / 1.50);
        auto material_right = make_shared<metal>(color(0.8, 0.6, 0.2), 1.0);

        hittable_list world;
        world.add(make_shared<sphere>(point3(0.0, -100.5, -1.0), 100.0, material_ground));
        world.add(make_shared<sphere>(point3(0.0, 0.0, -1.2), 0.5, material_center));
        world.add(make_shared<sphere>(point3(-1.0, 0.0, -1.0), 0.5, material_left));
        world.add(make_shared<sphere>(point3(-1.0, 0.0, -1.0), 0.4, material_bubble));
        world.add(make_shared<sphere>(point3(1.0, 0.0, -1.0), 0.5, material_right));

        camera cam;
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 100;
        cam.max_depth = 50;

        cam.vfov = 20;
        cam.lookfrom = point3(-2, 2, 1);
        cam.lookat = point3(0, 0, -1);
        cam.vup = vec3(0, 1, 0);

        cam.defocus_angle = 10.0;
        cam.focus_dist = 3.4;

        opt.apply(cam);
        rt::render_result result = rt::render(cam, world); // the path tracer
        app::write_output(opt, result);
    });
}
