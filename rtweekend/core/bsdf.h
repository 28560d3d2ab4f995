#pragma once
// The material contract: what every built-in material answers, once, for every integrator (the
// path tracer, light tracing, the Whitted integrator), in the manner of pbrt's BxDFs (Pharr,
// Jakob, Humphreys, Physically Based Rendering, 4th ed., ch. 9) and Nori's BSDFs. The kinds are
// the headers of core/materials/, one each, listed in core/material_kinds.h, whose
// compiled_material is what the compiled scene's table holds and what the integrators ask.
//
// A material kind M (a struct of its parameters) answers:
//   m.sample(wo, sp, u, s, lobes)   draws wi for wo, restricted to `lobes`; s.value = f |cos| / pdf,
//                                   s.pdf, s.sampled; false when the light is absorbed (or no lobe
//                                   of `lobes` exists). Draws a choice (lobe, Fresnel) from
//                                   u.next_float(), a direction's pair from draw_2d(u) (rng.h)
//   m.eval(wo, wi, sp)              f(wo, wi) |cos theta_i|       (0 on delta lobes)
//   m.pdf(wo, wi, sp)               the solid-angle density sample() draws wi with
//   m.emitted(wo, sp), m.emission() radiance emitted towards wo; the constant emission (a light's)
//   m.transmittance(d)              the fraction of light left after a distance d inside it (Beer)
//   m.properties()                  what the integrators ask instead of its kind: material_properties
//   m.lobe_weight()                 its lobes' largest reflectance, against which a course material's
//                                   Lambertian base is chosen (compiled_material::sample)
//   m.reversal_ratio(n, wo, front, s)   for a light path that drew s from the side `front` says: the
//                                   probability the path tracer would draw it from the other end
//                                   over s's own (1 but for the book's Schlick glass;
//                                   render/caustic_paths.h)
//   M::takes_texture, m.set_colour(c)   whether a texture colours it, and how (its albedo, or a
//   m.colour()                      light's emission), and that colour untextured
//
// Directions are unit vectors pointing away from the surface: wo towards where the light goes
// (the previous vertex: minus the ray's direction), wi towards where it comes from (the scattered
// ray's direction). The shading point gives the unit normal on wo's side and which face was hit.
//
// Lobes. Glass, mirrors and smooth conductors scatter into single directions (delta lobes): their
// eval and pdf are 0 for every pair of directions, and sample() reports the lobe's discrete
// probability as s.pdf. Light sampling must treat them apart (pbrt, 4th ed., 9.1.3). sample() can
// be restricted to some lobes: the Whitted integrator follows the delta reflection and the delta
// transmission one after the other (as pbrt-v3's Whitted integrator does with BxDF type flags).

#include "vec3f.h"

#include <cmath>
#include <cstdint>

namespace rt {

// Which lobes sample() may choose from: bit flags.
enum lobe : uint8_t {
    non_delta_lobe = 1,          // diffuse and glossy reflection, with a density
    delta_reflection = 2,        // a mirror direction
    delta_transmission = 4,      // a refracted direction
    all_lobes = 7,
};

// Where a material is asked: the unit normal on the side of wo (the geometric or the shading
// normal, as the integrator chooses) and whether the ray hit the front face (glass needs to
// know which index is on which side). A phase function (isotropic) ignores both: its point is
// inside a volume, and whatever normal the medium reports there means nothing.
struct shading_point {
    vec3f n;
    bool front_face = true;
};

struct material_sample {
    vec3f wi;                // unit direction the light arrives from: the scattered ray's direction
    vec3f value;             // f |cos theta_i| / pdf: what the path throughput is multiplied by
    float pdf = 0;           // solid-angle density; for a delta lobe, the probability of choosing it
    lobe sampled = non_delta_lobe;
    bool is_delta() const { return sampled != non_delta_lobe; }
};

// What the integrators ask of a material instead of its kind.
struct material_properties {
    bool emits = false;            // it emits light (a nonzero emission)
    bool two_sided = false;        // it emits from its back face too
    bool scatters = true;          // light that reaches it goes on (an emitter absorbs it: paths end)
    bool has_delta_lobe = false;   // some lobe is a single direction (glass, a mirror, a smooth coat):
                                   // light leaving it can form a caustic (render/caustic_paths.h)
    bool has_density = false;      // some lobe has a density (diffuse or glossy): light sampling reaches it
    bool refracts = false;         // light crosses into it (glass: its inside is another medium)
    bool transmits = false;        // light can pass through the surface: its back face is never culled
    bool density_crosses = false;  // a lobe with a density reaches the far side (rough glass): smooth
                                   // shading's fold, which keeps lobes on the near side, must not apply
    bool phase_function = false;   // it scatters to the whole sphere at a point inside a volume: eval
                                   // has no cosine, and light may arrive from any side
    bool absorbs_inside = false;   // light travelling inside loses energy with distance (Beer)
    bool lambertian_only = false;  // its one lobe is Lambertian: it leaves by the cosine from either end
    bool user = false;             // a user's material, rendered through its virtual scatter()
};

// --- what the kinds share -----------------------------------------------------------------------

inline vec3f reflect_f(const vec3f& v, const vec3f& n) { return v - 2.0f * dot(v, n) * n; }

// Refraction of the unit direction `d` through the unit normal `n` facing it, for the index
// ratio ri = n_incident / n_transmitted and cos_theta = -d.n (the book's form: perpendicular and
// parallel parts).
inline vec3f refract_f(const vec3f& d, const vec3f& n, float cos_theta, float ri) {
    vec3f perp = ri * (d + cos_theta * n);
    vec3f parallel = -std::sqrt(std::fabs(1.0f - length_squared(perp))) * n;
    return perp + parallel;
}

// Beer-Lambert law: the fraction of light left after a distance d in a medium of absorption
// coefficient sigma, exp(-sigma d), per channel.
inline vec3f beer_transmittance(const vec3f& sigma, float d) {
    return {std::exp(-sigma.x * d), std::exp(-sigma.y * d), std::exp(-sigma.z * d)};
}

inline float max_component(const vec3f& v) { return fmax_inline(v.x, fmax_inline(v.y, v.z)); }

} // namespace rt
