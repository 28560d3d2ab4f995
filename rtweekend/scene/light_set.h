#pragma once
// light_set: the lights of a compiled scene, for light sampling (next-event estimation).
//
//   light_set::sample(p, u, s)     a light chosen in proportion to its power, a direction towards
//                                  it from p, the radiance arriving along it and its density
//   light_set::pdf(l, p, y, ny)    the density sample() gives the direction from p to the point
//                                  y of light l: what multiple importance sampling weighs a
//                                  material-sampled ray that happened to hit the light against
//
// An emitter is a built-in sphere, quad or triangle whose material is a diffuse_light; the scene
// compiler finds them (scene_compiler.h) and records, per shape, which light it is. Point lights
// (intensity I: irradiance I cos / d^2) come from the scene description. Each shape is sampled by
// the routine of light_sampling.h that suits it: spheres by the cone of directions they subtend,
// quads by solid angle (spherical rectangles) or by area, triangles by area.
//
// A light is chosen with probability proportional to its power (an alias table, alias_table.h):
// Le * area * pi for a one-sided area light (twice that two-sided), 4 pi I for a point light,
// per channel averaged. Positions are relative to the scene origin, in float, like the shapes.

#include "../core/alias_table.h"
#include "leaf_query.h"
#include "light_sampling.h"
#include "../core/rng.h"
#include "../core/vec3f.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace rt {

enum class light_kind : uint8_t { sphere, quad, triangle, point };

struct light {
    light_kind kind = light_kind::point;
    vec3f p0, p1, p2;   // sphere: centre; quad: corner Q and edges u, v; triangle: vertices; point: position
    float radius = 0;   // sphere
    vec3f emission;     // area lights: the radiance Le they emit; point lights: the intensity I
    bool two_sided = false;
    // A textured emitter: its index in the compiled scene's texture table (UINT32_MAX: none, the
    // constant `emission`), with `emission` then the texture's mean, which sets the light's power;
    // and the index of its shape in its set, for the surface coordinates of a sampled point.
    uint32_t texture = UINT32_MAX;
    uint32_t shape = 0;

    bool is_delta() const { return kind == light_kind::point; }
    float area() const;
    // The power the light emits, averaged over channels (up to a common factor); in double where
    // float overflows (a radiance of 1e37 over a few square units), so that every finite light
    // has a finite weight.
    double power() const;
};

// One light sample, as seen from the shading point p.
struct light_choice {
    vec3f wi;              // unit direction from p towards the light
    vec3f radiance;        // arriving at p along wi if nothing is in the way (I / d^2 for a point light)
    float pdf = 0;         // solid-angle density of wi times the light's selection probability;
                           // for a point light, the selection probability alone
    bool delta = false;    // a point light: no material-sampled ray can find it
    vec3f y;               // the sampled point (a point light's position), where the shadow ray ends
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
    // lights and the point lights apart (book 3's mixture estimator).
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
    // The same among the area lights alone, and among the point lights alone.
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

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline float light::area() const {
    switch (kind) {
    case light_kind::sphere: return 4.0f * pi_f * radius * radius;
    case light_kind::quad: return length(cross(p1, p2));
    case light_kind::triangle: return 0.5f * length(cross(p1 - p0, p2 - p0));
    case light_kind::point: break;
    }
    return 0;
}

inline double light::power() const {
    const float mean = (emission.x + emission.y + emission.z) * (1.0f / 3.0f);
    const float p = kind == light_kind::point ? 4.0f * pi_f * mean : mean * area() * pi_f * (two_sided ? 2.0f : 1.0f);
    if (std::isfinite(p)) return p; // float, as always: the same weights, the same images
    // Beyond float's range: the same product in double (a NaN stays NaN, and is refused).
    const double pi_d = 3.14159265358979323846;
    const double mean_d = (double(emission.x) + double(emission.y) + double(emission.z)) / 3.0;
    // |a x b| in double, of float vectors.
    auto cross_length = [](double ax, double ay, double az, double bx, double by, double bz) {
        const double x = ay * bz - az * by, y = az * bx - ax * bz, z = ax * by - ay * bx;
        return std::sqrt(x * x + y * y + z * z);
    };
    double area_d = 0;
    switch (kind) {
    case light_kind::sphere: area_d = 4.0 * pi_d * double(radius) * double(radius); break;
    case light_kind::quad: area_d = cross_length(p1.x, p1.y, p1.z, p2.x, p2.y, p2.z); break;
    case light_kind::triangle:
        area_d = 0.5 * cross_length(double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z, double(p2.x) - p0.x,
                                    double(p2.y) - p0.y, double(p2.z) - p0.z);
        break;
    case light_kind::point: return 4.0 * pi_d * mean_d;
    }
    return mean_d * area_d * pi_d * (two_sided ? 2.0 : 1.0);
}

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
    const auto [u1, u2] = draw_2d(u);
    if (l.kind == light_kind::point) {
        const vec3f to = l.p0 - p;
        const float d2 = length_squared(to);
        if (!(d2 > 0)) return false;
        s.wi = to / sqrt_f(d2);
        s.y = l.p0;
        s.radiance = l.emission / d2;
        s.pdf = pmf;
        s.delta = true;
        return true;
    }
    light_sample ls;
    bool ok = false;
    switch (l.kind) {
    case light_kind::sphere: ok = sample_sphere_light(p, l.p0, l.radius, u1, u2, ls); break;
    case light_kind::quad: ok = sample_quad_light(p, l.p0, l.p1, l.p2, u1, u2, ls); break;
    case light_kind::triangle: ok = sample_triangle_light(p, l.p0, l.p1, l.p2, u1, u2, ls); break;
    case light_kind::point: break;
    }
    if (!ok || !(ls.pdf > 0)) return false;
    s.wi = ls.wi;
    s.y = ls.y;
    s.n = ls.n;
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
    switch (l.kind) {
    case light_kind::sphere: return sphere_light_pdf(p, l.p0, l.radius, y, ny);
    case light_kind::quad: return quad_light_pdf(p, l.p0, l.p1, l.p2, y, ny);
    case light_kind::triangle: return triangle_light_pdf(p, l.p0, l.p1, l.p2, y, ny);
    case light_kind::point: break;
    }
    return 0;
}

inline bool light_set::meet(const light& l, const vec3f& p, const vec3f& wi, vec3f& y, vec3f& ny) {
    switch (l.kind) {
    case light_kind::sphere: {
        // The near root of |p + t wi - c|^2 = r^2 that is positive (the far one from inside).
        const vec3f oc = l.p0 - p;
        const float h = dot(wi, oc);
        const vec3f perp = oc - h * wi;
        const float disc = l.radius * l.radius - length_squared(perp);
        if (!(disc >= 0)) return false;
        const float s = sqrt_f(disc);
        float t = h - s;
        if (!(t > 0)) t = h + s;
        if (!(t > 0)) return false;
        y = p + t * wi;
        ny = normalize(y - l.p0);
        return true;
    }
    case light_kind::quad:
    case light_kind::triangle: {
        const vec3f e1 = l.kind == light_kind::quad ? l.p1 : l.p1 - l.p0;
        const vec3f e2 = l.kind == light_kind::quad ? l.p2 : l.p2 - l.p0;
        const vec3f n = cross(e1, e2);
        const float denom = dot(n, wi);
        if (denom == 0) return false;
        const float t = dot(n, l.p0 - p) / denom;
        if (!(t > 0)) return false;
        const vec3f rel = p + t * wi - l.p0;
        const vec3f w = n / dot(n, n);
        const float a = dot(w, cross(rel, e2)), b = dot(w, cross(e1, rel));
        const bool inside = l.kind == light_kind::quad ? (a >= 0 && a <= 1 && b >= 0 && b <= 1)
                                                       : (a >= 0 && b >= 0 && a + b <= 1);
        if (!inside) return false;
        y = p + t * wi;
        ny = normalize(n);
        return true;
    }
    case light_kind::point: break;
    }
    return false;
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
