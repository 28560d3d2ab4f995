#pragma once
// user_shape_set: the shape kind of the user's own hittables that report a bounding box (and of
// what the compiler makes to stand for one: convex_medium for fog in a box), in BVH leaf order
// (scene/shape_kinds.h says what a kind answers). Their leaf kernel calls each shape's virtual
// hit() in double precision and world coordinates, as the book's code would; the BVH around them
// means a ray only asks the few whose boxes it enters. Hittables without a usable box stay in
// compiled_scene::unbounded_user_shapes and meet every ray.

#include "../../core/box3f.h"
#include "../../core/vec3f.h"
#include "../../hittable.h"
#include "../../interval.h"
#include "../../ray.h"
#include "../leaf_query.h"
#include "../surface_hit.h"
#include "../validate.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace rt {

// Fills `hit` from the record a user's hittable `shape` reported (in world coordinates).
inline void complete_user_hit(const hittable* shape, const hit_record& rec, const vec3& origin, surface_hit& hit) {
    hit.user_shape = shape;
    if (&hit.user_record != &rec) hit.user_record = rec;
    hit.t = static_cast<float>(rec.t);
    hit.p = vec3f(rec.p - origin);
    hit.normal = normalize(vec3f(rec.normal));
    hit.shading_normal = hit.normal;
    hit.front_face = rec.front_face;
    hit.offset = 0;
}

struct user_shape_set {
    static constexpr const char* name = "user shape";
    // Whether its shapes move with the ray's time (a user's hit() may read the ray's time: the
    // scene then calls user code, which draws times anyway).
    static constexpr bool moves = false;
    // Scenes of these alone are rare: they share the walk of mixed scenes (shape_kinds.h).
    static constexpr bool own_walk = false;

    // --- compiling ---------------------------------------------------------------------------
    // A user's hittable and its box relative to the scene origin, rounded outwards.
    struct input {
        const hittable* shape;
        box3f bounds;
    };
    // A hittable the compiler does not know: into the BVH when its bounding box is usable
    // (non-empty, finite and within float's range of the origin); otherwise (a book-1 class has
    // only the default box, all of space) among the scene's unbounded user shapes, tested against
    // every ray. Owned by the world (or by the scene, compiled_scene::owned_user_shapes).
    template <class Compiler>
    static void add(Compiler& compiler, const hittable& shape);
    template <class Scene>
    static box3f bounds(const input& s, const Scene&) { return s.bounds; }
    template <class Scene>
    void lay_out(const Scene&, const std::vector<input>& inputs, const std::vector<uint32_t>& order) {
        for (uint32_t i : order) shapes.push_back(inputs[i].shape);
    }

    // --- the compiled shapes -------------------------------------------------------------------
    std::vector<const hittable*> shapes;

    size_t size() const { return shapes.size(); }

    // Where the closest hit's record goes (the caller's surface_hit::user_record).
    struct ray_state {
        hit_record* record = nullptr;
    };
    // Tests shapes [first, first + n) against the ray (relative to the scene origin): see
    // leaf_query.h. Kept out of line: it makes virtual calls anyway, and inlined it would crowd
    // the traversal loop every other kind runs in.
    template <query Q, shape_kind Self, class Scene>
#if defined(__GNUC__)
    __attribute__((noinline))
#endif
    bool intersect_leaf(const Scene& scene, const ray3f& r, uint32_t first, uint32_t n, float& t_best, hit_ref& best,
                        ray_state& state) const {
        const ray world_ray(scene.origin + r.origin.to_double(), r.dir.to_double(), r.time);
        hit_record rec;
        bool found = false;
        for (uint32_t i = first; i < first + n; ++i) {
            if (!shapes[i]->hit(world_ray, interval(r.tmin, t_best), rec)) continue;
            if constexpr (Q == query::any) return true;
            // Rounded to nearest, a t below t_best stays at or below it.
            t_best = static_cast<float>(rec.t);
            best = {Self, i};
            *state.record = rec;
            found = true;
        }
        return found;
    }
    template <class Scene>
    void complete_hit(const Scene& scene, const ray3f&, float, uint32_t i, const ray_state& state, surface_hit& hit) const {
        complete_user_hit(shapes[i], *state.record, scene.origin, hit);
    }
    // The (u, v) the shape's own record reports.
    void surface_coordinates(const surface_hit& hit, double& u, double& v) const {
        u = hit.user_record.u;
        v = hit.user_record.v;
    }

    // Its materials are reported per hit: an emitting user shape is not light-sampled (a path
    // that hits it counts its emission in full).
    static constexpr bool light_sampled = false;
    // Nothing: its materials are not known before a hit.
    template <class Scene, class Predicate>
    void bound_where(const Scene&, Predicate, box3f&) const {}
    // Never culled: the user's hit() decides what it reports.
    template <class Predicate>
    void mark_culled(Predicate) {}

    size_t bytes() const { return shapes.size() * sizeof(const hittable*); }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

// Not inlined: inlined into a caller whose world is a hittable_list, GCC 12 speculates `shape` is
// that list and warns about the devirtualised call it made up.
template <class Compiler>
#if defined(__GNUC__)
__attribute__((noinline))
#endif
void user_shape_set::add(Compiler& compiler, const hittable& shape) {
    const aabb box = shape.bounding_box();
    const vec3 origin = compiler.origin();
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = box.axis_interval(a).min - origin[a];
        hi[a] = box.axis_interval(a).max - origin[a];
        if (!(lo[a] <= hi[a] && std::fabs(lo[a]) < max_float_extent && std::fabs(hi[a]) < max_float_extent)) {
            compiler.scene().unbounded_user_shapes.push_back(&shape);
            return;
        }
    }
    box3f b; // rounded outwards: the float box must hold the double one
    b.lo = {float_below(lo[0]), float_below(lo[1]), float_below(lo[2])};
    b.hi = {float_above(hi[0]), float_above(hi[1]), float_above(hi[2])};
    compiler.template inputs<user_shape_set>().push_back({&shape, b});
}

} // namespace rt
