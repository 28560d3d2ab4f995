// merge: adds sample slices (`render --samples A:B -o part.pfm`) up to the image of the whole
// render, bit for bit the one `render` writes with the same scene, seed and --spp.
//
//   render scene.txt --spp 64 --samples 0:32 -o a.pfm      (on one machine)
//   render scene.txt --spp 64 --samples 32:64 -o b.pfm     (on another)
//   merge a.pfm b.pfm -o scene.png                         (= render scene.txt --spp 64 -o scene.png)
//
// Slices of different renders (size, samples per pixel, seed, sampler, depth, estimator or the
// scene's files), overlapping slices, and slices that leave samples out are refused with one
// error line; --allow-gaps merges what there is (each pixel the mean of the samples present).
// The output's format follows its extension, as render's does; it is written atomically.

#include <rtweekend/render/fixed_point.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/io/slice_file.h>
#include <rtweekend/core/scene_error.h>

#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

namespace {

struct merge_options {
    std::vector<std::string> slices;
    std::string output;
    bool allow_gaps = false, quiet = false;
};

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: merge SLICE.pfm... -o OUT [--allow-gaps] [--quiet]\n"
                 "Adds sample slices written by `render --samples A:B` up to the image of the whole render.\n"
                 "  SLICE.pfm     slices of one render (same scene, size, --spp, --seed, sampler, depth and\n"
                 "                estimator), in any order, not overlapping\n"
                 "  -o OUT        the image: .ppm, .png, .bmp, .pfm or .exr, as render writes it\n"
                 "  --allow-gaps  merge even if some samples are in no slice: each pixel is then the mean\n"
                 "                of the samples the slices hold (default: an error naming the missing ones)\n"
                 "  --quiet       no summary on stderr\n"
                 "  --help        show this help\n");
}

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "merge: error: %s\n", message.c_str());
    print_usage(stderr);
    std::exit(2);
}

merge_options parse(int argc, char** argv) {
    merge_options o;
    bool options_ended = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (!options_ended && (arg == "--help" || arg == "-h")) {
            print_usage(stdout);
            std::exit(0);
        } else if (!options_ended && arg == "--") {
            options_ended = true;
        } else if (!options_ended && (arg == "-o" || arg == "--output")) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0') usage_error("-o needs a file name");
            o.output = argv[++i];
        } else if (!options_ended && arg == "--allow-gaps") {
            o.allow_gaps = true;
        } else if (!options_ended && (arg == "--quiet" || arg == "-q")) {
            o.quiet = true;
        } else if (!options_ended && arg.size() > 1 && arg[0] == '-') {
            usage_error("unknown option '" + arg + "'");
        } else {
            o.slices.push_back(arg);
        }
    }
    if (o.slices.empty()) usage_error("expected SLICE.pfm... (one or more slices)");
    if (o.output.empty()) usage_error("expected -o OUT");
    return o;
}

std::string range_text(int first, int end) { return std::to_string(first) + " to " + std::to_string(end - 1); }

void merge(const merge_options& o) {
    // Refuse an output that cannot be written before reading gigabytes of slices.
    rt::check_output_path(o.output);
    rt::slice_merger merger;
    for (const std::string& path : o.slices) merger.add(rt::read_slice(path), path); // one slice in memory at a time
    const rt::merged_render m = merger.result(o.allow_gaps);
    rt::write_image(o.output, rt::mean_image(m.sums));
    if (o.quiet) return;
    const int spp = m.render.samples_per_pixel;
    std::string held = "all " + std::to_string(spp) + " samples per pixel";
    if (!m.gaps.empty()) {
        int missing = 0;
        std::string ranges;
        for (const auto& g : m.gaps) {
            missing += g.second - g.first;
            ranges += (ranges.empty() ? "" : ", ") + range_text(g.first, g.second);
        }
        held = std::to_string(spp - missing) + " of " + std::to_string(spp) + " samples per pixel (missing " + ranges + ")";
    }
    const std::string clamped = m.saturated > 0 ? ", " + std::to_string(m.saturated) + " samples clamped" : "";
    std::fprintf(stderr, "merge: %d slice%s of %dx%d, %s: %llu rays, %llu NaN/Inf samples%s; wrote %s\n", m.slices,
                 m.slices == 1 ? "" : "s", m.render.width, m.render.height, held.c_str(),
                 static_cast<unsigned long long>(m.rays), static_cast<unsigned long long>(m.nonfinite), clamped.c_str(),
                 o.output.c_str());
}

} // namespace

int main(int argc, char** argv) {
    const merge_options o = parse(argc, argv);
    try {
        merge(o);
        return 0;
    } catch (const rt::scene_error& e) {
        std::fprintf(stderr, "merge: error: %s\n", e.what());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "merge: error: out of memory\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "merge: error: %s\n", e.what());
    }
    return 1;
}
