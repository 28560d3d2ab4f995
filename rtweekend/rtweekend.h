#pragma once
// rtweekend.h: the umbrella header. Includes the whole teaching surface and, like the book's
// rtweekend.h, brings the names book-style code uses unqualified into the global namespace:
// shared_ptr, make_shared, infinity, pi, degrees_to_radians, random_double, and every rt class
// a book chapter introduces (unless RTWEEKEND_NO_GLOBAL_NAMES is defined).

// The teaching surface, in the book's order.
#include "constants.h"
#include "engine/rng.h"
#include "vec3.h"
#include "color.h"
#include "ray.h"
#include "interval.h"
#include "hittable.h"
#include "hittable_list.h"
#include "sphere.h"
#include "material.h"
#include "camera.h"
#include "triangle.h"
#include "mesh.h"

// The engine underneath, and files.
#include "engine/bsdf.h"
#include "engine/bvh.h"
#include "engine/fresnel.h"
#include "engine/image.h"
#include "io/file.h"
#include "io/image_write.h"
#include "io/obj.h"
#include "io/ply.h"
#include "engine/ray_offset.h"
#include "engine/path_tracer.h"
#include "engine/sampling.h"
#include "engine/compiled_scene.h"
#include "scene_error.h"
#include "io/scene_file.h"
#include "engine/simd.h"
#include "engine/vec3f.h"
#include "engine/whitted.h"
#include "io/xml_scene.h"

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
