#pragma once
// course_lights: the lights CENG795's homeworks 3 and 5 add to the point light (point_light.h), as
// the course's classic ray tracer shades them (shared/formats/ceng795-later.md, section 6; the
// whitted_scene holds them, course/whitted.h shades them). Each gives, at a point x, a direction
// towards the light, the distance a shadow ray must cover, and the irradiance E that multiplies
// the course's bracket (kd max(0, n.l) + ks max(0, n.h)^p):
//
//   directional_light  light travelling along `direction`: towards it is -direction, E = radiance
//                      at any distance, the shadow ray unbounded (homework 5)
//   spot_light         a point light whose intensity falls off inside a cone about `direction`:
//                      E = I s(alpha) / d^2, alpha the angle between direction and x - position,
//                      s = 1 within half the falloff angle, 0 beyond half the coverage angle, and
//                      ((cos alpha - cos(coverage/2)) / (cos(falloff/2) - cos(coverage/2)))^4
//                      between (the angles are full cone angles, in degrees; the fall-off is the
//                      one the instructor's images show, section 6.3) (homework 5)
//   area_light         an invisible square of edge `size` centred at `position`, perpendicular to
//                      `normal`, of radiance L, two-sided: one uniform point y on it per sample,
//                      E = L size^2 |n_l . w_i| / |y - x|^2 (homework 3; section 6.1)
//   light_mesh         <LightMesh> (homework 6): triangles (world space) of radiance L, which the
//                      scene also holds as geometry (camera rays that hit it see L); one point y
//                      per shading, uniform over the area A: E = L A |n_y . w_i| / |y - x|^2
//   light_sphere       <LightSphere> (homework 6): a sphere (centre, radius) under an affine map
//                      (an ellipsoid when it scales unevenly) of radiance L, also in the scene as
//                      geometry: y uniform over the object sphere, carried out by the map, whose
//                      area density is 1 / (4 pi r^2 J), J = |det M| |M^-T n| the map's stretch
//                      of area there: E = L max(0, n_y . w_i) 4 pi r^2 J / |y - x|^2 (the far
//                      side is hidden by the sphere itself)

#include "../color.h"
#include "../transform.h"
#include "../vec3.h"

#include <array>
#include <cmath>
#include <vector>

namespace rt {

// The course's frame about a unit direction d (section 4 of the spec): d' is d with its
// smallest-magnitude component set to 1, u = normalize(d x d'), v = d x u. An area light's square
// spans u and v about its normal; a rough material's ray is tilted along them.
inline void course_frame(const vec3& d, vec3& u, vec3& v) {
    vec3 other = d;
    const double ax = std::fabs(d.x()), ay = std::fabs(d.y()), az = std::fabs(d.z());
    if (ax <= ay && ax <= az) other[0] = 1;
    else if (ay <= az) other[1] = 1;
    else other[2] = 1;
    u = unit_vector(cross(d, other));
    v = cross(d, u);
}

struct directional_light {
    vec3 direction; // the way the light travels (any length)
    color radiance;
};

struct spot_light {
    point3 position;
    vec3 direction; // the cone's axis (any length)
    color intensity;
    double coverage_degrees = 0, falloff_degrees = 0; // full cone angles, falloff <= coverage

    // s(alpha) above, from cos alpha.
    double falloff(double cos_alpha) const {
        const double pi = 3.14159265358979323846;
        const double cos_falloff = std::cos(falloff_degrees * pi / 360), cos_coverage = std::cos(coverage_degrees * pi / 360);
        if (cos_alpha >= cos_falloff) return 1;
        if (cos_alpha < cos_coverage) return 0;
        const double s = (cos_alpha - cos_coverage) / (cos_falloff - cos_coverage);
        return (s * s) * (s * s);
    }
};

struct area_light {
    point3 position; // the square's centre
    vec3 normal;     // any length
    double size = 0; // edge length
    color radiance;
};

struct light_mesh {
    std::vector<std::array<point3, 3>> triangles; // world space
    color radiance;
};

struct light_sphere {
    point3 center; // object space, as the file gives them
    double radius = 0;
    mat3 linear;   // then x -> linear x + offset
    vec3 offset{0, 0, 0};
    color radiance;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::area_light;
using rt::directional_light;
using rt::light_mesh;
using rt::light_sphere;
using rt::spot_light;
#endif
