#pragma once
// hittable: anything a ray can hit, and hit_record, what a hit reports (the book's interface).
//
// The built-in shapes are recognised by the renderer and copied into flat arrays (scene.h), so
// their virtual hit() below serves the teaching surface and user code only. A user's own
// subclass is still rendered, through the slower virtual path.

#include "interval.h"
#include "ray.h"

#include <memory>

namespace rt {

class material;

class hit_record {
  public:
    point3 p;
    vec3 normal;
    std::shared_ptr<material> mat;
    double t = 0;
    bool front_face = false;

    // Sets the hit record normal vector against the ray.
    // NOTE: the parameter `outward_normal` is assumed to have unit length.
    void set_face_normal(const ray& r, const vec3& outward_normal) {
        front_face = dot(r.direction(), outward_normal) < 0;
        normal = front_face ? outward_normal : -outward_normal;
    }
};

class hittable {
  public:
    virtual ~hittable() = default;

    virtual bool hit(const ray& r, interval ray_t, hit_record& rec) const = 0;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::hit_record;
using rt::hittable;
#endif
