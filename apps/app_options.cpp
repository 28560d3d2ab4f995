// The shared command line of the apps (app_options.h), compiled once into the library every app
// links (rtweekend_app_options), rather than into each app's own file.

#include "app_options.h"

#include <rtweekend/image/image_write.h>
#include <rtweekend/io/sky_map_file.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <iostream>

#include <time.h> // clock_gettime (POSIX)

namespace app {

// The SIGINT handler. The first asks the render to stop; a repeat within repeated_interrupt_ns is
// ignored; a later one, or any once the render is over, ends the program at once: the default
// action, raised again (it is delivered when the handler returns). clock_gettime and raise are
// async-signal-safe (POSIX.1-2008, 2.4.3).
extern "C" void on_interrupt(int) {
    timespec t{};
    clock_gettime(CLOCK_MONOTONIC, &t);
    const int64_t now = int64_t(t.tv_sec) * 1'000'000'000 + int64_t(t.tv_nsec) + 1; // > 0
    int64_t seen = interrupt_state_rendering;
    if (interrupt_state.compare_exchange_strong(seen, now)) {
        interrupt_requested.store(true);
        return;
    }
    if (seen > 0 && now - seen < repeated_interrupt_ns) return;
    std::signal(SIGINT, SIG_DFL);
    std::raise(SIGINT);
}

void catch_interrupts() {
    static const bool installed = [] {
        std::signal(SIGINT, on_interrupt);
        return true;
    }();
    (void)installed;
    int64_t over = interrupt_state_over;
    interrupt_state.compare_exchange_strong(over, interrupt_state_rendering);
}

void render_over() {
    int64_t rendering = interrupt_state_rendering;
    interrupt_state.compare_exchange_strong(rendering, interrupt_state_over);
}

bool is_xml_scene(const std::string& path) {
    auto dot = path.find_last_of('.');
    if (dot == std::string::npos) return false;
    std::string ext = path.substr(dot);
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext == ".xml" || ext == ".json"; // the course's JSON form reads as its XML
}

void tool_usage_error(const description& d, void (*print_tool_usage)(std::FILE*), const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", d.name, message.c_str());
    print_tool_usage(stderr);
    std::exit(2);
}

std::vector<std::string> parse_tool_arguments(int argc, char** argv, const description& d,
                                              void (*print_tool_usage)(std::FILE*), const tool_option& option) {
    std::vector<std::string> operands;
    bool options_ended = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (options_ended || arg.size() < 2 || arg[0] != '-') {
            operands.push_back(arg);
        } else if (arg == "--help" || arg == "-h") {
            print_tool_usage(stdout);
            std::exit(0);
        } else if (arg == "--") {
            options_ended = true;
        } else {
            const auto value = [&]() -> std::string {
                if (i + 1 >= argc) tool_usage_error(d, print_tool_usage, arg + " needs a value");
                return argv[++i];
            };
            if (!option(arg, value)) tool_usage_error(d, print_tool_usage, "unknown option '" + arg + "'");
        }
    }
    if (operands.size() < d.min_positional || operands.size() > d.max_positional)
        tool_usage_error(d, print_tool_usage,
                         std::string("expected ") + d.operands + ", got " + std::to_string(operands.size()) +
                             (operands.size() == 1 ? " operand" : " operands"));
    return operands;
}

long long tool_integer(const description& d, void (*print_tool_usage)(std::FILE*), const std::string& flag,
                       const std::string& text, long long min, long long max) {
    try {
        return detail::integer_value(flag, text, min, max);
    } catch (const parse_stop& stop) {
        tool_usage_error(d, print_tool_usage, stop.message);
    }
}

double tool_real(const description& d, void (*print_tool_usage)(std::FILE*), const std::string& flag,
                 const std::string& text, double min, double max) {
    try {
        return detail::real_value(flag, text, min, max);
    } catch (const parse_stop& stop) {
        tool_usage_error(d, print_tool_usage, stop.message);
    }
}

