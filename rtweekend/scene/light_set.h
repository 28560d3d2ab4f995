#pragma once
// light_set: the lights of a compiled scene, for light sampling (next-event estimation).
//
//   light_set::sample(p, u, s)     a light chosen in proportion to its power, a direction towards
//                                  it from p, the radiance arriving along it and its density
//   light_set::pdf(l, p, y, ny)    the density sample() gives the direction from p to the point
//                                  y of light l: what multiple importance sampling weighs a
//                                  material-sampled ray that happened to hit the light against
//
// An emitter is a built-in shape whose material is a diffuse_light, of a shape kind that is light
// sampled (scene/shape_kinds.h); the scene compiler finds them (scene_compiler.h) and records, per
// shape, which light it is. Point lights (intensity I: irradiance I cos / d^2) and directional
// lights (irradiance E cos at any distance) come from the scene description. Each light is sampled by its kind (scene/light_kinds.h): spheres by the cone of
// directions they subtend, quads by solid angle (spherical rectangles) or by area, triangles by
// area.
//
// A light is chosen with probability proportional to its power (an alias table, alias_table.h):
// Le * area * pi for a one-sided area light (twice that two-sided), 4 pi I for a point light,
// E pi R^2 for a directional light over a scene of bounding radius R, per channel averaged. Positions are relative to the scene origin, in float, like the shapes.

#include "../core/alias_table.h"
#include "../core/rng.h"
#include "../core/vec3f.h"
#include "leaf_query.h"
#include "light_kinds.h"
#include "light_sampling.h"
#include "shape_kinds.h"
#include "surface_hit.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace rt {

// One light sample, as seen from the shading point p.
struct light_choice {
    vec3f wi;              // unit direction from p towards the light
    vec3f radiance;        // arriving at p along wi if nothing is in the way (I / d^2 for a point
                           // light, E for a directional one)
    float pdf = 0;         // solid-angle density of wi times the light's selection probability;
                           // for a delta light, the selection probability alone
    bool delta = false;    // a point or directional light: no material-sampled ray can find it
    vec3f y;               // the sampled point (a point light's position; beyond the scene for a
                           // directional light), where the shadow ray ends
    vec3f n;               // an area light's outward unit normal at y
    // For a textured area light (texture != UINT32_MAX), whose radiance the caller looks up: the light.
    uint32_t texture = UINT32_MAX;
    uint32_t light = 0;
};

class light_set {
  public:
    static constexpr uint32_t none = UINT32_MAX;

    std::vector<light> lights;
    // For each shape kind, the light each shape of its set is (none when it does not emit); empty
    // for a kind without emitters.
    std::array<std::vector<uint32_t>, shape_kind_count> of_shape;

    // Adds a light; finish() must be called once all are in.
    uint32_t add(const light& l) {
        lights.push_back(l);
        return static_cast<uint32_t>(lights.size() - 1);
    }
    // Builds the selection tables: over every light (next-event estimation), and over the area
    // lights and the delta (point and directional) lights apart (book 3's mixture estimator).
    void finish();

    bool empty() const { return lights.empty(); }
    bool has_area_lights() const { return !area_.empty(); }
    bool has_point_lights() const { return !point_.empty(); }

    // The light shape `index` of kind `k` is, or none.
    uint32_t light_at(shape_kind k, uint32_t index) const {
        const auto& table = of_shape[size_t(k)];
        return index < table.size() ? table[index] : none;
    }

    // Chooses a light in proportion to power and samples a direction towards it from p (u: three
    // uniforms). False when the chosen light cannot be sampled from p (p on its plane, say).
    template <class Uniform>
    bool sample(const vec3f& p, Uniform& u, light_choice& s) const { return sample_from(all_, p, u, s); }
    // The same among the area lights alone, and among the delta lights alone.
    template <class Uniform>
    bool sample_area(const vec3f& p, Uniform& u, light_choice& s) const { return sample_from(area_, p, u, s); }
    template <class Uniform>
    bool sample_point(const vec3f& p, Uniform& u, light_choice& s) const { return sample_from(point_, p, u, s); }

    // A light chosen in proportion to power, as sample() chooses (u uniform in [0, 1)), and the
    // probability it had; none when there is no light.
    uint32_t pick(float u, float& pmf) const {
        if (all_.empty()) return none;
        const uint32_t slot = all_.select.sample(u);
        pmf = all_.select.pmf(slot);
        return all_.members[slot];
    }

    // The probability pick() (and sample()) chooses light l with.
    float pick_pmf(uint32_t l) const { return all_.select.pmf(all_.slot[l]); }

    // The density sample() gives the direction from p to the point y (normal ny) of area light l,
    // selection included.
    float pdf(uint32_t l, const vec3f& p, const vec3f& y, const vec3f& ny) const {
        return all_.select.pmf(all_.slot[l]) * shape_pdf(lights[l], p, y, ny);
    }

    // The density sample_area() gives the direction wi from p: the sum over every area light the
    // half-line p + t wi meets (occluded or not, as book 3's hittable_pdf counts them).
    float area_pdf_along(const vec3f& p, const vec3f& wi) const;

