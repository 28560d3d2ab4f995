#pragma once
// compile_scene: turns the world as users build it (hittable_list, sphere, triangle,
// triangle_mesh, materials) into the compiled scene the renderer traces (compiled_scene.h).
// It recognises the books' classes through classify.h and hands each shape to its shape kind
// (scene/shapes/: each kind compiles the classes it stands for); what it does itself is walk the
// containers and transforms, decide what to flatten and what to instance, and build the BVH.
//
//   compiled_scene scene = compile_scene(world, camera_position);
//
// It walks the world once, before rendering. Built-in spheres and triangles (single ones and
// whole meshes) go into their shape sets, in the order of the leaves of a BVH built over all of
// them, so a leaf's shapes are tested several per SIMD instruction; built-in materials go into
// the material table (material_compiler.h); anything else (a user's own hittable or material
// subclass) is kept by pointer and called through its virtual functions. Positions are stored
// relative to `origin` (the camera), computed in double before rounding to float, so a scene far
// from the world origin renders as precisely as one near it; shared mesh vertices round
// identically, so meshes stay watertight.
//
// Invalid input (NaN or infinite coordinates, non-positive radii, invalid material parameters,
// a shape without a material, mesh indices out of range) throws scene_error. Triangles of zero
// area can never be hit: a mesh's are left out and counted, a single one is an error.

#include "../core/engine_linkage.h"
#include "../core/scene_error.h"
#include "../hittable.h"
#include "../material.h"
#include "../directional_light.h"
#include "../point_light.h"
#include "compiled_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace rt {

RTWEEKEND_ENGINE_FUNCTION compiled_scene compile_scene(const hittable& world, const point3& origin);
// The same, with point and directional lights for light sampling (besides the emitters the world
// holds).
RTWEEKEND_ENGINE_FUNCTION compiled_scene compile_scene(const hittable& world, const point3& origin,
                                                       const std::vector<point_light>& point_lights,
                                                       const std::vector<directional_light>& directional_lights = {});

// Adds a light no ray can hit to a compiled scene: a parallelogram of sides edge_u and edge_v
// centred at `centre` (world space), radiance Le from both faces, found by light sampling alone
// (scene/lights/hidden_square_emitter.h; CENG795's <AreaLight>). Throws scene_error on a
// non-finite or degenerate square or radiance.
inline void add_hidden_square_light(compiled_scene& scene, const point3& centre, const vec3& edge_u, const vec3& edge_v,
                                    const color& radiance) {
    if (!finite3(centre) || !finite3(edge_u) || !finite3(edge_v))
        throw scene_error("area light corners must be finite, got centre " + point_text(centre));
    check_color(radiance, "area light radiance");
    const vec3 n = cross(edge_u, edge_v);
    const double area = n.length();
    if (!(area > 0) || !std::isfinite(area) || !(area < 1e30)) throw scene_error("area light must have a finite, non-zero area");
    light l;
    l.emitter = hidden_square_emitter{vec3f(centre - scene.origin), vec3f(edge_u), vec3f(edge_v), vec3f(n / area), float(area)};
    l.emission = vec3f(radiance);
    l.two_sided = true;
    scene.lights.add(l);
    scene.lights.finish();
}

// The table entry for the material a user's hittable reported at a hit (compiled on the spot).
RTWEEKEND_ENGINE_FUNCTION compiled_material compile_reported_material(const hit_record& rec);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "affine_map.h"
#include "bvh.h"
#include "classify.h"
#include "convex_medium.h"
#include "material_compiler.h"
#include "shape_kinds.h"
#include "validate.h"

