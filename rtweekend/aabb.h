#pragma once
// aabb: an axis-aligned bounding box, three intervals, as book 2 ("The Next Week") has it. A
// hittable that reports one (hittable::bounding_box) goes into the renderer's BVH.
//
//   aabb box(point3(0, 0, 0), point3(1, 2, 3));     // from two opposite corners, in any order
//   aabb both(box, other);                          // the box around two boxes
//   box.hit(r, interval(0.001, infinity))           // whether the ray passes through it
//
// As in the book, a box given by corners or intervals is padded to at least 0.0001 on every axis,
// so that a flat shape (a quad in a plane) still has a box a ray can enter.

#include "interval.h"
#include "ray.h"
#include "vec3.h"

#include <utility>

namespace rt {

class aabb {
  public:
    interval x, y, z;

    aabb() {} // empty: intervals are empty by default

    aabb(const interval& x, const interval& y, const interval& z) : x(x), y(y), z(z) { pad_to_minimums(); }

    // The box with corners a and b (any two opposite corners).
    aabb(const point3& a, const point3& b)
        : x(a[0] <= b[0] ? interval(a[0], b[0]) : interval(b[0], a[0])),
          y(a[1] <= b[1] ? interval(a[1], b[1]) : interval(b[1], a[1])),
          z(a[2] <= b[2] ? interval(a[2], b[2]) : interval(b[2], a[2])) {
        pad_to_minimums();
    }

    // The smallest box holding both boxes.
    aabb(const aabb& box0, const aabb& box1) : x(box0.x, box1.x), y(box0.y, box1.y), z(box0.z, box1.z) {}

    const interval& axis_interval(int n) const { return n == 1 ? y : (n == 2 ? z : x); }

    // Whether the ray passes through the box for some t in ray_t (the slab test: the ray's
    // parameter range inside each axis's pair of planes, intersected). An empty box is never hit
    // (the slab arithmetic alone would take an empty interval, min > max, for all of space).
    bool hit(const ray& r, interval ray_t) const {
        if (x.min > x.max || y.min > y.max || z.min > z.max) return false;
        for (int axis = 0; axis < 3; ++axis) {
            const interval& slab = axis_interval(axis);
            const double inv_d = 1.0 / r.direction()[axis];
            double t_enter = (slab.min - r.origin()[axis]) * inv_d;
            double t_leave = (slab.max - r.origin()[axis]) * inv_d;
            if (t_enter > t_leave) std::swap(t_enter, t_leave);
            if (t_enter > ray_t.min) ray_t.min = t_enter;
            if (t_leave < ray_t.max) ray_t.max = t_leave;
            if (ray_t.max <= ray_t.min) return false;
        }
        return true;
    }

    // The index (0, 1, 2 for x, y, z) of the longest axis.
    int longest_axis() const {
        if (x.size() > y.size()) return x.size() > z.size() ? 0 : 2;
        return y.size() > z.size() ? 1 : 2;
    }

    static const aabb empty, universe;

  private:
    // Pads every axis narrower than delta to delta, about its middle.
    void pad_to_minimums() {
        constexpr double delta = 0.0001;
        if (x.size() < delta) x = x.expand(delta);
        if (y.size() < delta) y = y.expand(delta);
        if (z.size() < delta) z = z.expand(delta);
    }
};

inline const aabb aabb::empty = aabb(interval::empty, interval::empty, interval::empty);
inline const aabb aabb::universe = aabb(interval::universe, interval::universe, interval::universe);

inline aabb operator+(const aabb& bbox, const vec3& offset) {
    return aabb(bbox.x + offset.x(), bbox.y + offset.y(), bbox.z + offset.z());
}
inline aabb operator+(const vec3& offset, const aabb& bbox) { return bbox + offset; }

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::aabb;
#endif
