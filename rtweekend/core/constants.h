#pragma once
// Numeric constants and unit conversions shared by the whole renderer (the book keeps these in
// rtweekend.h; they live here so that every header can include them on its own).

#include <limits>

namespace rt {

inline constexpr double infinity = std::numeric_limits<double>::infinity();
inline constexpr double pi = 3.1415926535897932385;

inline constexpr double degrees_to_radians(double degrees) { return degrees * pi / 180.0; }

} // namespace rt
