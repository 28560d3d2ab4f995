#pragma once
// The compiled scene: what the renderer actually traces.
//
//   compiled_scene compile_scene(const hittable& world, const point3& origin);
//
// compile_scene walks the world once, before rendering. Built-in spheres go into flat float
// arrays (one array per coordinate, so the intersection loop runs across several spheres per
// SIMD instruction); built-in materials go into a tagged table; anything else (a user's own
// hittable or material subclass) is kept by pointer and called through its virtual functions.
// Positions are stored relative to `origin` (the camera), computed in double before rounding to
// float, so a scene far from the world origin renders as precisely as one near it.
//
// Invalid input (NaN or infinite coordinates, non-positive radii, negative colours, NaN fuzz or
// refraction index, a sphere without a material) throws scene_error at compile time.

#include "bsdf.h"
#include "hittable.h"
#include "hittable_list.h"
#include "material.h"
#include "scene_error.h"
#include "simd.h"
#include "sphere.h"
#include "vec3f.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <typeinfo>
#include <unordered_map>
#include <vector>

namespace rt {

// What the closest-hit query reports.
struct surface_hit {
    float t = std::numeric_limits<float>::infinity();
    vec3f p;               // hit point, relative to the scene origin
    vec3f normal;          // unit geometric normal, facing the incoming ray
    bool front_face = true;
    float offset = 0;      // extra push off the surface for spawned rays (primitive's own error)
    uint32_t material = 0; // index into compiled_scene::materials
    // Set when a user-written hittable was hit: its record, in world coordinates.
    const hittable* custom_object = nullptr;
    hit_record custom_record;
};

class compiled_scene {
  public:
    // Lanes processed together by the sphere loop; arrays are padded to a multiple of this.
    static constexpr size_t sphere_block = 16;

    vec3 origin;                          // world position that float coordinates are relative to
    std::vector<material_desc> materials;
    size_t sphere_count = 0;

    // Sphere arrays (padded with spheres that can never be hit).
    std::vector<float> sphere_x, sphere_y, sphere_z, sphere_r2, sphere_r, sphere_offset;
    std::vector<uint32_t> sphere_material;

    // User-written hittables, rendered through their virtual hit(). Owned by the world.
    std::vector<const hittable*> custom_objects;

    bool has_custom_materials = false;

    // The closest hit with t in (ray.tmin, ray.tmax); false when the ray escapes.
    bool intersect(const ray3f& r, surface_hit& hit) const;

    // The material entry for a material pointer met during rendering (user shapes only).
    material_desc describe_material(const material* m) const;
};

compiled_scene compile_scene(const hittable& world, const point3& origin);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

inline bool finite3(const vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

inline std::string describe(const vec3& v) {
    return "(" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " + std::to_string(v.z()) + ")";
}

inline void check_color(const color& c, const char* what) {
    if (!finite3(c) || c.x() < 0 || c.y() < 0 || c.z() < 0)
        throw scene_error(std::string(what) + " must be finite and non-negative, got " + describe(c));
}

// The table entry for a built-in material, or a custom one.
inline material_desc make_material_desc(const material* m) {
    material_desc d;
    const std::type_info& type = typeid(*m);
    if (type == typeid(lambertian)) {
        auto* l = static_cast<const lambertian*>(m);
        check_color(l->albedo(), "lambertian albedo");
        d.kind = material_kind::lambertian;
        d.albedo = vec3f(l->albedo());
    } else if (type == typeid(metal)) {
        auto* mt = static_cast<const metal*>(m);
        check_color(mt->albedo(), "metal albedo");
        if (!(mt->fuzz() >= 0)) throw scene_error("metal fuzz must be non-negative, got " + std::to_string(mt->fuzz()));
        d.kind = material_kind::metal;
        d.albedo = vec3f(mt->albedo());
        d.fuzz = static_cast<float>(mt->fuzz());
    } else if (type == typeid(dielectric)) {
        auto* g = static_cast<const dielectric*>(m);
        double ri = g->refraction_index();
        if (!(std::isfinite(ri) && ri > 0))
            throw scene_error("dielectric refraction index must be positive and finite, got " + std::to_string(ri));
        d.kind = material_kind::dielectric;
        d.albedo = {1, 1, 1};
        d.refraction_index = static_cast<float>(ri);
    } else {
        d.kind = material_kind::custom;
        d.custom = m;
    }
    return d;
}

class scene_compiler {
  public:
    explicit scene_compiler(compiled_scene& out) : out_(out) {}

