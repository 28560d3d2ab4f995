#pragma once
// material: how a surface scatters light (the book's interface), and the three book materials:
//   lambertian(albedo)           ideal diffuse
//   metal(albedo, fuzz)          mirror reflection, its direction moved by a uniform random point
//                                in a ball of radius fuzz (<= 1)
//   dielectric(refraction_index) glass: reflects or refracts, chosen by Schlick's approximation
// and two beyond the book, with the exact Fresnel equations (fresnel.h):
//   conductor(n, k, tint)        a smooth metal of complex index n + ik: mirror reflection
//                                weighted by tint * Fr(cos); n, k scalars or per-channel colours
//   dielectric(refraction_index, absorption)
//                                glass that reflects with the exact Fresnel probability and,
//                                inside, keeps exp(-absorption * distance) per channel (Beer's law)
//
// The renderer recognises these and uses its own float kernels (bsdf.h), without virtual
// calls. The virtual scatter() below is the book's code path; it runs for materials attached to
// user-written shapes, and a user's own material subclass is rendered through it.

#include "color.h"
#include "engine/fresnel.h"
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
    // The book's glass: Schlick's reflectance, no absorption.
    dielectric(double refraction_index) : refraction_index_(refraction_index) {}

    // Glass with the exact Fresnel reflectance and Beer's law: light that travels a distance d
    // inside keeps exp(-absorption * d) of itself, per channel (absorption per unit length;
    // 0 0 0 is clear glass).
    dielectric(double refraction_index, const color& absorption)
        : refraction_index_(refraction_index), absorption_(absorption), exact_fresnel_(true) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        if (exact_fresnel_) return scatter_exact(r_in, rec, attenuation, scattered);
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
    const color& absorption() const { return absorption_; }
    // True for the two-argument constructor: exact Fresnel and Beer's law instead of Schlick.
    bool exact_fresnel() const { return exact_fresnel_; }

  private:
    bool scatter_exact(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const {
        // A ray that reaches the back face has travelled inside from its origin: the previous
        // scattering point, on this glass (there are no nested media here).
        if (rec.front_face) {
            attenuation = color(1.0, 1.0, 1.0);
        } else {
            double d = rec.t * r_in.direction().length();
            attenuation = color(std::exp(-absorption_.x() * d), std::exp(-absorption_.y() * d),
                                std::exp(-absorption_.z() * d));
        }
        double eta = rec.front_face ? refraction_index_ : 1.0 / refraction_index_; // n_t / n_i
        vec3 unit_direction = unit_vector(r_in.direction());
        double cos_theta = std::fmin(dot(-unit_direction, rec.normal), 1.0);
        double fr = fresnel_dielectric(cos_theta, eta); // 1 under total internal reflection
        vec3 direction;
        if (fr >= 1 || random_double() < fr)
            direction = reflect(unit_direction, rec.normal);
        else
            direction = refract(unit_direction, rec.normal, 1.0 / eta);
        scattered = ray(rec.p, direction);
        return true;
    }

    // Refractive index in vacuum or air, or the ratio of the material's refractive index over
    // the refractive index of the enclosing media
    double refraction_index_;
    color absorption_{0, 0, 0};
    bool exact_fresnel_ = false;
};

// A smooth conductor (metal) of complex refractive index n + ik, seen from air: a perfect mirror
// whose reflectance is the exact Fresnel reflectance Fr(cos, n, k) per channel, times `tint` (an
// artist's control; 1 1 1 is the physical metal). Per-channel n and k give coloured metals:
// gold is roughly n = (0.18, 0.42, 1.37), k = (3.42, 2.35, 1.77) at 650, 550, 450 nm.
class conductor : public material {
  public:
    conductor(double n, double k, const color& tint) : conductor(color(n, n, n), color(k, k, k), tint) {}
    conductor(const color& n, const color& k, const color& tint) : n_(n), k_(k), tint_(tint) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        vec3 unit_direction = unit_vector(r_in.direction());
        double cos_theta = std::fmin(dot(-unit_direction, rec.normal), 1.0);
        attenuation = tint_ * reflectance(cos_theta);
        scattered = ray(rec.p, reflect(unit_direction, rec.normal));
        return true;
    }

    // Fr per channel at incidence cosine `cos_theta`.
    color reflectance(double cos_theta) const {
        return color(fresnel_conductor(cos_theta, n_.x(), k_.x()), fresnel_conductor(cos_theta, n_.y(), k_.y()),
                     fresnel_conductor(cos_theta, n_.z(), k_.z()));
    }

    const color& n() const { return n_; }
    const color& k() const { return k_; }
    const color& tint() const { return tint_; }

  private:
    color n_, k_, tint_;
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::conductor;
using rt::dielectric;
using rt::lambertian;
using rt::material;
using rt::metal;
#endif
