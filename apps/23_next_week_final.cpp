// 23_next_week_final: book 2's final scene (section 10, "A Scene Testing All New Features").
//
// Everything of book 2 in one picture: a ground of boxes, a moving sphere, glass, brushed metal,
// a glass sphere filled with blue smoke, thin fog over everything, the earth, a marble sphere and
// a cloud of 1000 spheres turned and moved as a group. By default the book's quick settings
// (400 x 400, 250 samples per pixel, depth 4); the book's full quality is
// --width 800 --spp 10000 --depth 40. Scene file: tests/data/next_week_final.txt.
//
//   23_next_week_final > 23_next_week_final.ppm
//   23_next_week_final --width 800 --spp 10000 --depth 40 -o 23_next_week_final.png

#include "app_options.h"
#include "next_week_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"23_next_week_final", "Path traces book 2's final scene.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        next_week_scene s = make_next_week_final();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
