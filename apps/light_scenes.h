#pragma once
// The scenes lit by emitters, written in the books' vocabulary: book 2's simple light and Cornell
// boxes ("Ray Tracing: The Next Week", sections 7-8), book 3's final Cornell box ("The Rest of
// Your Life", section 12) and the CENG795 course renderer's sphere room. The milestone apps
// 12_simple_light ... 16_sphere_room render them; tests/data/<name>.txt holds each as a scene
// file for `render` (tests/test_light_scenes.cpp checks that file and code give the same image).
//
// Each returns the world, the book's camera settings and `lights`, the shapes book 3's code aims
// its rays at (this renderer finds the emitters itself; see camera::render(world, lights)).

#include <rtweekend/rtweekend.h>

struct light_scene {
    rt::hittable_list world;
    rt::hittable_list lights;
    rt::camera cam;
};

// Book 2's "simple light": a sphere on the ground lit by a sphere light and a quad light, in the
// dark. Book 2's diffuse_light emits from both faces, so these lights do (two_sided = true). Both
// spheres wear the book's marble noise texture.
inline light_scene make_simple_light() {
    using namespace rt;
    light_scene s;
    auto pertext = make_shared<noise_texture>(4);
    s.world.add(make_shared<sphere>(point3(0, -1000, 0), 1000, make_shared<lambertian>(pertext)));
    s.world.add(make_shared<sphere>(point3(0, 2, 0), 2, make_shared<lambertian>(pertext)));

    auto difflight = make_shared<diffuse_light>(color(4, 4, 4), /*two_sided=*/true);
    s.world.add(make_shared<sphere>(point3(0, 7, 0), 2, difflight));
    s.world.add(make_shared<quad>(point3(3, 1, -2), vec3(2, 0, 0), vec3(0, 2, 0), difflight));

    camera& cam = s.cam;
    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 400;
    cam.samples_per_pixel = 100;
    cam.max_depth = 50;
    cam.background = color(0, 0, 0);
    cam.vfov = 20;
    cam.lookfrom = point3(26, 3, 6);
    cam.lookat = point3(0, 2, 0);
    cam.vup = vec3(0, 1, 0);
    cam.defocus_angle = 0;
    return s;
}

// Book 2's Cornell box: five walls 555 units wide and a light in the ceiling; with_boxes adds the
// two boxes, each turned about y and moved into place. The light's normal, (-130,0,0) x
// (0,0,-105), points down into the room: it emits from that face.
inline light_scene make_cornell_box(bool with_boxes) {
    using namespace rt;
    light_scene s;
    auto red = make_shared<lambertian>(color(.65, .05, .05));
    auto white = make_shared<lambertian>(color(.73, .73, .73));
    auto green = make_shared<lambertian>(color(.12, .45, .15));
    auto light = make_shared<diffuse_light>(color(15, 15, 15));

    hittable_list& world = s.world;
    world.add(make_shared<quad>(point3(555, 0, 0), vec3(0, 555, 0), vec3(0, 0, 555), green));
    world.add(make_shared<quad>(point3(0, 0, 0), vec3(0, 555, 0), vec3(0, 0, 555), red));
    world.add(make_shared<quad>(point3(343, 554, 332), vec3(-130, 0, 0), vec3(0, 0, -105), light));
    world.add(make_shared<quad>(point3(0, 0, 0), vec3(555, 0, 0), vec3(0, 0, 555), white));
    world.add(make_shared<quad>(point3(555, 555, 555), vec3(-555, 0, 0), vec3(0, 0, -555), white));
    world.add(make_shared<quad>(point3(0, 0, 555), vec3(555, 0, 0), vec3(0, 555, 0), white));

    if (with_boxes) {
        shared_ptr<hittable> box1 = box(point3(0, 0, 0), point3(165, 330, 165), white);
        box1 = make_shared<rotate_y>(box1, 15);
        box1 = make_shared<translate>(box1, vec3(265, 0, 295));
        world.add(box1);

        shared_ptr<hittable> box2 = box(point3(0, 0, 0), point3(165, 165, 165), white);
        box2 = make_shared<rotate_y>(box2, -18);
        box2 = make_shared<translate>(box2, vec3(130, 0, 65));
        world.add(box2);
    }
    s.lights.add(make_shared<quad>(point3(343, 554, 332), vec3(-130, 0, 0), vec3(0, 0, -105), shared_ptr<material>()));

    camera& cam = s.cam;
    cam.aspect_ratio = 1.0;
    cam.image_width = 600;
    cam.samples_per_pixel = 200;
    cam.max_depth = 50;
    cam.background = color(0, 0, 0);
    cam.vfov = 40;
    cam.lookfrom = point3(278, 278, -800);
    cam.lookat = point3(278, 278, 0);
    cam.vup = vec3(0, 1, 0);
    cam.defocus_angle = 0;
    return s;
}

