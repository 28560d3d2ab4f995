// 22_cornell_smoke: volumes (book 2, section 9, "Volumes").
//
// The Cornell box with its boxes made of smoke: constant_medium(boundary, density, albedo) lets a
// ray pass a distance drawn from exp(-density * distance) before it scatters, in every direction
// alike (the isotropic phase function). Scene file: tests/data/cornell_smoke.txt.
//
//   22_cornell_smoke > 22_cornell_smoke.ppm
//   22_cornell_smoke --spp 1000 -o 22_cornell_smoke.png

#include "app_options.h"
#include "next_week_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"22_cornell_smoke", "Path traces book 2's Cornell box with smoke.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        next_week_scene s = make_cornell_smoke();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
