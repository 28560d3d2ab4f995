#pragma once
// translate and rotate_y: a hittable moved or turned as a whole (book 2), without touching the
// object itself. Each moves the ray into the object's own frame, hits the object there, and moves
// the hit point and normal back.
//
// Beyond the book, any affine transform x -> M x + offset, in the same manner:
//
//   make_shared<rotate>(object, vec3(1, 1, 0), 30);       // degrees about an axis through the origin
//   make_shared<scale>(object, vec3(2, 1, 1));            // per axis (non-uniform); or one factor
//   make_shared<transform>(object, mat3(...), offset);    // any invertible M, then + offset
//
// rotate turns counter-clockwise seen from the tip of the axis (the right-hand rule), so
// rotate(object, vec3(0, 1, 0), a) is rotate_y(object, a). The ray goes into the object's frame
// as M^-1 (o - offset) and M^-1 d, unnormalised, so t is the same in both frames; the hit point
// comes back by M p + offset and the normal by the inverse transpose M^-T n (normals are
// gradients: a sphere scaled to an ellipsoid gets the ellipsoid's normals), renormalised. A
// mirroring M (negative determinant) keeps what the object calls its front face. Light sampling
// (book 3's pdf_value and random) passes through a transform that keeps solid angles (a rotation,
// with any offset); through one that scales or shears it is not offered (the hittable defaults).
//
// The renderer applies a transform to the shapes themselves when it can (a mesh under any of
// them, a sphere under one that keeps it round) and otherwise, or when one object is placed many
// times, traces the object in its own frame (an instance: scene/instance_set.h).
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
#include "core/constants.h"
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

// A 3x3 matrix of doubles, by rows: the linear part of a transform.
class mat3 {
  public:
    mat3() : rows_{vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)} {} // the identity
    mat3(const vec3& row0, const vec3& row1, const vec3& row2) : rows_{row0, row1, row2} {}

    static mat3 diagonal(const vec3& d) { return mat3(vec3(d.x(), 0, 0), vec3(0, d.y(), 0), vec3(0, 0, d.z())); }
    // Rotation by `degrees` about `axis` (any length), by Rodrigues' formula:
    // R = cos I + sin [k]x + (1 - cos) k k^T with k the unit axis.
    static mat3 rotation(const vec3& axis, double degrees);

    const vec3& row(int i) const { return rows_[i]; }
    vec3 column(int j) const { return vec3(rows_[0][j], rows_[1][j], rows_[2][j]); }
    double operator()(int i, int j) const { return rows_[i][j]; }

    vec3 operator*(const vec3& v) const { return vec3(dot(rows_[0], v), dot(rows_[1], v), dot(rows_[2], v)); }
    mat3 operator*(const mat3& b) const {
        const vec3 c0 = b.column(0), c1 = b.column(1), c2 = b.column(2);
        auto row_times = [&](const vec3& r) { return vec3(dot(r, c0), dot(r, c1), dot(r, c2)); };
        return mat3(row_times(rows_[0]), row_times(rows_[1]), row_times(rows_[2]));
    }
    mat3 transpose() const { return mat3(column(0), column(1), column(2)); }
    double determinant() const { return dot(rows_[0], cross(rows_[1], rows_[2])); }
    // The inverse, from the cofactors; NaN or infinite entries when M is singular.
    mat3 inverse() const;

  private:
    vec3 rows_[3];
};

// An object under x -> M x + offset (see the top of this file). rotate and scale are this with
// their own M.
class transform : public hittable {
  public:
    transform(std::shared_ptr<hittable> object, const mat3& linear, const vec3& offset = vec3(0, 0, 0))
        : object_(std::move(object)), linear_(linear), inverse_(linear.inverse()), normal_(inverse_.transpose()),
          offset_(offset), bbox_(transformed_box(object_->bounding_box())) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        // Unnormalised into the object's frame: the same t names the same point in both.
        ray object_r(inverse_ * (r.origin() - offset_), inverse_ * r.direction(), r.time());
        if (!object_->hit(object_r, ray_t, rec)) return false;
        rec.p = linear_ * rec.p + offset_;
        rec.normal = unit_vector(normal_ * rec.normal); // still facing the ray, front_face kept
        return true;
    }

    aabb bounding_box() const override { return bbox_; }

    double pdf_value(const point3& origin, const vec3& direction) const override {
        if (!keeps_solid_angles()) return hittable::pdf_value(origin, direction);
        return object_->pdf_value(inverse_ * (origin - offset_), inverse_ * direction);
    }
    vec3 random(const point3& origin) const override {
        if (!keeps_solid_angles()) return hittable::random(origin);
        return linear_ * object_->random(inverse_ * (origin - offset_));
    }

    const std::shared_ptr<hittable>& object() const { return object_; }
    const mat3& linear() const { return linear_; } // M
    const vec3& offset() const { return offset_; }

  private:
    std::shared_ptr<hittable> object_;
    mat3 linear_, inverse_, normal_; // M, M^-1, M^-T
    vec3 offset_;
    aabb bbox_;

    // M is a rotation: M^T M = I (up to rounding) and det M = +1.
    bool keeps_solid_angles() const {
        const mat3 mtm = linear_.transpose() * linear_;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (std::fabs(mtm(i, j) - (i == j ? 1.0 : 0.0)) > 1e-9) return false;
        return linear_.determinant() > 0;
    }

    // The box around the eight transformed corners; empty stays empty, unbounded stays unbounded.
    aabb transformed_box(const aabb& box) const {
        if (box.x.min > box.x.max || box.y.min > box.y.max || box.z.min > box.z.max) return aabb::empty;
        point3 lo(infinity, infinity, infinity), hi(-infinity, -infinity, -infinity);
        for (double x : {box.x.min, box.x.max})
            for (double y : {box.y.min, box.y.max})
                for (double z : {box.z.min, box.z.max}) {
                    const vec3 corner = linear_ * vec3(x, y, z) + offset_;
                    for (int c = 0; c < 3; ++c) {
                        lo[c] = std::fmin(lo[c], corner[c]);
                        hi[c] = std::fmax(hi[c], corner[c]);
                    }
                }
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(lo[c]) || !std::isfinite(hi[c])) return aabb::universe; // inf - inf on the way
        return aabb(lo, hi);
    }
};