namespace rt {

namespace detail {

// The books' transform classes: a node over one object that moves, turns or stretches it.
template <class T>
inline constexpr bool is_transform_class = std::is_same_v<T, translate> || std::is_same_v<T, rotate_y> ||
                                           std::is_same_v<T, transform> || std::is_same_v<T, rotate> ||
                                           std::is_same_v<T, scale>;

// The object under a transform node.
inline const hittable* transformed_child(const translate& t) { return t.object().get(); }
inline const hittable* transformed_child(const rotate_y& t) { return t.object().get(); }
inline const hittable* transformed_child(const transform& t) { return t.object().get(); }

// A transform node's map, checked.
inline affine_map transform_map(const translate& tr) {
    if (!finite3(tr.offset())) throw scene_error("translate offset must be finite, got " + point_text(tr.offset()));
    return affine_map::translation(tr.offset());
}
inline affine_map transform_map(const rotate_y& ro) {
    if (!(std::isfinite(ro.sin_theta()) && std::isfinite(ro.cos_theta())))
        throw scene_error("rotate_y angle must be finite, got " + number_text(ro.angle()));
    return affine_map::rotation_y(ro.sin_theta(), ro.cos_theta());
}
inline affine_map transform_map(const transform& tf, const char* problem = "transform matrix must be finite and invertible") {
    const mat3& m = tf.linear();
    const mat3 inverse = m.inverse();
    for (int i = 0; i < 3; ++i)
        if (!finite3(m.row(i)) || !finite3(inverse.row(i)) || m.determinant() == 0)
            throw scene_error(std::string(problem) + ", got rows " + point_text(m.row(0)) + " " + point_text(m.row(1)) +
                              " " + point_text(m.row(2)));
    if (!finite3(tf.offset())) throw scene_error("transform offset must be finite, got " + point_text(tf.offset()));
    return affine_map::linear(m, tf.offset());
}
inline affine_map transform_map(const rotate& r) {
    return transform_map(r, "rotate axis must be non-zero and its angle finite");
}
inline affine_map transform_map(const scale& s) { return transform_map(s, "scale factors must be finite and non-zero"); }

// Calls f(child) for every object a list, book 2's tree or a transform node names.
template <class F>
void for_each_child(const hittable& object, F&& f) {
    visit_book_class<book_hittables>(
        object,
        [&](const auto& known) {
            using T = std::decay_t<decltype(known)>;
            if constexpr (std::is_same_v<T, hittable_list>) {
                for (const auto& child : known.objects)
                    if (child) f(*child);
            } else if constexpr (std::is_same_v<T, bvh_node>) {
                if (known.left()) f(*known.left());
                if (known.right() && known.right() != known.left()) f(*known.right());
            } else if constexpr (is_transform_class<T>) {
                if (const hittable* child = transformed_child(known)) f(*child);
            } else if constexpr (std::is_same_v<T, moving>) {
                if (known.object()) f(*known.object());
            }
        },
        [](const hittable&) {});
}

// Whether every shape under `object` is one the compiler lays out itself (so a transform over it
// can be applied to the shapes); a user's hittable anywhere below makes the transform node a user
// shape as a whole, rendered through its virtual hit().
inline bool built_in_only(const hittable& object) {
    return visit_book_class<book_hittables>(
        object,
        [&](const auto& known) {
            using T = std::decay_t<decltype(known)>;
            if constexpr (std::is_same_v<T, constant_medium>) {
                return false; // a medium is a user shape (or convex_medium) of its own
            } else if constexpr (is_transform_class<T>) {
                const hittable* child = transformed_child(known);
                return child && built_in_only(*child);
            } else {
                bool all = true;
                for_each_child(known, [&](const hittable& child) { all = all && built_in_only(child); });
                return all; // a shape, or a container whose children all are built in
            }
        },
        [](const hittable&) { return false; });
}

// Shapes in the subtree, through every node.
inline size_t primitive_count(const hittable& object) {
    return visit_book_class<book_hittables>(
        object,
        [&](const auto& known) -> size_t {
            using T = std::decay_t<decltype(known)>;
            if constexpr (std::is_same_v<T, triangle_mesh>) {
                return known.faces.size();
            } else if constexpr (std::is_same_v<T, hittable_list> || std::is_same_v<T, bvh_node> || is_transform_class<T> ||
                                 std::is_same_v<T, moving>) {
                size_t n = 0;
                for_each_child(known, [&](const hittable& child) { n += primitive_count(child); });
                return n;
            } else {
                return 1;
            }
        },
        [](const hittable&) -> size_t { return 1; });
}

// Whether a sphere is reached through lists alone (one under a further transform is decided when
// that transform is reached).
inline bool holds_spheres(const hittable& object) {
    return visit_book_class<book_hittables>(
        object,
        [&](const auto& known) {
            using T = std::decay_t<decltype(known)>;
            if constexpr (std::is_same_v<T, sphere>) {
                return true;
            } else if constexpr (std::is_same_v<T, hittable_list> || std::is_same_v<T, bvh_node>) {
                bool found = false;
                for_each_child(known, [&](const hittable& child) { found = found || holds_spheres(child); });
                return found;
            } else {
                return false;
            }
        },
        [](const hittable&) { return false; });
}

// The faces of a medium's boundary when it is quads (under lists, book 2's trees and transforms),
// for convex_medium; false when it is anything else, or has more faces than convex_medium takes.
inline bool collect_faces(const hittable& object, const affine_map& xf, std::vector<convex_medium::face>& faces) {
    if (faces.size() > convex_medium::max_faces) return false;
    return visit_book_class<book_hittables>(
        object,
        [&](const auto& known) {
            using T = std::decay_t<decltype(known)>;
            if constexpr (std::is_same_v<T, quad>) {
                faces.push_back({xf.point(known.corner()), xf.vector(known.edge_u()), xf.vector(known.edge_v())});
                return true;
            } else if constexpr (std::is_same_v<T, hittable_list> || std::is_same_v<T, bvh_node> || is_transform_class<T>) {
                affine_map inner; // a list's or a tree's children stay where they are
                if constexpr (is_transform_class<T>) {
                    try {
                        inner = transform_map(known);
                    } catch (const scene_error&) {
                        return false; // a transform the medium's own hit() is left to cope with
                    }
                }
                bool all_quads = true;
                for_each_child(known, [&](const hittable& child) {
                    all_quads = all_quads && collect_faces(child, xf.then(inner), faces);
                });
                return all_quads;
            } else {
                return false;
            }
        },
        [](const hittable&) { return false; });
}

// The medium as a convex_medium when its boundary is quads that close up a convex solid; null
// otherwise.
inline std::shared_ptr<convex_medium> convex_form(const constant_medium& medium) {
    std::vector<convex_medium::face> faces;
    if (!medium.boundary() || !collect_faces(*medium.boundary(), affine_map{}, faces)) return nullptr;
    return convex_medium::make(medium, faces);
}

class scene_compiler {
  public:
    explicit scene_compiler(compiled_scene& out) : out_(out), root_(this) {}

