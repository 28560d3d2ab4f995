#pragma once
// translate and rotate_y: a hittable moved or turned as a whole (book 2), without touching the
// object itself. Each moves the ray into the object's own frame, hits the object there, and moves
// the hit point and normal back.
//
//   shared_ptr<hittable> box1 = box(point3(0, 0, 0), point3(165, 330, 165), white);
//   box1 = make_shared<rotate_y>(box1, 15);                   // degrees, about the y axis
//   box1 = make_shared<translate>(box1, vec3(265, 0, 295));
//
// rotate_y by theta takes the object's (x, z) to the world's (cos x + sin z, -sin x + cos z): a
// positive angle turns +x towards -z (90 degrees takes +x to -z), counter-clockwise seen from +y.
//
// Book 3's light sampling passes through both (the book's own rotate_y does not), so a moved or
// turned light can still be sampled: origin and direction go into the object's frame, the
// sampled direction comes back out. Neither changes solid angles, so densities carry over as they
// are.

#include "aabb.h"
#include "constants.h"
#include "hittable.h"
#include "interval.h"
#include "ray.h"
#include "vec3.h"

#include <cmath>
#include <initializer_list>
#include <memory>

namespace rt {

class translate : public hittable {
  public:
    translate(std::shared_ptr<hittable> object, const vec3& offset)
        : object_(std::move(object)), offset_(offset), bbox_(object_->bounding_box() + offset_) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        // Moving the object by +offset is moving the ray by -offset; t is the same in both frames.
        ray offset_r(r.origin() - offset_, r.direction());
        if (!object_->hit(offset_r, ray_t, rec)) return false;
        rec.p += offset_;
        return true;
    }

    aabb bounding_box() const override { return bbox_; }

    double pdf_value(const point3& origin, const vec3& direction) const override {
        return object_->pdf_value(origin - offset_, direction);
    }
    vec3 random(const point3& origin) const override { return object_->random(origin - offset_); }

    const std::shared_ptr<hittable>& object() const { return object_; }
    const vec3& offset() const { return offset_; }

  private:
    std::shared_ptr<hittable> object_;
    vec3 offset_;
    aabb bbox_;
};

class rotate_y : public hittable {
  public:
    rotate_y(std::shared_ptr<hittable> object, double angle)
        : object_(std::move(object)), angle_(angle), sin_theta_(std::sin(degrees_to_radians(angle))),
          cos_theta_(std::cos(degrees_to_radians(angle))), bbox_(rotated_box(object_->bounding_box())) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        // Into the object's frame (the rotation is rigid, so t is the same in both), hit, and out.
        ray rotated_r(to_object(r.origin()), to_object(r.direction()));
        if (!object_->hit(rotated_r, ray_t, rec)) return false;
        rec.p = to_world(rec.p);
        rec.normal = to_world(rec.normal);
        return true;
    }

    aabb bounding_box() const override { return bbox_; }

    double pdf_value(const point3& origin, const vec3& direction) const override {
        return object_->pdf_value(to_object(origin), to_object(direction));
    }
    vec3 random(const point3& origin) const override { return to_world(object_->random(to_object(origin))); }

    const std::shared_ptr<hittable>& object() const { return object_; }
    double angle() const { return angle_; } // degrees
    double sin_theta() const { return sin_theta_; }
    double cos_theta() const { return cos_theta_; }

  private:
    std::shared_ptr<hittable> object_;
    double angle_;
    double sin_theta_, cos_theta_;
    aabb bbox_;

    // The object's frame to the world's: rotation by +theta about y.
    vec3 to_world(const vec3& p) const {
        return vec3(cos_theta_ * p.x() + sin_theta_ * p.z(), p.y(), -sin_theta_ * p.x() + cos_theta_ * p.z());
    }
    // The world's frame to the object's: the inverse rotation, by -theta.
    vec3 to_object(const vec3& p) const {
        return vec3(cos_theta_ * p.x() - sin_theta_ * p.z(), p.y(), sin_theta_ * p.x() + cos_theta_ * p.z());
    }

    // The box around the rotated corners of the object's box. An empty box stays empty; one
    // unbounded in x or z (a shape without a box of its own) is unbounded in both after turning,
    // which the corner arithmetic would turn into inf - inf = NaN.
    aabb rotated_box(const aabb& box) const {
        if (box.x.min > box.x.max || box.y.min > box.y.max || box.z.min > box.z.max) return aabb::empty;
        if (!std::isfinite(box.x.min) || !std::isfinite(box.x.max) || !std::isfinite(box.z.min) ||
            !std::isfinite(box.z.max))
            return aabb(interval::universe, box.y, interval::universe);
        point3 lo(infinity, infinity, infinity);
        point3 hi(-infinity, -infinity, -infinity);
        for (double x : {box.x.min, box.x.max})
            for (double y : {box.y.min, box.y.max})
                for (double z : {box.z.min, box.z.max}) {
                    vec3 corner = to_world(vec3(x, y, z));
                    for (int c = 0; c < 3; ++c) {
                        lo[c] = std::fmin(lo[c], corner[c]);
                        hi[c] = std::fmax(hi[c], corner[c]);
                    }
                }
        return aabb(lo, hi);
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::rotate_y;
using rt::translate;
#endif
