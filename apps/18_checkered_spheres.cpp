// 18_checkered_spheres: solid textures (book 2, section 4, "Texture Mapping").
//
// Two spheres under one checker_texture: a 3-D pattern, the parity of floor(x / scale) +
// floor(y / scale) + floor(z / scale), so the checks cut through both spheres alike.
// Scene file: tests/data/checkered_spheres.txt.
//
//   18_checkered_spheres > 18_checkered_spheres.ppm
//   18_checkered_spheres --spp 1000 -o 18_checkered_spheres.png

#include "app_options.h"
#include "next_week_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"18_checkered_spheres", "Path traces book 2's checkered spheres.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        next_week_scene s = make_checkered_spheres();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