    void add(const hittable& object) {
        const std::type_info& type = typeid(object);
        if (type == typeid(hittable_list)) {
            for (const auto& child : static_cast<const hittable_list&>(object).objects) {
                if (!child) throw scene_error("hittable_list holds a null object");
                add(*child);
            }
        } else if (type == typeid(sphere)) {
            add_sphere(static_cast<const sphere&>(object));
        } else {
            out_.custom_objects.push_back(&object);
        }
    }

    void finish() {
        out_.sphere_count = out_.sphere_x.size();
        // Pad to whole blocks with spheres of negative squared radius: never hit.
        while (out_.sphere_x.size() % compiled_scene::sphere_block != 0) {
            out_.sphere_x.push_back(0);
            out_.sphere_y.push_back(0);
            out_.sphere_z.push_back(0);
            out_.sphere_r2.push_back(-1);
            out_.sphere_r.push_back(0);
            out_.sphere_offset.push_back(0);
            out_.sphere_material.push_back(0);
        }
    }

  private:
    uint32_t material_index(const material* m) {
        auto found = index_.find(m);
        if (found != index_.end()) return found->second;
        material_desc d = make_material_desc(m);
        if (d.kind == material_kind::custom) out_.has_custom_materials = true;
        auto index = static_cast<uint32_t>(out_.materials.size());
        out_.materials.push_back(d);
        index_.emplace(m, index);
        return index;
    }

    void add_sphere(const sphere& s) {
        if (!finite3(s.center())) throw scene_error("sphere centre must be finite, got " + describe(s.center()));
        if (!(std::isfinite(s.radius()) && s.radius() > 0))
            throw scene_error("sphere radius must be positive and finite, got " + std::to_string(s.radius()));
        if (!s.mat()) throw scene_error("sphere at " + describe(s.center()) + " has no material");

        vec3 c = s.center() - out_.origin; // in double, then rounded once
        auto r = static_cast<float>(s.radius());
        vec3f cf(c);
        out_.sphere_x.push_back(cf.x);
        out_.sphere_y.push_back(cf.y);
        out_.sphere_z.push_back(cf.z);
        out_.sphere_r2.push_back(r * r);
        out_.sphere_r.push_back(r);
        // Float evaluation of |o - c|^2 - r^2 is only good to a few ulps of the larger of |c| and
        // r, so a spawned ray must start at least that far off the surface (on top of the
        // hit-point offset) or it may re-hit the sphere it leaves: 2^-21 is about 8 ulps.
        out_.sphere_offset.push_back(std::ldexp(max_abs_component(cf) + r, -21));
        out_.sphere_material.push_back(material_index(s.mat().get()));
    }

    compiled_scene& out_;
    std::unordered_map<const material*, uint32_t> index_;
};

} // namespace detail

inline compiled_scene compile_scene(const hittable& world, const point3& origin) {
    if (!detail::finite3(origin)) throw scene_error("camera position must be finite, got " + detail::describe(origin));
    compiled_scene scene;
    scene.origin = origin;
    detail::scene_compiler compiler(scene);
    compiler.add(world);
    compiler.finish();
    return scene;
}

inline material_desc compiled_scene::describe_material(const material* m) const {
    if (!m) throw scene_error("a custom hittable reported a hit without a material");
    return detail::make_material_desc(m);
}

inline bool compiled_scene::intersect(const ray3f& r, surface_hit& hit) const {
    hit.custom_object = nullptr;
    // Spheres, floatv::width at a time: every lane keeps its own closest t and sphere index (as
    // a float, exact below 2^24); the lanes are reduced at the end.
    constexpr size_t W = floatv::width;
    static_assert(sphere_block % W == 0, "sphere arrays are padded to whole SIMD blocks");
    alignas(64) static constexpr float lane_offsets[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
    const floatv ox(r.origin.x), oy(r.origin.y), oz(r.origin.z);
    const floatv dx(r.dir.x), dy(r.dir.y), dz(r.dir.z), tmin(r.tmin), zero(0.0f);
    const floatv lanes = floatv::load(lane_offsets);
    floatv best_t(r.tmax), best_i(-1.0f);
    const float *cx = sphere_x.data(), *cy = sphere_y.data(), *cz = sphere_z.data(), *r2 = sphere_r2.data();
    const size_t n = sphere_x.size();
    for (size_t i = 0; i < n; i += W) {
        // Stable ray-sphere test for a unit direction (see sphere_roots in sphere.h).
        floatv ocx = floatv::load(cx + i) - ox, ocy = floatv::load(cy + i) - oy, ocz = floatv::load(cz + i) - oz;
        floatv rr = floatv::load(r2 + i);
        floatv h = dx * ocx + dy * ocy + dz * ocz;
        floatv px = ocx - h * dx, py = ocy - h * dy, pz = ocz - h * dz;
        floatv disc = rr - (px * px + py * py + pz * pz);
        maskv crosses = disc >= zero;
        if (!any(crosses)) continue; // the usual case: the ray passes all of these spheres by
        floatv c = (ocx * ocx + ocy * ocy + ocz * ocz) - rr;
        floatv s = sqrt(max(disc, zero));
        floatv q = select(h >= zero, h + s, h - s);
        floatv ta = c / q;
        floatv t0 = min(ta, q), t1 = max(ta, q);
        floatv t = select(t0 > tmin, t0, t1);
        maskv closer = crosses & (t > tmin) & (t < best_t);
        best_t = select(closer, t, best_t);
        best_i = select(closer, lanes + floatv(float(i)), best_i);
    }
    alignas(64) float lane_t[W], lane_i[W];
    best_t.store(lane_t);
    best_i.store(lane_i);
    float t = r.tmax;
    uint32_t index = UINT32_MAX;
    for (size_t k = 0; k < W; ++k) {
        if (lane_i[k] < 0) continue;
        auto candidate = static_cast<uint32_t>(lane_i[k]);
        if (lane_t[k] < t || (lane_t[k] == t && candidate < index)) {
            t = lane_t[k];
            index = candidate;
        }
    }

    bool found = false;
    if (index != UINT32_MAX) {
        found = true;
        vec3f center{cx[index], cy[index], cz[index]};
        float radius = sphere_r[index];
        // Re-project the hit point onto the sphere: removes the error of o + t d along the ray.
        vec3f outward = normalize(r.at(t) - center);
        hit.t = t;
        hit.p = center + radius * outward;
        hit.front_face = dot(r.dir, outward) < 0;
        hit.normal = hit.front_face ? outward : -outward;
        hit.offset = sphere_offset[index];
        hit.material = sphere_material[index];
        hit.custom_object = nullptr;
    }

    // User-written hittables, in double precision and world coordinates.
    if (!custom_objects.empty()) {
        ray world_ray(origin + r.origin.to_double(), r.dir.to_double());
        double closest = found ? hit.t : r.tmax;
        hit_record rec;
        for (const hittable* object : custom_objects) {
            if (object->hit(world_ray, interval(r.tmin, closest), rec)) {
                found = true;
                closest = rec.t;
                hit.custom_object = object;
                hit.custom_record = rec;
            }
        }
        if (hit.custom_object) {
            const hit_record& h = hit.custom_record;
            hit.t = static_cast<float>(h.t);
            hit.p = vec3f(h.p - origin);
            hit.normal = normalize(vec3f(h.normal));
            hit.front_face = h.front_face;
            hit.offset = 0;
        }
    }
    return found;
}

} // namespace rt