void print_usage(const description& d, std::FILE* to) {
    std::fprintf(to,
                 "usage: %s%s%s [--width N] [--spp N] [--depth N] [--threads N] [--seed N] [--adaptive E]\n"
                 "          [--estimator nee|bsdf|mixture] [--sampler sobol|stratified|independent] [--caustic-paths X]\n"
                 "          [--filter F] [--look-from X,Y,Z] [--look-at X,Y,Z] [--fov DEG] [--sky-map FILE]\n"
                 "          [-o FILE] [--quiet]\n"
                 "%s\n"
                 "  --width N    image width in pixels (height follows the aspect ratio)\n"
                 "  --spp N      samples per pixel\n"
                 "  --depth N    maximum rays per path (the book's max_depth)\n"
                 "  --threads N  worker threads (0 = all cores)\n"
                 "  --seed N     random seed (same seed, same image)\n"
                 "  --adaptive E adaptive sampling: a pixel stops once its 95%% interval is narrow enough\n"
                 "               relative to its value, E the target (--spp is then the most a pixel\n"
                 "               takes; 0 = off)\n"
                 "  --estimator E how light is found: nee (light sampling and material sampling weighed\n"
                 "               by multiple importance sampling; default), bsdf (the books' path tracer of\n"
                 "               books 1 and 2) or mixture (book 3's one-sample mixture)\n"
                 "  --sampler S  where each sample's random numbers come from: sobol (Owen-scrambled Sobol\n"
                 "               in Morton order, error spread as blue noise; default), stratified\n"
                 "               (jittered) or independent (plain random numbers)\n"
                 "  --caustic-paths X with nee: X light paths per pixel per sample find the caustics\n"
                 "               (light through glass or off mirrors onto a surface the camera sees) from\n"
                 "               the lights; default 0.25, 0 = leave them to the camera paths\n"
                 "  --filter F   the pixel filter: box (the books'; default), tent[:R] (radius R, 1),\n"
                 "               gaussian[:SIGMA] (0.5; radius 3 sigma) or mitchell[:B,C] (1/3,1/3; radius\n"
                 "               2), each sampled by importance, so pixels stay independent\n"
                 "  --look-from X,Y,Z, --look-at X,Y,Z, --fov DEG  the camera's position, the point it looks at,\n"
                 "               and its vertical field of view in degrees, over the scene's (a model's default\n"
                 "               view: docs/models.md)\n"
                 "  --sky-map FILE a lat-long picture of the sky (EXR, HDR, PFM; PNG or JPEG sRGB-decoded),\n"
                 "               lighting the scene and light-sampled, in place of its sky or background\n"
                 "  -o FILE      write FILE (.ppm, .png, .bmp, or linear .pfm or .exr); default: P3 PPM on stdout\n"
                 "  --quiet      no progress or statistics on stderr\n"
                 "  --help       show this help\n",
                 d.name, d.operands[0] ? " " : "", d.operands, d.summary);
    if (d.time_budget)
        std::fprintf(to,
                     "  --time S     a time budget: passes of samples (of --spp at most) until S seconds are spent;\n"
                     "               the image of the passes completed, the same as `--samples 0:M` of them\n"
                     "  --preview S  render in passes and rewrite -o FILE (atomically) after a pass once S seconds\n"
                     "               have passed since it was last written: a viewer that reloads shows it converge\n");
    if (d.aovs)
        std::fprintf(to,
                     "  --aov LIST   also write guides for a denoiser, any of albedo,normal,depth,position: as\n"
                     "               channels of -o FILE.exr (albedo.R, N.X, Z, P.X, ...), else as FILE.albedo.pfm, ...\n"
                     "  --aov-only   write the guides alone (fast), no render\n");
    if (d.slices)
        std::fprintf(to,
                     "  --samples A:B render samples A to B-1 of every pixel (of a render of --spp N, B <= N) and\n"
                     "               write them as a slice: -o must name a .pfm file, which holds the slice's\n"
                     "               mean as an image and its exact sums; `merge` adds slices up to the whole\n"
                     "               render's image (text scenes, uniform sampling)\n");
    if (d.xml_scenes)
        std::fprintf(to,
                     "For a CENG795 scene (.xml, or the course's JSON form, .json), every camera is rendered by the\n"
                     "course's renderer it names (the Whitted ray tracer, or its path tracer) to its ImageName (.png,\n"
                     ".ppm, .pfm or .exr); only --threads, --quiet and these apply:\n"
                     "  -o DIR       write the images into DIR (created if missing); default: the current directory\n"
                     "  --spp N      every camera's NumSamples (a quick preview of a long render, or more)\n"
                     "  --bfc on|off back-face culling for primary and reflected rays of opaque objects (default off)\n"
                     "  --integrator path\n"
                     "               render every camera with our path tracer instead (point, directional,\n"
                     "               spot, area, object and environment lights with indirect light, the\n"
                     "               diffuse reflectance as a Lambertian albedo); --spp (its samples), --depth,\n"
                     "               --seed, --adaptive, --estimator, --sampler, --caustic-paths and --filter\n"
                     "               then apply too\n");
}

