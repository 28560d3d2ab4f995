#pragma once
// box3f: an axis-aligned box in float, what the BVH is built from and what each shape kind
// reports of its shapes (scene/shape_kinds.h).

#include "vec3f.h"

#include <limits>

namespace rt {

// An axis-aligned box in float. Empty when lo > hi (the default).
struct box3f {
    vec3f lo{+std::numeric_limits<float>::infinity(), +std::numeric_limits<float>::infinity(),
             +std::numeric_limits<float>::infinity()};
    vec3f hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
             -std::numeric_limits<float>::infinity()};

    void grow(const vec3f& p) {
        lo = {fmin_inline(lo.x, p.x), fmin_inline(lo.y, p.y), fmin_inline(lo.z, p.z)};
        hi = {fmax_inline(hi.x, p.x), fmax_inline(hi.y, p.y), fmax_inline(hi.z, p.z)};
    }
    void grow(const box3f& b) {
        lo = {fmin_inline(lo.x, b.lo.x), fmin_inline(lo.y, b.lo.y), fmin_inline(lo.z, b.lo.z)};
        hi = {fmax_inline(hi.x, b.hi.x), fmax_inline(hi.y, b.hi.y), fmax_inline(hi.z, b.hi.z)};
    }
    // Shrinks to the part inside b (empty when they do not overlap).
    void clip(const box3f& b) {
        lo = {fmax_inline(lo.x, b.lo.x), fmax_inline(lo.y, b.lo.y), fmax_inline(lo.z, b.lo.z)};
        hi = {fmin_inline(hi.x, b.hi.x), fmin_inline(hi.y, b.hi.y), fmin_inline(hi.z, b.hi.z)};
    }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    vec3f centre() const { return 0.5f * (lo + hi); }
    // Half the surface area: the SAH only needs areas up to a common factor.
    float half_area() const {
        if (empty()) return 0;
        vec3f e = hi - lo;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

} // namespace rt
