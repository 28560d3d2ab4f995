#pragma once
// Checks of what users give the renderer (colours, points, sizes), each throwing scene_error with
// one line that names the value and says what is wrong with it; and the float range the compiled
// scene keeps its coordinates in.

#include "../color.h"
#include "../core/scene_error.h"
#include "../vec3.h"
#include "../core/vec3f.h"

#include <cmath>
#include <limits>
#include <string>

namespace rt {

// The float intersection tests square coordinates (relative to the camera) and radii, so they
// must stay well inside float's range (squares up to 3.4e38).
inline constexpr double max_float_extent = 1e18;

inline bool finite3(const vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// The largest |coordinate|.
inline double max_abs(const vec3& v) { return fmax_inline(std::fabs(v.x()), fmax_inline(std::fabs(v.y()), std::fabs(v.z()))); }

// x rounded to the float below and above it: a box rounded outwards holds the double one.
inline float float_below(double x) { return std::nextafter(static_cast<float>(x), -std::numeric_limits<float>::infinity()); }
inline float float_above(double x) { return std::nextafter(static_cast<float>(x), std::numeric_limits<float>::infinity()); }

// "(x, y, z)", for messages.
inline std::string point_text(const vec3& v) {
    return "(" + number_text(v.x()) + ", " + number_text(v.y()) + ", " + number_text(v.z()) + ")";
}

// A colour (reflectance, absorption, light intensity) must be finite, non-negative and within
// float's range, since the renderer multiplies in float.
inline void check_color(const color& c, const char* what) {
    if (!finite3(c) || c.x() < 0 || c.y() < 0 || c.z() < 0)
        throw scene_error(std::string(what) + " must be finite and non-negative, got " + point_text(c));
    if (!is_finite(vec3f(c))) throw scene_error(std::string(what) + " is too large for single precision, got " + point_text(c));
}

} // namespace rt
