// render: renders a scene file. A text scene (format: docs/scene-files.md) or a model (an OBJ with
// its MTL materials, a glTF 2.0 .gltf or .glb: docs/models.md) goes through the path tracer, flags
// overriding the camera;
// a CENG795 XML scene (docs/course.md) goes through the Whitted ray tracer, one image per camera,
// named by the camera's ImageName.
//
//   render scene.txt -o scene.png
//   render scene.txt --width 1200 --spp 100 > scene.ppm
//   render model.obj --look-from 2,2,3 -o model.png
//   render model.glb -o model.png
//   render scene.xml -o out/ --bfc on
//   render scene.xml -o out/ --integrator path --spp 256

#include "render_command.h"

int main(int argc, char** argv) {
    const app::description d = app::render_description();
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        const std::string& scene_path = opt.positional[0];
        if (app::is_xml_scene(scene_path)) {
            rt::whitted_scene scene = app::read_xml_scene(opt);
            const std::vector<std::string> outputs = app::xml_output_paths(scene, scene_path, opt.output);
            app::render_xml_scene(opt, scene, outputs);
            return;
        }
        rt::scene_description scene = app::read_text_scene(opt);
        app::render_text_scene(opt, scene);
    });
}
