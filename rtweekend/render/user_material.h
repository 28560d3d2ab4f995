#pragma once
// The bridge to user code: a user's own material subclass is rendered through the books' virtual
// interface, in double precision and world coordinates. User code may call random_double();
// scoped_sample_rng makes that draw from the current sample's generator, so the image stays the
// same at any thread count.
//
// A user_material_hit asks the material once per hit, through book 3's scatter(r_in, rec, srec)
// (whose default calls book 1's scatter(r_in, rec, attenuation, scattered)), and answers in the
// material contract's terms (bsdf.h):
//   - srec.skip_pdf (a mirror, glass, or any book-1 material): one direction, reported as a delta
//     lobe with pdf 1: light sampling never relies on it;
//   - a pdf (book 3's lambertian and the like): a lobe with a density. eval(wi) is
//     attenuation * scattering_pdf(wi) (book 3's f |cos|), pdf(wi) is srec.pdf_ptr->value(wi), and
//     sample() draws from srec.pdf_ptr->generate(): next-event estimation and multiple importance
//     sampling work with it as with a built-in material.
// Its emission is the book-3 emitted(r_in, rec, u, v, p); such an emitter is not light-sampled
// (its power is unknown), so a path counts it in full when it hits it.

#include "../hittable.h"
#include "../material.h"
#include "../pdf.h"
#include "../core/material_kinds.h"
#include "../scene/compiled_scene.h"
#include "../scene/surface_coordinates.h"
#include "../core/vec3f.h"

#include <cmath>
#include <memory>

namespace rt {

class user_material_hit {
  public:
    // The hit `hit` of the ray r (relative to the scene origin) on a surface of the user's
    // material m.
    user_material_hit(const compiled_scene& scene, const material& m, const ray3f& r, const surface_hit& hit);

    vec3f emitted() const;
    // Asks the material to scatter; false when it absorbs the ray.
    bool scatter();
    // Whether the scattered light has a density (a pdf), so light sampling can reach it.
    bool has_density() const { return !srec_.skip_pdf && srec_.pdf_ptr; }

    bool sample(material_sample& s) const;
    vec3f eval(const vec3f& wi) const;
    float pdf(const vec3f& wi) const;

  private:
    const material& m_;
    vec3 origin_;       // the scene origin: hit points are relative to it
    vec3f normal_;      // the geometric normal facing the ray, to tell reflection from transmission
    hit_record rec_;
    ray r_in_;
    scatter_record srec_;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {
// A non-owning shared_ptr, for handing the renderer's material pointers to user code.
inline std::shared_ptr<material> borrow(const material* m) {
    return std::shared_ptr<material>(std::shared_ptr<material>(), const_cast<material*>(m));
}
} // namespace detail

inline user_material_hit::user_material_hit(const compiled_scene& scene, const material& m, const ray3f& r,
                                            const surface_hit& hit)
    : m_(m), origin_(scene.origin), normal_(hit.normal) {
    if (hit.user_shape) {
        rec_ = hit.user_record; // a user's hittable filled it in world coordinates
    } else {
        rec_.p = scene.origin + hit.p.to_double();
        rec_.normal = hit.normal.to_double();
        rec_.t = hit.t;
        rec_.front_face = hit.front_face;
        rec_.mat = detail::borrow(&m);
        surface_coordinates(scene, hit, rec_.u, rec_.v);
    }
    r_in_ = ray(scene.origin + r.origin.to_double(), r.dir.to_double(), r.time);
}

inline vec3f user_material_hit::emitted() const { return vec3f(m_.emitted(r_in_, rec_, rec_.u, rec_.v, rec_.p)); }

inline bool user_material_hit::scatter() { return m_.scatter(r_in_, rec_, srec_); }

inline bool user_material_hit::sample(material_sample& s) const {
    if (has_density()) {
        s.wi = normalize(vec3f(srec_.pdf_ptr->generate()));
        s.pdf = pdf(s.wi);
        const vec3f f = eval(s.wi);
        if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return false;
        s.value = f * (1.0f / s.pdf);
        s.sampled = non_delta_lobe;
        return true;
    }
    s.wi = normalize(vec3f(srec_.skip_pdf_ray.direction()));
    s.value = vec3f(srec_.attenuation);
    s.pdf = 1;
    s.sampled = dot(s.wi, normal_) >= 0 ? delta_reflection : delta_transmission;
    return std::isfinite(s.wi.x) && std::isfinite(s.wi.y) && std::isfinite(s.wi.z);
}

inline vec3f user_material_hit::eval(const vec3f& wi) const {
    const double density = m_.scattering_pdf(r_in_, rec_, ray(rec_.p, wi.to_double(), r_in_.time()));
    return vec3f(srec_.attenuation) * static_cast<float>(density);
}

inline float user_material_hit::pdf(const vec3f& wi) const {
    return has_density() ? static_cast<float>(srec_.pdf_ptr->value(wi.to_double())) : 0.0f;
}

} // namespace rt
