#pragma once
// rtweekend.h: the umbrella header. Includes the whole teaching surface and, like the book's
// rtweekend.h, brings the names book-style code uses unqualified into the global namespace:
// shared_ptr, make_shared, infinity, pi, degrees_to_radians, random_double, and every rt class
// a book chapter introduces (unless RTWEEKEND_NO_GLOBAL_NAMES is defined).

// The teaching surface, in the book's order.
#include "constants.h"
#include "rng.h"
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
#include "bsdf.h"
#include "bvh.h"
#include "fresnel.h"
#include "image.h"
#include "ply.h"
#include "ray_offset.h"
#include "render.h"
#include "sampling.h"
#include "scene.h"
#include "scene_error.h"
#include "scene_io.h"
#include "simd.h"
#include "vec3f.h"
#include "whitted.h"
#include "xml_scene.h"

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
