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

[[noreturn]] void usage_error(const std::string& message) { app::tool_usage_error(d, print_usage, message); }

struct arguments {
    std::vector<std::string> files;
    rt::photographic_tonemap tonemap;
};

arguments parse(int argc, char** argv) {
    arguments args;
    bool options_ended = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&](double min, double max) {
            if (i + 1 >= argc) usage_error(arg + " needs a value");
            try {
                return app::detail::real_value(arg, argv[++i], min, max);
            } catch (const app::parse_stop& stop) {
                usage_error(stop.message);
            }
        };
        if (!options_ended && (arg == "--help" || arg == "-h")) {
            print_usage(stdout);
            std::exit(0);
        } else if (!options_ended && arg == "--key") {
            args.tonemap.key = value(1e-300, 1e300);
        } else if (!options_ended && arg == "--burn") {
            args.tonemap.burn = value(0, 99.999999);
        } else if (!options_ended && arg == "--saturation") {
            args.tonemap.saturation = value(0, 1e6);
        } else if (!options_ended && arg == "--gamma") {
            args.tonemap.gamma = value(1e-6, 1e6);
        } else if (!options_ended && arg == "--") {
            options_ended = true;
        } else if (!options_ended && arg.size() > 1 && arg[0] == '-') {
            usage_error("unknown option '" + arg + "'");
        } else {
            args.files.push_back(arg);
        }
    }
    if (args.files.size() != 2)
        usage_error(std::string("expected ") + d.operands + " (two file names), got " + std::to_string(args.files.size()));
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
