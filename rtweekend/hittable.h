#pragma once
// hittable: anything a ray can hit, and hit_record, what a hit reports (the books' interface).
//
// The built-in shapes are recognised by the renderer and copied into flat arrays
// (scene/scene_compiler.h), so their virtual hit() below serves the teaching surface and user
// code only. A user's own subclass is rendered through its virtual hit(): inside the renderer's
// BVH when it reports a bounding box (book 2's bounding_box()), tested against every ray when it
// does not (a book-1 class, which has none). Book 3's pdf_value() and random() let a shape be
// sampled as a light (pdf.h's hittable_pdf).

#include "aabb.h"
#include "interval.h"
#include "ray.h"

#include <memory>
#include <utility>

namespace rt {

class material;

class hit_record {
  public:
    point3 p;
    vec3 normal;
    std::shared_ptr<material> mat;
    double t = 0;
    double u = 0; // surface coordinates of the hit, for textures (book 2)
    double v = 0;
    bool front_face = false;
    // The older books' (v3) name for mat: rec.mat_ptr->scatter(...) in their ray_color. Always
    // this record's own mat (a copy binds it anew, which the copies below see to).
    std::shared_ptr<material>& mat_ptr = mat;

    hit_record() = default;
    hit_record(const hit_record& o)
        : p(o.p), normal(o.normal), mat(o.mat), t(o.t), u(o.u), v(o.v), front_face(o.front_face) {}
    hit_record(hit_record&& o) noexcept
        : p(o.p), normal(o.normal), mat(std::move(o.mat)), t(o.t), u(o.u), v(o.v), front_face(o.front_face) {}
    hit_record& operator=(const hit_record& o) {
        mat = o.mat;
        copy_values(o);
        return *this;
    }
    hit_record& operator=(hit_record&& o) noexcept {
        mat = std::move(o.mat);
        copy_values(o);
        return *this;
    }

  private:
    void copy_values(const hit_record& o) {
        p = o.p;
        normal = o.normal;
        t = o.t;
        u = o.u;
        v = o.v;
        front_face = o.front_face;
    }

  public:

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
    // The older books' (v3) form, world.hit(r, 0.001, infinity, rec) in their ray_color: hits
    // with t in (ray_tmin, ray_tmax).
    bool hit(const ray& r, double ray_tmin, double ray_tmax, hit_record& rec) const {
        return hit(r, interval(ray_tmin, ray_tmax), rec);
    }

    // A box that holds everything hit() can hit (book 2). The default, for shapes written before
    // book 2 introduces it, is the whole of space: such a shape is tested against every ray.
    virtual aabb bounding_box() const { return aabb::universe; }

    // Book 3's light sampling. pdf_value: the solid-angle density, seen from `origin`, with which
    // random(origin) picks `direction`. random: a direction (not necessarily unit) from `origin`
    // towards the shape. A shape that cannot be sampled keeps these defaults (density 0, and an
    // arbitrary direction, which a mixture with another pdf then weighs at nothing).
    virtual double pdf_value(const point3& /*origin*/, const vec3& /*direction*/) const { return 0.0; }
    virtual vec3 random(const point3& /*origin*/) const { return vec3(1, 0, 0); }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::hit_record;
using rt::hittable;
#endif
