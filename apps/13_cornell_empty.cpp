// 13_cornell_empty: the empty Cornell box (book 2, section 7.6, "Creating an Empty Cornell Box").
//
// Five walls and a ceiling light, all quads: red on the left, green on the right, white floor,
// ceiling and back. The light emits from its front face only, the side its normal u x v points
// to, which is down into the room. Colour bleeds from the side walls onto the white ones: light
// that has bounced more than once. Scene file: tests/data/cornell_empty.txt.
//
//   13_cornell_empty > 13_cornell_empty.ppm
//   13_cornell_empty --estimator bsdf -o 13_cornell_empty.png

#include "app_options.h"
#include "light_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"13_cornell_empty", "Path traces book 2's empty Cornell box.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        light_scene s = make_cornell_box(false);
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
