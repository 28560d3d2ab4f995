#pragma once
// compile_scene: turns the world as users build it (hittable_list, sphere, triangle,
// triangle_mesh, materials) into the compiled scene the renderer traces (compiled_scene.h).
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

#include "../bvh.h"
#include "../constant_medium.h"
#include "../hittable.h"
#include "../hittable_list.h"
#include "../material.h"
#include "../mesh.h"
#include "../point_light.h"
#include "../quad.h"
#include "../core/scene_error.h"
#include "../sphere.h"
#include "../transform.h"
#include "../triangle.h"
#include "bvh.h"
#include "compiled_scene.h"
#include "convex_medium.h"
#include "material_compiler.h"
#include "validate.h"
#include "../core/vec3f.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <typeinfo>
#include <unordered_map>
#include <vector>

namespace rt {

compiled_scene compile_scene(const hittable& world, const point3& origin);
// The same, with point lights for light sampling (besides the emitters the world holds).
compiled_scene compile_scene(const hittable& world, const point3& origin, const std::vector<point_light>& point_lights);

// The table entry for the material a user's hittable reported at a hit (compiled on the spot).
compiled_material compile_reported_material(const hit_record& rec);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// An affine map x -> M x + t, in double: the transform nodes a shape sits under (translate,
// rotate_y, transform, rotate, scale), composed. The compiler applies it to the shapes themselves
// when it can (flattened, they cost nothing more at render time), or makes the subtree an
// instance that keeps it (instance_set.h): see scene_compiler::must_instance.
struct affine_map {
    mat3 m; // M
    vec3 t{0, 0, 0};
    bool identity = true;

    vec3 vector(const vec3& v) const { return identity ? v : m * v; }
    point3 point(const point3& p) const { return identity ? p : m * p + t; }
    // A normal through the map: by the inverse transpose (normals are gradients), unnormalised.
    vec3 normal(const vec3& n) const { return identity ? n : m.inverse().transpose() * n; }
    // This map after `inner` (inner applied first).
    affine_map then(const affine_map& inner) const {
        if (inner.identity) return *this;
        if (identity) return inner;
        affine_map r;
        r.m = m * inner.m;
        r.t = vector(inner.t) + t;
        r.identity = false;
        return r;
    }
    static affine_map linear(const mat3& linear, const vec3& offset) {
        affine_map r;
        r.m = linear;
        r.t = offset;
        r.identity = false;
        return r;
    }
    static affine_map translation(const vec3& offset) { return linear(mat3(), offset); }
    // rotate_y's object-to-world rotation: x' = cos x + sin z, z' = -sin x + cos z.
    static affine_map rotation_y(double sin_theta, double cos_theta) {
        return linear(mat3(vec3(cos_theta, 0, sin_theta), vec3(0, 1, 0), vec3(-sin_theta, 0, cos_theta)), vec3(0, 0, 0));
    }
    // s when M is s times a rotation (M^T M = s^2 I and det M > 0), so that a sphere of radius r
    // maps to the sphere of radius s r; 0 when it is not (a sphere would become an ellipsoid).
    double sphere_scale() const {
        if (identity) return 1;
        const mat3 mtm = m.transpose() * m;
        const double s2 = (mtm(0, 0) + mtm(1, 1) + mtm(2, 2)) / 3;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (!(std::fabs(mtm(i, j) - (i == j ? s2 : 0.0)) <= 1e-12 * s2)) return 0;
        return m.determinant() > 0 ? std::sqrt(s2) : 0;
    }
};

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

