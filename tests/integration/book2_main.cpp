// A main written the way "Ray Tracing: The Next Week" (v4) writes its scenes, most of its
// vocabulary in one: a checker_texture ground, noise_texture spheres, a moving sphere, quads, a
// box turned and moved, smoke (constant_medium), a diffuse_light, bvh_node over the world,
// camera::background, and two classes of the reader's own (a texture and a light overriding the
// book-2 emitted(u, v, p)), which the renderer calls through their virtual functions. The
// book's header names only, unqualified book names, only rtweekend/ on the include path: it
// proves a book-2 program compiles unchanged. The image is tiny so the test is quick.

#include "rtweekend.h"

#include "bvh.h"
#include "camera.h"
#include "constant_medium.h"
#include "hittable.h"
#include "hittable_list.h"
#include "material.h"
#include "quad.h"
#include "sphere.h"
#include "texture.h"

// Stripes along x: a texture of the reader's own.
class stripes : public texture {
  public:
    stripes(const color& a, const color& b) : a(a), b(b) {}
    color value(double u, double, const point3&) const override { return int(u * 20) % 2 ? a : b; }

  private:
    color a, b;
};

// A light that glows brighter towards its top edge (book 2's emitted(u, v, p)).
class graded_light : public material {
  public:
    color emitted(double, double v, const point3&) const override { return color(4, 4, 4) * (0.5 + v); }
};

int main() {
    hittable_list world;

    auto checker = make_shared<checker_texture>(0.32, color(.2, .3, .1), color(.9, .9, .9));
    world.add(make_shared<sphere>(point3(0, -1000, 0), 1000, make_shared<lambertian>(checker)));

    auto pertext = make_shared<noise_texture>(4);
    world.add(make_shared<sphere>(point3(0, 2, 0), 2, make_shared<lambertian>(pertext)));

    auto center = point3(4, 1, 2);
    world.add(make_shared<sphere>(center, center + vec3(0, 0.5, 0), 1, make_shared<lambertian>(color(0.7, 0.3, 0.1))));
    world.add(make_shared<sphere>(point3(-4, 1, 2), 1, make_shared<lambertian>(make_shared<stripes>(color(1, 1, 1), color(0.1, 0.1, 0.8)))));

    shared_ptr<hittable> box1 = box(point3(0, 0, 0), point3(1.5, 3, 1.5), make_shared<lambertian>(color(.73, .73, .73)));
    box1 = make_shared<rotate_y>(box1, 15);
    box1 = make_shared<translate>(box1, vec3(-3, 0, -3));
    world.add(make_shared<constant_medium>(box1, 0.5, color(1, 1, 1)));

    auto difflight = make_shared<diffuse_light>(color(4, 4, 4));
    world.add(make_shared<quad>(point3(3, 1, -2), vec3(2, 0, 0), vec3(0, 2, 0), difflight));
    world.add(make_shared<quad>(point3(-2, 5, -2), vec3(4, 0, 0), vec3(0, 0, 4), make_shared<graded_light>()));

    world = hittable_list(make_shared<bvh_node>(world));

    camera cam;

    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 48;
    cam.samples_per_pixel = 16;
    cam.max_depth = 50;
    cam.background = color(0.1, 0.1, 0.15);

    cam.vfov = 20;
    cam.lookfrom = point3(26, 3, 6);
    cam.lookat = point3(0, 2, 0);
    cam.vup = vec3(0, 1, 0);

    cam.defocus_angle = 0;

    cam.render(world);
}