    // Counts, before add(world), how many parents name each node of the world: a subtree named
    // more than once may become an instance (must_instance).
    void count_uses(const hittable& object) {
        for_each_child(object, [&](const hittable& child) {
            if (++uses_[&child] == 1) count_uses(child);
        });
    }

    // The world, or a part of it under the map xf (object frame -> this compiler's frame).
    void add(const hittable& object, const affine_map& xf = {}) {
        visit_book_class<book_hittables>(
            object, [&](const auto& known) { add_book(known, xf); },
            [&](const hittable& other) { add_user_shape(other, xf); });
    }

    // Builds the BVH over every kind's inputs and lays each kind's shapes out in its leaf order.
    void finish();

    // What the shape kinds' add() asks of the compiler (scene/shapes/).
    const vec3& origin() const { return out_.origin; }
    template <class K>
    std::vector<typename K::input>& inputs() { return std::get<std::vector<typename K::input>>(inputs_); }
    template <class K>
    K& set() { return out_.template set<K>(); }
    compiled_scene& scene() { return out_; }

    // The table index of material m, compiled once (one table for the scene and its objects).
    uint32_t material_index(const material* m) {
        if (root_ != this) return root_->material_index(m); // one table for the scene and its objects
        auto found = index_.find(m);
        if (found != index_.end()) return found->second;
        // A normal map: the base material compiled as itself, under an index of its own, the map
        // beside it in the scene's table (compiled_scene::normal_maps).
        const material* base = m;
        const auto* mapped = dynamic_cast<const normal_mapped*>(m);
        if (mapped) {
            const std::string kind = mapped->holds_heights() ? "bump_mapped" : "normal_mapped";
            if (!mapped->base()) throw scene_error(kind + " material has no base material");
            if (!mapped->normals()) throw scene_error(kind + (mapped->holds_heights() ? " material has no height map" : " material has no normal map"));
            if (!std::isfinite(mapped->scale())) throw scene_error(kind + " scale must be finite");
            if (dynamic_cast<const normal_mapped*>(mapped->base().get()))
                throw scene_error(kind + " material's base has a normal or bump map of its own");
            base = mapped->base().get();
        }
        compiled_material d = compile_material(*base, &out_.textures);
        if (d.is_user()) out_.has_user_materials = true;
        const auto index = static_cast<uint32_t>(out_.materials.size());
        // A metallic-roughness map: beside it in compiled_scene::metallic_roughness_maps, and the
        // material textured so that textured() looks the map up (its base colour, if constant, as
        // a constant texture of the table).
        const auto* blend = dynamic_cast<const metal_roughness*>(base);
        if (blend && blend->metallic_roughness_map() && !d.is_user()) {
            if (d.texture == no_texture) d.texture = out_.textures.add_constant(vec3f(blend->base_colour()));
            out_.metallic_roughness_maps.resize(index + 1);
            out_.metallic_roughness_maps[index] = {out_.textures.add(*blend->metallic_roughness_map()),
                                                   float(blend->metallic()), float(blend->roughness())};
        }
        out_.materials.push_back(d);
        if (mapped) {
            out_.normal_maps.resize(out_.materials.size());
            out_.normal_maps[index] = {out_.textures.add(*mapped->normals()), float(mapped->scale()), mapped->holds_heights()};
        } else if (!out_.normal_maps.empty()) {
            out_.normal_maps.resize(out_.materials.size());
        }
        index_.emplace(m, index);
        return index;
    }