    void add(const hittable& object, const affine_map& xf = {}) {
        const std::type_info& type = typeid(object);
        if (type == typeid(hittable_list)) {
            for (const auto& child : static_cast<const hittable_list&>(object).objects) {
                if (!child) throw scene_error("hittable_list holds a null object");
                add(*child, xf);
            }
        } else if (type == typeid(bvh_node)) {
            // Book 2's tree: only its shapes matter here (the engine builds its own BVH).
            const auto& node = static_cast<const bvh_node&>(object);
            add(*node.left(), xf);
            if (node.right() != node.left()) add(*node.right(), xf);
        } else if (type == typeid(sphere)) {
            add_sphere(static_cast<const sphere&>(object), xf);
        } else if (type == typeid(triangle)) {
            const auto& t = static_cast<const triangle&>(object);
            if (!t.mat()) throw scene_error("triangle at " + point_text(t.a()) + " has no material");
            uint32_t m = material_index(t.mat().get());
            if (!add_triangle(xf.point(t.a()), xf.point(t.b()), xf.point(t.c()), m))
                throw scene_error("triangle " + point_text(t.a()) + " " + point_text(t.b()) + " " + point_text(t.c()) +
                                  " has zero area");
        } else if (type == typeid(quad)) {
            add_quad(static_cast<const quad&>(object), xf);
        } else if (type == typeid(triangle_mesh)) {
            add_mesh(static_cast<const triangle_mesh&>(object), xf);
        } else if (const hittable* child = transformed_child(object); child && built_in_only(*child)) {
            // A moved, turned or stretched group of built-in shapes.
            place(*child, xf.then(transform_map(object)));
        } else {
            // A user's own hittable (or a transform over one): called through its virtual hit().
            // Under a transform, the whole transform node is the user shape.
            if (!xf.identity) throw scene_error("internal: a user shape under a flattened transform");
            if (typeid(object) == typeid(constant_medium)) {
                // Fog in a box: its chord in closed form (convex_medium.h), in the medium's place.
                if (auto convex = convex_form(static_cast<const constant_medium&>(object))) {
                    out_.owned_user_shapes.push_back(convex);
                    add_user_shape(*convex);
                    return;
                }
            }
            add_user_shape(object);
        }
    }

    // The medium as a convex_medium when its boundary is quads (under lists, book 2's trees and
    // transforms) that close up a convex solid; null otherwise.
    static std::shared_ptr<convex_medium> convex_form(const constant_medium& medium) {
        std::vector<convex_medium::face> faces;
        if (!medium.boundary() || !collect_faces(*medium.boundary(), affine_map{}, faces)) return nullptr;
        return convex_medium::make(medium, faces);
    }
    static bool collect_faces(const hittable& object, const affine_map& xf, std::vector<convex_medium::face>& faces) {
        if (faces.size() > convex_medium::max_faces) return false;
        const std::type_info& type = typeid(object);
        if (type == typeid(quad)) {
            const auto& q = static_cast<const quad&>(object);
            faces.push_back({xf.point(q.corner()), xf.vector(q.edge_u()), xf.vector(q.edge_v())});
            return true;
        }
        if (type != typeid(hittable_list) && type != typeid(bvh_node) && !is_transform(type)) return false;
        affine_map inner; // a list's or a tree's children stay where they are
        if (is_transform(type)) {
            try {
                inner = transform_map(object);
            } catch (const scene_error&) {
                return false; // a transform the medium's own hit() is left to cope with
            }
        }
        bool all_quads = true;
        for_each_child(object, [&](const hittable& child) {
            all_quads = all_quads && collect_faces(child, xf.then(inner), faces);
        });
        return all_quads;
    }

    // Whether every shape under `object` is one the compiler lays out itself (so a transform over
    // it can be applied to the shapes); a user's hittable anywhere below makes the transform node
    // a user shape as a whole, rendered through its virtual hit().
    static bool built_in_only(const hittable& object) {
        const std::type_info& type = typeid(object);
        if (type == typeid(hittable_list)) {
            for (const auto& child : static_cast<const hittable_list&>(object).objects)
                if (child && !built_in_only(*child)) return false;
            return true;
        }
        if (type == typeid(bvh_node)) {
            const auto& node = static_cast<const bvh_node&>(object);
            return built_in_only(*node.left()) && built_in_only(*node.right());
        }
        if (is_transform(type)) {
            const hittable* child = transformed_child(object);
            return child && built_in_only(*child);
        }
        return type == typeid(sphere) || type == typeid(triangle) || type == typeid(quad) ||
               type == typeid(triangle_mesh);
    }

