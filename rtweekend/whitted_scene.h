#pragma once
// whitted_scene: what a classic recursive (Whitted) ray tracer needs beyond geometry: point and
// ambient lights, Blinn-Phong materials with a mirror, conductor or dielectric part, and the
// cameras of the CENG795 course scenes (xml_scene.h reads them from XML; whitted.h renders them).
//
//   whitted_scene s;
//   auto red = make_shared<whitted_surface>(whitted_material{...});
//   s.world.add(make_shared<sphere>(point3(0, 0, -5), 1, red));
//   s.lights.push_back({point3(0, 4, 0), color(1000, 1000, 1000)});
//   s.cameras.push_back(view_camera{...});
//
// Colours here are in the course's units: 0..255 per channel on output, no gamma.

#include "color.h"
#include "hittable_list.h"
#include "material.h"
#include "vec3.h"

#include <string>
#include <vector>

namespace rt {

// A point light of intensity I (power per unit solid angle): irradiance I / d^2 at distance d.
struct point_light {
    point3 position;
    color intensity;
};

// A CENG795 material: Blinn-Phong shading (ambient, diffuse, specular with exponent) plus, by
// kind, a perfect mirror, a conductor (exact Fresnel from n and k, tinted by `mirror`) or a
// dielectric (exact Fresnel, refraction, Beer's law absorption inside).
struct whitted_material {
    enum class kind_t { plain, mirror, conductor, dielectric };
    kind_t kind = kind_t::plain;
    color ambient{0, 0, 0};   // ka: multiplies the ambient light
    color diffuse{0, 0, 0};   // kd
    color specular{0, 0, 0};  // ks
    double phong_exponent = 1;
    color mirror{0, 0, 0};    // MirrorReflectance: mirror and conductor
    double refraction_index = 1;  // conductor and dielectric
    double absorption_index = 0;  // k: conductor
    color absorption_coefficient{0, 0, 0}; // c per unit length: dielectric (Beer's law)
};

// The material object that geometry carries: the parameters above. The Whitted renderer reads
// them; the path tracer, which has no point lights, sees a Lambertian surface of albedo kd
// (clamped to 1) through the virtual scatter().
class whitted_surface : public material {
  public:
    explicit whitted_surface(const whitted_material& m) : params_(m) {}

    bool scatter(const ray& /*r_in*/, const hit_record& rec, color& attenuation, ray& scattered) const override {
        auto direction = rec.normal + random_unit_vector();
        if (direction.near_zero()) direction = rec.normal;
        scattered = ray(rec.p, direction);
        attenuation = color(std::fmin(params_.diffuse.x(), 1.0), std::fmin(params_.diffuse.y(), 1.0),
                            std::fmin(params_.diffuse.z(), 1.0));
        return true;
    }

    const whitted_material& params() const { return params_; }

  private:
    whitted_material params_;
};

// A CENG795 camera: position e, gaze, up, the image plane's extent (left, right, bottom, top) at
// distance near_distance along the gaze, and the image size. Pixel (i, j), j = 0 the top row,
// is sampled once, at its centre (see whitted.h for the mapping).
struct view_camera {
    point3 position{0, 0, 0};
    vec3 gaze{0, 0, -1};
    vec3 up{0, 1, 0};
    double left = -1, right = 1, bottom = -1, top = 1;
    double near_distance = 1;
    int width = 0, height = 0;
    std::string image_name; // as the file gives it; .png or .ppm
};

struct whitted_scene {
    color background{0, 0, 0};          // seen by primary rays that miss
    double shadow_ray_epsilon = 1e-3;   // offset of secondary ray origins along the normal
    double intersection_test_epsilon = 1e-6;
    int max_recursion_depth = 0;        // bounces; primary rays are depth 0
    color ambient_light{0, 0, 0};
    std::vector<point_light> lights;
    std::vector<view_camera> cameras;
    hittable_list world;                // spheres, triangles and meshes with whitted_surface materials
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::point_light;
using rt::view_camera;
using rt::whitted_material;
using rt::whitted_scene;
using rt::whitted_surface;
#endif
