#pragma once
// onb: an orthonormal basis u, v, w around a given direction w (book 3). Directions drawn about
// the z axis (random_cosine_direction(), a cone towards a sphere) are carried over to any axis by
// transform(): (x, y, z) becomes x u + y v + z w.
//
//   onb uvw(rec.normal);                                 // w = the unit normal
//   vec3 d = uvw.transform(random_cosine_direction());   // cosine-weighted about the normal
//
// The basis is right-handed (cross(u, v) = w). The book builds its u the other way round, a
// left-handed basis; every distribution sampled through it is symmetric about w, so the mirror
// image changes no density, only which direction a given pair of random numbers maps to.
//
// The earlier edition's spelling also compiles: onb uvw; uvw.build_from_w(n); uvw.local(a, b, c),
// uvw.local(d), uvw[i].

#include "vec3.h"

#include <cmath>

namespace rt {

class onb {
  public:
    onb() = default; // the world axes x, y, z

    onb(const vec3& n) {
        // Scaled by its largest component first, so that its squared length neither underflows
        // (|n| ~ 1e-300) nor overflows (|n| ~ 1e300) on the way to unit length.
        double largest = std::fmax(std::fabs(n.x()), std::fmax(std::fabs(n.y()), std::fabs(n.z())));
        vec3 w = unit_vector(n / largest);
        // A helper axis far from parallel to w (|w.x| <= 0.9 makes x safe), so the cross product
        // below is at least sin(acos(0.9)) ~ 0.44 long and normalising it loses nothing.
        vec3 helper = std::fabs(w.x()) > 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0);
        vec3 v = unit_vector(cross(w, helper));
        axis_[0] = cross(v, w); // unit, as v and w are unit and orthogonal
        axis_[1] = v;
        axis_[2] = w;
    }

    const vec3& u() const { return axis_[0]; }
    const vec3& v() const { return axis_[1]; }
    const vec3& w() const { return axis_[2]; }

    // The vector with coordinates a in this basis, in world coordinates.
    vec3 transform(const vec3& a) const { return a[0] * axis_[0] + a[1] * axis_[1] + a[2] * axis_[2]; }

    // The earlier edition's names for the same things.
    const vec3& operator[](int i) const { return axis_[i]; }
    vec3 local(double a, double b, double c) const { return transform(vec3(a, b, c)); }
    vec3 local(const vec3& a) const { return transform(a); }
    void build_from_w(const vec3& n) { *this = onb(n); }

  private:
    vec3 axis_[3] = {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)};
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::onb;
#endif
