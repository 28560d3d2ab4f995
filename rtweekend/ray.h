#pragma once
// ray: origin + t * direction, in double precision on the teaching surface (the renderer's
// float rays, ray3f, live in engine/vec3f.h).

#include "vec3.h"

namespace rt {

class ray {
  public:
    ray() {}
    ray(const point3& origin, const vec3& direction) : orig(origin), dir(direction) {}

    const point3& origin() const { return orig; }
    const vec3& direction() const { return dir; }

    point3 at(double t) const { return orig + t * dir; }

  private:
    point3 orig;
    vec3 dir;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::ray;
#endif
