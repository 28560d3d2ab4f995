#pragma once
// ray: origin + t * direction, in double precision on the teaching surface (the renderer's
// float rays, ray3f, live in core/vec3f.h). Book 2 gives rays a time, for motion blur; it is
// kept and handed on so book-2 and book-3 code compiles (nothing in the scene moves yet).

#include "vec3.h"

namespace rt {

class ray {
  public:
    ray() {}
    ray(const point3& origin, const vec3& direction) : orig(origin), dir(direction) {}
    ray(const point3& origin, const vec3& direction, double time) : orig(origin), dir(direction), tm(time) {}

    const point3& origin() const { return orig; }
    const vec3& direction() const { return dir; }
    double time() const { return tm; }

    point3 at(double t) const { return orig + t * dir; }

  private:
    point3 orig;
    vec3 dir;
    double tm = 0;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::ray;
#endif
