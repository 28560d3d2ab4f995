// render: renders a scene file (format: README, "Scene files"). Flags override the file's
// camera settings.
//
//   render scene.txt -o scene.png
//   render scene.txt --width 1200 --spp 100 > scene.ppm

#include "app_options.h"

#include <rtweekend/render.h>
#include <rtweekend/scene_io.h>

int main(int argc, char** argv) {
    const app::description d{"render", "Renders a scene file.", "SCENE.txt", 1, 1};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        rt::scene_description scene = rt::load_scene(opt.positional[0]);
        opt.apply(scene.cam);
        app::write_output(opt, scene.cam.render_image(scene.world));
    });
}
