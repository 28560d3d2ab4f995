// 15_cornell_final: book 3's final Cornell box ("The Rest of Your Life", section 12).
//
// The tall box and a glass sphere under the ceiling light. Book 3 aims half its rays at the light
// and the sphere (a mixture of densities); this renderer samples the light with a shadow ray at
// every diffuse bounce and weighs it against the material's sample by multiple importance
// sampling, which is several times more efficient (BENCHMARKS.md). The glass focuses light into a
// caustic on the floor. --estimator mixture renders with book 3's estimator. Scene file:
// tests/data/cornell_final.txt.
//
//   15_cornell_final > 15_cornell_final.ppm
//   15_cornell_final --estimator bsdf -o 15_cornell_final.png

#include "app_options.h"
#include "light_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"15_cornell_final", "Path traces book 3's final Cornell box: a tall box and a glass sphere.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        light_scene s = make_cornell_final();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
