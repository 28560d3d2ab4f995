#pragma once
// material: how a surface scatters light (the book's interface), and the three book materials:
//   lambertian(albedo)           ideal diffuse
//   metal(albedo, fuzz)          mirror reflection, its direction moved by a uniform random point
//                                in a ball of radius fuzz (<= 1)
//   dielectric(refraction_index) glass: reflects or refracts, chosen by Schlick's approximation
//
// The renderer recognises these three and uses its own float kernels (bsdf.h), without virtual
// calls. The virtual scatter() below is the book's code path; it runs for materials attached to
// user-written shapes, and a user's own material subclass is rendered through it.

#include "color.h"
#include "hittable.h"
#include "ray.h"

#include <cmath>

namespace rt {

class material {
  public:
    virtual ~material() = default;

    virtual bool scatter(const ray& /*r_in*/, const hit_record& /*rec*/, color& /*attenuation*/,
                         ray& /*scattered*/) const {
        return false;
    }
};

// Schlick's approximation of the Fresnel reflectance (C. Schlick, "An Inexpensive BRDF Model for
// Physically-based Rendering", 1994): r0 + (1 - r0)(1 - cos)^5 with r0 = ((1 - ri)/(1 + ri))^2,
// for the cosine of the incident angle and the ratio ri of refractive indices, as the book uses it.
inline double schlick_reflectance(double cosine, double refraction_index) {
    double r0 = (1 - refraction_index) / (1 + refraction_index);
    r0 = r0 * r0;
    double m = 1 - cosine;
    return r0 + (1 - r0) * (m * m * m * m * m);
}

class lambertian : public material {
  public:
    lambertian(const color& albedo) : albedo_(albedo) {}

    bool scatter(const ray& /*r_in*/, const hit_record& rec, color& attenuation, ray& scattered) const override {
        auto scatter_direction = rec.normal + random_unit_vector();

        // Catch degenerate scatter direction
        if (scatter_direction.near_zero()) scatter_direction = rec.normal;

        scattered = ray(rec.p, scatter_direction);
        attenuation = albedo_;
        return true;
    }

    const color& albedo() const { return albedo_; }

  private:
    color albedo_;
};

class metal : public material {
  public:
    // Fuzz above 1 is clamped to 1, as in the book; NaN is kept so the renderer can reject it.
    metal(const color& albedo, double fuzz) : albedo_(albedo), fuzz_(fuzz > 1 ? 1 : fuzz) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        // The fuzz offset is a point inside the ball (random_in_unit_sphere), as in the book's
        // edition that rendered the team's reference images; later editions moved it onto the
        // sphere's surface, which blurs reflections a little more.
        vec3 reflected = reflect(r_in.direction(), rec.normal);
        reflected = unit_vector(reflected) + (fuzz_ * random_in_unit_sphere());
        scattered = ray(rec.p, reflected);
        attenuation = albedo_;
        return dot(scattered.direction(), rec.normal) > 0;
    }

    const color& albedo() const { return albedo_; }
    double fuzz() const { return fuzz_; }

  private:
    color albedo_;
    double fuzz_;
};

class dielectric : public material {
  public:
    dielectric(double refraction_index) : refraction_index_(refraction_index) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        attenuation = color(1.0, 1.0, 1.0);
        double ri = rec.front_face ? (1.0 / refraction_index_) : refraction_index_;

        vec3 unit_direction = unit_vector(r_in.direction());
        double cos_theta = std::fmin(dot(-unit_direction, rec.normal), 1.0);
        double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);

        bool cannot_refract = ri * sin_theta > 1.0;
        vec3 direction;
        if (cannot_refract || schlick_reflectance(cos_theta, ri) > random_double())
            direction = reflect(unit_direction, rec.normal);
        else
            direction = refract(unit_direction, rec.normal, ri);

        scattered = ray(rec.p, direction);
        return true;
    }

    double refraction_index() const { return refraction_index_; }

  private:
    // Refractive index in vacuum or air, or the ratio of the material's refractive index over
    // the refractive index of the enclosing media
    double refraction_index_;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::dielectric;
using rt::lambertian;
using rt::material;
using rt::metal;
#endif
