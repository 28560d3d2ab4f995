// aov_sheet: a scene's render beside its denoiser guides (render/guides.h), one picture of four
// panels for looking at them (the guides themselves are for programs: `render --aov` writes them
// as EXR channels or PFM files, docs/apps.md):
//
//   aov_sheet scene.txt sheet.png --spp 64
//
//   render  | albedo          the image and the albedo as `render` writes them (the book's gamma 2)
//   --------+--------
//   normal  | depth           the normal as the colour 0.5 + 0.5 n (x red, y green, z blue), as
//                             normal maps show them; the inverse depth, nearest / depth: white
//                             at the nearest point, half as bright twice as far, black where
//                             nothing was hit (a ground to the horizon keeps near things apart)
//
// Takes what `render` takes: a text scene or a model (.obj, .gltf, .glb), at its own size. Exit
// status 1 for a scene it cannot use, 2 for bad usage.

#include "aov_sheet.h"
#include "app_options.h"

#include <rtweekend/camera.h>
#include <rtweekend/core/file.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/io/model_scene.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/render/guides.h>
#include <rtweekend/scene/scene_compiler.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

const app::description d{"aov_sheet", "Renders a scene beside its albedo, normal and depth guides, as one picture.",
                         "SCENE OUT", 2, 2};

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: aov_sheet SCENE OUT [--spp N] [--help]\n"
                 "%s\n"
                 "  SCENE      a text scene (.txt) or a model (.obj, .gltf, .glb), as render takes\n"
                 "  OUT        .png, .ppm or .bmp, written atomically: render | albedo over normal | depth\n"
                 "  --spp N    samples per pixel of the render (default: the scene's); the guides take\n"
                 "             the first 16 at most\n"
                 "  --help     show this help\n",
                 d.summary);
}

struct arguments {
    std::vector<std::string> files;
    int spp = 0; // 0: the scene's
};

arguments parse(int argc, char** argv) {
    arguments args;
    args.files = app::parse_tool_arguments(argc, argv, d, print_usage, [&](const std::string& flag, const auto& value) {
        if (flag != "--spp") return false;
        args.spp = int(app::tool_integer(d, print_usage, flag, value(), 1, 1 << 20));
        return true;
    });
    return args;
}

} // namespace

int main(int argc, char** argv) {
    const arguments args = parse(argc, argv);
    return app::run(d, [&] {
        const std::string& path = args.files[0];
        const rt::scene_description scene = rt::is_model_file(path) ? rt::load_model_scene(path) : rt::load_scene(path);
        for (const std::string& w : scene.warnings) std::fprintf(stderr, "aov_sheet: warning: %s\n", w.c_str());
        const rt::camera_frame frame = scene.cam.frame();
        rt::render_settings settings = scene.cam.effective_settings();
        if (args.spp > 0) settings.samples_per_pixel = args.spp;
        const rt::compiled_scene compiled = rt::compile_scene(scene.world, frame.position, scene.point_lights, scene.directional_lights);
        const rt::guide_images g = rt::render_guides(compiled, frame, scene.cam.sky(), settings);
        const rt::render_result r = rt::path_trace(compiled, frame, scene.cam.sky(), settings);
        const rt::image out = app::aov_sheet_image(r.img, g);
        rt::write_file_atomically(args.files[1],
                                  rt::encode_8bit_image(args.files[1], out.width(), out.height(), rt::encode_8bit(out)));
    });
}
