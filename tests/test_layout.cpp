// The include graph of rtweekend/ is a one-way ladder (README, "Architecture"): every header
// stands on one rung, and includes only headers of its own rung or lower ones, with no cycle. The
// ladder below is the one the README draws; a new header must be given its rung here.

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

// The rungs, lowest first.
const std::vector<std::vector<std::string>> ladder = {
    // 1. foundations
    {"constants.h", "scene_error.h", "engine/rng.h", "engine/simd.h", "engine/force_inline.h", "engine/in_place_array.h",
     "io/input_limits.h", "io/file.h", "io/text_lines.h", "io/image_header.h", "io/jpeg_check.h"},
    // 2. math: the book's vectors and intervals, the engine's float vectors, warps, Fresnel
    {"vec3.h", "interval.h", "ray.h", "color.h", "aabb.h", "engine/vec3f.h", "engine/sampling.h", "engine/sampler.h",
     "engine/alias_table.h", "engine/light_sampling.h",
     "engine/ray_offset.h", "engine/fresnel.h", "engine/image.h", "engine/fixed_point.h", "engine/validate.h",
     "point_light.h", "perlin.h", "rtw_stb_image.h"},
    // 3. the material contract
    {"engine/bsdf.h"},
    // 4. the scene as users write it
    {"hittable.h", "hittable_list.h", "sphere.h", "triangle.h", "mesh.h", "material.h", "whitted_material.h",
     "whitted_scene.h", "texture.h", "constant_medium.h", "onb.h", "pdf.h", "quad.h", "transform.h", "bvh.h"},
    // 5. the compiled scene: shape sets and their kernels, the BVH, the compilers
    {"engine/leaf_query.h", "engine/bvh.h", "engine/surface_hit.h", "engine/sphere_set.h", "engine/triangle_set.h",
     "engine/quad_set.h", "engine/user_shape_set.h", "engine/convex_medium.h", "engine/moving_sphere_set.h",
     "engine/instance_set.h",
     "engine/light_set.h", "engine/compiled_scene.h",
     "engine/material_compiler.h", "engine/scene_compiler.h", "engine/texture_table.h",
     "engine/surface_coordinates.h"},
    // 6. rendering: settings, the scheduler, the integrators, writing images
    {"measure/adaptive.h", "engine/render_settings.h", "engine/scheduler.h", "engine/camera_frame.h",
     "engine/environment.h", "engine/user_material.h", "engine/caustic_paths.h", "engine/path_tracer.h",
     "engine/whitted.h",
     "io/image_write.h", "io/exr.h"},
    // 7. the book's camera, over the path tracer
    {"camera.h"},
    // 8. files and measuring tools; the render over MPI ranks (over the camera and the integrators)
    {"io/obj.h", "io/ply.h", "io/scene_file.h", "io/xml_scene.h", "io/ray_file.h", "io/image_read.h",
     "io/slice_file.h", "measure/metrics.h", "engine/mpi_render.h"},
    // 9. the umbrella header
    {"rtweekend.h"},
};

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

TEST_CASE("layout: every header has a rung on the include ladder, and includes only down or across it") {
    const auto graph = include_graph();
    REQUIRE(graph.size() > 40);
    std::map<std::string, int> rung;
    for (size_t r = 0; r < ladder.size(); ++r)
        for (const std::string& h : ladder[r]) {
            CAPTURE(h);
            CHECK(rung.count(h) == 0); // on one rung only
            rung[h] = int(r);
        }
    for (const auto& [header, includes] : graph) {
        CAPTURE(header);
        REQUIRE(rung.count(header) == 1); // a new header must be placed on the ladder
        for (const std::string& target : includes) {
            CAPTURE(target);
            REQUIRE(graph.count(target) == 1); // includes resolve to headers of the library
            CHECK(rung.at(target) <= rung.at(header));
        }
    }
    for (const auto& [h, r] : rung) {
        CAPTURE(h);
        CHECK(graph.count(h) == 1); // the ladder names no header that does not exist
    }
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
    CHECK(seen.count("engine/path_tracer.h") == 1);
    CHECK(seen.count("engine/scene_compiler.h") == 1);
}

} // namespace test_layout
