#pragma once
// course_lights: the lights CENG795's homeworks 3 and 5 add to the point light (point_light.h), as
// the course's classic ray tracer shades them (shared/formats/ceng795-later.md, section 6; the
// whitted_scene holds them, course/whitted.h shades them). Each gives, at a point x, a direction
// towards the light, the distance a shadow ray must cover, and the irradiance E that multiplies
// the course's bracket (kd max(0, n.l) + ks max(0, n.h)^p):
//
//   directional_light  (directional_light.h, shared with the path tracer) light travelling along
//                      `direction`: towards it is -direction, E = `irradiance` (the course's
//                      <Radiance>) at any distance, the shadow ray unbounded (homework 5)
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
//   environment_light  <SphericalDirectionalLight> (homework 5): radiance from every direction at
//                      infinity, a lat-long image: one direction w uniform on the hemisphere about
//                      n per shading, E = 2 pi L(w) when nothing is in the way (L over the density
//                      1 / (2 pi)); rays that leave the scene see L of their direction

#include "../color.h"
#include "../directional_light.h"
#include "../hittable.h"
#include "../core/vec3f.h"
#include "../image/image.h"
#include "../render/environment_map.h"
#include "../transform.h"
#include "../vec3.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
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
    // The shape the scene's world holds for it (with a course material that emits L), so that a
    // renderer with lights of its own can put another in its place (render --integrator path).
    std::shared_ptr<hittable> shape;
};

struct light_sphere {
    point3 center; // object space, as the file gives them
    double radius = 0;
    mat3 linear;   // then x -> linear x + offset
    vec3 offset{0, 0, 0};
    color radiance;
    std::shared_ptr<hittable> shape; // as light_mesh's
};

// A lat-long map of the radiance arriving from each direction d (unit, world space): the texel at
// u = (1 + atan2(d_x, -d_z) / pi) / 2 across and v = acos(d_y) / pi down (v = 0 the top row: +y),
// the nearest one, (floor(u W), floor(v H)) clamped to the image (section 6.4 of the spec). Texels
// are radiance as they are (an EXR's or HDR's floats; an 8-bit image's codes 0-255).
struct environment_light {
    std::shared_ptr<const image> map;
    std::string path; // the file it was read from, for messages

    vec3f radiance(const vec3f& d) const {
        int x, y;
        latlong_texel(d, map->width(), map->height(), x, y);
        return vec3f(map->pixel(x, y));
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::area_light;
using rt::environment_light;
using rt::light_mesh;
using rt::light_sphere;
using rt::spot_light;
#endif
