#pragma once
// rtweekend.h: the umbrella header. Includes the whole teaching surface and, like the book's
// rtweekend.h, brings the names book-style code uses unqualified into the global namespace:
// shared_ptr, make_shared, infinity, pi, degrees_to_radians, random_double, and every rt class
// a book chapter introduces (unless RTWEEKEND_NO_GLOBAL_NAMES is defined).

// The teaching surface: the books' headers in the books' order, then the shapes, materials and
// scene types this library adds in the same vocabulary.
#include "core/constants.h"
#include "vec3.h"
#include "color.h"
#include "ray.h"
#include "interval.h"
#include "aabb.h"
#include "hittable.h"
#include "hittable_list.h"
#include "sphere.h"
#include "material.h"
#include "camera.h"
#include "texture.h"   // book 2
#include "quad.h"
#include "transform.h"
#include "bvh.h"
#include "constant_medium.h"
#include "onb.h"       // book 3
#include "pdf.h"
#include "triangle.h"
#include "mesh.h"
#include "whitted_material.h"
#include "course/whitted_scene.h"
#include "core/scene_error.h"

// The engine underneath (the integrators), and the file formats. Not included here:
// scene/scene_compiler.h (compile_scene and the compiled scene's definition, for programs that
// compile a scene once and render it from several cameras: a book main needs neither, and every
// main that links the engine would pay half a second to parse them), image/image_read.h,
// measure/metrics.h and io/ray_file.h, which serve the measuring tools only; io/xml_scene.h
// (the course's XML and JSON scenes: pugixml and nlohmann/json, whose parsing alone is about 2 s
// of every header-only compile; the course programs include it); io/gltf_model.h and
// io/model_scene.h (glTF models through tinygltf, and models as ready scenes: `render` uses them).
#include "render/path_tracer.h"
#include "course/whitted.h"
#include "core/file.h"
#include "image/image_write.h"
#include "io/obj.h"
#include "io/obj_model.h"
#include "io/ply.h"
#include "io/scene_file.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using std::make_shared;
using std::shared_ptr;

using rt::degrees_to_radians;
using rt::infinity;
using rt::pi;
using rt::random_double;
using rt::random_int;
#endif
