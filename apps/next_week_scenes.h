#pragma once
// Book 2's scenes ("Ray Tracing: The Next Week"), written in the book's vocabulary, with the
// book's camera settings: bouncing (moving) spheres, checkered spheres, the earth, Perlin
// spheres, quads, the Cornell box filled with smoke, and the final scene. The milestone apps
// 17_bouncing_spheres ... 23_next_week_final render them; tests/data/<name>.txt holds each as a
// scene file for `render` (tests/test_next_week_scenes.cpp checks that file and code agree).
// Book 2's simple light and Cornell box are in light_scenes.h.
//
// Scenes with random content (the bouncing spheres, the final scene's boxes and spheres) draw
// from random_double(), which outside a render is the C library's rand() as in the book: with the
// same C library they are the book's scenes exactly. Given a stream, those two also write
// themselves there as a scene file while they draw (apps/write_next_week_scenes.cpp), so file and
// code hold the same numbers.

#include <rtweekend/rtweekend.h>

#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>

struct next_week_scene {
    rt::hittable_list world;
    rt::camera cam;
};

// Where the earth texture is: $RTW_IMAGES/earthmap.png when that variable is set (the book's own
// convention for its images), else the copy in this project's tests/data/textures.
inline std::string earth_texture_path() {
    if (const char* dir = std::getenv("RTW_IMAGES")) return std::string(dir) + "/earthmap.png";
#ifdef RTWEEKEND_TEXTURE_DIR
    return std::string(RTWEEKEND_TEXTURE_DIR) + "/earthmap.png";
#else
    return "earthmap.png";
#endif
}

namespace next_week_detail {
// Numbers as a scene file holds them: 17 significant digits, so they read back exactly.
inline std::string num(double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", x);
    return buffer;
}
inline std::string vec(const rt::vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }

inline void sky_camera(rt::camera& cam, const rt::point3& lookfrom) {
    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 400;
    cam.samples_per_pixel = 100;
    cam.max_depth = 50;
    cam.background = rt::color(0.70, 0.80, 1.00);
    cam.vfov = 20;
    cam.lookfrom = lookfrom;
    cam.lookat = rt::point3(0, 0, 0);
    cam.vup = rt::vec3(0, 1, 0);
    cam.defocus_angle = 0;
}
} // namespace next_week_detail

// Book 2, section 2 (motion blur): book 1's cover with its diffuse spheres bouncing upward
// during the shutter (moving spheres), on a checkered ground.
inline next_week_scene make_bouncing_spheres(std::ostream* file = nullptr) {
    using namespace rt;
    using next_week_detail::num;
    using next_week_detail::vec;
    std::ostream null_stream(nullptr);
    std::ostream& text = file ? *file : null_stream;
    next_week_scene s;
    hittable_list& world = s.world;
    auto checker = make_shared<checker_texture>(0.32, color(.2, .3, .1), color(.9, .9, .9));
    world.add(make_shared<sphere>(point3(0, -1000, 0), 1000, make_shared<lambertian>(checker)));
    text << "texture checker checker 0.32 0.2 0.3 0.1 0.9 0.9 0.9\n"
         << "sphere 0 -1000 0 1000 lambertian @checker 0 0\n";
    for (int a = -11; a < 11; a++) {
        for (int b = -11; b < 11; b++) {
            auto choose_mat = random_double();
            point3 center(a + 0.9 * random_double(), 0.2, b + 0.9 * random_double());
            if ((center - point3(4, 0.2, 0)).length() <= 0.9) continue;
            if (choose_mat < 0.8) {
                auto albedo = color::random() * color::random();
                auto center2 = center + vec3(0, random_double(0, .5), 0);
                world.add(make_shared<sphere>(center, center2, 0.2, make_shared<lambertian>(albedo)));
                text << "moving_sphere " << vec(center) << " " << vec(center2) << " 0.2 lambertian " << vec(albedo)
                     << " 0 0\n";
            } else if (choose_mat < 0.95) {
                auto albedo = color::random(0.5, 1);
                auto fuzz = random_double(0, 0.5);
                world.add(make_shared<sphere>(center, 0.2, make_shared<metal>(albedo, fuzz)));
                text << "sphere " << vec(center) << " 0.2 metal " << vec(albedo) << " " << num(fuzz) << " 0\n";
            } else {
                world.add(make_shared<sphere>(center, 0.2, make_shared<dielectric>(1.5)));
                text << "sphere " << vec(center) << " 0.2 dielectric 0 0 0 0 1.5\n";
            }
        }
    }
    text << "sphere 0 1 0 1 dielectric 0 0 0 0 1.5\n"
         << "sphere -4 1 0 1 lambertian 0.4 0.2 0.1 0 0\n"
         << "sphere 4 1 0 1 metal 0.7 0.6 0.5 0 0\n";
    world.add(make_shared<sphere>(point3(0, 1, 0), 1.0, make_shared<dielectric>(1.5)));
    world.add(make_shared<sphere>(point3(-4, 1, 0), 1.0, make_shared<lambertian>(color(0.4, 0.2, 0.1))));
    world.add(make_shared<sphere>(point3(4, 1, 0), 1.0, make_shared<metal>(color(0.7, 0.6, 0.5), 0.0)));
    world = hittable_list(make_shared<bvh_node>(world));

    next_week_detail::sky_camera(s.cam, point3(13, 2, 3));
    s.cam.defocus_angle = 0.6;
    s.cam.focus_dist = 10.0;
    return s;
}

