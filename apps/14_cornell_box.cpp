// 14_cornell_box: the Cornell box with two boxes (book 2, section 8, "Instances").
//
// Two white boxes, each six quads (box()), turned about the vertical axis by rotate_y and moved
// into place by translate. The renderer applies those instance transforms to the quads once,
// before rendering, so a moved box costs what a box at the origin costs. Scene file:
// tests/data/cornell_box.txt.
//
//   14_cornell_box > 14_cornell_box.ppm
//   14_cornell_box --estimator bsdf -o 14_cornell_box.png

#include "app_options.h"
#include "light_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"14_cornell_box", "Path traces book 2's Cornell box with two rotated boxes.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        light_scene s = make_cornell_box(true);
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