    // The table index of material m for a mesh with vertex colours (triangle_mesh::colors), which
    // textured() multiplies into the colour its kind takes: a kind with a colour of its own is
    // given it as a constant texture, so that textured() is asked at every hit. Emitters keep
    // their emission.
    uint32_t vertex_coloured_material_index(const material* m) {
        if (root_ != this) return root_->vertex_coloured_material_index(m);
        const uint32_t index = material_index(m);
        compiled_material& d = out_.materials[index];
        if (d.texture == no_texture && d.takes_colour() && !d.emits() && !d.is_user())
            d.texture = out_.textures.add_constant(d.colour());
        out_.vertex_colours = true;
        return index;
    }

    // The material of a sphere with a negative radius (the books' v3 hollow glass), whose
    // outward normal (p - c) / r points inwards: a ray from outside meets its back face. Only
    // the materials that tell the faces apart change: a dielectric of index n seen inside out
    // is one of index 1 / n seen the right way round (the ratio at each crossing is the same),
    // and a two-sided light or any other built-in material is the same either way. What cannot
    // be turned round is refused: absorbing glass (its inside would be the outside), a
    // one-sided light (it would shine inwards) and a user's material (it reads front_face).
    uint32_t inside_out_material_index(const material* m) {
        if (root_ != this) return root_->inside_out_material_index(m);
        auto found = inside_out_index_.find(m);
        if (found != inside_out_index_.end()) return found->second;
        const uint32_t right_way_round = material_index(m);
        compiled_material d = out_.materials[right_way_round];
        uint32_t index = right_way_round;
        const char* refusal = nullptr;
        if (d.refracts()) {
            if (d.absorbs_inside()) {
                refusal = "absorbing glass";
            } else {
                d.edit<dielectric_bsdf>([](dielectric_bsdf& g) { g.refraction_index = 1.0f / g.refraction_index; });
                d.edit<fresnel_glass_bsdf>([](fresnel_glass_bsdf& g) { g.refraction_index = 1.0f / g.refraction_index; });
                d.edit<rough_dielectric_bsdf>([](rough_dielectric_bsdf& g) { g.refraction_index = 1.0f / g.refraction_index; });
                index = static_cast<uint32_t>(out_.materials.size());
                out_.materials.push_back(d);
                if (!out_.normal_maps.empty()) out_.normal_maps.push_back(out_.normal_maps[right_way_round]);
            }
        } else if (d.is_user() && !is_exactly<isotropic>(*m)) { // a phase function has no faces
            refusal = "a material of the program's own";
        } else if (d.emits() && !d.two_sided()) {
            refusal = "a one-sided diffuse_light";
        }
        if (refusal)
            throw scene_error(std::string("a sphere with a negative radius (inside out) cannot have ") + refusal +
                              ": give it a positive radius");
        inside_out_index_.emplace(m, index);
        return index;
    }

