// A main written the way "Ray Tracing: The Next Week" writes its earth scene: an image_texture
// read from "earthmap.jpg" (found in the working directory, in $RTW_IMAGES or in images/ above
// it, as the book's rtw_image looks), wrapped around a globe by the sphere's (u, v). Without
// the file the render stops with one error line naming it and exit status 1. The image is tiny
// so the test is quick.

#include "rtweekend.h"

#include "camera.h"
#include "hittable.h"
#include "hittable_list.h"
#include "material.h"
#include "sphere.h"
#include "texture.h"

int main() {
    auto earth_texture = make_shared<image_texture>("earthmap.jpg");
    auto earth_surface = make_shared<lambertian>(earth_texture);
    auto globe = make_shared<sphere>(point3(0, 0, 0), 2, earth_surface);

    camera cam;

    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 48;
    cam.samples_per_pixel = 4;
    cam.max_depth = 8;

    cam.vfov = 20;
    cam.lookfrom = point3(0, 0, 12);
    cam.lookat = point3(0, 0, 0);
    cam.vup = vec3(0, 1, 0);

    cam.defocus_angle = 0;

    cam.render(hittable_list(globe));
}