// Book 2, section 4 (texture mapping): two spheres under one 3-D checker texture.
inline next_week_scene make_checkered_spheres() {
    using namespace rt;
    next_week_scene s;
    auto checker = make_shared<checker_texture>(0.32, color(.2, .3, .1), color(.9, .9, .9));
    s.world.add(make_shared<sphere>(point3(0, -10, 0), 10, make_shared<lambertian>(checker)));
    s.world.add(make_shared<sphere>(point3(0, 10, 0), 10, make_shared<lambertian>(checker)));
    next_week_detail::sky_camera(s.cam, point3(13, 2, 3));
    return s;
}

// Book 2, section 4.4 (image texture mapping): a globe under an image texture. The book's
// earthmap.jpg is not ours to ship; tests/data/textures/earthmap.png is a planet map this project
// generated (apps/make_earth_texture.cpp).
inline next_week_scene make_earth() {
    using namespace rt;
    next_week_scene s;
    auto earth_texture = make_shared<image_texture>(earth_texture_path().c_str());
    auto earth_surface = make_shared<lambertian>(earth_texture);
    s.world.add(make_shared<sphere>(point3(0, 0, 0), 2, earth_surface));
    next_week_detail::sky_camera(s.cam, point3(0, 0, 12));
    return s;
}

// Book 2, section 5 (Perlin noise): the marble texture on a ground sphere and a small sphere.
inline next_week_scene make_perlin_spheres() {
    using namespace rt;
    next_week_scene s;
    auto pertext = make_shared<noise_texture>(4);
    s.world.add(make_shared<sphere>(point3(0, -1000, 0), 1000, make_shared<lambertian>(pertext)));
    s.world.add(make_shared<sphere>(point3(0, 2, 0), 2, make_shared<lambertian>(pertext)));
    next_week_detail::sky_camera(s.cam, point3(13, 2, 3));
    return s;
}

// Book 2, section 6 (quadrilaterals): five coloured quads around the camera's view.
inline next_week_scene make_quads() {
    using namespace rt;
    next_week_scene s;
    auto left_red = make_shared<lambertian>(color(1.0, 0.2, 0.2));
    auto back_green = make_shared<lambertian>(color(0.2, 1.0, 0.2));
    auto right_blue = make_shared<lambertian>(color(0.2, 0.2, 1.0));
    auto upper_orange = make_shared<lambertian>(color(1.0, 0.5, 0.0));
    auto lower_teal = make_shared<lambertian>(color(0.2, 0.8, 0.8));
    s.world.add(make_shared<quad>(point3(-3, -2, 5), vec3(0, 0, -4), vec3(0, 4, 0), left_red));
    s.world.add(make_shared<quad>(point3(-2, -2, 0), vec3(4, 0, 0), vec3(0, 4, 0), back_green));
    s.world.add(make_shared<quad>(point3(3, -2, 1), vec3(0, 0, 4), vec3(0, 4, 0), right_blue));
    s.world.add(make_shared<quad>(point3(-2, 3, 1), vec3(4, 0, 0), vec3(0, 0, 4), upper_orange));
    s.world.add(make_shared<quad>(point3(-2, -3, 5), vec3(4, 0, 0), vec3(0, 0, -4), lower_teal));
    next_week_detail::sky_camera(s.cam, point3(0, 0, 9));
    s.cam.aspect_ratio = 1.0;
    s.cam.vfov = 80;
    return s;
}