[[noreturn]] void usage_error(const description& d, const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", d.name, message.c_str());
    print_usage(d, stderr);
    std::exit(2);
}

namespace detail {

[[noreturn]] void stop_parsing(const std::string& message) { throw parse_stop{2, message}; }

long long integer_value(const std::string& flag, const std::string& text, long long min, long long max) {
    errno = 0;
    char* end = nullptr;
    long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || end == text.c_str() || *end != '\0' || errno == ERANGE)
        stop_parsing(flag + " needs an integer, got '" + text + "'");
    if (v < min || v > max)
        stop_parsing(flag + " must be between " + std::to_string(min) + " and " + std::to_string(max) + ", got " + text);
    return v;
}

double real_value(const std::string& flag, const std::string& text, double min, double max) {
    errno = 0;
    char* end = nullptr;
    double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end == text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
        stop_parsing(flag + " needs a number, got '" + text + "'");
    if (v < min || v > max)
        stop_parsing(flag + " must be between " + std::to_string(min) + " and " + std::to_string(max) + ", got " + text);
    return v;
}

} // namespace detail

long long parse_integer(const description& d, const std::string& flag, const std::string& text, long long min,
                        long long max) {
    try {
        return detail::integer_value(flag, text, min, max);
    } catch (const parse_stop& stop) {
        usage_error(d, stop.message);
    }
}

double parse_real(const description& d, const std::string& flag, const std::string& text, double min,
                  double max) {
    try {
        return detail::real_value(flag, text, min, max);
    } catch (const parse_stop& stop) {
        usage_error(d, stop.message);
    }
}

