// 10_camera: a camera that can be placed and aimed (book section 12, "Positionable Camera").
//
// Until now the camera sat at the origin looking down -z with a 90 degree vertical field of
// view. Here it is described by:
//   lookfrom  where the camera is:           (-2, 2, 1), up and to the left of the scene
//   lookat    the point it looks at:         (0, 0, -1), the centre sphere
//   vup       which way is "up" in the view: (0, 1, 0), so the horizon stays level
//   vfov      vertical field of view:        20 degrees, a telephoto view
// The camera builds an orthonormal frame (u, v, w) from these (see camera::frame() in camera.h)
// and lays the viewport out in it. The scene is 09_dielectrics' unchanged.
//
//   10_camera > camera.ppm
//   10_camera -o camera.png

#include <rtweekend/rtweekend.h>

#include "app_options.h"

int main(int argc, char** argv) {
    const app::description d{"10_camera", "Path traces 09's scene from a raised camera with a 20 degree view.", ""};
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

        opt.apply(cam);
        rt::render_result result = rt::render(cam, world); // the path tracer
        app::write_output(opt, result);
    });
}