  private:
    // --- the books' classes, one rule each (classify.h's list) ---------------------------------
    void add_book(const hittable_list& list, const affine_map& xf) {
        for (const auto& child : list.objects) {
            if (!child) throw scene_error("hittable_list holds a null object");
            add(*child, xf);
        }
    }
    // Book 2's tree: only its shapes matter here (the engine builds its own BVH).
    void add_book(const bvh_node& node, const affine_map& xf) {
        add(*node.left(), xf);
        if (node.right() != node.left()) add(*node.right(), xf);
    }
    // A moved, turned or stretched group of built-in shapes; over anything else the transform
    // node is a user shape as a whole, rendered through its virtual hit().
    template <class T, std::enable_if_t<is_transform_class<T>, int> = 0>
    void add_book(const T& node, const affine_map& xf) {
        const hittable* child = transformed_child(node);
        if (child && built_in_only(*child)) return place(*child, xf.then(transform_map(node)));
        add_user_shape(node, xf);
    }
    // A moving group of built-in shapes: an instance of it whose place shifts with the ray's time
    // (instance_set.h); over anything else, a user shape as a whole.
    void add_book(const moving& node, const affine_map& xf) {
        const hittable* child = node.object().get();
        if (!child) throw scene_error("moving holds a null object");
        if (!finite3(node.displacement()))
            throw scene_error("moving displacement must be finite, got " + point_text(node.displacement()));
        if (!built_in_only(*child)) return add_user_shape(node, xf);
        const vec3 motion = xf.vector(node.displacement());
        if (motion.x() == 0 && motion.y() == 0 && motion.z() == 0) return add(*child, xf);
        place(*child, xf, motion);
    }
    void add_book(const sphere& s, const affine_map& xf) { sphere_set::add(*this, s, xf); }
    void add_book(const triangle& t, const affine_map& xf) { triangle_set::add(*this, t, xf); }
    void add_book(const triangle_mesh& mesh, const affine_map& xf) { triangle_set::add(*this, mesh, xf); }
    void add_book(const quad& q, const affine_map& xf) { quad_set::add(*this, q, xf); }
    // Fog: in a convex box of quads, its chord in closed form (convex_medium.h) in the medium's
    // place; otherwise the medium's own hit().
    void add_book(const constant_medium& medium, const affine_map& xf) {
        if (auto convex = convex_form(medium)) {
            out_.owned_user_shapes.push_back(convex);
            return add_user_shape(*convex, xf);
        }
        add_user_shape(medium, xf);
    }
    // A user's own hittable (or a transform over one).
    void add_user_shape(const hittable& object, const affine_map& xf) {
        if (!xf.identity) throw scene_error("internal: a user shape under a flattened transform");
        user_shape_set::add(*this, object);
    }

    // What the compiler made of a subtree it instances: its object (none when everything in it
    // was itself instanced), and the instances inside it, which are placed beside it in the
    // scene (an object holds no instances: two levels, one walk each).
    // A subtree an object's compiler lifts out to be placed beside the object (object_record):
    // the map into the object's frame and the motion in it (zero for one that stands still).
    struct lifted {
        const hittable* child;
        affine_map map;
        vec3 motion;
    };
    struct object_record {
        uint32_t object = UINT32_MAX;
        std::vector<lifted> inner;
    };
    // Subtrees of more primitives than this, named more than once, are instanced; smaller ones
    // are copied (six quads of a box cost less than the walk into an instance).
    static constexpr size_t flatten_limit = 16;

    // An object's compiler: its shapes go to `object`, its materials to the scene's table.
    scene_compiler(compiled_scene& object, scene_compiler& root) : out_(object), root_(&root) {}

    // Flatten or instance: a subtree is traced as an instance when its shapes cannot take the
    // map exactly (a sphere under a map that is not a rotation times a uniform scale becomes an
    // ellipsoid), when the map mirrors (flattened triangles would swap front and back; an
    // instance keeps the object's own), or when it is named more than once and is large (one
    // copy of a mesh serves every placement). Otherwise the map is applied to the shapes: what a
    // single box or mesh costs today, the fastest to trace.
    bool must_instance(const hittable& child, const affine_map& m) const {
        if (m.identity) return false;
        if (!(m.m.determinant() > 0)) return true;
        if (holds_spheres(child) && !(m.sphere_scale() > 0)) return true;
        const auto uses = root_->uses_.find(&child);
        return uses != root_->uses_.end() && uses->second > 1 && primitive_count(child) > flatten_limit;
    }

    // The subtree `child` under the map m (object frame -> this compiler's frame), moving by
    // `motion` (in this compiler's frame) over the shutter interval: a moving subtree is always
    // an instance.
    void place(const hittable& child, const affine_map& m, const vec3& motion = vec3(0, 0, 0)) {
        const bool moves = motion.x() != 0 || motion.y() != 0 || motion.z() != 0;
        if (!moves && !must_instance(child, m)) return add(child, m);
        if (root_ != this) { // inside an object: the instance goes beside it (object_record)
            lifted_.push_back({&child, m, motion});
            return;
        }
        const object_record record = object_of(child);
        if (record.object != UINT32_MAX) inputs<instance_set>().push_back({record.object, m, vec3f(motion)});
        for (const lifted& l : record.inner) place(*l.child, m.then(l.map), motion + m.vector(l.motion));
    }

