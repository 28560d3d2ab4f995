// 02_rays_background: a camera shooting one ray through each pixel into an empty world
// (book section 4, "Rays, a Simple Camera, and Background").
//
// The colour a ray sees is decided only by where it points: take its unit direction, map the
// y component from [-1, 1] to a = [0, 1], and blend linearly from white (a = 0, looking down)
// to light blue (a = 1, looking up). The image is that sky: light blue at the top fading to
// nearly white at the bottom, with a slight left-right variation because the rays at the sides
// are tilted.
//
// The image is paler than the book's figure: our writers apply gamma 2 (a square root, book
// section 9.5) to every image they write, while the book's early chapters write the raw values.
//
//   02_rays_background > sky.ppm
//   02_rays_background --width 800 -o sky.png
//
// One ray through the centre of each pixel by default (the book samples several per pixel only
// from section 8 on); --spp N > 1 jitters the rays within their pixels.

#include <rtweekend/rtweekend.h>

#include "app_options.h"

// The background: a vertical lerp between white and blue on the ray's unit direction.
color ray_color(const ray& r, const hittable& /*world*/) {
    vec3 unit_direction = unit_vector(r.direction());
    auto a = 0.5 * (unit_direction.y() + 1.0);
    return (1.0 - a) * color(1.0, 1.0, 1.0) + a * color(0.5, 0.7, 1.0);
}

int main(int argc, char** argv) {
    const app::description d{"02_rays_background", "Renders the sky gradient: one ray per pixel, nothing to hit.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        hittable_list world; // empty: every ray escapes to the sky

        camera cam; // at the origin looking down -z, vertical field of view 90 degrees
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 1; // the ray through each pixel's centre

        opt.apply(cam);
        // The image and its statistics: on Ctrl-C, write_output says how many samples it holds.
        app::write_output(opt, rt::render(cam, world, ray_color));
    });
}
