// subdivide: Loop subdivision of an OBJ triangle mesh (rules: apps/loop_subdivision.h).
//
//   subdivide IN.obj OUT.obj [--levels N] [--quiet]
//   subdivide IN.obj OUT.ply --levels 0             (converts to binary PLY, for XML scenes)
//
// Reads positions and faces (polygons fanned into triangles), subdivides N times (default 2),
// writes "v" and "f" lines to OUT.obj, or a binary little-endian PLY when OUT ends in .ply,
// through a temporary file and a rename. One summary line on
// stderr unless --quiet; one "subdivide: error: ..." line and exit 1 for bad input, 2 for bad
// usage.

#include "loop_subdivision.h"

#include <rtweekend/core/file.h>
#include <rtweekend/io/obj.h>
#include <rtweekend/io/ply.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <new>
#include <string>
#include <system_error>
#include <vector>

namespace {

const char* const program = "subdivide";

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: subdivide IN.obj OUT.obj|OUT.ply [--levels N] [--quiet]\n"
                 "Loop subdivision of a triangle mesh (each level: 4x the triangles).\n"
                 "An output ending in .ply is written as binary PLY (--levels 0 just converts).\n"
                 "  --levels N  rounds of subdivision, 0 to 8 (default 2)\n"
                 "  --quiet     no summary line on stderr\n"
                 "  --help      show this help\n");
}

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program, message.c_str());
    print_usage(stderr);
    std::exit(2);
}

struct arguments {
    std::string input, output;
    int levels = 2;
    bool quiet = false;
};

int parse_levels(const std::string& text) {
    char* end = nullptr;
    errno = 0;
    long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE) usage_error("--levels needs an integer, got '" + text + "'");
    // Each level multiplies memory by about 4; 8 levels of a single triangle is already 65536.
    if (v < 0 || v > 8) usage_error("--levels must be between 0 and 8, got " + text);
    return int(v);
}

arguments parse(int argc, char** argv) {
    arguments a;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            print_usage(stdout);
            std::exit(0);
        } else if (arg == "--levels") {
            if (i + 1 >= argc) usage_error("--levels needs a value");
            a.levels = parse_levels(argv[++i]);
        } else if (arg.rfind("--levels=", 0) == 0) {
            a.levels = parse_levels(arg.substr(9));
        } else if (arg == "--quiet" || arg == "-q") {
            a.quiet = true;
        } else if (arg.size() > 1 && arg[0] == '-') {
            usage_error("unknown option '" + arg + "'");
        } else {
            positional.push_back(arg);
        }
    }
    if (positional.size() != 2) usage_error("expected IN.obj OUT.obj");
    a.input = positional[0];
    a.output = positional[1];
    return a;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int main(int argc, char** argv) {
    const arguments a = parse(argc, argv);
    try {
        rt::check_writable(a.output);
        auto t0 = std::chrono::steady_clock::now();
        app::tri_mesh in = app::read_obj(a.input);
        double read_s = seconds_since(t0);

        auto t1 = std::chrono::steady_clock::now();
        app::tri_mesh out;
        try {
            out = app::loop_subdivide(in, a.levels);
        } catch (const rt::scene_error& e) {
            throw rt::scene_error("'" + a.input + "': " + e.what());
        }
        double subdivide_s = seconds_since(t1);

        auto t2 = std::chrono::steady_clock::now();
        if (rt::lowercase_extension(a.output) == ".ply") {
            rt::triangle_mesh mesh(out.positions, out.triangles, nullptr);
            rt::write_ply(a.output, mesh, /*binary=*/true);
        } else {
            app::write_obj(a.output, out,
                           std::to_string(out.positions.size()) + " vertices, " + std::to_string(out.triangles.size()) +
                               " triangles: Loop subdivision of " + a.input + ", levels " + std::to_string(a.levels));
        }
        double write_s = seconds_since(t2);

        if (!a.quiet)
            std::fprintf(stderr,
                         "subdivide: %zu vertices, %zu triangles -> %zu vertices, %zu triangles (%d level%s); "
                         "read %.3f s, subdivide %.3f s, write %.3f s\n",
                         in.positions.size(), in.triangles.size(), out.positions.size(), out.triangles.size(), a.levels,
                         a.levels == 1 ? "" : "s",
                         read_s, subdivide_s, write_s);
        return 0;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: error: out of memory\n", program);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    }
    return 1;
}
