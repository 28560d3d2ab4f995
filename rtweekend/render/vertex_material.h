#pragma once
// vertex_material: the material at a path vertex, as the path tracer's estimators ask it, with
// smooth shading's fold (below).

#include "../core/material_kinds.h"
#include "../core/vec3f.h"
#include "user_material.h"

namespace rt {
namespace detail {

// The material at a path vertex, as the estimators ask it: a built-in material through the
// contract (bsdf.h), a user's through its virtual functions (user_material.h).
//
// Smooth shading. A smooth mesh's interpolated normal ns (the shading normal) tilts away from the
// triangle's own normal ng, so a lobe drawn about ns can dip below the surface, where a ray
// would pass through it: rays lost (dark facets) or leaking. The rule here keeps every bit of
// energy instead: a direction below the geometric surface is mirrored through it,
// w -> w - 2 (w . ng) ng, and the material seen by the path is the folded one,
//   f'(wi) = f(wi) + f(mirror(wi))   (wi above the surface; 0 below), pdf' likewise,
// which reflects exactly what f reflects over the whole sphere (the mirror maps the lower half
// onto the upper one and keeps solid angle). A Lambertian surface under shading normals thus
// weighs every sample by its albedo exactly, as it does without them: a white furnace stays
// white and no facet turns black. Delta lobes are mirrored back to the side they belong to
// (reflection: the incoming side; refraction: the other). Light sampling and multiple importance
// sampling see the same folded f' and pdf'. User materials get the shading normal as is.
template <bool UserMaterials>
struct vertex_material {
    const compiled_material& m;
    const shading_point& sp; // the caller's: a copy, written field by field and read back whole, stalled the store buffer
    vec3f wo;
    const user_material_hit* user; // set for a user's material, which has scattered already
    vec3f ng;                      // the geometric normal, on wo's side
    bool folded = false;           // shading normal differs from ng: fold as above

    bool is_user() const { return UserMaterials && user; }
    bool has_density() const { return is_user() ? user->has_density() : m.has_non_delta_lobe(); }
    vec3f mirror(const vec3f& w) const { return w - (2.0f * dot(w, ng)) * ng; }
    vec3f eval(const vec3f& wi) const {
        if (is_user()) return user->eval(wi);
        if (!folded) return m.eval(wo, wi, sp);
        if (!(dot(wi, ng) > 0)) return {0, 0, 0};
        return m.eval(wo, wi, sp) + m.eval(wo, mirror(wi), sp);
    }
    float pdf(const vec3f& wi) const {
        if (is_user()) return user->pdf(wi);
        if (!folded) return m.pdf(wo, wi, sp);
        if (!(dot(wi, ng) > 0)) return 0;
        return m.pdf(wo, wi, sp) + m.pdf(wo, mirror(wi), sp);
    }
    template <class Uniform>
    bool sample(Uniform& u, material_sample& s) const {
        if (is_user()) return user->sample(s);
        if (!m.sample(wo, sp, u, s)) return false;
        if (!folded) return true;
        if (s.is_delta()) {
            const float side = dot(s.wi, ng);
            if (s.sampled == delta_transmission ? side > 0 : side < 0) s.wi = mirror(s.wi);
            return true;
        }
        if (dot(s.wi, ng) < 0) s.wi = mirror(s.wi);
        const float density = pdf(s.wi);
        if (!(density > 0)) return false;
        s.value = eval(s.wi) * (1.0f / density);
        s.pdf = density;
        return true;
    }
};

} // namespace detail
} // namespace rt
