#pragma once
// sphere(center, radius, material): the book's sphere, with book 2's texture coordinates (rec.u,
// rec.v from get_sphere_uv) and book 3's light sampling (pdf_value, random: the cone of
// directions towards the sphere).
//
// sphere(center, radius): book 1's sphere before materials (sections 6 to 9), grey diffuse.
//
// A negative radius is the older (v3) books' hollow glass: the sphere of radius |r| with its
// normals (p - c) / r pointing inwards, so that a ray from outside meets its back face and a
// dielectric of index n inside it bends light as a bubble of air in glass does (the v4 books
// clamp the radius to 0 and make the bubble a dielectric of index 1 / n instead; both images
// are the same).
//
// sphere(center1, center2, radius, material): book 2's moving sphere, for motion blur. Its centre
// travels in a straight line from center1 at time 0 to center2 at time 1, and a ray meets it
// where it is at the ray's time(); its bounding box covers the whole motion (the box around the
// boxes at both ends). As in the book the centre is kept as a ray, centre(t) = center1 + t
// (center2 - center1), and a still sphere is one whose centre does not move.
//
// The ray-sphere test uses the numerically stable form of Haines, Guenther and Akenine-Moller,
// "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): the
// discriminant is computed from the distance of the centre to the ray's line, and the near root
// from c/q, so neither suffers catastrophic cancellation for small or distant spheres.

#include "core/constants.h"
#include "hittable.h"
#include "interval.h"
#include "material.h"
#include "onb.h"
#include "ray.h"
#include "vec3.h"

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
    // A still sphere.
    sphere(const point3& center, double radius, std::shared_ptr<material> mat)
        : path_(center, vec3(0, 0, 0)), radius_(radius), mat_(std::move(mat)) {}
    // Book 1's sphere before materials exist (sections 6 to 9), which a main shades with its own
    // ray_color: grey diffuse (albedo 0.5) when the camera renders it, section 9's image.
    sphere(const point3& center, double radius)
        : sphere(center, radius, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))) {}
    // A moving sphere: at center1 at time 0, at center2 at time 1.
    sphere(const point3& center1, const point3& center2, double radius, std::shared_ptr<material> mat)
        : path_(center1, center2 - center1), radius_(radius), mat_(std::move(mat)) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        const point3 current_center = path_.at(r.time()); // where the sphere is when the ray passes
        double t0, t1;
        if (!sphere_roots(r.origin(), r.direction(), current_center, radius_, t0, t1)) return false;

        // Find the nearest root that lies in the acceptable range.
        double root = t0;
        if (!ray_t.surrounds(root)) {
            root = t1;
            if (!ray_t.surrounds(root)) return false;
        }

        rec.t = root;
        rec.p = r.at(rec.t);
        vec3 outward_normal = (rec.p - current_center) / radius_;
        rec.set_face_normal(r, outward_normal);
        get_sphere_uv(outward_normal, rec.u, rec.v);
        rec.mat = mat_;

        return true;
    }

    aabb bounding_box() const override {
        const double size = std::fabs(radius_); // a hollow (negative-radius) sphere is as big
        vec3 r(size, size, size);
        const point3 c0 = path_.origin(), c1 = path_.at(1);
        return aabb(aabb(c0 - r, c0 + r), aabb(c1 - r, c1 + r));
    }

    // Book 3: the density of `direction` when random(origin) draws directions uniformly within
    // the cone of directions from origin that meet the sphere: 1 / the cone's solid angle,
    // 2 pi (1 - cos theta_max), with sin^2 theta_max = r^2 / d^2. Beyond the book: from inside
    // the sphere every direction meets it, and directions are drawn uniformly over all of them.
    // A moving sphere is sampled where it is at time 0, as book 3 does (its pdfs know no time).
    double pdf_value(const point3& origin, const vec3& direction) const override {
        hit_record rec;
        if (!this->hit(ray(origin, direction), interval(0.001, infinity), rec)) return 0;
        double distance_squared = (center() - origin).length_squared();
        if (!(distance_squared > radius_ * radius_)) return 1 / (4 * pi);
        double solid_angle = 2 * pi * one_minus_cos_theta_max(radius_, distance_squared);
        return 1 / solid_angle;
    }

    vec3 random(const point3& origin) const override {
        vec3 direction = center() - origin;
        double distance_squared = direction.length_squared();
        if (!(distance_squared > radius_ * radius_)) return random_unit_vector();
        onb uvw(direction);
        return uvw.transform(random_to_sphere(radius_, distance_squared));
    }

    // The centre at time 0 (a still sphere's only centre), and at `time`.
    const point3& center() const { return path_.origin(); }
    point3 center(double time) const { return path_.at(time); }
    // How far the centre moves from time 0 to time 1 (center2 - center1); zero for a still sphere.
    const vec3& motion() const { return path_.direction(); }
    bool is_moving() const { return motion().x() != 0 || motion().y() != 0 || motion().z() != 0; }
    double radius() const { return radius_; }
    const std::shared_ptr<material>& mat() const { return mat_; }

  private:
    ray path_; // the centre's path: origin center1, direction center2 - center1
    double radius_;
    std::shared_ptr<material> mat_;

    // Book 2's texture coordinates of a point p of the unit sphere about the origin: u, the
    // angle around the y axis from -x (through +z, +x, -z), and v, the angle from -y, both as
    // fractions of their range [0, 1]: (1 0 0) -> (0.5, 0.5), (0 1 0) -> (0.5, 1), (0 0 1) ->
    // (0.25, 0.5), (-1 0 0) -> (0, 0.5), (0 -1 0) -> (0.5, 0), (0 0 -1) -> (0.75, 0.5).
    static void get_sphere_uv(const point3& p, double& u, double& v) {
        double theta = std::acos(std::fmax(-1.0, std::fmin(1.0, -p.y()))); // clamped: |p.y| may round above 1
        double phi = std::atan2(-p.z(), p.x()) + pi;
        u = phi / (2 * pi);
        v = theta / pi;
    }

    // 1 - cos theta_max for a sphere of `radius` seen from `distance_squared` away, written as
    // x / (1 + sqrt(1 - x)) with x = r^2 / d^2: the plain 1 - sqrt(1 - x) cancels to nothing
    // for small or distant spheres.
    static double one_minus_cos_theta_max(double radius, double distance_squared) {
        double x = radius * radius / distance_squared;
        return x / (1 + std::sqrt(1 - x));
    }

    // Book 3: a direction uniform in the cone about +z of half-angle theta_max: cos theta is
    // uniform between cos theta_max and 1, phi uniform around the axis.
    static vec3 random_to_sphere(double radius, double distance_squared) {
        double r1 = random_double();
        double r2 = random_double();
        double one_minus_z = r2 * one_minus_cos_theta_max(radius, distance_squared);
        double z = 1 - one_minus_z;
        double phi = 2 * pi * r1;
        double sin_theta = std::sqrt(one_minus_z * (2 - one_minus_z)); // 1 - z^2, without cancelling
        return vec3(std::cos(phi) * sin_theta, std::sin(phi) * sin_theta, z);
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::sphere;
#endif
