// 09_dielectrics: glass (book section 11, "Dielectrics").
//
// The scene of 08_metal with the silver sphere on the left replaced by glass. A dielectric
// either refracts a ray (Snell's law) or reflects it: always when refraction is impossible
// (total internal reflection), otherwise with the probability Schlick's approximation gives,
// which grows towards grazing angles. Glass absorbs nothing, so its attenuation is 1.
//
// The left sphere is hollow, as in section 11.5: a glass ball of index 1.5 with a sphere of air
// (radius 0.4) inside it. The inner sphere's index is 1.0 / 1.5, the ratio of air to the
// surrounding glass, because a dielectric's index is taken relative to the medium around it.
// A solid glass ball shows the scene behind it upside down; the bubble adds a thin bright rim.
//
//   09_dielectrics > glass.ppm
//   09_dielectrics -o glass.png

#include <rtweekend/rtweekend.h>

#include "app_options.h"

int main(int argc, char** argv) {
    const app::description d{"09_dielectrics", "Path traces a hollow glass sphere beside diffuse and metal ones.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        auto material_ground = make_shared<lambertian>(color(0.8, 0.8, 0.0));
        auto material_center = make_shared<lambertian>(color(0.1, 0.2, 0.5));
        auto material_left = make_shared<dielectric>(1.50);          // glass, in air
        auto material_bubble = make_shared<dielectric>(1.00 / 1.50); // air, inside the glass
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

        opt.apply(cam);
        rt::render_result result = rt::render(cam, world); // the path tracer
        app::write_output(opt, result);
    });
}