// Book 3's final Cornell box: the tall white box turned 15 degrees, a glass sphere in front, and
// `lights` = the ceiling light and the glass sphere (book 3 aims rays at the sphere for its
// caustic). The book renders 600 x 600 at 1000 samples per pixel.
inline light_scene make_cornell_final() {
    using namespace rt;
    light_scene s = make_cornell_box(false);
    auto white = make_shared<lambertian>(color(.73, .73, .73));
    shared_ptr<hittable> box1 = box(point3(0, 0, 0), point3(165, 330, 165), white);
    box1 = make_shared<rotate_y>(box1, 15);
    box1 = make_shared<translate>(box1, vec3(265, 0, 295));
    s.world.add(box1);

    auto glass = make_shared<dielectric>(1.5);
    s.world.add(make_shared<sphere>(point3(190, 90, 190), 90, glass));
    s.lights.add(make_shared<sphere>(point3(190, 90, 190), 90, shared_ptr<material>()));
    s.cam.samples_per_pixel = 1000;
    return s;
}

// The CENG795 course renderer's "sphere room": six walls that are huge spheres (radius 940,
// centres 1000 away along +-x, +-y, +-z, so each wall is 60 from the origin; the floor's radius
// is 990, putting it at y = -10), a mirror sphere, a glass sphere and a hollow glass sphere (a
// glass shell between radii 10 and 9.5) of radius 10 standing on the floor, and a spherical light
// of radius 5 up and to the left. Soft shadows, and a caustic under each glass sphere.
inline light_scene make_sphere_room() {
    using namespace rt;
    light_scene s;
    auto wall = [](double r, double g, double b) { return make_shared<lambertian>(color(r, g, b)); };
    hittable_list& world = s.world;
    world.add(make_shared<sphere>(point3(0, 1000, 0), 940, wall(0.75, 0.15, 0.15)));  // ceiling: red
    world.add(make_shared<sphere>(point3(0, -1000, 0), 990, wall(0.15, 0.2, 0.75)));  // floor: blue
    world.add(make_shared<sphere>(point3(0, 0, -1000), 940, wall(0.15, 0.65, 0.2)));  // far wall: green
    world.add(make_shared<sphere>(point3(0, 0, 1000), 940, wall(0.75, 0.15, 0.15)));  // behind the camera: red
    world.add(make_shared<sphere>(point3(1000, 0, 0), 940, wall(0.8, 0.75, 0.15)));   // +x: yellow
    world.add(make_shared<sphere>(point3(-1000, 0, 0), 940, wall(0.15, 0.7, 0.75)));  // -x: cyan

    world.add(make_shared<sphere>(point3(-24, 0, -8), 10, make_shared<metal>(color(0.95, 0.95, 0.95), 0.0)));
    world.add(make_shared<sphere>(point3(0, 0, 4), 10, make_shared<dielectric>(1.5)));
    // The hollow sphere: an outer surface of glass and an inner one whose index ratio is 1 / 1.5
    // (glass to air), as book 1 makes its bubble.
    world.add(make_shared<sphere>(point3(24, 0, -8), 10, make_shared<dielectric>(1.5)));
    world.add(make_shared<sphere>(point3(24, 0, -8), 9.5, make_shared<dielectric>(1.0 / 1.5)));

    auto light = make_shared<diffuse_light>(color(30, 30, 30));
    auto lamp = make_shared<sphere>(point3(-10, 20, 40), 5, light);
    world.add(lamp);
    s.lights.add(make_shared<sphere>(point3(-10, 20, 40), 5, shared_ptr<material>()));

    camera& cam = s.cam;
    cam.aspect_ratio = 4.0 / 3.0;
    cam.image_width = 480;
    cam.samples_per_pixel = 256;
    cam.max_depth = 50;
    cam.background = color(0, 0, 0);
    cam.vfov = 60;
    cam.lookfrom = point3(0, 0, 55);
    cam.lookat = point3(0, 0, 0);
    cam.vup = vec3(0, 1, 0);
    cam.defocus_angle = 0;
    return s;
}
