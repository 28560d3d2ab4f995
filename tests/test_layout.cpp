// The include graph of rtweekend/ is a one-way ladder (docs/architecture.md): every folder is a
// rung, and a header includes only headers of its own rung or lower ones, with no cycle.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace test_layout {

namespace {

namespace fs = std::filesystem;

// The rungs, lowest first. Each folder of rtweekend/ is one rung: a header stands on the rung of
// its folder. The books' headers at the top of rtweekend/ (vec3.h, sphere.h, material.h, ...) are
// the rung "books", between core/, which they stand on, and the engine, which compiles them; two of
// them stand higher, over the renderer: camera.h (whose render() runs the path tracer) and the
// umbrella rtweekend.h.
const std::vector<std::string> ladder = {
    "core",        // float math, RNG, SIMD, sampling, Fresnel, the material contract, file limits
    "books",       // the books' classes: vec3, ray, hittable, sphere, material, texture, ...
    "image",       // the framebuffer, image files (PPM, PNG, BMP, PFM, EXR)
    "measure",     // error metrics, adaptive sampling's estimates
    "scene",       // shape, light and texture kinds, the BVH, the compiled scene and its compilers
    "render",      // samplers, the scheduler, the path tracer, light tracing, render settings, MPI
    "camera.h",    // the book's camera, over the path tracer
    "course",      // CENG795: the Whitted integrator, course cameras and scenes
    "io",          // scene files (text, XML), meshes (OBJ, PLY), ray files, slice files
    "rtweekend.h", // the umbrella header
};

// The rung of a header, by its path relative to rtweekend/; -1 for a folder not on the ladder.
int rung_of(const std::string& header) {
    const size_t slash = header.find('/');
    const std::string step = slash == std::string::npos ? (header == "camera.h" || header == "rtweekend.h" ? header : "books")
                                                        : header.substr(0, slash);
    const auto found = std::find(ladder.begin(), ladder.end(), step);
    return found == ladder.end() ? -1 : int(found - ladder.begin());
}

// Every header under rtweekend/, by its path relative to it, with the headers it includes.
std::map<std::string, std::vector<std::string>> include_graph() {
    const fs::path root = RTWEEKEND_SOURCE_DIR;
    std::map<std::string, std::vector<std::string>> graph;
    const std::regex include(R"re(^\s*#\s*include\s+"([^"]+)")re");
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (entry.path().extension() != ".h") continue;
        const std::string name = entry.path().lexically_relative(root).generic_string();
        std::vector<std::string>& edges = graph[name];
        std::ifstream in(entry.path());
        for (std::string line; std::getline(in, line);) {
            std::smatch m;
            if (!std::regex_search(line, m, include)) continue;
            fs::path target = (entry.path().parent_path() / m[1].str()).lexically_normal();
            edges.push_back(target.lexically_relative(root).generic_string());
        }
    }
    return graph;
}

} // namespace

TEST_CASE("layout: every header stands on its folder's rung, and includes only down or across the ladder") {
    const auto graph = include_graph();
    REQUIRE(graph.size() > 40);
    std::set<int> used;
    for (const auto& [header, includes] : graph) {
        CAPTURE(header);
        const int rung = rung_of(header);
        REQUIRE(rung >= 0); // a new folder must be given its rung in `ladder`
        used.insert(rung);
        for (const std::string& target : includes) {
            CAPTURE(target);
            REQUIRE(graph.count(target) == 1); // includes resolve to headers of the library
            CHECK(rung_of(target) <= rung);
        }
    }
    CHECK(used.size() == ladder.size()); // the ladder names no empty rung
}

TEST_CASE("layout: the include graph has no cycle") {
    const auto graph = include_graph();
    std::map<std::string, int> state; // 0 unvisited, 1 on the current path, 2 done
    std::vector<std::string> path, cycle;
    std::function<void(const std::string&)> visit = [&](const std::string& h) {
        state[h] = 1;
        path.push_back(h);
        for (const std::string& next : graph.at(h)) {
            if (!cycle.empty()) break;
            if (state[next] == 1) {
                cycle.assign(std::find(path.begin(), path.end(), next), path.end());
                cycle.push_back(next);
            } else if (state[next] == 0) {
                visit(next);
            }
        }
        path.pop_back();
        state[h] = 2;
    };
    for (const auto& entry : graph)
        if (state[entry.first] == 0 && cycle.empty()) visit(entry.first);
    std::ostringstream text;
    for (const std::string& h : cycle) text << h << " -> ";
    INFO("cycle: " << text.str());
    CHECK(cycle.empty());
    // A book main that includes only camera.h reaches the path tracer through it.
    std::set<std::string> seen;
    std::function<void(const std::string&)> reach = [&](const std::string& h) {
        if (!seen.insert(h).second) return;
        for (const std::string& next : graph.at(h)) reach(next);
    };
    reach("camera.h");
    CHECK(seen.count("render/path_tracer.h") == 1);
    CHECK(seen.count("scene/scene_compiler.h") == 1);
}

} // namespace test_layout
