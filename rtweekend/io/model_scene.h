#pragma once
// load_model_scene(path): a model downloaded from the web (an OBJ with its MTL materials,
// io/obj_model.h, or a glTF 2.0 `.gltf`/`.glb`, io/gltf_model.h) as a scene ready to render, as
// `render model.obj` and `render model.glb` show it.
//
//   rt::scene_description s = rt::load_model_scene("helmet.glb");   // throws scene_error
//   rt::render(s.cam, s.world, s.point_lights, s.directional_lights);
//
// The view is the model's own camera when a glTF has one (its position, direction, up and
// vertical field of view; its aspect ratio when it gives one). Otherwise the default view: looking
// at the centre of the model's bounds from the front (+z), right and above, along (0.6, 0.45, 1),
// far enough that a 35-degree vertical view holds the bounding sphere. 640 pixels wide at 4:3 (or
// the camera's aspect ratio), 64 samples, depth 16. Lit by the book's sky when the model has no
// emitter and no light; in the dark otherwise.

#include "../core/engine_linkage.h"
#include "scene_file.h"

#include <string>

namespace rt {

// Whether `path` names a model load_model_scene reads: .obj, .gltf or .glb (any case).
RTWEEKEND_ENGINE_FUNCTION bool is_model_file(const std::string& path);

// The model at `path` with its materials, lights and view (the rules above).
RTWEEKEND_ENGINE_FUNCTION scene_description load_model_scene(const std::string& path);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/constants.h"
#include "../core/file.h"
#include "gltf_model.h"
#include "obj_model.h"

#include <cmath>

namespace rt {

RTWEEKEND_ENGINE_FUNCTION bool is_model_file(const std::string& path) {
    const std::string ext = lowercase_extension(path);
    return ext == ".obj" || ext == ".gltf" || ext == ".glb";
}

RTWEEKEND_ENGINE_FUNCTION scene_description load_model_scene(const std::string& path) {
    scene_description scene;
    point3 lo, hi;
    bool emits = false;
    camera& cam = scene.cam;
    cam.aspect_ratio = 4.0 / 3.0;
    cam.image_width = 640;
    cam.samples_per_pixel = 64;
    cam.max_depth = 16;
    cam.vfov = 35;
    bool has_view = false;
    if (lowercase_extension(path) == ".obj") {
        obj_model model = load_obj_model(path);
        scene.warnings = std::move(model.warnings);
        scene.files = std::move(model.files);
        scene.world = std::move(model.world);
        lo = model.lo;
        hi = model.hi;
        emits = model.emits;
    } else {
        gltf_model model = load_gltf_model(path);
        scene.warnings = std::move(model.warnings);
        scene.files = std::move(model.files);
        scene.world = std::move(model.world);
        scene.point_lights = std::move(model.point_lights);
        scene.directional_lights = std::move(model.directional_lights);
        lo = model.lo;
        hi = model.hi;
        emits = model.emits || !scene.point_lights.empty() || !scene.directional_lights.empty();
        if (model.has_view) {
            has_view = true;
            cam.lookfrom = model.view.lookfrom;
            cam.lookat = model.view.lookat;
            cam.vup = model.view.vup;
            cam.vfov = model.view.vfov;
            if (model.view.aspect_ratio > 0) cam.aspect_ratio = model.view.aspect_ratio;
        }
    }
    if (scene.world.objects.empty()) throw scene_error(path + ": the model has no triangles to render");
    if (!has_view) {
        cam.lookat = 0.5 * (lo + hi);
        const double radius = 0.5 * (hi - lo).length();
        const double distance = (radius > 0 ? radius : 1.0) / std::sin(0.5 * cam.vfov * pi / 180) * 1.05;
        cam.lookfrom = cam.lookat + distance * unit_vector(vec3(0.6, 0.45, 1.0));
    }
    if (emits) cam.background = color(0, 0, 0);
    return scene;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::is_model_file;
using rt::load_model_scene;
#endif
