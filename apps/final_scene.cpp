// final_scene: the book-1 cover, 1200x675 at 10 samples per pixel by default (the book's final
// render uses --spp 500).
//
//   final_scene > image.ppm
//   final_scene --spp 500 -o cover.png

#include "app_options.h"
#include "cover_scene.h"

int main(int argc, char** argv) {
    const app::description d{"final_scene", "Renders the cover of Ray Tracing in One Weekend.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        rt::hittable_list world = make_cover_scene();
        rt::camera cam = make_cover_camera();
        opt.apply(cam);
        app::write_output(opt, rt::render(cam, world));
    });
}
