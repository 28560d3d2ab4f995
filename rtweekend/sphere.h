#pragma once
// sphere(center, radius, material): the book's sphere.
//
// The ray-sphere test uses the numerically stable form of Haines, Guenther and Akenine-Moller,
// "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): the
// discriminant is computed from the distance of the centre to the ray's line, and the near root
// from c/q, so neither suffers catastrophic cancellation for small or distant spheres.

#include "hittable.h"

#include <cmath>
#include <memory>

namespace rt {

// The ray parameters (t0 <= t1) where the ray o + t d meets the sphere, or false when it misses.
// `d` need not be normalised.
inline bool sphere_roots(const point3& o, const vec3& d, const point3& center, double radius, double& t0,
                         double& t1) {
    // Compute the quadratic a t^2 - 2 h t + c = 0, with h = d.(C - O).
    vec3 oc = center - o;
    double a = d.length_squared();
    if (!(a > 0)) return false;
    double h = dot(d, oc);
    // The discriminant h^2 - a c, computed from the squared distance of the centre to the line.
    vec3 perp = oc - (h / a) * d;
    double discriminant = a * (radius * radius - perp.length_squared());
    if (!(discriminant >= 0)) return false;
    double c = oc.length_squared() - radius * radius;
    // q has the sign of h, so h + sign(h) sqrt(disc) never cancels; the other root is c / q.
    double q = h + std::copysign(std::sqrt(discriminant), h);
    if (q == 0) { // h = 0 and a tangent ray: the double root is t = h / a = 0
        t0 = t1 = 0;
        return true;
    }
    double ta = c / q, tb = q / a;
    t0 = std::fmin(ta, tb);
    t1 = std::fmax(ta, tb);
    return true;
}

class sphere : public hittable {
  public:
    sphere(const point3& center, double radius, std::shared_ptr<material> mat)
        : center_(center), radius_(radius), mat_(std::move(mat)) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        double t0, t1;
        if (!sphere_roots(r.origin(), r.direction(), center_, radius_, t0, t1)) return false;

        // Find the nearest root that lies in the acceptable range.
        double root = t0;
        if (!ray_t.surrounds(root)) {
            root = t1;
            if (!ray_t.surrounds(root)) return false;
        }

        rec.t = root;
        rec.p = r.at(rec.t);
        vec3 outward_normal = (rec.p - center_) / radius_;
        rec.set_face_normal(r, outward_normal);
        rec.mat = mat_;

        return true;
    }

    aabb bounding_box() const override {
        vec3 r(radius_, radius_, radius_);
        return aabb(center_ - r, center_ + r);
    }

    const point3& center() const { return center_; }
    double radius() const { return radius_; }
    const std::shared_ptr<material>& mat() const { return mat_; }

  private:
    point3 center_;
    double radius_;
    std::shared_ptr<material> mat_;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::sphere;
#endif
