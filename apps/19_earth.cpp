// 19_earth: image textures (book 2, section 4.4, "Image Texture Mapping").
//
// A globe under image_texture: the sphere's (u, v) (longitude, latitude) pick a pixel of an
// equirectangular map, its 8-bit sRGB colour made linear. The map is one this project generated
// (apps/make_earth_texture.cpp); set RTW_IMAGES to a directory holding another earthmap.png to
// use that one. Scene file: tests/data/earth.txt.
//
//   19_earth > 19_earth.ppm
//   19_earth --spp 1000 -o 19_earth.png

#include "app_options.h"
#include "next_week_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"19_earth", "Path traces book 2's earth (an image texture).", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        next_week_scene s = make_earth();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