    // Builds the BVH and lays the primitives out in its leaf order.
    void finish() {
        std::vector<bvh_primitive> prims;
        prims.reserve(spheres_.size() + triangles_.size());
        for (size_t i = 0; i < spheres_.size(); ++i) {
            const sphere_input& s = spheres_[i];
            box3f b;
            // Rounded outwards: the box must contain the float sphere the leaf test sees.
            b.lo = {down(s.c.x() - s.r), down(s.c.y() - s.r), down(s.c.z() - s.r)};
            b.hi = {up(s.c.x() + s.r), up(s.c.y() + s.r), up(s.c.z() + s.r)};
            prims.push_back({b, shape_kind::sphere, uint32_t(i)});
        }
        for (size_t i = 0; i < triangles_.size(); ++i) {
            box3f b;
            for (const vec3f& v : triangles_[i].v) b.grow(v);
            prims.push_back({b, shape_kind::triangle, uint32_t(i)});
        }
        for (size_t i = 0; i < quads_.size(); ++i) {
            box3f b;
            const quad_input& q = quads_[i];
            for (const vec3& corner : {q.q, q.q + q.u, q.q + q.v, q.q + q.u + q.v})
                b.grow({down(corner.x()), down(corner.y()), down(corner.z())}),
                    b.grow({up(corner.x()), up(corner.y()), up(corner.z())});
            prims.push_back({b, shape_kind::quad, uint32_t(i)});
        }
        for (size_t i = 0; i < user_shapes_.size(); ++i) prims.push_back({user_shapes_[i].bounds, shape_kind::user, uint32_t(i)});
        for (size_t i = 0; i < moving_spheres_.size(); ++i) {
            const moving_sphere_input& s = moving_spheres_[i];
            // Both ends of the motion, and a few ulps more: the kernel's centre c0 + time * m,
            // in float, may stray that far from the exact line.
            const double pad = s.r + std::ldexp(fmax_inline(max_abs(s.c0), max_abs(s.c1)) + s.r, -20);
            box3f b;
            for (const vec3& c : {s.c0, s.c1})
                b.grow({down(c.x() - pad), down(c.y() - pad), down(c.z() - pad)}),
                    b.grow({up(c.x() + pad), up(c.y() + pad), up(c.z() + pad)});
            prims.push_back({b, shape_kind::moving_sphere, uint32_t(i)});
        }
        for (size_t i = 0; i < instances_.size(); ++i)
            prims.push_back({instance_bounds(instances_[i]), shape_kind::instance, uint32_t(i)});
        for (const bvh_primitive& p : prims) out_.bounds.grow(p.bounds);
        bvh_build_options options;
        // Triangles may be split by planes through them (bvh.h): a mesh's boxes overlap less.
        if (!triangles_.empty()) options.triangle_corners = [this](uint32_t i) { return triangles_[i].v; };
        out_.bvh = build_wide_bvh(prims, options);
        // One kind of shape only (counted in prims: order names a split triangle more than once).
        for (int k = 0; k < shape_kind_count; ++k) {
            auto of_kind = [k](const bvh_primitive& p) { return int(p.kind) == k; };
            if (!prims.empty() && std::all_of(prims.begin(), prims.end(), of_kind))
                out_.single_kind = static_cast<shape_kind>(k);
        }

        // Leaf loads read floatv::width lanes from any leaf start: pad every array that far.
        const size_t pad = floatv::width;
        const auto& sphere_order = out_.bvh.order[size_t(shape_kind::sphere)];
        out_.spheres.count = sphere_order.size();
        for (uint32_t i : sphere_order) push_sphere(spheres_[i]);
        for (size_t k = 0; k < pad; ++k) out_.spheres.append(vec3f(0, 0, 0), 0, 0, /*padding=*/true);

        const auto& triangle_order = out_.bvh.order[size_t(shape_kind::triangle)];
        out_.triangles.count = triangle_order.size();
        out_.triangles.distinct = triangles_.size();
        for (uint32_t i : triangle_order) push_triangle(triangles_[i]);
        if (out_.triangles.count > 0)
            for (size_t k = 0; k < pad; ++k) push_triangle({{vec3f(), vec3f(), vec3f()}, 0});

        const auto& quad_order = out_.bvh.order[size_t(shape_kind::quad)];
        out_.quads.count = quad_order.size();
        for (uint32_t i : quad_order) push_quad(quads_[i]);
        if (out_.quads.count > 0)
            for (size_t k = 0; k < pad; ++k) out_.quads.append_padding();

        for (uint32_t i : out_.bvh.order[size_t(shape_kind::user)]) out_.user_shapes.shapes.push_back(user_shapes_[i].shape);

        const auto& moving_order = out_.bvh.order[size_t(shape_kind::moving_sphere)];
        out_.moving_spheres.count = moving_order.size();
        for (uint32_t i : moving_order) {
            const moving_sphere_input& s = moving_spheres_[i];
            out_.moving_spheres.append(vec3f(s.c0), vec3f(s.c1 - s.c0), float(s.r), s.material);
        }
        if (out_.moving_spheres.count > 0)
            for (size_t k = 0; k < pad; ++k) out_.moving_spheres.append({}, {}, 0, 0, /*padding=*/true);
        out_.has_motion = out_.has_motion || out_.moving_spheres.count > 0;

        for (uint32_t i : out_.bvh.order[size_t(shape_kind::instance)]) push_instance(instances_[i]);
        // An object's emitters are not light-sampled (compiled_scene::objects), nor moving ones:
        // a path that hits one counts it in full.
        if (root_ == this) find_lights();
    }

