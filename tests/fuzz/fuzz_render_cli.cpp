// libFuzzer harness: the command line of apps/render, and the scene file it names.
//
// The input's first line is the command line after "render", split into words at spaces and tabs
// (no quoting); the rest of the input is the scene file. The words go through the parser render
// uses (app::parse_arguments, which throws what app::parse would print and exit with); a parse
// error must be one clear line. When the parser accepts, the scene file is written under the
// name the command line gave it, and the steps of render's main run (apps/render_command.h):
// load the scene with the flags applied, then render and write -o FILE (or -o DIR for an XML
// scene); in between, the image is made tiny (tiny_render.h: at most 8x8 pixels, 2 samples, depth
// 4; XML cameras 4x4, 3 bounces; one thread, quiet). A refused scene must give one clear error
// line. Without -o, a text scene's image goes to stdout.ppm rather than stdout. A --samples A:B
// slice that fits the scene's samples per pixel is cut to one sample that fits the tiny render.
//
// Containment: the harness runs inside this process's scratch directory, emptied before each
// input, and every word loses its '/' and '\' characters (a word of dots only becomes "_"), so
// every path the command line names lies inside that directory.

#include "fuzz_support.h"
#include "tiny_render.h"

#include "render_command.h"

#include <algorithm>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace {

// A word that names nothing outside the current directory.
std::string contained(std::string word) {
    for (char& c : word)
        if (c == '/' || c == '\\') c = '_';
    if (!word.empty() && word.find_first_not_of('.') == std::string::npos) word = "_";
    return word;
}

std::vector<std::string> command_words(const std::string& line) {
    std::vector<std::string> words{"render"};
    std::string word;
    for (char c : line + ' ') {
        if (c != ' ' && c != '\t' && c != '\0') {
            word += c;
        } else if (!word.empty()) {
            if (words.size() < 64) words.push_back(contained(word));
            word.clear();
        }
    }
    return words;
}

void run(const std::string& command_line, const std::string& scene_text) {
    const app::description d = app::render_description();
    std::vector<std::string> words = command_words(command_line);
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    app::options opt;
    try {
        opt = app::parse_arguments(int(words.size()), argv.data(), d);
    } catch (const app::parse_stop& stop) {
        if (stop.status != 0) fuzz::refused(rt::scene_error(stop.message));
        return;
    }
    const std::string& scene_path = opt.positional[0];
    // A name too long for the file system leaves no file: loading then says so.
    std::ofstream(scene_path, std::ios::binary) << scene_text;
    opt.threads = 1;
    opt.quiet = true;
    try {
        if (app::is_xml_scene(scene_path)) {
            if (opt.path_integrator) { // render's defaults are 64 samples and depth 10
                opt.spp = std::min(opt.spp.value_or(64), 2);
                opt.depth = std::min(opt.depth.value_or(10), 4);
            }
            rt::whitted_scene scene = app::read_xml_scene(opt);
            fuzz::shrink(scene);
            const std::vector<std::string> outputs = app::xml_output_paths(scene, scene_path, opt.output);
            app::render_xml_scene(opt, scene, outputs);
        } else {
            if (opt.output.empty()) opt.output = "stdout.ppm";
            rt::scene_description scene = app::read_text_scene(opt);
            // --samples A:B within the scene's samples per pixel stays within them once they are
            // cut to 2: one sample, from A = 0 or 1 (beyond them, render refuses it as it would).
            if (opt.samples && opt.samples->second <= scene.cam.samples_per_pixel) {
                const int first = std::min(opt.samples->first, 1);
                opt.samples = std::make_pair(first, first + 1);
            }
            fuzz::shrink(scene.cam);
            app::render_text_scene(opt, scene);
        }
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const bool inside = ::chdir(fuzz::scratch().c_str()) == 0;
    if (!inside) {
        std::fprintf(stderr, "fuzz: cannot enter the scratch directory %s\n", fuzz::scratch().c_str());
        std::abort();
    }
    fuzz::empty_scratch();
    // render installs its Ctrl-C handler, then puts the default one back; libFuzzer's own is
    // restored after each input.
    struct sigaction fuzzer_sigint;
    sigaction(SIGINT, nullptr, &fuzzer_sigint);
    const fuzz::halves parts = fuzz::split(fuzz::bytes(data, size), "\n");
    run(parts.before, parts.after);
    sigaction(SIGINT, &fuzzer_sigint, nullptr);
    return 0;
}
