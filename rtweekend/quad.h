#pragma once
// quad(Q, u, v, material): the parallelogram with corner Q and edges u and v (book 2), and
// box(a, b, material), the six quads of an axis-aligned box.
//
//   world.add(make_shared<quad>(point3(-3, -2, 5), vec3(0, 0, -4), vec3(0, 4, 0), red));
//   shared_ptr<hittable> crate = box(point3(0, 0, 0), point3(165, 330, 165), white);
//
// The front face is the side cross(u, v) points to: a one-sided light (diffuse_light) shines
// that way. A hit reports its position on the quad as (u, v) in [0, 1]^2, the fractions of the
// two edges (the plane coordinates alpha and beta below).
//
// Book 3's light sampling: random(origin) is a uniform point of the quad, as a direction from
// origin, and pdf_value converts that area density, 1 / area, to solid angle (distance^2 / |cos|).

#include "aabb.h"
#include "core/constants.h"
#include "core/rng.h"
#include "hittable.h"
#include "hittable_list.h"
#include "interval.h"
#include "ray.h"
#include "vec3.h"

#include <cmath>
#include <memory>

namespace rt {

class material;

class quad : public hittable {
  public:
    quad(const point3& Q, const vec3& u, const vec3& v, std::shared_ptr<material> mat)
        : Q_(Q), u_(u), v_(v), mat_(std::move(mat)) {
        vec3 n = cross(u_, v_);
        normal_ = unit_vector(n);
        D_ = dot(normal_, Q_);
        w_ = n / dot(n, n);
        area_ = n.length();
        set_bounding_box();
    }

    // The box of the two diagonals (aabb pads it where the quad lies flat in an axis plane).
    // Virtual, as in the book, for shapes derived from quad.
    virtual void set_bounding_box() { bbox_ = aabb(aabb(Q_, Q_ + u_ + v_), aabb(Q_ + u_, Q_ + v_)); }

    aabb bounding_box() const override { return bbox_; }

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        // A ray (almost) parallel to the plane misses it.
        double denom = dot(normal_, r.direction());
        if (std::fabs(denom) < 1e-8) return false;

        // Where the ray meets the plane n.P = D, if within ray_t.
        double t = (D_ - dot(normal_, r.origin())) / denom;
        if (!ray_t.contains(t)) return false;

        // The hit point's plane coordinates: P = Q + alpha u + beta v. Solving with w = n / n.n
        // gives alpha and beta from two cross products, without forming a 2x2 system.
        point3 intersection = r.at(t);
        vec3 planar_hit = intersection - Q_;
        double alpha = dot(w_, cross(planar_hit, v_));
        double beta = dot(w_, cross(u_, planar_hit));
        if (!is_interior(alpha, beta, rec)) return false;

        rec.t = t;
        rec.p = intersection;
        rec.mat = mat_;
        rec.set_face_normal(r, normal_);
        return true;
    }

    // Whether plane coordinates (a, b) lie on the shape; if so, sets the hit's (u, v). Virtual,
    // as in the book, so a derived shape (a triangle, a disk) can change only this test.
    virtual bool is_interior(double a, double b, hit_record& rec) const {
        const interval unit_interval(0, 1);
        if (!unit_interval.contains(a) || !unit_interval.contains(b)) return false;
        rec.u = a;
        rec.v = b;
        return true;
    }

    double pdf_value(const point3& origin, const vec3& direction) const override {
        hit_record rec;
        if (!this->hit(ray(origin, direction), interval(0.001, infinity), rec)) return 0;

        // dA = distance^2 / |cos| dOmega: the uniform area density 1 / area in solid angle.
        double distance_squared = rec.t * rec.t * direction.length_squared();
        double cosine = std::fabs(dot(direction, rec.normal) / direction.length());
        return distance_squared / (cosine * area_);
    }

    vec3 random(const point3& origin) const override {
        double alpha = random_double(); // drawn in this order, whatever order the compiler evaluates operands in
        double beta = random_double();
        point3 p = Q_ + alpha * u_ + beta * v_;
        return p - origin;
    }

    const point3& corner() const { return Q_; }
    const vec3& edge_u() const { return u_; }
    const vec3& edge_v() const { return v_; }
    const std::shared_ptr<material>& mat() const { return mat_; }

  private:
    point3 Q_;     // a corner
    vec3 u_, v_;   // the edges from it
    vec3 w_;       // n / (n.n), n = cross(u, v): turns plane vectors into (alpha, beta)
    std::shared_ptr<material> mat_;
    aabb bbox_;
    vec3 normal_;  // unit cross(u, v)
    double D_;     // the plane: dot(normal, P) = D
    double area_;  // |cross(u, v)|
};

// The closed box with opposite corners a and b: six quads whose normals point out of it.
inline std::shared_ptr<hittable_list> box(const point3& a, const point3& b, std::shared_ptr<material> mat) {
    auto sides = std::make_shared<hittable_list>();

    const point3 lo(std::fmin(a.x(), b.x()), std::fmin(a.y(), b.y()), std::fmin(a.z(), b.z()));
    const point3 hi(std::fmax(a.x(), b.x()), std::fmax(a.y(), b.y()), std::fmax(a.z(), b.z()));

    const vec3 dx(hi.x() - lo.x(), 0, 0);
    const vec3 dy(0, hi.y() - lo.y(), 0);
    const vec3 dz(0, 0, hi.z() - lo.z());

    // Each face's edges are ordered so that cross(u, v) points out of the box.
    sides->add(std::make_shared<quad>(point3(lo.x(), lo.y(), hi.z()), dx, dy, mat));  // front  (+z)
    sides->add(std::make_shared<quad>(point3(hi.x(), lo.y(), hi.z()), -dz, dy, mat)); // right  (+x)
    sides->add(std::make_shared<quad>(point3(hi.x(), lo.y(), lo.z()), -dx, dy, mat)); // back   (-z)
    sides->add(std::make_shared<quad>(point3(lo.x(), lo.y(), lo.z()), dz, dy, mat));  // left   (-x)
    sides->add(std::make_shared<quad>(point3(lo.x(), hi.y(), hi.z()), dx, -dz, mat)); // top    (+y)
    sides->add(std::make_shared<quad>(point3(lo.x(), lo.y(), lo.z()), dx, dz, mat));  // bottom (-y)

    return sides;
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::box;
using rt::quad;
#endif
