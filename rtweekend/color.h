#pragma once
// color: linear RGB radiance as a vec3, and the book's write_color, which applies gamma 2 (the
// square root) and the book's 8-bit quantisation int(256 * clamp(x, 0, 0.999)).

#include "interval.h"
#include "vec3.h"

#include <cmath>
#include <iostream>

namespace rt {

using color = vec3;

inline double linear_to_gamma(double linear_component) {
    if (linear_component > 0) return std::sqrt(linear_component);
    return 0;
}

// The book's encoding of one linear component to a byte.
inline int encode_byte(double linear_component) {
    static constexpr interval intensity(0.000, 0.999);
    return static_cast<int>(256 * intensity.clamp(linear_to_gamma(linear_component)));
}

// Writes one pixel as a "r g b" line of a P3 PPM.
inline void write_color(std::ostream& out, const color& pixel_color) {
    out << encode_byte(pixel_color.x()) << ' ' << encode_byte(pixel_color.y()) << ' '
        << encode_byte(pixel_color.z()) << '\n';
}

// The book's earlier (v3) form: the sum of `samples_per_pixel` samples, averaged here.
inline void write_color(std::ostream& out, const color& pixel_color_sum, int samples_per_pixel) {
    write_color(out, pixel_color_sum / samples_per_pixel);
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::color;
using rt::linear_to_gamma;
using rt::write_color;
#endif
