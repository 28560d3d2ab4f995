// compare: how far an image is from a reference (metrics: rtweekend/measure/metrics.h).
//
//   compare render.pfm reference.pfm     linear and 8-bit metrics (.exr works as .pfm does)
//   compare render.png reference.pfm     8-bit metrics (the PFM is encoded as our writers do)
//   compare render.pfm reference.pfm --cells 30    and where the error lies: each 30x30 cell's
//                                        percentage of the summed squared error
//
// stdout starts with one machine-readable line per comparison,
//   linear rmse X relmse Y psnr Z bias R G B nonfinite NA NREF
//   8bit rmse X relmse Y psnr Z bias R G B nonfinite NA NREF
// then the same figures for a reader. Exit status 1 for a file it cannot use, 2 for bad usage.

#include "app_options.h"

#include <rtweekend/image/image_read.h>
#include <rtweekend/measure/metrics.h>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {

const app::description d{"compare", "Compares IMAGE with the reference image REFERENCE and prints error metrics.",
                         "IMAGE REFERENCE", 2, 2};

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: compare IMAGE REFERENCE [--cells N] [--help]\n"
                 "%s\n"
                 "  IMAGE, REFERENCE  PPM (P3 or P6), PFM, EXR, PNG, BMP, JPEG or Radiance HDR files of the same size\n"
                 "  --cells N         also print where the error lies: the image cut into N x N pixel\n"
                 "                    cells from the top left, each cell's percentage of the summed\n"
                 "                    squared error (linear if both files are, else 8-bit codes),\n"
                 "                    one line per row of cells, top row first\n"
                 "  --help            show this help\n"
                 "Two linear files (PFM or EXR) give linear metrics and 8-bit metrics (both encoded as the\n"
                 "writers do, gamma 2); if either file is 8-bit, the linear one is encoded and the metrics\n"
                 "are 8-bit.\n"
                 "RMSE and bias are in the images' units (radiance or 8-bit codes); relMSE divides by\n"
                 "ref^2 + 0.01 on values scaled to white = 1; PSNR's peak is 1 (linear) or 255 (8-bit).\n",
                 d.summary);
}

struct arguments {
    std::vector<std::string> files;
    int cells = 0; // 0: no error map
};

arguments parse(int argc, char** argv) {
    arguments args;
    args.files = app::parse_tool_arguments(argc, argv, d, print_usage, [&](const std::string& flag, const auto& value) {
        if (flag != "--cells") return false;
        args.cells = int(app::tool_integer(d, print_usage, flag, value(), 1, 65536));
        return true;
    });
    return args;
}

std::string size_text(const rt::image& img) { return std::to_string(img.width()) + "x" + std::to_string(img.height()); }

std::string image_summary(const std::string& path, const rt::loaded_image& img) {
    return path + " (" + size_text(img.pixels) + " " + img.format +
           (img.display_encoded ? ", 8-bit display-encoded)" : ", linear)");
}

void print_machine_line(const char* label, const rt::image_error& e) {
    std::printf("%s rmse %.6g relmse %.6g psnr %.6g bias %.6g %.6g %.6g nonfinite %zu %zu\n", label, e.rmse, e.rel_mse,
                e.psnr, e.bias[0], e.bias[1], e.bias[2], e.nonfinite_a, e.nonfinite_ref);
}

void print_readable_line(const char* label, const rt::image_error& e) {
    std::printf("  %-8s %-10.4g %-10.4g %-10.4g %+-10.3g %+-10.3g %+-10.3g\n", label, e.rmse, e.rel_mse, e.psnr,
                e.bias[0], e.bias[1], e.bias[2]);
}

void print_nonfinite_note(const rt::image_error& e, bool linear) {
    if (e.nonfinite_a == 0 && e.nonfinite_ref == 0) return;
    std::printf("  note: NaN/Inf channel values: %zu in the image, %zu in the reference; %s\n", e.nonfinite_a,
                e.nonfinite_ref,
                linear ? "left out of the linear metrics"
                       : "the 8-bit encoding stores NaN as 0 and Inf as 255, as a written file would");
}

} // namespace

int main(int argc, char** argv) {
    const arguments args = parse(argc, argv);
    const std::vector<std::string>& files = args.files;
    return app::run(d, [&] {
        rt::loaded_image a = rt::read_image(files[0]);
        rt::loaded_image ref = rt::read_image(files[1]);
        if (a.pixels.width() != ref.pixels.width() || a.pixels.height() != ref.pixels.height())
            throw rt::scene_error("'" + files[0] + "' is " + size_text(a.pixels) + " but the reference '" + files[1] +
                                  "' is " + size_text(ref.pixels));
        rt::image_comparison c = rt::compare_loaded(a, ref);

        if (c.linear) print_machine_line("linear", *c.linear);
        print_machine_line("8bit", c.display);

        std::printf("\nimage:     %s\nreference: %s\n", image_summary(files[0], a).c_str(), image_summary(files[1], ref).c_str());
        std::printf("  %-8s %-10s %-10s %-10s %-10s %-10s %-10s\n", "", "RMSE", "relMSE", "PSNR (dB)", "bias R", "bias G",
                    "bias B");
        if (c.linear) print_readable_line("linear", *c.linear);
        print_readable_line("8-bit", c.display);
        const char* how = c.linear                                   ? "both encoded as the writers do (gamma 2)"
                          : a.display_encoded && ref.display_encoded ? "the stored codes"
                                                                     : "the linear image encoded as the writers do (gamma 2)";
        std::printf("  (PSNR peak: 1 linear, 255 8-bit; 8-bit compares %s)\n", how);
        if (c.linear) print_nonfinite_note(*c.linear, true);
        print_nonfinite_note(c.display, false);
        if (args.cells > 0) {
            const rt::error_map map = rt::error_shares(a, ref, args.cells);
            std::printf("\nsquared error by %dx%d-pixel cell (%s), percent of the total, top row first:\n", map.cell,
                        map.cell, map.linear ? "linear" : "8-bit codes");
            for (int row = 0; row < map.rows; ++row) {
                for (int col = 0; col < map.columns; ++col) std::printf(col ? " %6.2f" : "%6.2f", 100 * map.at(col, row));
                std::printf("\n");
            }
        }

        std::fflush(stdout);
        if (std::ferror(stdout)) throw rt::scene_error("cannot write the results to standard output");
    });
}
