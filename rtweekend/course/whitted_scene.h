#pragma once
// whitted_scene: what a classic recursive (Whitted) ray tracer needs beyond geometry: point and
// ambient lights, the course's materials (whitted_material.h) and the cameras of the CENG795
// course scenes (io/xml_scene.h reads them from XML; engine/whitted.h renders them).
//
//   whitted_scene s;
//   auto red = make_shared<whitted_material>();
//   red->diffuse = color(0.8, 0.1, 0.1);
//   s.world.add(make_shared<sphere>(point3(0, 0, -5), 1, red));
//   s.lights.push_back({point3(0, 4, 0), color(1000, 1000, 1000)});
//   s.cameras.push_back(view_camera{...});
//
// Colours here are in the course's units: 0..255 per channel on output, no gamma.

#include "../color.h"
#include "../hittable_list.h"
#include "../point_light.h"
#include "../vec3.h"
#include "../whitted_material.h"
#include "course_lights.h"
#include "course_textures.h"
#include "view_camera.h"

#include <optional>
#include <string>
#include <vector>

namespace rt {


struct whitted_scene {
    color background{0, 0, 0};          // seen by primary rays that miss
    double shadow_ray_epsilon = 1e-3;   // offset of secondary ray origins along the normal
    double intersection_test_epsilon = 1e-6;
    int max_recursion_depth = 0;        // bounces; primary rays are depth 0
    color ambient_light{0, 0, 0};
    std::vector<point_light> lights;
    std::vector<directional_light> directional_lights; // course_lights.h
    std::vector<spot_light> spot_lights;
    std::vector<area_light> area_lights;
    std::vector<light_mesh> light_meshes;   // also in `world`, with emitting materials
    std::vector<light_sphere> light_spheres;
    std::vector<environment_light> environment_lights; // rays that miss see their sum (not the background)
    std::vector<view_camera> cameras;
    // Objects with texture maps (homework 4; course_textures.h), each with its own material, and
    // the map that replaces the background colour for camera rays that miss (replace_background).
    std::vector<textured_object> textured_objects;
    std::optional<texture_map> background_texture;
    hittable_list world;                // spheres, triangles and meshes with whitted_material materials
    // The files the scene was read from (load_xml_scene): the XML file, then its PLY meshes. Empty
    // for a scene built in code. A fingerprint of the scene hashes them (render_mpi's ranks check
    // that they all read the same scene).
    std::vector<std::string> files;
    // What the reader could not honour but the scene still renders without: an element it does not
    // read, one line each ("scene.xml:12: <NumSamples> is not supported yet and is ignored").
    std::vector<std::string> warnings;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::whitted_scene;
#endif
