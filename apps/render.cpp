// render: renders a scene file. A text scene (format: README, "Scene files") goes through the
// path tracer, flags overriding the file's camera settings; a CENG795 XML scene (README,
// "Whitted mode") goes through the Whitted ray tracer, one image per camera, named by the
// camera's ImageName.
//
//   render scene.txt -o scene.png
//   render scene.txt --width 1200 --spp 100 > scene.ppm
//   render scene.xml -o out/ --bfc on
//   render scene.xml -o out/ --integrator path --spp 256
//   render scene.txt --spp 64 --samples 0:32 -o part0.pfm    (a slice, for apps/merge)

#include "render_common.h"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

// A course scene through the path tracer (app::xml_path_settings says what carries over).
void render_xml_path_traced(const app::options& opt, const rt::whitted_scene& scene,
                            const std::vector<std::string>& outputs) {
    rt::render_settings settings = app::xml_path_settings(opt);
    app::catch_interrupts(); // Ctrl-C: the current camera's image so far, then exit 130
    settings.stop = &app::interrupt_requested;
    const rt::environment env = rt::environment::backdrop(rt::vec3f(scene.background));
    const std::vector<rt::point_light> lights = app::xml_path_lights(scene);
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        rt::render_result r = rt::path_trace(scene.world, rt::view_camera_frame(scene.cameras[i]), env, settings, lights);
        rt::write_whitted_image(outputs[i], r.img);
        if (r.stats.interrupted) {
            std::fprintf(stderr,
                         "render: interrupted after %d %% of camera %zu (average %.1f samples per pixel); wrote %s "
                         "with the samples taken\n",
                         int(r.stats.completed * 100), i + 1, r.stats.mean_pixel_samples(), outputs[i].c_str());
            std::exit(130);
        }
        if (!opt.quiet) std::fprintf(stderr, "render: wrote %s\n", outputs[i].c_str());
    }
}

void render_xml(const app::options& opt) {
    const std::string& scene_path = opt.positional[0];
    rt::whitted_scene scene = rt::load_xml_scene(scene_path);
    if (scene.cameras.empty()) throw rt::scene_error(scene_path + ": the scene has no <Camera>: nothing to render");
    std::vector<std::string> outputs = app::output_paths(scene, scene_path, opt.output);
    if (opt.path_integrator) {
        render_xml_path_traced(opt, scene, outputs);
        return;
    }

    rt::whitted_renderer renderer(scene, app::whitted_settings(opt));
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        rt::whitted_render r = renderer.render(i);
        rt::write_whitted_image(outputs[i], r.img);
        if (!opt.quiet) std::fprintf(stderr, "render: wrote %s\n", outputs[i].c_str());
    }
}

// A text scene through the path tracer: the image, or with --samples A:B a slice.
void render_text(const app::options& opt) {
    rt::scene_description scene = app::load_text_scene(opt);
    if (!opt.samples) {
        app::write_output(opt, rt::render(scene.cam, scene.world, scene.point_lights));
        return;
    }
    // The fingerprint of what was read, taken now: the files could change during a long render.
    const std::string fingerprint = rt::scene_fingerprint(scene.files);
    const rt::render_settings settings = app::text_scene_settings(opt, scene.cam);
    rt::render_result r = rt::path_trace(scene.world, scene.cam.frame(), scene.cam.sky(), settings, scene.point_lights);
    app::write_slice_output(opt, settings, r, fingerprint);
}

} // namespace

int main(int argc, char** argv) {
    app::description d{"render", "Renders a scene file: a text scene with the path tracer, or a CENG795 XML scene "
                                 "with the Whitted ray tracer.",
                       "SCENE.txt|SCENE.xml", 1, 1};
    d.xml_scenes = true;
    d.slices = true;
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        if (app::is_xml_scene(opt.positional[0])) render_xml(opt);
        else render_text(opt);
    });
}