  private:
    struct sphere_input {
        vec3 c; // relative to the scene origin, in double
        double r;
        uint32_t material;
    };
    struct moving_sphere_input {
        vec3 c0, c1; // the centre at times 0 and 1, relative to the scene origin
        double r;
        uint32_t material;
    };
    struct instance_input {
        uint32_t object; // in out_.objects
        affine_map map;  // object frame -> world
    };
    // What the compiler made of a subtree it instances: its object (none when everything in it
    // was itself instanced), and the instances inside it, which are placed beside it in the
    // scene (an object holds no instances: two levels, one walk each).
    struct object_record {
        uint32_t object = UINT32_MAX;
        std::vector<std::pair<const hittable*, affine_map>> inner; // subtree, map into this object's frame
    };
    // Subtrees of more primitives than this, named more than once, are instanced; smaller ones
    // are copied (six quads of a box cost less than the walk into an instance).
    static constexpr size_t flatten_limit = 16;

    // An object's compiler: its shapes go to `object`, its materials to the scene's table.
    scene_compiler(compiled_scene& object, scene_compiler& root) : out_(object), root_(&root) {}

    static double max_abs(const vec3& v) { return fmax_inline(std::fabs(v.x()), fmax_inline(std::fabs(v.y()), std::fabs(v.z()))); }

    static bool is_transform(const std::type_info& type) {
        return type == typeid(translate) || type == typeid(rotate_y) || type == typeid(transform) ||
               type == typeid(rotate) || type == typeid(scale);
    }
    // The object under a transform node, or null for anything else.
    static const hittable* transformed_child(const hittable& object) {
        const std::type_info& type = typeid(object);
        if (type == typeid(translate)) return static_cast<const translate&>(object).object().get();
        if (type == typeid(rotate_y)) return static_cast<const rotate_y&>(object).object().get();
        if (type == typeid(transform) || type == typeid(rotate) || type == typeid(scale))
            return static_cast<const transform&>(object).object().get();
        return nullptr;
    }
    // A transform node's map, checked.
    static affine_map transform_map(const hittable& object) {
        const std::type_info& type = typeid(object);
        if (type == typeid(translate)) {
            const auto& tr = static_cast<const translate&>(object);
            if (!finite3(tr.offset())) throw scene_error("translate offset must be finite, got " + point_text(tr.offset()));
            return affine_map::translation(tr.offset());
        }
        if (type == typeid(rotate_y)) {
            const auto& ro = static_cast<const rotate_y&>(object);
            if (!(std::isfinite(ro.sin_theta()) && std::isfinite(ro.cos_theta())))
                throw scene_error("rotate_y angle must be finite, got " + std::to_string(ro.angle()));
            return affine_map::rotation_y(ro.sin_theta(), ro.cos_theta());
        }
        const auto& tf = static_cast<const transform&>(object);
        const mat3& m = tf.linear();
        const mat3 inverse = m.inverse();
        for (int i = 0; i < 3; ++i)
            if (!finite3(m.row(i)) || !finite3(inverse.row(i)) || m.determinant() == 0)
                throw scene_error(std::string(type == typeid(rotate) ? "rotate axis must be non-zero and its angle finite"
                                              : type == typeid(scale) ? "scale factors must be finite and non-zero"
                                                                      : "transform matrix must be finite and invertible") +
                                  ", got rows " + point_text(m.row(0)) + " " + point_text(m.row(1)) + " " +
                                  point_text(m.row(2)));
        if (!finite3(tf.offset())) throw scene_error("transform offset must be finite, got " + point_text(tf.offset()));
        return affine_map::linear(m, tf.offset());
    }

    // Calls f(child) for every object a list, book 2's tree or a transform node names.
    template <class F>
    static void for_each_child(const hittable& object, F&& f) {
        const std::type_info& type = typeid(object);
        if (type == typeid(hittable_list)) {
            for (const auto& child : static_cast<const hittable_list&>(object).objects)
                if (child) f(*child);
        } else if (type == typeid(bvh_node)) {
            const auto& node = static_cast<const bvh_node&>(object);
            if (node.left()) f(*node.left());
            if (node.right() && node.right() != node.left()) f(*node.right());
        } else if (const hittable* child = transformed_child(object)) {
            f(*child);
        }
    }
    // Shapes in the subtree, through every node.
    static size_t primitive_count(const hittable& object) {
        const std::type_info& type = typeid(object);
        if (type == typeid(triangle_mesh)) return static_cast<const triangle_mesh&>(object).faces.size();
        if (type == typeid(hittable_list) || type == typeid(bvh_node) || is_transform(type)) {
            size_t n = 0;
            for_each_child(object, [&](const hittable& child) { n += primitive_count(child); });
            return n;
        }
        return 1;
    }
    // Whether a sphere is reached through lists alone (one under a further transform is decided
    // when that transform is reached).
    static bool holds_spheres(const hittable& object) {
        const std::type_info& type = typeid(object);
        if (type == typeid(sphere)) return true;
        if (type != typeid(hittable_list) && type != typeid(bvh_node)) return false;
        bool found = false;
        for_each_child(object, [&](const hittable& child) { found = found || holds_spheres(child); });
        return found;
    }

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

