#pragma once
// What the xml_scene and json_scene harnesses share: the input is a course scene, optionally
// followed by the line "==> mesh.ply <==" and the bytes of a PLY file (the layout `head scene.xml
// mesh.ply` prints). The PLY part is written to mesh.ply in this process's scratch directory,
// beside where the scene is said to be, so that <Faces plyFile="mesh.ply"/> reads it; the scene is
// read from memory by rt::decode_xml_scene under `scene_name` (whose extension says XML or JSON).
// A scene it accepts is rendered by the Whitted ray tracer at 4x4 pixels per camera, 3 bounces at
// most (tiny_render.h), at most 64 rays per camera ray (a path of the course's path tracer, or a
// classic ray's tree), with back-face culling on for inputs of odd length. A refused scene must
// give one clear error line.

#include "fuzz_support.h"
#include "tiny_render.h"

#include <rtweekend/course/whitted.h>
#include <rtweekend/io/xml_scene.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace fuzz {

inline void course_scene(const uint8_t* data, size_t size, const char* scene_name) {
    const halves parts = split(bytes(data, size), "\n==> mesh.ply <==\n");
    const std::string ply_path = (scratch() / "mesh.ply").string();
    if (parts.found) put("mesh.ply", parts.after);
    else std::remove(ply_path.c_str());
    try {
        rt::whitted_scene scene = rt::decode_xml_scene(parts.before, (scratch() / scene_name).string());
        shrink(scene);
        rt::render_settings settings = rt::whitted_renderer::defaults();
        settings.threads = 1;
        settings.whitted.cull_back_faces = size % 2 == 1;
        // The course's path tracer under Russian roulette keeps a path going while its throughput
        // is 1 or more, which a scene of albedo above 1 (the level-1 model's pi kd) never leaves:
        // such a path stops at max_branch_rays, 2^14 rays by default, minutes per input here.
        settings.whitted.max_branch_rays = 64;
        const rt::whitted_renderer renderer(scene);
        for (size_t i = 0; i < scene.cameras.size(); ++i) renderer.render(i, settings);
    } catch (const rt::scene_error& e) {
        refused(e);
    }
}

} // namespace fuzz
