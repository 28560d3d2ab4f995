#pragma once
// A triangle mesh compiled for tracing on its own, as the benchmarks time it (bench, and
// embree_bench --side-by-side against Embree):
//
//   app::compiled_mesh m = app::compile_mesh(mesh);   m.scene.intersect(ray, hit), m.scene.occluded(ray)
//
// The mesh is the whole world, compiled about the origin: ray files are in the mesh's own
// coordinates. `world` keeps the shape the compiled scene was made from alive.

#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/mesh.h>

#include <cstddef>
#include <memory>
#include <utility>

namespace app {

struct compiled_mesh {
    rt::hittable_list world;
    rt::compiled_scene scene;
    size_t triangles = 0;
    double load_ms = 0; // set by a caller that read the mesh from a file
};

inline compiled_mesh compile_mesh(std::shared_ptr<rt::triangle_mesh> mesh) {
    compiled_mesh m;
    m.triangles = mesh->triangle_count();
    m.world.add(std::move(mesh));
    m.scene = rt::compile_scene(m.world, rt::point3(0, 0, 0));
    return m;
}

} // namespace app
