#pragma once
// triangle(a, b, c, material): a flat triangle, hit from either side.
//
// The ray-triangle test is the watertight one of Woop, Benthin and Wald, "Watertight
// Ray/Triangle Intersection", JCGT 2(1), 2013: the vertices are moved into a frame where the ray
// is the +z axis, and the 2D edge functions U, V, W are evaluated there. Two triangles that share
// an edge compute that edge's function from the same two vertices, so a ray through the edge is
// counted by one of them and never slips between them, which the classic Moller-Trumbore test
// cannot promise.
//
// The renderer tests triangles in float, several at a time (scene/triangle_set.h), and falls back to
// triangle_edge_functions in double when a ray passes exactly through an edge.

#include "core/simd.h"
#include "hittable.h"

#include <cmath>
#include <memory>

namespace rt {

// The ray, sheared so that it points along +z: the permutation (kx, ky, kz) of the axes that makes
// |dir[kz]| largest (kx, ky swapped when dir[kz] < 0 to keep the winding), and the shear.
template <class Real>
struct sheared_ray {
    int kx = 0, ky = 1, kz = 2;
    Real sx = 0, sy = 0, sz = 1;

    sheared_ray() = default;
    template <class Vec>
    explicit sheared_ray(const Vec& dir) {
        Real ax = std::fabs(Real(dir[0])), ay = std::fabs(Real(dir[1])), az = std::fabs(Real(dir[2]));
        kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
        kx = kz == 2 ? 0 : kz + 1;
        ky = kx == 2 ? 0 : kx + 1;
        if (dir[kz] < 0) std::swap(kx, ky);
        sx = Real(dir[kx]) / Real(dir[kz]);
        sy = Real(dir[ky]) / Real(dir[kz]);
        sz = Real(1) / Real(dir[kz]);
    }
};

// The edge functions U, V, W (twice the signed areas opposite a, b, c in the ray's frame) for
// vertices given relative to the ray origin, in double.
inline void triangle_edge_functions(const sheared_ray<double>& s, const vec3& a, const vec3& b, const vec3& c,
                                    double& u, double& v, double& w) {
    double ax = a[s.kx] - s.sx * a[s.kz], ay = a[s.ky] - s.sy * a[s.kz];
    double bx = b[s.kx] - s.sx * b[s.kz], by = b[s.ky] - s.sy * b[s.kz];
    double cx = c[s.kx] - s.sx * c[s.kz], cy = c[s.ky] - s.sy * c[s.kz];
    // Each product rounded on its own: a fused multiply-add would break the exact antisymmetry of
    // a shared edge's function between its two triangles (see rounded() in simd.h).
    u = rounded(cx * by) - rounded(cy * bx);
    v = rounded(ax * cy) - rounded(ay * cx);
    w = rounded(bx * ay) - rounded(by * ax);
}

// The watertight test in double: true when the ray o + t d meets triangle (a, b, c) with t in the
// open interval (tmin, tmax); then t and the barycentric weights of a, b and c.
inline bool intersect_triangle(const point3& o, const vec3& d, const point3& a, const point3& b, const point3& c,
                               double tmin, double tmax, double& t, double bary[3]) {
    const sheared_ray<double> s(d);
    vec3 A = a - o, B = b - o, C = c - o;
    double u, v, w;
    triangle_edge_functions(s, A, B, C, u, v, w);
    // Inside when the three edge functions share a sign (either winding).
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
    double det = u + v + w;
    if (det == 0) return false; // the ray lies in the triangle's plane, or the triangle is degenerate
    // Distance, scaled by det: interpolate the vertices' sheared z.
    double T = u * (s.sz * A[s.kz]) + v * (s.sz * B[s.kz]) + w * (s.sz * C[s.kz]);
    t = T / det;
    if (!(t > tmin && t < tmax)) return false;
    bary[0] = u / det;
    bary[1] = v / det;
    bary[2] = w / det;
    return true;
}

class triangle : public hittable {
  public:
    triangle(const point3& a, const point3& b, const point3& c, std::shared_ptr<material> mat)
        : a_(a), b_(b), c_(c), mat_(std::move(mat)) {}

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        double t, bary[3];
        if (!intersect_triangle(r.origin(), r.direction(), a_, b_, c_, ray_t.min, ray_t.max, t, bary)) return false;
        rec.t = t;
        // The point from the barycentric weights is on the triangle's plane, unlike o + t d.
        rec.p = bary[0] * a_ + bary[1] * b_ + bary[2] * c_;
        rec.set_face_normal(r, unit_vector(cross(b_ - a_, c_ - a_)));
        rec.mat = mat_;
        return true;
    }

    aabb bounding_box() const override {
        auto span = [&](int axis) {
            return interval(std::fmin(a_[axis], std::fmin(b_[axis], c_[axis])),
                            std::fmax(a_[axis], std::fmax(b_[axis], c_[axis])));
        };
        return aabb(span(0), span(1), span(2)); // a flat axis is padded, as book 2 pads quads
    }

    const point3& a() const { return a_; }
    const point3& b() const { return b_; }
    const point3& c() const { return c_; }
    const std::shared_ptr<material>& mat() const { return mat_; }

  private:
    point3 a_, b_, c_;
    std::shared_ptr<material> mat_;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::triangle;
#endif