    // The subtree `child` under the map m (object frame -> this compiler's frame).
    void place(const hittable& child, const affine_map& m) {
        if (!must_instance(child, m)) return add(child, m);
        if (root_ != this) { // inside an object: the instance goes beside it (object_record)
            lifted_.push_back({&child, m});
            return;
        }
        const object_record record = object_of(child);
        if (record.object != UINT32_MAX) instances_.push_back({record.object, m});
        for (const auto& [inner, n] : record.inner) place(*inner, m.then(n));
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

    // The box, in the scene's frame, around instance i's object: its eight corners mapped, and
    // padded by a few ulps of their magnitude for the float maps the walk uses.
    box3f instance_bounds(const instance_input& in) const {
        const box3f& b = out_.objects[in.object]->bounds;
        vec3 lo(infinity, infinity, infinity), hi(-infinity, -infinity, -infinity);
        for (float x : {b.lo.x, b.hi.x})
            for (float y : {b.lo.y, b.hi.y})
                for (float z : {b.lo.z, b.hi.z}) {
                    const vec3 corner = in.map.point(vec3(x, y, z)) - out_.origin;
                    for (int c = 0; c < 3; ++c) lo[c] = fmin_inline(lo[c], corner[c]), hi[c] = fmax_inline(hi[c], corner[c]);
                }
        if (!(max_abs(lo) < max_float_extent && max_abs(hi) < max_float_extent))
            throw scene_error("an instance is out of single-precision range: it must be within 1e18 of the camera");
        const double pad = std::ldexp(fmax_inline(max_abs(lo), max_abs(hi)), -20);
        box3f out;
        out.lo = {down(lo.x() - pad), down(lo.y() - pad), down(lo.z() - pad)};
        out.hi = {up(hi.x() + pad), up(hi.y() + pad), up(hi.z() + pad)};
        return out;
    }

    // The maps of an instance in float: object frame -> scene (relative to its origin), and back.
    void push_instance(const instance_input& in) {
        const mat3& a = in.map.m;
        const vec3 b = in.map.t - out_.origin;
        const mat3 inv = a.inverse();
        const vec3 c = -(inv * b);
        affine3f to_world, to_object;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                to_world.m[i][j] = static_cast<float>(a(i, j));
                to_object.m[i][j] = static_cast<float>(inv(i, j));
            }
        to_world.t = vec3f(b);
        to_object.t = vec3f(c);
        out_.instances.append(to_world, to_object, in.object);
    }
    struct quad_input {
        vec3 q, u, v; // corner relative to the scene origin, and edges, in double
        uint32_t material;
    };
    struct triangle_input {
        std::array<vec3f, 3> v;
        uint32_t material;
        std::array<vec3f, 3> n{}; // shading normals at the vertices (smooth meshes), else zero
        bool smooth = false;
        std::array<std::array<float, 2>, 3> uv{}; // texture coordinates at the vertices, else zero
    };

    static float down(double x) { return std::nextafter(static_cast<float>(x), -std::numeric_limits<float>::infinity()); }
    static float up(double x) { return std::nextafter(static_cast<float>(x), std::numeric_limits<float>::infinity()); }

    uint32_t material_index(const material* m) {
        if (root_ != this) return root_->material_index(m); // one table for the scene and its objects
        auto found = index_.find(m);
        if (found != index_.end()) return found->second;
        compiled_material d = compile_material(*m, &out_.textures);
        if (d.kind == material_kind::user) out_.has_user_materials = true;
        auto index = static_cast<uint32_t>(out_.materials.size());
        out_.materials.push_back(d);
        index_.emplace(m, index);
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
        if (d.kind == material_kind::dielectric || d.kind == material_kind::fresnel_dielectric) {
            if (d.absorbs_inside()) {
                refusal = "absorbing glass";
            } else {
                d.refraction_index = 1.0f / d.refraction_index;
                index = static_cast<uint32_t>(out_.materials.size());
                out_.materials.push_back(d);
            }
        } else if (d.kind == material_kind::user && typeid(*m) != typeid(isotropic)) { // a phase function has no faces
            refusal = "a material of the program's own";
        } else if (d.emits() && !d.two_sided) {
            refusal = "a one-sided diffuse_light";
        }
        if (refusal)
            throw scene_error(std::string("a sphere with a negative radius (inside out) cannot have ") + refusal +
                              ": give it a positive radius");
        inside_out_index_.emplace(m, index);
        return index;
    }