    // The object compiled from `child`, once per distinct subtree (by address).
    object_record object_of(const hittable& child) {
        if (auto found = objects_.find(&child); found != objects_.end()) return found->second;
        auto object = std::make_shared<compiled_scene>(); // origin zero: the object's own frame
        scene_compiler nested(*object, *this);
        nested.add(child);
        nested.finish();
        object_record record;
        record.inner = std::move(nested.lifted_);
        if (object->bvh.root != bvh_ref::empty) {
            record.object = uint32_t(out_.objects.size());
            out_.has_motion = out_.has_motion || object->has_motion;
            out_.objects.push_back(std::move(object));
        }
        objects_.emplace(&child, record);
        return record;
    }

    // Records every emitting shape of a light-sampled kind as a light, in the sets' final order.
    void find_lights();

    // The inputs of every shape kind, as the kinds' add() collect them.
    template <class List>
    struct inputs_of;
    template <class... Kinds>
    struct inputs_of<kind_list<Kinds...>> {
        using type = std::tuple<std::vector<typename Kinds::input>...>;
    };

    compiled_scene& out_;
    typename inputs_of<shape_kinds>::type inputs_;
    std::unordered_map<const material*, uint32_t> index_;
    std::unordered_map<const material*, uint32_t> inside_out_index_; // inside_out_material_index's
    scene_compiler* root_; // the scene's compiler (this one, or the one whose object this compiles)
    std::unordered_map<const hittable*, uint32_t> uses_;         // root only: see count_uses
    std::unordered_map<const hittable*, object_record> objects_; // root only: see object_of
    std::vector<lifted> lifted_; // an object's: instances inside it
};

inline void scene_compiler::finish() {
    std::vector<bvh_primitive> prims;
    for_each_kind<shape_kinds>([&](auto k) {
        using K = typename decltype(k)::type;
        const std::vector<typename K::input>& in = inputs<K>();
        for (size_t i = 0; i < in.size(); ++i) prims.push_back({K::bounds(in[i], out_), shape_id<K>, uint32_t(i)});
    });
    for (const bvh_primitive& p : prims) out_.bounds.grow(p.bounds);
    bvh_build_options options;
    // A kind whose shapes the BVH may split by planes through them (triangles: bvh.h) gives its corners.
    for_each_kind<shape_kinds>([&](auto k) {
        using K = typename decltype(k)::type;
        if constexpr (splits_by_planes<K>::value) {
            if (!inputs<K>().empty()) {
                options.split_kind = shape_id<K>;
                options.split_corners = [this](uint32_t i) { return K::corners(inputs<K>()[i]); };
            }
        }
    });
    out_.bvh = build_wide_bvh(prims, options);
    // One kind of shape only (counted in prims: order names a split triangle more than once).
    for (int k = 0; k < shape_kind_count; ++k) {
        auto of_kind = [k](const bvh_primitive& p) { return int(p.kind) == k; };
        if (!prims.empty() && std::all_of(prims.begin(), prims.end(), of_kind)) out_.single_kind = static_cast<shape_kind>(k);
    }
    for_each_kind<shape_kinds>([&](auto k) {
        using K = typename decltype(k)::type;
        K& s = out_.template set<K>();
        s.lay_out(out_, inputs<K>(), out_.bvh.order[size_t(shape_id<K>)]);
        if constexpr (K::moves) out_.has_motion = out_.has_motion || s.size() > 0;
        if constexpr (std::is_same_v<K, instance_set>) out_.has_motion = out_.has_motion || s.moving_count() > 0;
    });
    // An object's emitters are not light-sampled (compiled_scene::objects), nor are moving ones or
    // user shapes': a path that hits one counts it in full.
    if (root_ == this) find_lights();
}

inline void scene_compiler::find_lights() {
    light_set& lights = out_.lights;
    for_each_kind<shape_kinds>([&](auto k) {
        using K = typename decltype(k)::type;
        if constexpr (K::light_sampled) {
            const K& s = out_.template set<K>();
            std::vector<uint32_t>& table = lights.of_shape[size_t(shape_id<K>)];
            // A triangle the BVH split by a plane through it is laid out once for each leaf that
            // holds a part of it (bvh.h, spatial splits): one light, which all its copies name.
            const std::vector<uint32_t>& order = out_.bvh.order[size_t(shape_id<K>)];
            std::unordered_map<uint32_t, uint32_t> light_of_shape;
            for (uint32_t i = 0; i < s.size(); ++i) {
                const compiled_material& m = out_.materials[s.material_of(i)];
                if (!m.emits()) continue;
                if (table.empty()) table.assign(s.size(), light_set::none);
                const auto light_index = uint32_t(lights.lights.size());
                const auto [known, is_new] = light_of_shape.try_emplace(order[i], light_index);
                if (!is_new) {
                    table[i] = known->second;
                    continue;
                }
                light l;
                l.emitter = s.light_of(i);
                l.emission = m.emission(); // a textured light: its texture's mean (material_compiler.h)
                l.two_sided = m.two_sided();
                l.texture = m.texture;
                l.shape = shape_id<K>;
                l.shape_index = i;
                table[i] = lights.add(l);
            }
        }
    });
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION compiled_scene compile_scene(const hittable& world, const point3& origin,
                                                       const std::vector<point_light>& point_lights,
                                                       const std::vector<directional_light>& directional_lights) {
    if (!finite3(origin)) throw scene_error("camera position must be finite, got " + point_text(origin));
    compiled_scene scene;
    scene.origin = origin;
    detail::scene_compiler compiler(scene);
    compiler.count_uses(world);
    compiler.add(world);
    compiler.finish();
    for (const point_light& p : point_lights) {
        if (!finite3(p.position)) throw scene_error("point light position must be finite, got " + point_text(p.position));
        check_color(p.intensity, "point light intensity");
        const double inner = p.inner_cone, outer = p.outer_cone;
        const double axis_length = p.spot_direction.length();
        if (!std::isfinite(axis_length)) throw scene_error("spot light direction must be finite, got " + point_text(p.spot_direction));
        point_emitter e{vec3f(p.position - origin)};
        if (axis_length > 0) {
            if (!(inner >= 0 && inner <= outer && outer > 0 && outer <= pi))
                throw scene_error("spot light cones must satisfy 0 <= inner <= outer <= pi, outer > 0, got " +
                                  number_text(inner) + " and " + number_text(outer));
            if (!(p.cone_exponent >= 1 && p.cone_exponent <= 1e6))
                throw scene_error("spot light cone exponent must be in [1, 1e6], got " + number_text(p.cone_exponent));
            e.axis = vec3f(p.spot_direction / axis_length);
            e.exponent = float(p.cone_exponent);
            e.cos_outer = float(std::cos(outer));
            // glTF's guard against a zero-width cone: at most 1000.
            e.inv_cone_width = float(1.0 / std::max(1e-3, std::cos(inner) - std::cos(outer)));
        }
        light l;
        l.emitter = e;
        l.emission = vec3f(p.intensity);
        scene.lights.add(l);
    }
    // A directional light's power and light paths take the scene's bounding sphere (its box's
    // circumscribed sphere; directional_emitter.h).
    const bool bounded = !scene.bounds.empty();
    const vec3f centre = bounded ? 0.5f * (scene.bounds.lo + scene.bounds.hi) : vec3f{0, 0, 0};
    const float radius = bounded ? 0.5f * length(scene.bounds.hi - scene.bounds.lo) : 0.0f;
    for (const directional_light& d : directional_lights) {
        const double length = d.direction.length();
        if (!std::isfinite(length) || !(length > 0))
            throw scene_error("directional light direction must be a non-zero finite vector, got " + point_text(d.direction));
        check_color(d.irradiance, "directional light irradiance");
        light l;
        l.emitter = directional_emitter{vec3f(-d.direction / length), centre, std::isfinite(radius) ? radius : 0.0f};
        l.emission = vec3f(d.irradiance);
        scene.lights.add(l);
    }
    scene.lights.finish();
    return scene;
}

RTWEEKEND_ENGINE_FUNCTION compiled_scene compile_scene(const hittable& world, const point3& origin) {
    return compile_scene(world, origin, {});
}

RTWEEKEND_ENGINE_FUNCTION compiled_material compile_reported_material(const hit_record& rec) {
    if (!rec.mat) throw scene_error("a user-written hittable reported a hit without a material");
    return compile_material(*rec.mat);
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt
