#pragma once
// The compiled scene: what the renderer traces. Built by compile_scene (scene_compiler.h).
//
//   scene.intersect(ray, hit)   the closest hit        scene.occluded(ray)   any hit at all
//
// It holds one set per shape kind (shape_kinds.h lists them; scene/shapes/ holds them), each in
// the order of the leaves of one BVH over all of them (bvh.h), and the table of built-in
// materials (the material contract, core/bsdf.h). An instance's leaf walks its object, a
// compiled_scene of its own (objects), in the object's frame: a two-level BVH. User-written
// hittables are called through their virtual hit(): from the BVH when they report a bounding box,
// after it (for every ray) when they do not. Positions are relative to `origin`.
//
// One dispatch: a query walks the BVH and hands each leaf to the kernel of the leaf's shape kind
// (leaf_kernel below; with_shape_kind maps a kind's number to the kind, from the list). A scene
// pays only for what it has: when all its shapes are of one kind (the book's scenes are all
// spheres, a mesh all triangles) the walk calls that kind's kernel directly, without asking each
// leaf its kind; the triangle test's ray set-up is made at the first triangle leaf a ray reaches;
// and a scene of a handful of shapes has no BVH nodes at all.

#include "../core/constants.h"
#include "../core/engine_linkage.h"
#include "../hittable.h"
#include "../core/material_kinds.h"
#include "bvh.h"
#include "../core/force_inline.h"
#include "../core/in_place_array.h"
#include "leaf_query.h"
#include "light_set.h"
#include "shape_kinds.h"
#include "surface_hit.h"
#include "surface_map.h"
#include "texture_table.h"
#include "../core/vec3f.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <type_traits>
#include <vector>

namespace rt {

class compiled_scene {
  public:
    vec3 origin; // world position that float coordinates are relative to
    std::vector<compiled_material> materials;
    texture_table textures;     // the materials' textures (compiled_material::texture indexes it)
    // Tangent-space normal maps (material.h: normal_mapped), by material index: which texture,
    // and the scale of its x and y. Empty when no material has one, so a scene without them
    // pays one test of an empty vector per hit.
    struct normal_map {
        uint32_t texture = UINT32_MAX; // UINT32_MAX: none
        float scale = 1;
        bool heights = false; // a bump map (material.h: bump_mapped): scale is its displacement's
    };
    std::vector<normal_map> normal_maps;
    // Metallic-roughness maps (material.h: metal_roughness with a map), by material index: which
    // texture, and the factors its blue (metallic) and green (roughness) channels multiply. A
    // material with one is textured (its base colour a texture, if only a constant one), so that
    // textured() looks both up. Empty when no material has one.
    struct metallic_roughness_map {
        uint32_t texture = UINT32_MAX; // UINT32_MAX: none
        float metallic = 0, roughness = 0;
    };
    std::vector<metallic_roughness_map> metallic_roughness_maps;
    // Front ends' maps (surface_map.h), by material index: a null entry leaves its material as it
    // is. Empty when no material has one.
    std::vector<std::shared_ptr<const surface_map>> surface_maps;
    const surface_map* surface_map_of(uint32_t material) const {
        return material < surface_maps.size() ? surface_maps[material].get() : nullptr;
    }
    // The set of shapes of kind K (shape_kinds.h), in the BVH's leaf order.
    template <class K>
    K& set() { return std::get<K>(sets_); }
    template <class K>
    const K& set() const { return std::get<K>(sets_); }
    wide_bvh bvh;                   // over every set
    // The objects instances place: each a subtree of built-in shapes compiled once, with sets and
    // a BVH of its own in its own frame (origin zero), sharing this scene's material table. An
    // object holds no instances and no user shapes, and its emitters are not light-sampled (a
    // path that hits one counts its emission in full).
    std::vector<std::shared_ptr<compiled_scene>> objects;
    box3f bounds; // of every shape in the BVH (what an object's instances transform)
    light_set lights;           // the emitters among the shapes (and point lights), for light sampling

    // User-written hittables without a bounding box (the default hittable::bounding_box, or a box
    // that is empty, infinite or beyond float's range), tested after the BVH. Owned by the world.
    std::vector<const hittable*> unbounded_user_shapes;
    // Shapes the compiler made to stand for user shapes (convex_medium for fog in a box), which
    // user_shapes names in their place.
    std::vector<std::shared_ptr<const hittable>> owned_user_shapes;
    bool has_user_materials = false;

    // The kind of every shape in the BVH when there is only one kind; empty for a mix (or none).
    std::optional<shape_kind> single_kind;
    // When that kind has a walk of its own (shape_kinds.h: own_walk_kinds), its number there.
    static constexpr uint8_t no_single_walk = 255;
    uint8_t single_walk = no_single_walk;
    bool culls_back_faces = false; // set_back_face_culling was called

    // Whether rendering calls user code (shapes or materials), which may call random_double().
    bool calls_user_code() const {
        return set<user_shape_set>().size() > 0 || !unbounded_user_shapes.empty() || has_user_materials ||
               textures.calls_user_code();
    }

    // Whether the image depends on a ray's time: something moves, or user code (which may read
    // ray::time()) is called. Camera rays draw a time only then, so a still scene's samples
    // draw the same random numbers as before motion blur existed.
    bool uses_time() const { return has_motion || calls_user_code(); }
    bool has_motion = false; // a moving shape, here or in an object

    // The closest hit with t in (ray.tmin, ray.tmax); false when the ray escapes.
    bool intersect(const ray3f& r, surface_hit& hit) const;
    // The same for n rays at once (a batch's rays, bounce by bounce): found[k] and hits[k] are
    // what intersect(rays[k], hits[k]) gives, bit for bit. They walk the BVH in packets of up to
    // floatv::width (traverse_packet; spheres tested a sphere for all lanes at once, other shapes
    // by their kernels ray by ray), unless they are few, or the scene calls user code: a user's
    // hittable may draw random numbers in hit(), which must come in its own ray's order, so
    // there each ray walks alone.
    void intersect_batch(int n, const ray3f* rays, surface_hit* hits, bool* found) const;
    // The same, skipping back faces of the shapes set_back_face_culling marked (a sphere's back
    // face is the exit point of a ray that starts inside it). User hittables are never culled.
    bool intersect_culling_back_faces(const ray3f& r, surface_hit& hit) const;
    // Whether anything at all is hit with t in (ray.tmin, ray.tmax): for shadow rays.
    bool occluded(const ray3f& r) const;

    // Marks the shapes whose back faces intersect_culling_back_faces skips: those whose material
    // index `cullable` accepts (opaque ones: a glass object's back face must be found).
    template <class Predicate>
    void set_back_face_culling(Predicate cullable);

    // The texture coordinates (u, v) of a hit, as the books define them, by its shape's kind
    // (a sphere's from its outward normal, a quad's from its edges, ...); an instance's were found
    // in its object's frame when the hit was completed (surface_hit::has_uv).
    void surface_coordinates(const surface_hit& hit, double& u, double& v) const;
    // dp/du and dp/dv at a triangle's hit (in the scene's frame, an instance's carried out of its
    // object's), for normal maps; false for other shapes and for triangles without coordinates.
    bool surface_tangents(const surface_hit& hit, vec3& dpdu, vec3& dpdv) const;
    // The vertex colour at a triangle's hit (triangle_mesh::colors), an instance's looked up in
    // its object; false for other shapes and for triangles of meshes without colours.
    bool vertex_colour(const surface_hit& hit, vec3f& c) const;
    // Some mesh, here or in an object, has vertex colours (their materials are textured, so that
    // textured() multiplies them in).
    bool vertex_colours = false;

    // Bytes held for tracing: the sets and the BVH nodes.
    size_t geometry_bytes() const;

    // What a ray's walk keeps for the kinds' kernels (shape_kinds.h).
    using leaf_state = rt::leaf_state;
    // The walk and the completion of its closest hit, which the instance kind also asks of the
    // objects its instances place.
    template <query Q>
    bool trace(const ray3f& r, float& tmax, hit_ref& best, leaf_state& state) const;
    void complete_hit(const ray3f& r, float t, const hit_ref& best, const leaf_state& state, surface_hit& hit) const;

  private:
    kind_tuple<shape_kinds> sets_;

    // Tests the ray against the leaf `ref` of shapes of kind K (see leaf_query.h).
    // Forced inline: into every walk, beside the other kinds' (a call per leaf cost the Cornell box
    // with its quads and a sphere 4 %).
    template <query Q, class K>
    RTWEEKEND_FORCE_INLINE bool leaf_kernel(const ray3f& r, uint32_t ref, float& t_best, hit_ref& best,
                                            leaf_state& state) const {
        return set<K>().template intersect_leaf<Q, shape_id<K>>(*this, r, bvh_ref::first(ref), bvh_ref::count(ref),
                                                                 t_best, best, state_of<K>(state));
    }
    bool intersect_unbounded(const ray3f& r, bool found, surface_hit& hit) const;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

template <query Q>
bool compiled_scene::trace(const ray3f& r, float& tmax, hit_ref& best, leaf_state& state) const {
    if (single_walk != no_single_walk) {
        return visit_kind<own_walk_kinds>(single_walk, [&](auto kind) {
            return traverse<Q == query::any>(bvh, r, tmax, [&](uint32_t ref, float& t_best) {
                return leaf_kernel<Q, typename decltype(kind)::type>(r, ref, t_best, best, state);
            });
        });
    }
    return traverse<Q == query::any>(bvh, r, tmax, [&](uint32_t ref, float& t_best) {
        return with_shape_kind(bvh_ref::kind(ref), [&](auto kind) {
            return leaf_kernel<Q, typename decltype(kind)::type>(r, ref, t_best, best, state);
        });
    });
}

template <class Predicate>
void compiled_scene::set_back_face_culling(Predicate cullable) {
    for_each_kind<shape_kinds>([&](auto k) { set<typename decltype(k)::type>().mark_culled(cullable); });
    culls_back_faces = true;
    // Objects are compiled for this scene (a copy of the scene shares them, and their marks).
    for (auto& o : objects) o->set_back_face_culling(cullable);
}

namespace detail {

// A packet's count rays (count >= 1, at most floatv::width) across SIMD lanes: lane[0..2][k] the
// origin of ray k, lane[3..5][k] its direction, lane[6][k] its tmin and t_best[k] its tmax, zeros
// in the lanes from count on; bit k of dir_signs[a] is the sign bit of ray k's direction on axis
// a. With AVX or AVX-512 each ray's first eight floats (origin, direction, tmin, tmax) are loaded
// as one row and 8 x 8 blocks of rows transposed into columns by shuffles: a ray's floats written
// one by one and read back as a vector were a store-forwarding stall on every lane, and took the
// cover scene about 2.5 % longer (BENCHMARKS.md section 27).
inline void rays_to_lanes(const ray3f* r, int count, float (*lane)[floatv::width], float* t_best, unsigned dir_signs[3]) {
    constexpr int W = int(floatv::width);
#if defined(__AVX__)
    static_assert(offsetof(ray3f, tmax) == 7 * sizeof(float), "origin, dir, tmin and tmax lead a ray");
    static_assert(W % 8 == 0, "AVX lanes come in blocks of 8");
    constexpr int blocks = W / 8; // 1 with AVX, 2 with AVX-512
    __m256 column[blocks][8];
    for (int h = 0; h < blocks; ++h) {
        __m256 m[8];
        RTWEEKEND_UNROLL(8)
        for (int i = 0; i < 8; ++i) {
            const int k = 8 * h + i;
            m[i] = k < count ? _mm256_loadu_ps(&r[k].origin.x) : _mm256_setzero_ps();
        }
        const __m256 t0 = _mm256_unpacklo_ps(m[0], m[1]), t1 = _mm256_unpackhi_ps(m[0], m[1]);
        const __m256 t2 = _mm256_unpacklo_ps(m[2], m[3]), t3 = _mm256_unpackhi_ps(m[2], m[3]);
        const __m256 t4 = _mm256_unpacklo_ps(m[4], m[5]), t5 = _mm256_unpackhi_ps(m[4], m[5]);
        const __m256 t6 = _mm256_unpacklo_ps(m[6], m[7]), t7 = _mm256_unpackhi_ps(m[6], m[7]);
        const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
        const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
        const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xEE);
        const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xEE);
        const __m256 u[8] = {u0, u1, u2, u3, u4, u5, u6, u7};
        RTWEEKEND_UNROLL(4)
        for (int a = 0; a < 4; ++a) {
            column[h][a] = _mm256_permute2f128_ps(u[a], u[a + 4], 0x20);
            column[h][a + 4] = _mm256_permute2f128_ps(u[a], u[a + 4], 0x31);
        }
    }
    // The lanes from count on are +0: their sign bits are clear.
    RTWEEKEND_UNROLL(8)
    for (int a = 0; a < 8; ++a) {
        float* out = a < 7 ? lane[a] : t_best;
        unsigned signs = 0;
        for (int h = 0; h < blocks; ++h) {
            _mm256_store_ps(out + 8 * h, column[h][a]);
            signs |= unsigned(_mm256_movemask_ps(column[h][a])) << (8 * h);
        }
        if (a >= 3 && a < 6) dir_signs[a - 3] = signs;
    }
#else
    for (int a = 0; a < 3; ++a) dir_signs[a] = 0;
    for (int k = 0; k < count; ++k) {
        lane[0][k] = r[k].origin.x, lane[1][k] = r[k].origin.y, lane[2][k] = r[k].origin.z;
        lane[3][k] = r[k].dir.x, lane[4][k] = r[k].dir.y, lane[5][k] = r[k].dir.z;
        lane[6][k] = r[k].tmin;
        t_best[k] = r[k].tmax;
        for (int a = 0; a < 3; ++a) dir_signs[a] |= unsigned(std::signbit(r[k].dir[a])) << k;
    }
    for (int k = count; k < W; ++k) {
        for (int a = 0; a < 7; ++a) lane[a][k] = 0.0f;
        t_best[k] = 0.0f;
    }
#endif
}

} // namespace detail

// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

RTWEEKEND_ENGINE_FUNCTION void compiled_scene::complete_hit(const ray3f& r, float t, const hit_ref& best,
                                                            const leaf_state& state, surface_hit& hit) const {
    hit.t = t;
    hit.time = r.time;
    hit.has_uv = false;
    hit.user_shape = nullptr;
    hit.kind = best.kind;
    hit.index = best.index;
    with_shape_kind(best.kind, [&](auto kind) {
        using K = typename decltype(kind)::type;
        set<K>().complete_hit(*this, r, t, best.index, state_of<K>(state), hit);
    });
}

RTWEEKEND_ENGINE_FUNCTION void compiled_scene::surface_coordinates(const surface_hit& hit, double& u,
                                                                   double& v) const {
    if (hit.has_uv) {
        u = hit.u;
        v = hit.v;
        return;
    }
    with_shape_kind(hit.kind, [&](auto kind) { set<typename decltype(kind)::type>().surface_coordinates(hit, u, v); });
}

RTWEEKEND_ENGINE_FUNCTION bool compiled_scene::surface_tangents(const surface_hit& hit, vec3& dpdu, vec3& dpdv) const {
    if (hit.user_shape) return false;
    const bool direct = hit.kind == shape_id<triangle_set>;
    if (!direct && (hit.kind != shape_id<instance_set> || hit.object_kind != shape_id<triangle_set>)) return false;
    double u = 0, v = 0;
    surface_coordinates(hit, u, v);
    if (direct) return set<triangle_set>().surface_tangents(hit.index, u, v, dpdu, dpdv);
    const instance_set& instances = set<instance_set>();
    const compiled_scene& object = *objects[instances.object[hit.index]];
    if (!object.set<triangle_set>().surface_tangents(hit.object_index, u, v, dpdu, dpdv)) return false;
    const affine3f& to_world = instances.to_world[hit.index];
    dpdu = to_world.vector(vec3f(dpdu)).to_double();
    dpdv = to_world.vector(vec3f(dpdv)).to_double();
    return true;
}

RTWEEKEND_ENGINE_FUNCTION bool compiled_scene::vertex_colour(const surface_hit& hit, vec3f& c) const {
    if (hit.user_shape) return false;
    if (hit.kind == shape_id<triangle_set>) return set<triangle_set>().vertex_colour(hit.index, hit.p.to_double(), c);
    if (hit.kind != shape_id<instance_set> || hit.object_kind != shape_id<triangle_set>) return false;
    const instance_set& instances = set<instance_set>();
    const compiled_scene& object = *objects[instances.object[hit.index]];
    const vec3f local = instances.to_object[hit.index].point(hit.p - instances.shift(hit.index, hit.time));
    return object.set<triangle_set>().vertex_colour(hit.object_index, local.to_double(), c);
}

// The user's hittables without a box, in double precision and world coordinates, after the BVH
// found `hit` (if `found`); one of them wins if it is nearer.
RTWEEKEND_ENGINE_FUNCTION bool compiled_scene::intersect_unbounded(const ray3f& r, bool found,
                                                                   surface_hit& hit) const {
    const ray world_ray(origin + r.origin.to_double(), r.dir.to_double(), r.time);
    double closest = found ? hit.t : r.tmax;
    hit_record rec;
    const hittable* nearest = nullptr;
    for (const hittable* shape : unbounded_user_shapes) {
        if (shape->hit(world_ray, interval(r.tmin, closest), rec)) {
            closest = rec.t;
            nearest = shape;
            hit.user_record = rec;
        }
    }
    if (!nearest) return found;
    complete_user_hit(nearest, hit.user_record, origin, hit);
    hit.kind = shape_id<user_shape_set>;
    hit.time = r.time;
    return true;
}

RTWEEKEND_ENGINE_FUNCTION bool compiled_scene::intersect(const ray3f& r, surface_hit& hit) const {
    hit.user_shape = nullptr;
    float t = r.tmax;
    hit_ref best;
    leaf_state state;
    state_of<user_shape_set>(state).record = &hit.user_record;
    bool found = trace<query::closest>(r, t, best, state);
    if (found) complete_hit(r, t, best, state, hit);
    if (!unbounded_user_shapes.empty()) found = intersect_unbounded(r, found, hit);
    return found;
}

RTWEEKEND_ENGINE_FUNCTION void compiled_scene::intersect_batch(int n, const ray3f* rays, surface_hit* hits,
                                                               bool* found) const {
    constexpr int W = int(floatv::width);
    // Below this many rays a packet's tests (eight boxes for every lane a node) cost more than
    // the rays' own walks: 4 packets were 4 % fewer instructions on the cover than packets of
    // any size (callgrind, an AVX2 build: 544M -> 524M at 2 spp); on an AMD EPYC (Zen 4, whose
    // 512-bit instructions run as two halves) 6 and 8 measured 1.5 % faster than 4, 11 slower.
    constexpr int min_packet = 6;
    if (W == 1 || calls_user_code()) {
        for (int k = 0; k < n; ++k) found[k] = intersect(rays[k], hits[k]);
        return;
    }
    for (int start = 0; start < n; start += W) {
        const int count = std::min(W, n - start);
        const ray3f* r = rays + start;
        if (count < min_packet) { // a few rays: cheaper alone than one lane each of a packet's tests
            for (int k = 0; k < count; ++k) found[start + k] = intersect(r[k], hits[start + k]);
            continue;
        }
        // The rays across lanes; lanes past count hold zeros (never garbage: no denormal or NaN
        // slows their arithmetic down).
        alignas(64) float lane[7][W];
        alignas(64) float t_best[W];
        unsigned dir_signs[3];
        detail::rays_to_lanes(r, count, lane, t_best, dir_signs);
        const ray_lanes lanes{floatv::load(lane[0]), floatv::load(lane[1]), floatv::load(lane[2]), floatv::load(lane[3]),
                              floatv::load(lane[4]), floatv::load(lane[5]), floatv::load(lane[6])};
        const bvh_packet packet(lanes, dir_signs, count);
        hit_ref best[W];
        // What the kernels of shapes other than spheres keep per ray (leaf_state), made for the
        // packet's rays only when it meets such a leaf: a sphere packet never builds them.
        in_place_array<leaf_state, W> state;
        traverse_packet(bvh, packet, t_best, (1u << count) - 1u, [&](uint32_t ref, unsigned active) {
            const shape_kind kind = single_kind ? *single_kind : bvh_ref::kind(ref);
            with_shape_kind(kind, [&](auto k) {
                using K = typename decltype(k)::type;
                if constexpr (has_packet_kernel<K>::value) {
                    // A kind with a packet kernel (spheres): a shape for all lanes at once.
                    set<K>().template intersect_leaf_packet<shape_id<K>>(lanes, bvh_ref::first(ref), bvh_ref::count(ref),
                                                                          active, t_best, best);
                } else {
                    // Other kinds: each lane's ray through the kind's own kernel.
                    while (state.size() < count) state.emplace_back();
                    for (unsigned m = active; m; m &= m - 1) {
                        const unsigned i = unsigned(__builtin_ctz(m));
                        leaf_kernel<query::closest, K>(r[i], ref, t_best[i], best[i], state[i]);
                    }
                }
            });
        });
        const leaf_state nothing_kept;
        for (int k = 0; k < count; ++k) {
            surface_hit& hit = hits[start + k];
            hit.user_shape = nullptr;
            found[start + k] = best[k].index != hit_ref::none;
            if (found[start + k]) complete_hit(r[k], t_best[k], best[k], state.size() > 0 ? state[k] : nothing_kept, hit);
        }
    }
}

RTWEEKEND_ENGINE_FUNCTION bool compiled_scene::intersect_culling_back_faces(const ray3f& r, surface_hit& hit) const {
    if (!culls_back_faces) return intersect(r, hit);
    hit.user_shape = nullptr;
    float t = r.tmax;
    hit_ref best;
    leaf_state state;
    state_of<user_shape_set>(state).record = &hit.user_record; // user shapes: never culled
    bool found = trace<query::closest_culled>(r, t, best, state);
    if (found) complete_hit(r, t, best, state, hit);
    if (!unbounded_user_shapes.empty()) found = intersect_unbounded(r, found, hit);
    return found;
}

RTWEEKEND_ENGINE_FUNCTION bool compiled_scene::occluded(const ray3f& r) const {
    float t = r.tmax;
    hit_ref best;
    leaf_state state;
    if (trace<query::any>(r, t, best, state)) return true;
    if (!unbounded_user_shapes.empty()) {
        const ray world_ray(origin + r.origin.to_double(), r.dir.to_double(), r.time);
        hit_record rec;
        for (const hittable* shape : unbounded_user_shapes)
            if (shape->hit(world_ray, interval(r.tmin, r.tmax), rec)) return true;
    }
    return false;
}

RTWEEKEND_ENGINE_FUNCTION size_t compiled_scene::geometry_bytes() const {
    size_t b = bvh.stats.bytes();
    for_each_kind<shape_kinds>([&](auto k) { b += set<typename decltype(k)::type>().bytes(); });
    for (const auto& o : objects) b += o->geometry_bytes();
    return b;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt
