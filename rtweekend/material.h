#pragma once
// material: how a surface scatters light (the book's interface), and the three book materials:
//   lambertian(albedo)           ideal diffuse
//   metal(albedo, fuzz)          mirror reflection, its direction moved by a uniform random point
//                                in a ball of radius fuzz (<= 1)
//   dielectric(refraction_index) glass: reflects or refracts, chosen by Schlick's approximation
// and two beyond the book, with the exact Fresnel equations (engine/fresnel.h):
//   conductor(n, k, tint)        a smooth metal of complex index n + ik: mirror reflection
//                                weighted by tint * Fr(cos); n, k scalars or per-channel colours
//   dielectric(refraction_index, absorption)
//                                glass that reflects with the exact Fresnel probability and,
//                                inside, keeps exp(-absorption * distance) per channel (Beer's law)
//
// Each material's physics is written once, in the renderer's material contract (engine/bsdf.h:
// sample, eval, pdf), which every integrator calls. The renderer recognises these classes and
// calls the contract directly, without virtual calls. The virtual scatter() below is the book's
// interface, for code that calls it itself (a ray_color of one's own): for the built-in materials
// it draws from the same contract, in float (directions and weights agree with double arithmetic
// to about 1e-6), with random_double(). A user's own material subclass overrides scatter(), and
// the renderer calls it.

#include "color.h"
#include "engine/bsdf.h"
#include "engine/fresnel.h"
#include "engine/rng.h"
#include "engine/vec3f.h"
#include "hittable.h"
#include "ray.h"

namespace rt {

class material {
  public:
    virtual ~material() = default;

    virtual bool scatter(const ray& /*r_in*/, const hit_record& /*rec*/, color& /*attenuation*/,
                         ray& /*scattered*/) const {
        return false;
    }
};

namespace detail {

// random_double() as the contract draws its numbers: uniform in [0, 1) in float.
struct book_uniform {
    float next_float() {
        float u = static_cast<float>(random_double());
        return u < 1.0f ? u : 0x1.fffffep-1f; // a double just below 1 rounds up to 1 in float
    }
};

// The book's scatter() through the material contract: one draw of `m`'s sample() at the hit, in
// world coordinates. A ray that reaches the back face of absorbing glass has travelled
// rec.t * |direction| inside it: its weight includes Beer's law for that distance, as the path
// tracer's does.
inline bool scatter_through_contract(const compiled_material& m, const ray& r_in, const hit_record& rec,
                                     color& attenuation, ray& scattered) {
    const shading_point sp{vec3f(rec.normal), rec.front_face};
    book_uniform u;
    material_sample s;
    if (!m.sample(-normalize(vec3f(r_in.direction())), sp, u, s)) return false;
    vec3f weight = s.value;
    if (!rec.front_face && m.absorbs_inside())
        weight *= m.transmittance(static_cast<float>(rec.t * r_in.direction().length()));
    attenuation = weight.to_double();
    scattered = ray(rec.p, s.wi.to_double());
    return true;
}

} // namespace detail

class lambertian : public material {
  public:
    lambertian(const color& albedo) : albedo_(albedo) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    // The material as the renderer's contract sees it (unchecked: material_compiler.h checks).
    compiled_material compiled() const {
        compiled_material m;
        m.kind = material_kind::lambertian;
        m.albedo = vec3f(albedo_);
        m.source = this;
        return m;
    }

    const color& albedo() const { return albedo_; }

  private:
    color albedo_;
};

class metal : public material {
  public:
    // Fuzz above 1 is clamped to 1, as in the book; NaN is kept so the renderer can reject it.
    // The fuzz offset is a point inside the ball (as the book's edition that rendered the team's
    // reference images has it); later editions moved it onto the sphere's surface, which blurs
    // reflections a little more.
    metal(const color& albedo, double fuzz) : albedo_(albedo), fuzz_(fuzz > 1 ? 1 : fuzz) {}

    bool scatter(const ray& r_in, const hit_record& rec, color& attenuation, ray& scattered) const override {
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        compiled_material m;
        m.kind = material_kind::metal;
        m.albedo = vec3f(albedo_);
        m.fuzz = static_cast<float>(fuzz_);
        m.source = this;
        return m;
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
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        compiled_material m;
        m.kind = exact_fresnel_ ? material_kind::fresnel_dielectric : material_kind::dielectric;
        m.albedo = {1, 1, 1};
        m.refraction_index = static_cast<float>(refraction_index_);
        m.absorption = vec3f(absorption_);
        m.source = this;
        return m;
    }

    // Refractive index in vacuum or air, or the ratio of the material's refractive index over
    // the refractive index of the enclosing media.
    double refraction_index() const { return refraction_index_; }
    const color& absorption() const { return absorption_; }
    // True for the two-argument constructor: exact Fresnel and Beer's law instead of Schlick.
    bool exact_fresnel() const { return exact_fresnel_; }

  private:
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
        return detail::scatter_through_contract(compiled(), r_in, rec, attenuation, scattered);
    }

    compiled_material compiled() const {
        compiled_material m;
        m.kind = material_kind::conductor;
        m.albedo = vec3f(tint_);
        m.eta = vec3f(n_);
        m.k = vec3f(k_);
        m.source = this;
        return m;
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