    void add_sphere(const sphere& s, const affine_map& xf) {
        if (!finite3(s.center()) || !finite3(s.center(1)))
            throw scene_error("sphere centre must be finite, got " + point_text(s.center()) +
                              (s.is_moving() ? " moving to " + point_text(s.center(1)) : std::string()));
        if (!(std::isfinite(s.radius()) && s.radius() != 0))
            throw scene_error("sphere radius must be finite and not zero, got " + std::to_string(s.radius()));
        if (!s.mat()) throw scene_error("sphere at " + point_text(s.center()) + " has no material");
        // A negative radius is the books' v3 hollow glass: the sphere of radius |r|, inside out.
        const bool inside_out = s.radius() < 0;
        const uint32_t material = inside_out ? inside_out_material_index(s.mat().get()) : material_index(s.mat().get());
        const double radius = std::fabs(s.radius()) * xf.sphere_scale(); // must_instance saw to it that the map keeps it round
        const vec3 c = xf.point(s.center()) - out_.origin, c1 = xf.point(s.center(1)) - out_.origin;
        if (!(fmax_inline(max_abs(c), max_abs(c1)) + radius < max_float_extent))
            throw scene_error("sphere at " + point_text(s.center()) + " with radius " + std::to_string(s.radius()) +
                              " is out of single-precision range: its distance from the camera plus its radius must "
                              "be below 1e18");
        if (s.is_moving()) {
            moving_spheres_.push_back({c, c1, radius, material});
            return;
        }
        spheres_.push_back({c, radius, material});
    }

    // False when the triangle has zero area in float (it could never be hit).
    bool add_triangle(const point3& a, const point3& b, const point3& c, uint32_t material) {
        for (const point3* p : {&a, &b, &c}) {
            if (!finite3(*p)) throw scene_error("triangle vertex must be finite, got " + point_text(*p));
            vec3 q = *p - out_.origin;
            if (!(fmax_inline(std::fabs(q.x()), fmax_inline(std::fabs(q.y()), std::fabs(q.z()))) < max_float_extent))
                throw scene_error("triangle vertex " + point_text(*p) +
                                  " is out of single-precision range: it must be within 1e18 of the camera");
        }
        // Relative to the origin in double, then rounded once: a vertex shared by two triangles
        // gets the same float coordinates in both.
        triangle_input t{{vec3f(a - out_.origin), vec3f(b - out_.origin), vec3f(c - out_.origin)}, material};
        vec3 e1 = t.v[1].to_double() - t.v[0].to_double(), e2 = t.v[2].to_double() - t.v[0].to_double();
        if (cross(e1, e2).length_squared() == 0) return false;
        triangles_.push_back(t);
        return true;
    }

