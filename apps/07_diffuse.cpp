// 07_diffuse: diffuse surfaces and the path tracer (book section 9, "Diffuse Materials").
//
// Both spheres of 05_hittable_list are now matte grey: a ray that hits one bounces off in a
// random direction (cosine-weighted about the normal, the book's "true Lambertian" reflection)
// and keeps half of the light it gathers. We no longer write our own ray_color: render_image
// without one runs the library's path tracer, which follows each ray for up to max_depth
// bounces and returns the sky's light it finally reaches, dimmed by every surface it met.
// Contact shadows appear where the sphere meets the ground, because rays there have few ways
// out to the sky.
//
// The image holds linear light; the writers apply gamma 2 (section 9.5) when they encode it, so
// a 50% reflector looks mid-grey rather than dark. The book's other fix in this section, shadow
// acne, is handled by the renderer: bounced rays start just off the surface (ray_offset.h)
// instead of ignoring hits closer than 0.001.
//
//   07_diffuse > diffuse.ppm
//   07_diffuse --spp 10 -o noisy.png      fewer samples: visibly noisier
//   07_diffuse --depth 1 -o one.png       one bounce is never enough: the spheres turn black

#include <rtweekend/rtweekend.h>

#include "app_options.h"

int main(int argc, char** argv) {
    const app::description d{"07_diffuse", "Path traces two matte grey spheres (lambertian, 50% reflectance).", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        auto grey = make_shared<lambertian>(color(0.5, 0.5, 0.5));

        hittable_list world;
        world.add(make_shared<sphere>(point3(0, 0, -1), 0.5, grey));
        world.add(make_shared<sphere>(point3(0, -100.5, -1), 100, grey));

        camera cam;
        cam.aspect_ratio = 16.0 / 9.0;
        cam.image_width = 400;
        cam.samples_per_pixel = 100;
        cam.max_depth = 50; // bounces followed before a path gives up (and returns black)

        opt.apply(cam);
        rt::render_result result = rt::render(cam, world); // the path tracer
        app::write_output(opt, result);
    });
}
