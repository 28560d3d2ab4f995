#pragma once
// interval: a closed range of reals [min, max], as in the books (book 2 adds the union of two
// intervals and shifting by a displacement).

#include "core/constants.h"

namespace rt {

class interval {
  public:
    double min, max;

    constexpr interval() : min(+infinity), max(-infinity) {} // Default interval is empty
    constexpr interval(double min, double max) : min(min), max(max) {}
    // The smallest interval holding both a and b.
    constexpr interval(const interval& a, const interval& b)
        : min(a.min <= b.min ? a.min : b.min), max(a.max >= b.max ? a.max : b.max) {}

    constexpr double size() const { return max - min; }
    constexpr bool contains(double x) const { return min <= x && x <= max; }
    constexpr bool surrounds(double x) const { return min < x && x < max; }
    constexpr double clamp(double x) const { return x < min ? min : (x > max ? max : x); }
    constexpr interval expand(double delta) const { return interval(min - delta / 2, max + delta / 2); }

    static const interval empty, universe;
};

inline constexpr interval interval::empty = interval(+infinity, -infinity);
inline constexpr interval interval::universe = interval(-infinity, +infinity);

constexpr interval operator+(const interval& ival, double displacement) {
    return interval(ival.min + displacement, ival.max + displacement);
}
constexpr interval operator+(double displacement, const interval& ival) { return ival + displacement; }

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::interval;
#endif