    // A user-written hittable goes into the BVH when its bounding box is usable: non-empty, finite
    // and within float's range of the origin. Otherwise (a book-1 class has only the default box,
    // all of space) it is tested against every ray. (Not inlined: inlined into a caller whose
    // world is a hittable_list, GCC 12 speculates `shape` is that list and warns about the
    // devirtualised call it made up.)
#if defined(__GNUC__)
    __attribute__((noinline))
#endif
    void add_user_shape(const hittable& shape) {
        const aabb box = shape.bounding_box();
        double lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = box.axis_interval(a).min - out_.origin[a];
            hi[a] = box.axis_interval(a).max - out_.origin[a];
            if (!(lo[a] <= hi[a] && std::fabs(lo[a]) < max_float_extent && std::fabs(hi[a]) < max_float_extent)) {
                out_.unbounded_user_shapes.push_back(&shape);
                return;
            }
        }
        box3f b; // rounded outwards: the float box must hold the double one
        b.lo = {down(lo[0]), down(lo[1]), down(lo[2])};
        b.hi = {up(hi[0]), up(hi[1]), up(hi[2])};
        user_shapes_.push_back({&shape, b});
    }

    void add_quad(const quad& q, const affine_map& xf) {
        if (!finite3(q.corner()) || !finite3(q.edge_u()) || !finite3(q.edge_v()))
            throw scene_error("quad corner and edges must be finite, got " + point_text(q.corner()) + " " +
                              point_text(q.edge_u()) + " " + point_text(q.edge_v()));
        if (!q.mat()) throw scene_error("quad at " + point_text(q.corner()) + " has no material");
        const vec3 corner = xf.point(q.corner()) - out_.origin, u = xf.vector(q.edge_u()), v = xf.vector(q.edge_v());
        for (const vec3& p : {corner, corner + u, corner + v, corner + u + v})
            if (!(fmax_inline(std::fabs(p.x()), fmax_inline(std::fabs(p.y()), std::fabs(p.z()))) < max_float_extent))
                throw scene_error("quad at " + point_text(q.corner()) +
                                  " is out of single-precision range: it must be within 1e18 of the camera");
        // Zero area in float: no ray could hit it, and its dual vectors would be infinite.
        if (length_squared(cross(vec3f(u), vec3f(v))) == 0)
            throw scene_error("quad at " + point_text(q.corner()) + " with edges " + point_text(q.edge_u()) + " " +
                              point_text(q.edge_v()) + " has zero area");
        quads_.push_back({corner, u, v, material_index(q.mat().get())});
    }

    void push_quad(const quad_input& q) {
        const vec3 n = cross(q.u, q.v);
        const vec3 w = n / dot(n, n);
        out_.quads.append(vec3f(q.q), vec3f(q.u), vec3f(q.v), vec3f(n), vec3f(cross(q.v, w)), vec3f(cross(w, q.u)),
                          q.material);
    }

    // Records every built-in shape whose material emits as a light, in the sets' final order.
    void find_lights() {
        light_set& lights = out_.lights;
        auto emission = [&](uint32_t m) -> const compiled_material& { return out_.materials[m]; };
        auto record = [&](shape_kind kind, size_t count, const std::vector<uint32_t>& material, auto make) {
            std::vector<uint32_t>& table = lights.of_shape[size_t(kind)];
            // A triangle the BVH split by a plane through it is laid out once for each leaf that
            // holds a part of it (bvh.h, spatial splits): one light, which all its copies name.
            const std::vector<uint32_t>& order = out_.bvh.order[size_t(kind)];
            std::unordered_map<uint32_t, uint32_t> light_of_shape;
            for (size_t i = 0; i < count; ++i) {
                const compiled_material& m = emission(material[i]);
                if (!m.emits()) continue;
                if (table.empty()) table.assign(count, light_set::none);
                const auto light_index = uint32_t(lights.lights.size());
                const auto [known, is_new] = light_of_shape.try_emplace(order[i], light_index);
                if (!is_new) {
                    table[i] = known->second;
                    continue;
                }
                light l = make(uint32_t(i));
                l.emission = m.emission; // a textured light: its texture's mean (material_compiler.h)
                l.two_sided = m.two_sided;
                l.texture = m.texture;
                l.shape = uint32_t(i);
                table[i] = lights.add(l);
            }
        };
        const sphere_set& sp = out_.spheres;
        record(shape_kind::sphere, sp.count, sp.material, [&](uint32_t i) {
            light l;
            l.kind = light_kind::sphere;
            l.p0 = {sp.x[i], sp.y[i], sp.z[i]};
            l.radius = sp.r[i];
            return l;
        });
        const quad_set& qs = out_.quads;
        record(shape_kind::quad, qs.count, qs.material, [&](uint32_t i) {
            light l;
            l.kind = light_kind::quad;
            l.p0 = qs.corner(i);
            l.p1 = qs.edge_u(i);
            l.p2 = qs.edge_v(i);
            return l;
        });
        const triangle_set& ts = out_.triangles;
        record(shape_kind::triangle, ts.count, ts.material, [&](uint32_t i) {
            light l;
            l.kind = light_kind::triangle;
            auto vertex = [&](int k) {
                return vec3f(ts.vertex[size_t(3 * k)][i], ts.vertex[size_t(3 * k + 1)][i], ts.vertex[size_t(3 * k + 2)][i]);
            };
            l.p0 = vertex(0);
            l.p1 = vertex(1);
            l.p2 = vertex(2);
            return l;
        });
    }

    void add_mesh(const triangle_mesh& mesh, const affine_map& xf) {
        if (!mesh.mat) throw scene_error("triangle mesh has no material");
        uint32_t m = material_index(mesh.mat.get());
        for (size_t i = 0; i < mesh.faces.size(); ++i) {
            const auto& f = mesh.faces[i];
            for (uint32_t v : f)
                if (v >= mesh.positions.size())
                    throw scene_error("triangle mesh face " + std::to_string(i) + " uses vertex " + std::to_string(v) +
                                      " of " + std::to_string(mesh.positions.size()));
            if (!add_triangle(xf.point(mesh.positions[f[0]]), xf.point(mesh.positions[f[1]]),
                              xf.point(mesh.positions[f[2]]), m)) {
                ++out_.triangles.degenerate;
                continue;
            }
            if (mesh.smooth_shading && i < mesh.face_normals.size()) set_vertex_normals(mesh, i, xf);
            if (i < mesh.face_uvs.size()) set_vertex_uvs(mesh, i);
        }
    }

    // A textured mesh's triangle takes its corners' (u, v); a corner without one gets (0, 0).
    void set_vertex_uvs(const triangle_mesh& mesh, size_t face) {
        triangle_input& t = triangles_.back();
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t index = mesh.face_uvs[face][k];
            if (index >= mesh.uvs.size()) continue;
            for (size_t c = 0; c < 2; ++c) {
                const double x = mesh.uvs[index][c];
                if (!std::isfinite(x)) throw scene_error("triangle mesh texture coordinate " + std::to_string(index) + " is not finite");
                t.uv[k][c] = static_cast<float>(x);
            }
        }
        any_uv_ = true;
    }

    // A smooth mesh's triangle takes its corners' normals; a corner without a usable normal gets
    // the face normal.
    void set_vertex_normals(const triangle_mesh& mesh, size_t face, const affine_map& xf) {
        triangle_input& t = triangles_.back();
        vec3f face_normal = vec3f(unit_vector(cross(t.v[1].to_double() - t.v[0].to_double(),
                                                    t.v[2].to_double() - t.v[0].to_double())));
        for (size_t k = 0; k < 3; ++k) {
            uint32_t index = mesh.face_normals[face][k];
            vec3 n = index < mesh.normals.size() ? xf.normal(mesh.normals[index]) : vec3(0, 0, 0);
            double len = n.length();
            t.n[k] = finite3(n) && len > 0 ? vec3f(n / len) : face_normal;
        }
        t.smooth = true;
        any_smooth_ = true;
    }

    void push_sphere(const sphere_input& s) { out_.spheres.append(vec3f(s.c), static_cast<float>(s.r), s.material); }

    void push_triangle(const triangle_input& t) {
        out_.triangles.append(t.v, t.material);
        if (any_uv_) out_.triangles.append_uv(t.uv);
        if (!any_smooth_) return;
        std::array<vec3f, 3> n = t.n;
        if (!t.smooth) {
            vec3 e1 = t.v[1].to_double() - t.v[0].to_double(), e2 = t.v[2].to_double() - t.v[0].to_double();
            vec3 c = cross(e1, e2);
            vec3f face = c.length_squared() > 0 ? vec3f(unit_vector(c)) : vec3f(0, 0, 1); // padding: never hit
            n = {face, face, face};
        }
        out_.triangles.append_normals(n);
    }

    compiled_scene& out_;
    std::unordered_map<const material*, uint32_t> index_;
    std::unordered_map<const material*, uint32_t> inside_out_index_; // inside_out_material_index's
    std::vector<sphere_input> spheres_;
    std::vector<triangle_input> triangles_;
    std::vector<quad_input> quads_;
    struct user_shape_input {
        const hittable* shape;
        box3f bounds; // relative to the origin
    };
    std::vector<user_shape_input> user_shapes_;
    std::vector<moving_sphere_input> moving_spheres_;
    std::vector<instance_input> instances_;
    scene_compiler* root_; // the scene's compiler (this one, or the one whose object this compiles)
    std::unordered_map<const hittable*, uint32_t> uses_;         // root only: see count_uses
    std::unordered_map<const hittable*, object_record> objects_; // root only: see object_of
    std::vector<std::pair<const hittable*, affine_map>> lifted_; // an object's: instances inside it
    bool any_smooth_ = false;
    bool any_uv_ = false; // some mesh has texture coordinates: the triangle set stores them all
};

} // namespace detail

inline compiled_scene compile_scene(const hittable& world, const point3& origin,
                                    const std::vector<point_light>& point_lights) {
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
        light l;
        l.kind = light_kind::point;
        l.p0 = vec3f(p.position - origin);
        l.emission = vec3f(p.intensity);
        scene.lights.add(l);
    }
    scene.lights.finish();
    return scene;
}

inline compiled_scene compile_scene(const hittable& world, const point3& origin) {
    return compile_scene(world, origin, {});
}

inline compiled_material compile_reported_material(const hit_record& rec) {
    if (!rec.mat) throw scene_error("a user-written hittable reported a hit without a material");
    return compile_material(*rec.mat);
}

} // namespace rt
