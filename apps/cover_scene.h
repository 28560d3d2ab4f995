#pragma once
// The book-1 cover scene ("Ray Tracing in One Weekend", section 14.1): a large ground sphere,
// a grid of small random spheres, and one large glass, diffuse and metal sphere each.
//
// The random draws come from random_double(), which outside a render is the book's
// rand() / (RAND_MAX + 1.0), in the order the book's code draws them when built with g++. On
// glibc this reproduces the published scene exactly (tests/test_cover_scene.cpp checks it
// against tests/data/rtiow_cover.txt, the scene exported from the book's own program).

#include <rtweekend/rtweekend.h>

inline rt::hittable_list make_cover_scene() {
    using namespace rt;
    hittable_list world;

    auto ground_material = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    world.add(std::make_shared<sphere>(point3(0, -1000, 0), 1000, ground_material));

    for (int a = -11; a < 11; a++) {
        for (int b = -11; b < 11; b++) {
            auto choose_mat = random_double();
            // The book writes point3(a + 0.9*random_double(), 0.2, b + 0.9*random_double());
            // g++ evaluates those arguments last to first, so z is drawn before x.
            auto z_offset = 0.9 * random_double();
            auto x_offset = 0.9 * random_double();
            point3 center(a + x_offset, 0.2, b + z_offset);

            if ((center - point3(4, 0.2, 0)).length() > 0.9) {
                std::shared_ptr<material> sphere_material;

                if (choose_mat < 0.8) {
                    // diffuse (the book's color::random() * color::random(), right operand first)
                    auto right = color::random();
                    auto left = color::random();
                    sphere_material = std::make_shared<lambertian>(left * right);
                } else if (choose_mat < 0.95) {
                    // metal
                    auto albedo = color::random(0.5, 1);
                    auto fuzz = random_double(0, 0.5);
                    sphere_material = std::make_shared<metal>(albedo, fuzz);
                } else {
                    // glass
                    sphere_material = std::make_shared<dielectric>(1.5);
                }
                world.add(std::make_shared<sphere>(center, 0.2, sphere_material));
            }
        }
    }

    auto material1 = std::make_shared<dielectric>(1.5);
    world.add(std::make_shared<sphere>(point3(0, 1, 0), 1.0, material1));

    auto material2 = std::make_shared<lambertian>(color(0.4, 0.2, 0.1));
    world.add(std::make_shared<sphere>(point3(-4, 1, 0), 1.0, material2));

    auto material3 = std::make_shared<metal>(color(0.7, 0.6, 0.5), 0.0);
    world.add(std::make_shared<sphere>(point3(4, 1, 0), 1.0, material3));

    return world;
}

// The book's camera for the cover, at a size that renders in seconds.
inline rt::camera make_cover_camera() {
    rt::camera cam;
    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 1200;
    cam.samples_per_pixel = 10;
    cam.max_depth = 50;

    cam.vfov = 20;
    cam.lookfrom = rt::point3(13, 2, 3);
    cam.lookat = rt::point3(0, 0, 0);
    cam.vup = rt::vec3(0, 1, 0);

    cam.defocus_angle = 0.6;
    cam.focus_dist = 10.0;
    return cam;
}