// Book 2, section 9 (volumes): the Cornell box with its two boxes turned into smoke, one black,
// one white, under a larger, dimmer light.
inline next_week_scene make_cornell_smoke() {
    using namespace rt;
    next_week_scene s;
    auto red = make_shared<lambertian>(color(.65, .05, .05));
    auto white = make_shared<lambertian>(color(.73, .73, .73));
    auto green = make_shared<lambertian>(color(.12, .45, .15));
    auto light = make_shared<diffuse_light>(color(7, 7, 7), /*two_sided=*/true);
    hittable_list& world = s.world;
    world.add(make_shared<quad>(point3(555, 0, 0), vec3(0, 555, 0), vec3(0, 0, 555), green));
    world.add(make_shared<quad>(point3(0, 0, 0), vec3(0, 555, 0), vec3(0, 0, 555), red));
    world.add(make_shared<quad>(point3(113, 554, 127), vec3(330, 0, 0), vec3(0, 0, 305), light));
    world.add(make_shared<quad>(point3(0, 555, 0), vec3(555, 0, 0), vec3(0, 0, 555), white));
    world.add(make_shared<quad>(point3(0, 0, 0), vec3(555, 0, 0), vec3(0, 0, 555), white));
    world.add(make_shared<quad>(point3(0, 0, 555), vec3(555, 0, 0), vec3(0, 555, 0), white));

    shared_ptr<hittable> box1 = box(point3(0, 0, 0), point3(165, 330, 165), white);
    box1 = make_shared<rotate_y>(box1, 15);
    box1 = make_shared<translate>(box1, vec3(265, 0, 295));
    shared_ptr<hittable> box2 = box(point3(0, 0, 0), point3(165, 165, 165), white);
    box2 = make_shared<rotate_y>(box2, -18);
    box2 = make_shared<translate>(box2, vec3(130, 0, 65));
    world.add(make_shared<constant_medium>(box1, 0.01, color(0, 0, 0)));
    world.add(make_shared<constant_medium>(box2, 0.01, color(1, 1, 1)));

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

// Book 2, section 10: everything at once. A ground of 400 boxes of random heights, a moving
// sphere, glass, brushed metal, a glass sphere filled with blue smoke, thin fog over the whole
// scene, the earth, a marble sphere and a cube-shaped cloud of 1000 small spheres, turned and
// moved as one. The book renders it at 800 x 800, 10,000 samples, depth 40 (final_scene(800,
// 10000, 40)) and by default at 400 x 400, 250 samples, depth 4.
inline next_week_scene make_next_week_final(int image_width = 400, int samples_per_pixel = 250, int max_depth = 4,
                                            std::ostream* file = nullptr) {
    using namespace rt;
    using next_week_detail::num;
    using next_week_detail::vec;
    std::ostream null_stream(nullptr);
    std::ostream& text = file ? *file : null_stream;
    next_week_scene s;
    hittable_list boxes1;
    auto ground = make_shared<lambertian>(color(0.48, 0.83, 0.53));
    const int boxes_per_side = 20;
    for (int i = 0; i < boxes_per_side; i++) {
        for (int j = 0; j < boxes_per_side; j++) {
            auto w = 100.0;
            auto x0 = -1000.0 + i * w;
            auto z0 = -1000.0 + j * w;
            auto y0 = 0.0;
            auto x1 = x0 + w;
            auto y1 = random_double(1, 101);
            auto z1 = z0 + w;
            boxes1.add(box(point3(x0, y0, z0), point3(x1, y1, z1), ground));
            text << "box " << num(x0) << " " << num(y0) << " " << num(z0) << "  " << num(x1) << " " << num(y1) << " "
                 << num(z1) << " lambertian 0.48 0.83 0.53 0 0\n";
        }
    }
    hittable_list& world = s.world;
    world.add(make_shared<bvh_node>(boxes1));

    auto light = make_shared<diffuse_light>(color(7, 7, 7), /*two_sided=*/true);
    world.add(make_shared<quad>(point3(123, 554, 147), vec3(300, 0, 0), vec3(0, 0, 265), light));

    auto center1 = point3(400, 400, 200);
    auto center2 = center1 + vec3(30, 0, 0);
    auto sphere_material = make_shared<lambertian>(color(0.7, 0.3, 0.1));
    world.add(make_shared<sphere>(center1, center2, 50, sphere_material));

    world.add(make_shared<sphere>(point3(260, 150, 45), 50, make_shared<dielectric>(1.5)));
    world.add(make_shared<sphere>(point3(0, 150, 145), 50, make_shared<metal>(color(0.8, 0.8, 0.9), 1.0)));

    auto boundary = make_shared<sphere>(point3(360, 150, 145), 70, make_shared<dielectric>(1.5));
    world.add(boundary);
    world.add(make_shared<constant_medium>(boundary, 0.2, color(0.2, 0.4, 0.9)));
    boundary = make_shared<sphere>(point3(0, 0, 0), 5000, make_shared<dielectric>(1.5));
    world.add(make_shared<constant_medium>(boundary, .0001, color(1, 1, 1)));

    text << "quad 123 554 147  300 0 0  0 0 265 two_sided_light 7 7 7 0 0\n"
         << "moving_sphere 400 400 200  430 400 200  50 lambertian 0.7 0.3 0.1 0 0\n"
         << "sphere 260 150 45 50 dielectric 0 0 0 0 1.5\n"
         << "sphere 0 150 145 50 metal 0.8 0.8 0.9 1 0\n"
         << "sphere 360 150 145 70 dielectric 0 0 0 0 1.5\n"
         << "medium 0.2 0.2 0.4 0.9 sphere 360 150 145 70 dielectric 0 0 0 0 1.5\n"
         << "medium 0.0001 1 1 1 sphere 0 0 0 5000 dielectric 0 0 0 0 1.5\n"
         << "texture earth image textures/earthmap.png\n"
         << "sphere 400 200 400 100 lambertian @earth 0 0\n"
         << "texture marble noise 0.2\n"
         << "sphere 220 280 300 80 lambertian @marble 0 0\n";
    auto emat = make_shared<lambertian>(make_shared<image_texture>(earth_texture_path().c_str()));
    world.add(make_shared<sphere>(point3(400, 200, 400), 100, emat));
    auto pertext = make_shared<noise_texture>(0.2);
    world.add(make_shared<sphere>(point3(220, 280, 300), 80, make_shared<lambertian>(pertext)));

    hittable_list boxes2;
    auto white = make_shared<lambertian>(color(.73, .73, .73));
    int ns = 1000;
    text << "group cloud\n";
    for (int j = 0; j < ns; j++) {
        point3 centre = point3::random(0, 165);
        boxes2.add(make_shared<sphere>(centre, 10, white));
        text << "sphere " << vec(centre) << " 10 lambertian 0.73 0.73 0.73 0 0\n";
    }
    text << "end\ninstance cloud rotate_y 15 translate -100 270 395\n";
    world.add(make_shared<translate>(make_shared<rotate_y>(make_shared<bvh_node>(boxes2), 15), vec3(-100, 270, 395)));

    camera& cam = s.cam;
    cam.aspect_ratio = 1.0;
    cam.image_width = image_width;
    cam.samples_per_pixel = samples_per_pixel;
    cam.max_depth = max_depth;
    cam.background = color(0, 0, 0);
    cam.vfov = 40;
    cam.lookfrom = point3(478, 278, -600);
    cam.lookat = point3(278, 278, 0);
    cam.vup = vec3(0, 1, 0);
    cam.defocus_angle = 0;
    return s;
}
