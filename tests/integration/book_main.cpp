// A main written the way the book's final chapter writes its main.cc ("Ray Tracing in One
// Weekend", section 14.1): the book's headers by their book names, unqualified book names, a
// random field of small spheres and three large ones, and cam.render(world), which writes a P3
// PPM to stdout and statistics to stderr. Built with only rtweekend/ on the include path, so it
// proves a book-style program compiles unchanged. The image is tiny so the test is quick.

#include "rtweekend.h"

#include "camera.h"
#include "hittable.h"
#include "hittable_list.h"
#include "material.h"
#include "sphere.h"

int main() {
    hittable_list world;

    auto ground = make_shared<lambertian>(color(0.5, 0.5, 0.5));
    world.add(make_shared<sphere>(point3(0, -1000, 0), 1000, ground));

    // A smaller grid than the book's 22 x 22, drawn the same way.
    for (int a = -5; a < 5; a++) {
        for (int b = -5; b < 5; b++) {
            auto pick = random_double();
            point3 centre(a + 0.9 * random_double(), 0.2, b + 0.9 * random_double());

            if ((centre - point3(4, 0.2, 0)).length() <= 0.9) continue;

            shared_ptr<material> small_material;
            if (pick < 0.8) {
                auto albedo = color::random() * color::random();
                small_material = make_shared<lambertian>(albedo);
            } else if (pick < 0.95) {
                auto albedo = color::random(0.5, 1);
                auto fuzz = random_double(0, 0.5);
                small_material = make_shared<metal>(albedo, fuzz);
            } else {
                small_material = make_shared<dielectric>(1.5);
            }
            world.add(make_shared<sphere>(centre, 0.2, small_material));
        }
    }

    world.add(make_shared<sphere>(point3(0, 1, 0), 1.0, make_shared<dielectric>(1.5)));
    world.add(make_shared<sphere>(point3(-4, 1, 0), 1.0, make_shared<lambertian>(color(0.4, 0.2, 0.1))));
    world.add(make_shared<sphere>(point3(4, 1, 0), 1.0, make_shared<metal>(color(0.7, 0.6, 0.5), 0.0)));

    camera cam;

    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 64;
    cam.samples_per_pixel = 2;
    cam.max_depth = 8;

    cam.vfov = 20;
    cam.lookfrom = point3(13, 2, 3);
    cam.lookat = point3(0, 0, 0);
    cam.vup = vec3(0, 1, 0);

    cam.defocus_angle = 0.6;
    cam.focus_dist = 10.0;

    cam.render(world);
}
