// 04_normals: shading by the surface normal (book section 6.1, "Shading with Surface Normals").
//
// Same sphere as 03_sphere, but where a ray hits it we look at the unit normal N at the hit
// point, whose components lie in [-1, 1], and show it as a colour: 0.5 * (N + 1), mapping each
// component into [0, 1]. x becomes red, y green, z blue, so the sphere is lilac-blue in the
// middle (N points back at the camera), pink on the right, teal on the left, green at the top
// and purple at the bottom. It is a handy picture for checking that normals point the right way.
// (Colours are paler than in the book's figure: our writers apply gamma 2 to every image.)
//
//   04_normals > normals.ppm
//   04_normals -o normals.png

#include <rtweekend/rtweekend.h>

#include "app_options.h"

color ray_color(const ray& r, const hittable& world) {
    hit_record rec;
    if (world.hit(r, interval(0, infinity), rec)) {
        // rec.normal has unit length and faces the ray: from outside, the outward normal.
        return 0.5 * (rec.normal + color(1, 1, 1));
    }

    vec3 unit_direction = unit_vector(r.direction());
    auto a = 0.5 * (unit_direction.y() + 1.0);
    return (1.0 - a) * color(1.0, 1.0, 1.0) + a * color(0.5, 0.7, 1.0);
}

int main(int argc, char** argv) {
    const app::description d{"04_normals", "Renders a sphere coloured by its surface normal, 0.5 * (N + 1).", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        hittable_list world;
        world.add(make_shared<sphere>(point3(0, 0, -1), 0.5, nullptr)); // no material needed yet

        camera cam;
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 1;

        opt.apply(cam);
        // The image and its statistics: on Ctrl-C, write_output says how many samples it holds.
        app::write_output(opt, rt::render(cam, world, ray_color));
    });
}
