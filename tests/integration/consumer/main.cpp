// A user's program: renders a small scene through <rtweekend/rtweekend.h>, without the book's
// global names, checks the picture, and writes it with rt::write_image.
//
//   app OUTPUT.png

#define RTWEEKEND_NO_GLOBAL_NAMES
#include <rtweekend/rtweekend.h>

#include <cmath>
#include <cstdio>
#include <memory>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: app OUTPUT.png\n");
        return 2;
    }

    rt::hittable_list world;
    world.add(std::make_shared<rt::sphere>(rt::point3(0, -100.5, -1), 100,
                                           std::make_shared<rt::lambertian>(rt::color(0.8, 0.8, 0.0))));
    world.add(std::make_shared<rt::sphere>(rt::point3(0, 0, -1.2), 0.5,
                                           std::make_shared<rt::lambertian>(rt::color(0.1, 0.2, 0.5))));
    world.add(std::make_shared<rt::sphere>(rt::point3(-1, 0, -1), 0.5, std::make_shared<rt::dielectric>(1.5)));
    world.add(std::make_shared<rt::sphere>(rt::point3(1, 0, -1), 0.5,
                                           std::make_shared<rt::metal>(rt::color(0.8, 0.6, 0.2), 0.3)));

    rt::camera cam;
    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 48;
    cam.samples_per_pixel = 4;
    cam.max_depth = 8;
    cam.settings.quiet = true;

    try {
        rt::image img = cam.render_image(world);
        if (img.width() != 48 || img.height() != 27) {
            std::fprintf(stderr, "app: expected a 48x27 image, got %dx%d\n", img.width(), img.height());
            return 1;
        }
        // The top row sees only sky, which is bright; every pixel is finite and non-negative.
        for (int y = 0; y < img.height(); ++y)
            for (int x = 0; x < img.width(); ++x) {
                rt::color c = img.pixel(x, y);
                for (int k = 0; k < 3; ++k)
                    if (!std::isfinite(c[k]) || c[k] < 0) {
                        std::fprintf(stderr, "app: pixel (%d, %d) channel %d is %g\n", x, y, k, c[k]);
                        return 1;
                    }
                if (y == 0 && !(c.z() > 0.5)) {
                    std::fprintf(stderr, "app: sky pixel (%d, 0) is dark: blue = %g\n", x, c.z());
                    return 1;
                }
            }
        rt::write_image(argv[1], img);
    } catch (const rt::scene_error& e) {
        std::fprintf(stderr, "app: error: %s\n", e.what());
        return 1;
    }
    std::printf("app: wrote %s\n", argv[1]);
    return 0;
}
