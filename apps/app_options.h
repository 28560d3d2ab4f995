#pragma once
// The command line every app shares:
//   --width N  --spp N  --depth N  --threads N  --seed N  --adaptive E  -o FILE  --quiet  --help
// and the way every app ends: the image to FILE (format by extension) or a P3 PPM on stdout,
// and one "app: error: ..." line with exit status 1 for bad input, 2 for bad usage.
//
// Ctrl-C (SIGINT) during a render stops it cleanly: options::apply() points the camera's stop
// flag at interrupt_requested and installs on_interrupt() for SIGINT; the render returns the mean
// of the samples each pixel took so far, write_output() writes that image (atomically, like any
// output), says on stderr what it holds, and the app exits with status 130 (128 + SIGINT, as a
// shell reports a process killed by it). A second Ctrl-C, or one once the render is over, kills at
// once; a second SIGINT within half a second of the first is the same request delivered twice
// (see on_interrupt, app_options.cpp).

#include <rtweekend/camera.h>
#include <rtweekend/image/image.h>
#include <rtweekend/render/pixel_filter.h>
#include <rtweekend/render/scheduler.h>
#include <rtweekend/core/scene_error.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace app {

// Set by the SIGINT handler, read by the renderer's workers (render_settings::stop). With
// interrupt_state below, the only mutable globals of the project, and necessarily so: a signal
// handler can reach nothing else. Both are lock-free atomics, which a handler may touch (C++17
// [support.signal]).
inline std::atomic<bool> interrupt_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler may only touch lock-free atomics");

// Where the render is, for the handler: rendering and not yet asked to stop (0), asked to stop at
// this CLOCK_MONOTONIC time in nanoseconds (> 0), or over, its image being written (-1).
inline constexpr int64_t interrupt_state_rendering = 0, interrupt_state_over = -1;
inline std::atomic<int64_t> interrupt_state{interrupt_state_rendering};
static_assert(std::atomic<int64_t>::is_always_lock_free, "a signal handler may only touch lock-free atomics");

// A second SIGINT this soon after the first is the same request: GNU timeout signals the program
// and then its whole process group, so `timeout -s INT` delivers two SIGINTs microseconds apart
// (more on a loaded machine), and a handler that ran between them used to be killed by the second.
// A person's second Ctrl-C comes later than this.
inline constexpr int64_t repeated_interrupt_ns = 500'000'000;

// Installs on_interrupt() for SIGINT (once), and makes a render that starts after an earlier one
// was written stoppable by Ctrl-C again.
void catch_interrupts();

// The render is over: from here on Ctrl-C ends the program at once (outputs are written
// atomically, so that leaves no half-written file), unless it repeats a request to stop that came
// during the render (on_interrupt).
void render_over();

struct options {
    std::optional<int> width, spp, depth, threads;
    std::optional<double> adaptive;
    std::optional<uint64_t> seed;
    std::optional<bool> cull_back_faces; // --bfc on|off (apps that render XML scenes)
    std::optional<rt::path_estimator> estimator; // --estimator nee|bsdf|mixture
    std::optional<rt::sampler_kind> sampler;     // --sampler independent|stratified|sobol
    std::optional<double> caustic_paths;         // --caustic-paths X
    std::optional<rt::pixel_filter> filter;      // --filter box|tent[:R]|gaussian[:SIGMA]|mitchell[:B,C]
    std::optional<rt::point3> look_from, look_at; // --look-from X,Y,Z, --look-at X,Y,Z (text scenes, models)
    std::optional<double> fov;                    // --fov DEGREES: the vertical field of view
    std::optional<std::string> sky_map;           // --sky-map FILE: a lat-long sky lighting the scene (camera::sky_map)
    std::optional<double> time_budget;            // --time SECONDS: passes of samples until it is spent
    std::optional<double> preview;                // --preview SECONDS: -o rewritten after passes this far apart
    std::vector<std::string> aovs;                // --aov albedo,normal,depth,position: denoiser guides (render/guides.h)
    bool aov_only = false;                        // --aov-only: the guides without the render
    bool path_integrator = false;        // --integrator path (XML scenes: the path tracer, not Whitted)
    // --samples A:B (apps that write slices): samples A to B - 1 of every pixel, written as a slice
    // (rtweekend/io/slice_file.h) for `merge`.
    std::optional<std::pair<int, int>> samples;
    std::string output; // empty: PPM on stdout
    bool quiet = false;
    std::vector<std::string> positional;
    std::string program; // the app's name, for messages

    // Applies the flags that were given on top of the app's own camera settings.
    void apply(rt::camera& cam) const;
};