options parse_arguments(int argc, char** argv, const description& d) {
    using detail::stop_parsing;
    options o;
    o.program = d.name;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i], value;
        bool has_inline_value = false;
        if (arg.rfind("--", 0) == 0) {
            auto eq = arg.find('=');
            if (eq != std::string::npos) {
                value = arg.substr(eq + 1);
                arg = arg.substr(0, eq);
                has_inline_value = true;
            }
        }
        auto next = [&]() -> std::string {
            if (has_inline_value) return value;
            if (i + 1 >= argc) stop_parsing(arg + " needs a value");
            return argv[++i];
        };
        auto integer = [&](long long min, long long max) { return detail::integer_value(arg, next(), min, max); };
        constexpr long long max_size = 1 << 16;
        if (arg == "--help" || arg == "-h") {
            throw parse_stop{0, ""};
        } else if (arg == "--width") o.width = int(integer(1, max_size));
        else if (arg == "--spp") o.spp = int(integer(1, 1 << 24));
        else if (arg == "--depth") o.depth = int(integer(1, 1 << 16));
        else if (arg == "--threads") o.threads = int(integer(0, 1024));
        else if (arg == "--seed") o.seed = uint64_t(integer(0, INT64_MAX));
        else if (arg == "--adaptive") o.adaptive = detail::real_value(arg, next(), 0, 1e6);
        else if (arg == "--caustic-paths") o.caustic_paths = detail::real_value(arg, next(), 0, 1024);
        else if (arg == "--estimator") {
            std::string v = next();
            rt::path_estimator e;
            if (!rt::parse_estimator(v, e)) stop_parsing("--estimator needs nee, bsdf or mixture, got '" + v + "'");
            o.estimator = e;
        } else if (arg == "--sky-map") {
            o.sky_map = next();
        } else if (arg == "--filter") {
            const std::string v = next();
            try {
                o.filter = rt::parse_pixel_filter(v);
            } catch (const rt::scene_error& e) {
                stop_parsing(std::string("--filter: ") + e.what());
            }
        } else if (arg == "--sampler") {
            std::string v = next();
            rt::sampler_kind k;
            if (!rt::parse_sampler(v, k))
                stop_parsing("--sampler needs sobol, stratified or independent, got '" + v + "'");
            o.sampler = k;
        } else if (arg == "--look-from" || arg == "--look-at") {
            // Three numbers, comma-separated: X,Y,Z.
            const std::string v = next();
            double xyz[3];
            size_t start = 0;
            for (int k = 0; k < 3; ++k) {
                const size_t comma = k < 2 ? v.find(',', start) : v.size();
                if (comma == std::string::npos) stop_parsing(arg + " needs X,Y,Z, got '" + rt::token_text(v) + "'");
                xyz[k] = detail::real_value(arg, v.substr(start, comma - start), -1e30, 1e30);
                start = comma + 1;
            }
            (arg == "--look-from" ? o.look_from : o.look_at) = rt::point3(xyz[0], xyz[1], xyz[2]);
        } else if (arg == "--fov") {
            o.fov = detail::real_value(arg, next(), 1e-3, 179);
        } else if (arg == "--time" && d.time_budget) {
            o.time_budget = detail::real_value(arg, next(), 1e-3, 1e7);
        } else if (arg == "--aov" && d.aovs) {
            const std::string v = next();
            size_t start = 0;
            while (start <= v.size()) {
                const size_t comma = std::min(v.find(',', start), v.size());
                const std::string name = v.substr(start, comma - start);
                if (name != "albedo" && name != "normal" && name != "depth" && name != "position")
                    stop_parsing("--aov: unknown output '" + rt::token_text(name) + "' (expected albedo, normal, depth or position)");
                if (std::find(o.aovs.begin(), o.aovs.end(), name) == o.aovs.end()) o.aovs.push_back(name);
                start = comma + 1;
            }
        } else if (arg == "--aov-only" && d.aovs) {
            if (has_inline_value) stop_parsing("--aov-only takes no value");
            o.aov_only = true;
        } else if (arg == "--preview" && d.time_budget) {
            o.preview = detail::real_value(arg, next(), 0, 1e7); // 0: after every pass
        } else if (arg == "--integrator" && d.xml_scenes) {
            std::string v = next();
            if (v != "path" && v != "whitted") stop_parsing("--integrator needs path or whitted, got '" + v + "'");
            o.path_integrator = v == "path";
        } else if (arg == "--samples" && d.slices) {
            const std::string v = next();
            const size_t colon = v.find(':');
            if (colon == std::string::npos) stop_parsing("--samples needs A:B (samples A to B-1), got '" + v + "'");
            const int a = int(detail::integer_value(arg + " (first)", v.substr(0, colon), 0, (1 << 24) - 1));
            const int b = int(detail::integer_value(arg + " (end)", v.substr(colon + 1), 1, 1 << 24));
            if (b <= a) stop_parsing("--samples A:B needs A < B (samples A to B-1), got '" + v + "'");
            o.samples = std::make_pair(a, b);
        } else if (arg == "--bfc" && d.xml_scenes) {
            std::string v = next();
            if (v != "on" && v != "off") stop_parsing("--bfc needs on or off, got '" + v + "'");
            o.cull_back_faces = v == "on";
        }
        else if (arg == "-o" || arg == "--output") {
            o.output = next();
            if (o.output.empty()) stop_parsing("-o needs a file name");
        } else if (arg == "--quiet" || arg == "-q") {
            if (has_inline_value) stop_parsing("--quiet takes no value");
            o.quiet = true;
        } else if (arg.size() > 1 && arg[0] == '-') stop_parsing("unknown option '" + arg + "'");
        else o.positional.push_back(arg);
    }
    if (o.positional.size() < d.min_positional || o.positional.size() > d.max_positional)
        stop_parsing(d.max_positional == 0 ? "unexpected argument '" + o.positional.front() + "'"
                                           : std::string("expected ") + d.operands);
    const bool xml = d.xml_scenes && !o.positional.empty() && is_xml_scene(o.positional[0]);
    if (xml && !o.path_integrator && (o.width || o.depth || o.adaptive || o.seed || o.estimator || o.sampler || o.filter))
        stop_parsing("--depth, --adaptive, --seed, --estimator, --sampler and --filter apply to XML scenes only "
                     "with --integrator path, and --width never does (their files set the resolution)");
    if (xml && o.width) stop_parsing("--width does not apply to XML scenes (their files set the resolution)");
    if (o.time_budget && (xml || o.samples || o.adaptive.value_or(0) > 0))
        stop_parsing("--time applies to text scenes and models, without --samples or --adaptive");
    if (o.preview && (xml || o.samples || o.adaptive.value_or(0) > 0))
        stop_parsing("--preview applies to text scenes and models, without --samples or --adaptive");
    if (o.preview && o.output.empty()) stop_parsing("--preview needs -o FILE (the image it rewrites)");
    if (o.aov_only && o.aovs.empty()) stop_parsing("--aov-only needs --aov LIST (the guides to write)");
    if (!o.aovs.empty() && (xml || o.samples)) stop_parsing("--aov applies to text scenes and models, without --samples");
    if (!o.aovs.empty() && o.output.empty()) stop_parsing("--aov needs -o FILE (the guides are written beside it)");
    if (o.aov_only && (o.time_budget || o.preview)) stop_parsing("--aov-only renders no image: not with --time or --preview");
    if (xml && o.sky_map) stop_parsing("--sky-map applies to text scenes and models (an XML scene has its own lights)");
    if (xml && (o.look_from || o.look_at || o.fov))
        stop_parsing("--look-from, --look-at and --fov apply to text scenes and models (XML cameras are the file's)");
    if (xml && o.path_integrator && o.cull_back_faces) stop_parsing("--bfc applies to the Whitted integrator only");
    if (!xml && o.path_integrator) stop_parsing("--integrator applies to XML scenes only (text scenes are path traced)");
    if (!xml && o.cull_back_faces) stop_parsing("--bfc applies to XML scenes only");
    if (o.samples) {
        if (xml) stop_parsing("--samples applies to text scenes only");
        if (o.adaptive.value_or(0) > 0)
            stop_parsing("--samples and --adaptive do not go together (adaptive sampling decides the counts)");
        if (rt::lowercase_extension(o.output) != ".pfm") stop_parsing("--samples writes a slice: -o must name a .pfm file");
    }
    if (!o.output.empty() && !xml && d.check_output) {
        // Refuse a bad output path before rendering, not after.
        try {
            rt::check_output_path(o.output);
        } catch (const rt::scene_error& e) {
            throw parse_stop{1, e.what()};
        }
    }
    return o;
}

