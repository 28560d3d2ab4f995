// tonemap: a linear image (EXR, PFM or Radiance HDR) to an 8-bit PNG (or PPM, BMP) through the photographic
// tone reproduction operator (Reinhard et al. 2002) exactly as CENG795's homework 5 uses it
// (rtweekend/image/tonemap.h has the formulas):
//
//   tonemap render.exr render.png --key 0.18 --burn 1 --saturation 1 --gamma 2.2
//
// `render` writes such pairs itself for a course camera with a <Tonemap>. Exit status 1 for a file
// it cannot use, 2 for bad usage.

#include "app_options.h"

#include <rtweekend/core/file.h>
#include <rtweekend/image/image_read.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/image/tonemap.h>

#include <cstdio>
#include <string>
#include <vector>

namespace {

const app::description d{"tonemap", "Tone maps a linear image with the photographic operator and writes it as 8 bits.",
                         "IN OUT", 2, 2};

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: tonemap IN OUT [--key K] [--burn B] [--saturation S] [--gamma G] [--help]\n"
                 "%s\n"
                 "  IN              a linear image: EXR, PFM or Radiance HDR\n"
                 "  OUT             .png, .ppm or .bmp, written atomically\n"
                 "  --key K         the grey the log-average luminance maps to (default 0.18)\n"
                 "  --burn B        percent of the pixels burnt out to white, in [0, 100) (default 0)\n"
                 "  --saturation S  0 grey, 1 the image's colours (default 1)\n"
                 "  --gamma G       display gamma: out = clamp(C)^(1/G) (default 2.2)\n"
                 "  --help          show this help\n"
                 "Bytes are truncated, not rounded, as the course's reference images are.\n",
                 d.summary);
}

struct arguments {
    std::vector<std::string> files;
    rt::photographic_tonemap tonemap;
};

arguments parse(int argc, char** argv) {
    arguments args;
    args.files = app::parse_tool_arguments(argc, argv, d, print_usage, [&](const std::string& flag, const auto& value) {
        auto number = [&](double min, double max) { return app::tool_real(d, print_usage, flag, value(), min, max); };
        if (flag == "--key") args.tonemap.key = number(1e-300, 1e300);
        else if (flag == "--burn") args.tonemap.burn = number(0, 99.999999);
        else if (flag == "--saturation") args.tonemap.saturation = number(0, 1e6);
        else if (flag == "--gamma") args.tonemap.gamma = number(1e-6, 1e6);
        else return false;
        return true;
    });
    return args;
}

} // namespace

int main(int argc, char** argv) {
    const arguments args = parse(argc, argv);
    return app::run(d, [&] {
        const rt::loaded_image in = rt::read_image(args.files[0]);
        if (in.display_encoded)
            throw rt::scene_error("'" + args.files[0] + "' is an 8-bit " + in.format +
                                  " image: tone mapping needs linear radiance (EXR, PFM or Radiance HDR)");
        const std::vector<unsigned char> bytes = rt::tonemap_photographic(in.pixels, args.tonemap);
        rt::write_file_atomically(args.files[1], rt::encode_8bit_image(args.files[1], in.pixels.width(),
                                                                        in.pixels.height(), bytes));
    });
}
