#pragma once
// The bridge to user code: a user's own material subclass is rendered through the book's virtual
// interface, material::scatter(r_in, rec, attenuation, scattered), in double precision and world
// coordinates. User code may call random_double(); scoped_sample_rng makes that draw from the
// current sample's generator, so the image stays the same at any thread count.
//
// In the material contract's terms (bsdf.h) such a material has no density anyone knows: its
// samples are reported as delta lobes (reflection or transmission by the side wi leaves on),
// with pdf 1, and its eval and pdf are 0, so light sampling never relies on them.

#include "../hittable.h"
#include "../material.h"
#include "bsdf.h"
#include "compiled_scene.h"
#include "vec3f.h"

#include <memory>

namespace rt {

// Scatters the ray r (relative to the scene origin) at `hit` through the virtual scatter() of
// the user's material m. False when the material absorbs it.
bool sample_user_material(const compiled_scene& scene, const material& m, const ray3f& r, const surface_hit& hit,
                          material_sample& s);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {
// A non-owning shared_ptr, for handing the renderer's material pointers to user code.
inline std::shared_ptr<material> borrow(const material* m) {
    return std::shared_ptr<material>(std::shared_ptr<material>(), const_cast<material*>(m));
}
} // namespace detail

inline bool sample_user_material(const compiled_scene& scene, const material& m, const ray3f& r,
                                 const surface_hit& hit, material_sample& s) {
    hit_record rec;
    if (hit.user_shape) {
        rec = hit.user_record; // a user's hittable filled it in world coordinates
    } else {
        rec.p = scene.origin + hit.p.to_double();
        rec.normal = hit.normal.to_double();
        rec.t = hit.t;
        rec.front_face = hit.front_face;
        rec.mat = detail::borrow(&m);
    }
    ray r_in(scene.origin + r.origin.to_double(), r.dir.to_double());
    color att;
    ray scattered;
    if (!m.scatter(r_in, rec, att, scattered)) return false;
    s.wi = normalize(vec3f(scattered.direction()));
    s.value = vec3f(att);
    s.pdf = 1;
    s.sampled = dot(s.wi, hit.normal) >= 0 ? delta_reflection : delta_transmission;
    return true;
}

} // namespace rt