options parse(int argc, char** argv, const description& d) {
    try {
        return parse_arguments(argc, argv, d);
    } catch (const parse_stop& stop) {
        if (stop.status == 0) {
            print_usage(d, stdout);
            std::exit(0);
        }
        if (stop.status == 2) usage_error(d, stop.message);
        std::fprintf(stderr, "%s: error: %s\n", d.name, stop.message.c_str());
        std::exit(stop.status);
    }
}

void write_output(const options& o, const rt::image& img) {
    if (o.output.empty()) {
        rt::write_ppm(std::cout, img);
        std::cout.flush();
        if (!std::cout) throw rt::scene_error("cannot write the image to standard output");
    } else {
        rt::write_image(o.output, img);
    }
}

void write_output(const options& o, const rt::render_result& r) {
    render_over();
    write_output(o, r.img);
    if (!r.stats.interrupted) return;
    const rt::render_stats& s = r.stats;
    const std::string where = o.output.empty() ? "the image to standard output" : o.output;
    std::string done;
    char text[160];
    if (!(o.adaptive.value_or(0) > 0)) { // adaptive sampling does not know its total ahead
        std::snprintf(text, sizeof text, "after %d %% ", int(s.completed * 100));
        done = text;
    }
    std::snprintf(text, sizeof text, "(average %.1f samples per pixel, %d to %d)", s.mean_pixel_samples(),
                  s.min_pixel_samples, s.max_pixel_samples);
    std::string note = done + text;
    if (s.pixels_without_samples > 0)
        note += "; " + std::to_string(s.pixels_without_samples) + " pixels took no sample and are black";
    std::fprintf(stderr, "%s: interrupted %s; wrote %s with the samples taken\n", o.program.c_str(), note.c_str(),
                 where.c_str());
    std::fflush(nullptr);
    std::exit(130);
}

void options::apply(rt::camera& cam) const {
    if (width) {
        cam.image_width = *width;
        cam.image_height = 0; // keep the aspect ratio
    }
    if (spp) cam.samples_per_pixel = *spp;
    if (depth) cam.max_depth = *depth;
    if (threads) cam.settings.threads = *threads;
    if (adaptive) cam.settings.adaptive_error = *adaptive;
    if (seed) cam.settings.seed = *seed;
    if (estimator) cam.settings.estimator = *estimator;
    if (sampler) cam.settings.sampler = *sampler;
    if (caustic_paths) cam.settings.caustic_paths = *caustic_paths;
    if (filter) cam.filter = *filter;
    if (look_from) cam.lookfrom = *look_from;
    if (look_at) cam.lookat = *look_at;
    if (fov) cam.vfov = *fov;
    if (sky_map) cam.sky_map = rt::load_sky_map(*sky_map, 1.0);
    cam.settings.quiet = quiet;
    // Ctrl-C during the render: the image so far (see the top).
    catch_interrupts();
    cam.settings.stop = &interrupt_requested;
}

} // namespace app