// An object turned by `degrees` about `axis` (through the origin), counter-clockwise seen from
// the axis' tip.
class rotate : public transform {
  public:
    rotate(std::shared_ptr<hittable> object, const vec3& axis, double degrees)
        : transform(std::move(object), mat3::rotation(axis, degrees)), axis_(axis), angle_(degrees) {}
    const vec3& axis() const { return axis_; }
    double angle() const { return angle_; } // degrees

  private:
    vec3 axis_;
    double angle_;
};

// An object stretched by `factors` along x, y and z (about the origin), or by one factor in all.
class scale : public transform {
  public:
    scale(std::shared_ptr<hittable> object, const vec3& factors)
        : transform(std::move(object), mat3::diagonal(factors)), factors_(factors) {}
    scale(std::shared_ptr<hittable> object, double factor) : scale(std::move(object), vec3(factor, factor, factor)) {}
    const vec3& factors() const { return factors_; }

  private:
    vec3 factors_;
};

// An object moving in a straight line while the shutter is open: at the ray's time t (in [0, 1])
// it is displaced by t * displacement, as book 2's moving sphere is (CENG795's <MotionBlur> on any
// object). Its box covers the whole motion. The renderer traces the object in its own frame (an
// instance, scene/shapes/instance_set.h) with the ray moved back by t * displacement. Light
// sampling does not pass through it (the hittable defaults): a moving light is found by the rays
// that hit it.
//
//   auto blurred = make_shared<moving>(box(point3(0, 0, 0), point3(1, 1, 1), red), vec3(0, 0.5, 0));
class moving : public hittable {
  public:
    moving(std::shared_ptr<hittable> object, const vec3& displacement)
        : object_(std::move(object)), displacement_(displacement),
          bbox_(aabb(object_->bounding_box(), object_->bounding_box() + displacement_)) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        // Where the object is at the ray's time is where the ray, moved the other way, meets it.
        const vec3 shift = r.time() * displacement_;
        ray moved(r.origin() - shift, r.direction(), r.time());
        if (!object_->hit(moved, ray_t, rec)) return false;
        rec.p += shift;
        return true;
    }

    aabb bounding_box() const override { return bbox_; }

    const std::shared_ptr<hittable>& object() const { return object_; }
    const vec3& displacement() const { return displacement_; }

  private:
    std::shared_ptr<hittable> object_;
    vec3 displacement_;
    aabb bbox_;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline mat3 mat3::rotation(const vec3& axis, double degrees) {
    const vec3 k = unit_vector(axis);
    const double theta = degrees_to_radians(degrees), c = std::cos(theta), s = std::sin(theta), one_c = 1 - c;
    return mat3(vec3(c + one_c * k.x() * k.x(), one_c * k.x() * k.y() - s * k.z(), one_c * k.x() * k.z() + s * k.y()),
                vec3(one_c * k.y() * k.x() + s * k.z(), c + one_c * k.y() * k.y(), one_c * k.y() * k.z() - s * k.x()),
                vec3(one_c * k.z() * k.x() - s * k.y(), one_c * k.z() * k.y() + s * k.x(), c + one_c * k.z() * k.z()));
}

inline mat3 mat3::inverse() const {
    // The columns of M^-1 are the cross products of pairs of M's rows, over det M (r_i . (r_j x
    // r_k) is det M when (i, j, k) is a cyclic order, zero otherwise).
    const vec3 c0 = cross(rows_[1], rows_[2]), c1 = cross(rows_[2], rows_[0]), c2 = cross(rows_[0], rows_[1]);
    const double inv_det = 1 / dot(rows_[0], c0);
    return mat3(vec3(c0.x(), c1.x(), c2.x()) * inv_det, vec3(c0.y(), c1.y(), c2.y()) * inv_det,
                vec3(c0.z(), c1.z(), c2.z()) * inv_det);
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::mat3;
using rt::moving;
using rt::rotate;
using rt::rotate_y;
using rt::scale;
using rt::transform;
using rt::translate;
#endif
