// 21_quads: quadrilaterals (book 2, section 6, "Quadrilaterals").
//
// Five quads, quad(Q, u, v, material): a corner and two edges; a ray hits the plane, and the
// hit's coordinates along u and v, each in [0, 1], say whether it lies inside.
// Scene file: tests/data/quads.txt.
//
//   21_quads > 21_quads.ppm
//   21_quads --spp 1000 -o 21_quads.png

#include "app_options.h"
#include "next_week_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"21_quads", "Path traces book 2's quads.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        next_week_scene s = make_quads();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
