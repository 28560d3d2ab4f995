// 12_simple_light: light from emitters (book 2, section 7, "Lights").
//
// The first scene lit only by its own emitters: a black background, a sphere light and a quad
// light (diffuse_light on a sphere and on a quad) over a sphere on the ground. The path tracer
// finds them two ways at every diffuse bounce: it samples a point on a light and tests a shadow
// ray to it (next-event estimation), and it follows the material's own direction, which may hit
// a light; multiple importance sampling weighs the two (--estimator bsdf shows the book's way,
// material sampling alone, and how much noisier it is). Scene file: tests/data/simple_light.txt.
//
//   12_simple_light > 12_simple_light.ppm
//   12_simple_light --estimator bsdf -o 12_simple_light.png

#include "app_options.h"
#include "light_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"12_simple_light", "Path traces book 2's simple light: a sphere lit by a sphere light and a quad light.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        light_scene s = make_simple_light();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
