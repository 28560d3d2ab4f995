#pragma once
// The material kinds, and compiled_material: the entry of the compiled scene's material table
// that the integrators ask (core/bsdf.h says what; core/materials/ holds one header per kind).
//
//   compiled_material m = compiled_material::of(lambertian_bsdf{albedo});
//   m.sample(wo, sp, u, s)    m.eval(wo, wi, sp)    m.pdf(wo, wi, sp)    m.emitted(wo, sp)
//   m.emits(), m.has_delta_lobe(), m.is_phase_function(), ...   its properties, worked out once
//   m.is<metal_bsdf>(), m.as<metal_bsdf>()                      its kind, for tests and compilers
//
// Every query dispatches on the kind through the list below (core/kind_list.h): a kind added to
// the list that misses a query does not compile.
//
// A material compiled from the CENG795 course's (whitted_material.h) may also carry a Lambertian
// base (`diffuse`) under a delta lobe; sample() picks the base or the lobe in proportion to their
// largest reflectances.

#include "bsdf.h"
#include "constants.h"
#include "kind_list.h"
#include "materials/blinn_phong_bsdf.h"
#include "materials/conductor_bsdf.h"
#include "materials/course_brdf_bsdf.h"
#include "materials/dielectric_bsdf.h"
#include "materials/emitter_bsdf.h"
#include "materials/fresnel_glass_bsdf.h"
#include "materials/isotropic_phase.h"
#include "materials/lambertian_bsdf.h"
#include "materials/metal_bsdf.h"
#include "materials/metal_rough_bsdf.h"
#include "materials/plastic_bsdf.h"
#include "materials/rough_conductor_bsdf.h"
#include "materials/rough_dielectric_bsdf.h"
#include "materials/user_bsdf.h"
#include "rng.h"
#include "sampling.h"
#include "vec3f.h"

#include <cstdint>
#include <variant>

namespace rt {

class material;

using material_kinds = kind_list<lambertian_bsdf, metal_bsdf, dielectric_bsdf, fresnel_glass_bsdf, conductor_bsdf,
                                 emitter_bsdf, isotropic_phase, plastic_bsdf, blinn_phong_bsdf, course_brdf_bsdf,
                                 user_bsdf, rough_conductor_bsdf, rough_dielectric_bsdf, metal_rough_bsdf>;

// compiled_material::texture when the material has no texture.
inline constexpr uint32_t no_texture = UINT32_MAX;

class compiled_material {
  public:
    compiled_material() : compiled_material(lambertian_bsdf{}) {}
    template <class Kind, class = std::enable_if_t<std::is_constructible_v<kind_variant<material_kinds>, Kind>>>
    explicit compiled_material(const Kind& kind, const material* source_material = nullptr)
        : source(source_material), kind_(kind) {
        refresh();
    }
    template <class Kind>
    static compiled_material of(const Kind& kind, const material* source_material = nullptr) {
        return compiled_material(kind, source_material);
    }

    // f(the kind's record), for whichever kind it is.
    template <class F>
    RTWEEKEND_FORCE_INLINE decltype(auto) visit(F&& f) const {
        return visit_value<material_kinds>(kind_, f);
    }

    // A Lambertian base under the kind's delta lobe (course materials); 0: none.
    vec3f diffuse{0, 0, 0};
    // A kind that takes a texture (lambertian's albedo, a light's emission: M::takes_texture) looks
    // its colour up per hit in the compiled scene's texture table (scene/texture_table.h):
    // no_texture, the kind's own colour. The integrator then asks a copy with that colour in
    // (with_colour).
    uint32_t texture = no_texture;
    const material* source = nullptr; // what it was compiled from; a user material is called through it

    // Draws wi for wo, restricted to `lobes`; false when the light is absorbed (or no lobe of
    // `lobes` exists).
    template <class Uniform>
    bool sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes = all_lobes) const;
    vec3f eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const;
    float pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const;
    vec3f emitted(const vec3f& wo, const shading_point& sp) const {
        return visit([&](const auto& k) { return k.emitted(wo, sp); });
    }
    vec3f emission() const {
        return visit([](const auto& k) { return k.emission(); });
    }
    // The fraction of light left after `distance` inside it (Beer-Lambert): 1 unless absorbs_inside.
    vec3f transmittance(float distance) const {
        return visit([&](const auto& k) { return k.transmittance(distance); });
    }
    // For a light path (render/caustic_paths.h): see core/bsdf.h.
    float reversal_ratio(const vec3f& n, const vec3f& wo, bool front, const material_sample& s) const {
        return visit([&](const auto& k) { return k.reversal_ratio(n, wo, front, s); });
    }

    // What the integrators ask instead of its kind (core/bsdf.h: material_properties).
    const material_properties& properties() const { return props_; }
    bool emits() const { return props_.emits; }
    bool two_sided() const { return props_.two_sided; }
    bool scatters() const { return props_.scatters; }
    bool has_delta_lobe() const { return props_.has_delta_lobe; }
    bool has_non_delta_lobe() const { return props_.has_density; }
    bool refracts() const { return props_.refracts; }
    bool transmits() const { return props_.transmits; }
    bool density_crosses() const { return props_.density_crosses; }
    bool is_phase_function() const { return props_.phase_function; }
    bool absorbs_inside() const { return props_.absorbs_inside; }
    bool lambertian_only() const { return props_.lambertian_only; }
    bool is_user() const { return props_.user; }
    bool has_diffuse_base() const { return diffuse.x > 0 || diffuse.y > 0 || diffuse.z > 0; }