  private:
    struct table {
        std::vector<uint32_t> members; // light indices, in selection order
        alias_table select;
        std::vector<uint32_t> slot;    // light index -> its position in members (none: not a member)
        bool empty() const { return members.empty(); }
    };
    table all_, area_, point_;

    void build(table& t, bool (*member)(const light&));
    template <class Uniform>
    bool sample_from(const table& t, const vec3f& p, Uniform& u, light_choice& s) const;
    static float shape_pdf(const light& l, const vec3f& p, const vec3f& y, const vec3f& ny);
    // Where the half-line p + t wi (t > 0) first meets light l's surface, or false.
    static bool meet(const light& l, const vec3f& p, const vec3f& wi, vec3f& y, vec3f& ny);
};

namespace detail {
// The shadow ray from `hit` to a light's sampled point y (direction wi from hit.p). Both ends are
// pushed off their surfaces as spawned rays are (ray_offset.h): it starts where a ray leaving
// towards y starts (spawn_ray) and ends short of y pushed off the light towards that start (an
// area light; a point light's y is no surface), as pbrt-v4's SpawnRayTo does. Aimed along wi
// from the pushed start instead, it ran beside the line through y, and near a sphere light's
// silhouette it met the sphere up to ~sqrt(2 r push) before y, beyond any relative margin: the
// light shadowed itself. From a thousand units away nee lost all of a sphere light's direct
// light that way, and the sphere room 1.75 % of its image (tests/test_lights.cpp).
inline ray3f shadow_ray(const surface_hit& hit, const light_choice& lc, bool in_volume) {
    ray3f r = spawn_ray(hit, lc.wi, 0, in_volume);
    vec3f end = lc.y;
    if (!lc.delta) end = offset_ray_origin(lc.y, dot(r.origin - lc.y, lc.n) >= 0 ? lc.n : -lc.n);
    const vec3f to = end - r.origin;
    const float distance = length(to);
    r.dir = to / distance;
    r.tmax = distance * (1.0f - 1e-4f);
    return r;
}

} // namespace detail

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline void light_set::build(table& t, bool (*member)(const light&)) {
    t.members.clear();
    t.slot.assign(lights.size(), none);
    std::vector<double> weights;
    for (uint32_t i = 0; i < lights.size(); ++i) {
        if (!member(lights[i]) || !(lights[i].power() > 0)) continue;
        t.slot[i] = static_cast<uint32_t>(t.members.size());
        t.members.push_back(i);
        weights.push_back(lights[i].power());
    }
    t.select = t.members.empty() ? alias_table() : alias_table(weights);
}

inline void light_set::finish() {
    build(all_, [](const light&) { return true; });
    build(area_, [](const light& l) { return !l.is_delta(); });
    build(point_, [](const light& l) { return l.is_delta(); });
}

template <class Uniform>
bool light_set::sample_from(const table& t, const vec3f& p, Uniform& u, light_choice& s) const {
    if (t.empty()) return false;
    const uint32_t slot = t.select.sample(u.next_float());
    const light& l = lights[t.members[slot]];
    const float pmf = t.select.pmf(slot);
    const uniform2 uv = draw_2d(u); // named, not bound: C++17 lambdas cannot capture a binding
    light_sample ls;
    if (!l.visit([&](const auto& e) { return e.sample(p, uv.u1, uv.u2, ls); }) || !(ls.pdf > 0)) return false;
    s.wi = ls.wi;
    s.y = ls.y;
    s.n = ls.n;
    if (l.is_delta()) {
        // A point light (its intensity falls off with the squared distance) or a directional one:
        // no other strategy can find its direction.
        s.radiance = l.emission * l.visit([&](const auto& e) {
            if constexpr (std::decay_t<decltype(e)>::is_delta) return e.arriving(p, ls);
            else return 1.0f;
        });
        s.pdf = pmf;
        s.delta = true;
        return true;
    }
    // One-sided lights emit towards the side their normal points to.
    const bool front = dot(ls.wi, ls.n) < 0;
    s.radiance = front || l.two_sided ? l.emission : vec3f{0, 0, 0};
    s.pdf = pmf * ls.pdf;
    s.delta = false;
    s.texture = l.texture;
    if (l.texture != UINT32_MAX) s.light = t.members[slot];
    return true;
}

inline float light_set::shape_pdf(const light& l, const vec3f& p, const vec3f& y, const vec3f& ny) {
    return l.visit([&](const auto& e) { return e.pdf(p, y, ny); });
}

inline bool light_set::meet(const light& l, const vec3f& p, const vec3f& wi, vec3f& y, vec3f& ny) {
    return l.visit([&](const auto& e) { return e.meet(p, wi, y, ny); });
}

inline float light_set::area_pdf_along(const vec3f& p, const vec3f& wi) const {
    float sum = 0;
    for (size_t slot = 0; slot < area_.members.size(); ++slot) {
        const light& l = lights[area_.members[slot]];
        vec3f y, ny;
        if (meet(l, p, wi, y, ny)) sum += area_.select.pmf(uint32_t(slot)) * shape_pdf(l, p, y, ny);
    }
    return sum;
}

} // namespace rt