struct description {
    const char* name;     // program name, for messages
    const char* summary;  // one line: what the app shows
    const char* operands; // positional arguments in the usage line, or ""
    size_t min_positional = 0, max_positional = 0;
    // Set by apps that render CENG795 XML scenes: they take --bfc, and -o may name a directory.
    bool xml_scenes = false;
    // Set by apps that render sample slices: they take --samples A:B.
    bool slices = false;
    // Set by apps that take a time budget, --time S (render; render_mpi's ranks cannot stop apart).
    bool time_budget = false;
    // Set by apps that write denoiser guides, --aov LIST (render).
    bool aovs = false;
    // Whether parse() checks that -o can be written. render_mpi checks it itself, on rank 0 only
    // (the only rank that writes) and agreed with the others, so that no rank exits alone.
    bool check_output = true;
};

// Whether a scene file is a CENG795 XML scene (by extension), rather than a text scene.
bool is_xml_scene(const std::string& path);

void print_usage(const description& d, std::FILE* to);

// For a tool with a parser of its own (compare, tonemap, aov_sheet): "NAME: error: MESSAGE" and
// the tool's usage (print_tool_usage) on stderr, then exit status 2.
[[noreturn]] void tool_usage_error(const description& d, void (*print_tool_usage)(std::FILE*), const std::string& message);

// A tool's command line, the common part: --help or -h prints the tool's usage on stdout and
// exits 0; "--" ends the options; every other argument that starts with '-' goes to
// option(flag, value), which returns whether it knows the flag and calls value() for the
// argument after it ("FLAG needs a value" when there is none). An unknown option, or a number of
// operands outside d's [min_positional, max_positional], is a usage error (tool_usage_error).
// Returns the operands in order.
using tool_option = std::function<bool(const std::string& flag, const std::function<std::string()>& value)>;
std::vector<std::string> parse_tool_arguments(int argc, char** argv, const description& d,
                                              void (*print_tool_usage)(std::FILE*), const tool_option& option);

// A tool flag's number within [min, max] (finite, for a real); a usage error (tool_usage_error)
// otherwise.
long long tool_integer(const description& d, void (*print_tool_usage)(std::FILE*), const std::string& flag,
                       const std::string& text, long long min, long long max);
double tool_real(const description& d, void (*print_tool_usage)(std::FILE*), const std::string& flag,
                 const std::string& text, double min, double max);

[[noreturn]] void usage_error(const description& d, const std::string& message);

// Why parse_arguments() gave no options to run with, thrown by it: what parse() prints and the
// status it exits with. Status 2, a usage error: "app: error: MESSAGE", then the usage, on stderr;
// status 1, an output path that cannot be written: "app: error: MESSAGE" alone; status 0, --help:
// the usage on stdout (no message).
struct parse_stop {
    int status;
    std::string message;
};

namespace detail {

[[noreturn]] void stop_parsing(const std::string& message);

long long integer_value(const std::string& flag, const std::string& text, long long min, long long max);

double real_value(const std::string& flag, const std::string& text, double min, double max);

} // namespace detail

// An integer flag's value within [min, max]; a usage error (exit 2) otherwise.
long long parse_integer(const description& d, const std::string& flag, const std::string& text, long long min,
                        long long max);

// A real flag's value, finite and within [min, max]; a usage error (exit 2) otherwise.
double parse_real(const description& d, const std::string& flag, const std::string& text, double min,
                  double max);

// The command line read into options, without printing or exiting: throws parse_stop instead
// (a usage error, an unwritable output path, or --help). parse() is this for an app's main; a
// caller that must not exit (the command-line fuzzer) calls it directly.
options parse_arguments(int argc, char** argv, const description& d);

// The command line read into options; on bad usage, an unwritable output path or --help, prints
// what parse_stop says (above) and exits with its status.
options parse(int argc, char** argv, const description& d);

// Writes the image where the options say: -o FILE, or a P3 PPM on stdout.
void write_output(const options& o, const rt::image& img);

// Writes a render's image as write_output(o, img) does; if Ctrl-C stopped the render, then says
// on stderr how far it got and how many samples the image holds (no image format carries the
// note: PFM, for one, has no place for comments), and exits with status 130.
void write_output(const options& o, const rt::render_result& r);

// Runs an app's body, turning scene_error (and any other failure) into one error line.
template <class Body>
int run(const description& d, Body&& body) {
    try {
        body();
        return 0;
    } catch (const rt::scene_error& e) {
        std::fprintf(stderr, "%s: error: %s\n", d.name, e.what());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: error: out of memory\n", d.name);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", d.name, e.what());
    }
    return 1;
}

} // namespace app