    // Its kind: the number in material_kinds, and the kind's own record.
    size_t kind() const { return kind_.index(); }
    template <class Kind>
    bool is() const { return std::holds_alternative<Kind>(kind_); }
    template <class Kind>
    const Kind& as() const { return std::get<Kind>(kind_); }
    template <class Kind>
    const Kind* get_if() const { return std::get_if<Kind>(&kind_); }
    // Changes the kind's record by f(record) when it is of kind Kind.
    template <class Kind, class F>
    void edit(F&& f) {
        if (Kind* k = std::get_if<Kind>(&kind_)) {
            f(*k);
            refresh();
        }
    }

    // A copy coloured `c` by its texture: a lambertian's albedo, a light's emission.
    compiled_material with_colour(const vec3f& c) const;
    // Whether a texture colours its kind, and the kind's colour as compiled (white when none does).
    bool takes_colour() const {
        return visit([](const auto& k) { return std::decay_t<decltype(k)>::takes_texture; });
    }
    vec3f colour() const {
        return visit([](const auto& k) {
            if constexpr (std::decay_t<decltype(k)>::takes_texture) return k.colour();
            else return vec3f(1, 1, 1);
        });
    }
    // Sets the diffuse base (and what it adds to the properties).
    void set_diffuse_base(const vec3f& d) {
        diffuse = d;
        refresh();
    }

  private:
    material_properties props_;
    kind_variant<material_kinds> kind_;

    // The kind's own sample(), out of line: the kinds' draws are not repeated in every caller
    // (the same speed as inlined, within 0.1 % on the cover, and less code to compile).
    template <class Uniform>
#if defined(__GNUC__)
    __attribute__((noinline))
#endif
    bool sample_kind(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s, lobe lobes) const {
        return visit([&](const auto& k) { return k.sample(wo, sp, u, s, lobes); });
    }

    void refresh() {
        props_ = visit([](const auto& k) { return k.properties(); });
        if (has_diffuse_base()) {
            props_.has_density = true;
            props_.lambertian_only = false;
        }
    }
    // The probability sample() picks the diffuse base over the kind's lobe.
    float base_probability() const {
        const float base = max_component(diffuse);
        const float lobe_weight = visit([](const auto& k) { return k.lobe_weight(); });
        return base / (base + lobe_weight);
    }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline compiled_material compiled_material::with_colour(const vec3f& c) const {
    compiled_material out = *this;
    visit_kind<material_kinds>(kind_.index(), [&](auto k) {
        using K = typename decltype(k)::type;
        if constexpr (K::takes_texture) std::get_if<K>(&out.kind_)->set_colour(c);
    });
    out.refresh();
    return out;
}

template <class Uniform>
bool compiled_material::sample(const vec3f& wo, const shading_point& sp, Uniform& u, material_sample& s,
                               lobe lobes) const {
    if (!has_diffuse_base() || !(lobes & non_delta_lobe)) return sample_kind(wo, sp, u, s, lobes);
    // A diffuse base under a delta lobe: choose one in proportion to their reflectances (or
    // the base alone, when the lobe is not asked for).
    const bool lobe_allowed = (lobes & ~non_delta_lobe) != 0;
    const float p_base = lobe_allowed ? base_probability() : 1.0f;
    if (p_base >= 1.0f || u.next_float() < p_base) {
        const auto [u1, u2] = draw_2d(u);
        s.wi = sample_cosine_direction(sp.n, u1, u2);
        s.value = diffuse * (1.0f / p_base);
        s.pdf = p_base * fmax_inline(dot(s.wi, sp.n), 0.0f) * (1.0f / pi_f);
        s.sampled = non_delta_lobe;
        return true;
    }
    if (!sample_kind(wo, sp, u, s, lobes)) return false;
    s.value *= 1.0f / (1.0f - p_base);
    s.pdf *= 1.0f - p_base;
    return true;
}

inline vec3f compiled_material::eval(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
    vec3f f = visit([&](const auto& k) { return k.eval(wo, wi, sp); });
    if (has_diffuse_base()) {
        const float cos_i = dot(wi, sp.n);
        if (cos_i > 0) f += diffuse * (cos_i * (1.0f / pi_f));
    }
    return f;
}

inline float compiled_material::pdf(const vec3f& wo, const vec3f& wi, const shading_point& sp) const {
    const float lobe_pdf = visit([&](const auto& k) { return k.pdf(wo, wi, sp); });
    if (!has_diffuse_base()) return lobe_pdf;
    const float cos_i = dot(wi, sp.n);
    if (!(cos_i > 0)) return 0;
    const float p_base = base_probability();
    return p_base * cos_i * (1.0f / pi_f) + (1.0f - p_base) * lobe_pdf;
}

} // namespace rt
