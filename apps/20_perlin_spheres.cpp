// 20_perlin_spheres: Perlin noise (book 2, section 5, "Perlin Noise").
//
// noise_texture's marble: a sine of z shifted by turbulence, the sum of seven octaves of
// Perlin's gradient noise. Scene file: tests/data/perlin_spheres.txt.
//
//   20_perlin_spheres > 20_perlin_spheres.ppm
//   20_perlin_spheres --spp 1000 -o 20_perlin_spheres.png

#include "app_options.h"
#include "next_week_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"20_perlin_spheres", "Path traces book 2's Perlin spheres.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        next_week_scene s = make_perlin_spheres();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
