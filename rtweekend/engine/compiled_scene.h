#pragma once
// The compiled scene: what the renderer actually traces.
//
//   compiled_scene compile_scene(const hittable& world, const point3& origin);
//   scene.intersect(ray, hit)   the closest hit        scene.occluded(ray)   any hit at all
//
// compile_scene walks the world once, before rendering. Built-in spheres and triangles (single
// ones and whole meshes) go into flat float arrays, one array per coordinate, in the order of
// the leaves of a BVH built over all of them (bvh.h), so a leaf's primitives are tested several
// per SIMD instruction; built-in materials go into a tagged table; anything else (a user's own
// hittable or material subclass) is kept by pointer and called through its virtual functions.
// Positions are stored relative to `origin` (the camera), computed in double before rounding to
// float, so a scene far from the world origin renders as precisely as one near it; shared mesh
// vertices round identically, so meshes stay watertight.
//
// A scene pays only for what it has: the traversal is compiled separately for spheres only,
// triangles only, and both, and a scene of a handful of primitives has no BVH nodes at all.
//
// Invalid input (NaN or infinite coordinates, non-positive radii, negative colours, NaN fuzz or
// refraction index, a primitive without a material, mesh indices out of range) throws
// scene_error at compile time. Triangles of zero area can never be hit: they are left out and
// counted.

#include "bsdf.h"
#include "bvh.h"
#include "../hittable.h"
#include "../hittable_list.h"
#include "../material.h"
#include "../mesh.h"
#include "../scene_error.h"
#include "simd.h"
#include "../sphere.h"
#include "../triangle.h"
#include "vec3f.h"

#include <array>
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
    vec3f shading_normal;  // unit normal to shade with, on the same side: the geometric normal,
                           // or a smooth mesh's interpolated vertex normals
    bool front_face = true;
    float offset = 0;      // extra push off the surface for spawned rays (primitive's own error)
    uint32_t material = 0; // index into compiled_scene::materials
    // Set when a user-written hittable was hit: its record, in world coordinates.
    const hittable* custom_object = nullptr;
    hit_record custom_record;
};

class compiled_scene {
  public:
    vec3 origin;                          // world position that float coordinates are relative to
    std::vector<material_desc> materials;

    // Spheres, in BVH leaf order.
    size_t sphere_count = 0;
    std::vector<float> sphere_x, sphere_y, sphere_z, sphere_r2, sphere_r, sphere_offset;
    std::vector<uint32_t> sphere_material;

    // Triangles, in BVH leaf order: coordinate `axis` of vertex `v` of triangle i is
    // triangle_vertex[3 * v + axis][i].
    size_t triangle_count = 0;
    size_t degenerate_triangles = 0; // of zero area, left out
    std::array<std::vector<float>, 9> triangle_vertex;
    std::vector<uint32_t> triangle_material;
    // Vertex normals, laid out like triangle_vertex, for meshes with smooth_shading; empty when
    // no mesh has it (flat triangles then repeat their face normal).
    std::array<std::vector<float>, 9> triangle_normal;

    // Back-face culling (set_back_face_culling): per primitive, in leaf order, 1 where a hit on
    // the back face is skipped, 0 where it is kept; empty while culling is not set up.
    std::vector<float> triangle_cull, sphere_cull;

    bvh8 bvh; // over the spheres and triangles

    // User-written hittables, rendered through their virtual hit(). Owned by the world.
    std::vector<const hittable*> custom_objects;

    bool has_custom_materials = false;

    // The closest hit with t in (ray.tmin, ray.tmax); false when the ray escapes.
    bool intersect(const ray3f& r, surface_hit& hit) const;
    // The same, skipping back faces of the primitives set_back_face_culling marked (a sphere's
    // back face is the exit point of a ray that starts inside it).
    bool intersect_culling_back_faces(const ray3f& r, surface_hit& hit) const;
    // Marks the primitives whose back faces intersect_culling_back_faces skips: those whose
    // material index `cullable` accepts (opaque ones: a glass object's back face must be found).
    template <class Predicate>
    void set_back_face_culling(Predicate cullable);
    // Whether anything at all is hit with t in (ray.tmin, ray.tmax): for shadow rays.
    bool occluded(const ray3f& r) const;

    // The material entry for a material pointer met during rendering (user shapes only).
    material_desc describe_material(const material* m) const;

    // Bytes held for tracing: primitive arrays and BVH nodes.
    size_t geometry_bytes() const;

  private:
    struct hit_ref {
        primitive_type type = primitive_type::sphere;
        uint32_t index = UINT32_MAX;
    };
    template <bool Spheres, bool Triangles, bool AnyHit, bool Cull = false>
    bool trace(const ray3f& r, float& tmax, hit_ref& best) const;
    bool trace_any_feature(const ray3f& r, float& tmax, hit_ref& best, bool any_hit) const;
    // The same for closest hits with back faces culled: apart, so that only code that culls
    // compiles these traversals.
    bool trace_culling_back_faces(const ray3f& r, float& tmax, hit_ref& best) const;
    void fill_hit(const ray3f& r, float t, const hit_ref& best, surface_hit& hit) const;
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
    // The renderer multiplies in float: a colour beyond float's range would become infinite.
    if (!is_finite(vec3f(c))) throw scene_error(std::string(what) + " is too large for single precision, got " + describe(c));
}

// The float intersection tests square coordinates (relative to the camera) and radii, so they
// must stay well inside float's range (squares up to 3.4e38).
inline constexpr double max_float_extent = 1e18;

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
        if (g->exact_fresnel()) {
            check_color(g->absorption(), "dielectric absorption");
            d.kind = material_kind::exact_dielectric;
            d.absorption = vec3f(g->absorption());
        }
    } else if (type == typeid(conductor)) {
        auto* c = static_cast<const conductor*>(m);
        check_color(c->tint(), "conductor tint");
        check_color(c->n(), "conductor n");
        check_color(c->k(), "conductor k");
        if (!(c->n().x() > 0 && c->n().y() > 0 && c->n().z() > 0))
            throw scene_error("conductor n must be positive, got " + describe(c->n()));
        d.kind = material_kind::conductor;
        d.albedo = vec3f(c->tint());
        d.eta = vec3f(c->n());
        d.k = vec3f(c->k());
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
        } else if (type == typeid(triangle)) {
            const auto& t = static_cast<const triangle&>(object);
            if (!t.mat()) throw scene_error("triangle at " + describe(t.a()) + " has no material");
            uint32_t m = material_index(t.mat().get());
            if (!add_triangle(t.a(), t.b(), t.c(), m))
                throw scene_error("triangle " + describe(t.a()) + " " + describe(t.b()) + " " + describe(t.c()) +
                                  " has zero area");
        } else if (type == typeid(triangle_mesh)) {
            add_mesh(static_cast<const triangle_mesh&>(object));
        } else {
            out_.custom_objects.push_back(&object);
        }
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
            prims.push_back({b, primitive_type::sphere, uint32_t(i)});
        }
        for (size_t i = 0; i < triangles_.size(); ++i) {
            box3f b;
            for (const vec3f& v : triangles_[i].v) b.grow(v);
            prims.push_back({b, primitive_type::triangle, uint32_t(i)});
        }
        out_.bvh = build_bvh8(prims);

        // Leaf loads read floatv::width lanes from any leaf start: pad every array that far.
        const size_t pad = floatv::width;
        const auto& sphere_order = out_.bvh.order[size_t(primitive_type::sphere)];
        out_.sphere_count = sphere_order.size();
        for (uint32_t i : sphere_order) push_sphere(spheres_[i]);
        for (size_t k = 0; k < pad; ++k) push_sphere({vec3(0, 0, 0), 0, 0}, /*never_hit=*/true);

        const auto& triangle_order = out_.bvh.order[size_t(primitive_type::triangle)];
        out_.triangle_count = triangle_order.size();
        for (uint32_t i : triangle_order) push_triangle(triangles_[i]);
        if (out_.triangle_count > 0)
            for (size_t k = 0; k < pad; ++k) push_triangle({{vec3f(), vec3f(), vec3f()}, 0});
    }

  private:
    struct sphere_input {
        vec3 c; // relative to the scene origin, in double
        double r;
        uint32_t material;
    };
    struct triangle_input {
        std::array<vec3f, 3> v;
        uint32_t material;
        std::array<vec3f, 3> n{}; // shading normals at the vertices (smooth meshes), else zero
        bool smooth = false;
    };

    static float down(double x) { return std::nextafter(static_cast<float>(x), -std::numeric_limits<float>::infinity()); }
    static float up(double x) { return std::nextafter(static_cast<float>(x), std::numeric_limits<float>::infinity()); }

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
        vec3 c = s.center() - out_.origin;
        if (!(std::fmax(std::fabs(c.x()), std::fmax(std::fabs(c.y()), std::fabs(c.z()))) + s.radius() < max_float_extent))
            throw scene_error("sphere at " + describe(s.center()) + " with radius " + std::to_string(s.radius()) +
                              " is out of single-precision range: its distance from the camera plus its radius must "
                              "be below 1e18");
        spheres_.push_back({c, s.radius(), material_index(s.mat().get())});
    }

    // False when the triangle has zero area in float (it could never be hit).
    bool add_triangle(const point3& a, const point3& b, const point3& c, uint32_t material) {
        for (const point3* p : {&a, &b, &c}) {
            if (!finite3(*p)) throw scene_error("triangle vertex must be finite, got " + describe(*p));
            vec3 q = *p - out_.origin;
            if (!(std::fmax(std::fabs(q.x()), std::fmax(std::fabs(q.y()), std::fabs(q.z()))) < max_float_extent))
                throw scene_error("triangle vertex " + describe(*p) +
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

    void add_mesh(const triangle_mesh& mesh) {
        if (!mesh.mat) throw scene_error("triangle mesh has no material");
        uint32_t m = material_index(mesh.mat.get());
        for (size_t i = 0; i < mesh.faces.size(); ++i) {
            const auto& f = mesh.faces[i];
            for (uint32_t v : f)
                if (v >= mesh.positions.size())
                    throw scene_error("triangle mesh face " + std::to_string(i) + " uses vertex " + std::to_string(v) +
                                      " of " + std::to_string(mesh.positions.size()));
            if (!add_triangle(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]], m)) {
                ++out_.degenerate_triangles;
                continue;
            }
            if (mesh.smooth_shading && i < mesh.face_normals.size()) set_vertex_normals(mesh, i);
        }
    }

    // A smooth mesh's triangle takes its corners' normals; a corner without a usable normal gets
    // the face normal.
    void set_vertex_normals(const triangle_mesh& mesh, size_t face) {
        triangle_input& t = triangles_.back();
        vec3f face_normal = vec3f(unit_vector(cross(t.v[1].to_double() - t.v[0].to_double(),
                                                    t.v[2].to_double() - t.v[0].to_double())));
        for (size_t k = 0; k < 3; ++k) {
            uint32_t index = mesh.face_normals[face][k];
            vec3 n = index < mesh.normals.size() ? mesh.normals[index] : vec3(0, 0, 0);
            double len = n.length();
            t.n[k] = finite3(n) && len > 0 ? vec3f(n / len) : face_normal;
        }
        t.smooth = true;
        any_smooth_ = true;
    }

    void push_sphere(const sphere_input& s, bool never_hit = false) {
        vec3f cf(s.c);
        auto r = static_cast<float>(s.r);
        out_.sphere_x.push_back(cf.x);
        out_.sphere_y.push_back(cf.y);
        out_.sphere_z.push_back(cf.z);
        out_.sphere_r2.push_back(never_hit ? -1.0f : r * r); // negative squared radius: no ray crosses
        out_.sphere_r.push_back(r);
        // Float evaluation of |o - c|^2 - r^2 is only good to a few ulps of the larger of |c| and
        // r, so a spawned ray must start at least that far off the surface (on top of the
        // hit-point offset) or it may re-hit the sphere it leaves: 2^-21 is about 8 ulps.
        out_.sphere_offset.push_back(std::ldexp(max_abs_component(cf) + r, -21));
        out_.sphere_material.push_back(s.material);
    }

    void push_triangle(const triangle_input& t) {
        for (int v = 0; v < 3; ++v)
            for (int axis = 0; axis < 3; ++axis) out_.triangle_vertex[size_t(3 * v + axis)].push_back(t.v[size_t(v)][axis]);
        out_.triangle_material.push_back(t.material);
        if (!any_smooth_) return;
        std::array<vec3f, 3> n = t.n;
        if (!t.smooth) {
            vec3 e1 = t.v[1].to_double() - t.v[0].to_double(), e2 = t.v[2].to_double() - t.v[0].to_double();
            vec3 c = cross(e1, e2);
            vec3f face = c.length_squared() > 0 ? vec3f(unit_vector(c)) : vec3f(0, 0, 1); // padding: never hit
            n = {face, face, face};
        }
        for (int v = 0; v < 3; ++v)
            for (int axis = 0; axis < 3; ++axis) out_.triangle_normal[size_t(3 * v + axis)].push_back(n[size_t(v)][axis]);
    }

    compiled_scene& out_;
    std::unordered_map<const material*, uint32_t> index_;
    std::vector<sphere_input> spheres_;
    std::vector<triangle_input> triangles_;
    bool any_smooth_ = false;
};

// The ray in the frame of the watertight triangle test (triangle.h), for all of a leaf's lanes.
struct triangle_ray {
    sheared_ray<float> shear;
    float ox = 0, oy = 0, oz = 0; // origin, permuted to (kx, ky, kz)

    triangle_ray() = default;
    explicit triangle_ray(const ray3f& r) : shear(r.dir) {
        ox = r.origin[shear.kx];
        oy = r.origin[shear.ky];
        oz = r.origin[shear.kz];
    }
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

inline size_t compiled_scene::geometry_bytes() const {
    size_t bytes = bvh.stats.bytes();
    bytes += (sphere_x.size() * 6) * sizeof(float) + sphere_material.size() * sizeof(uint32_t);
    for (const auto& v : triangle_vertex) bytes += v.size() * sizeof(float);
    bytes += triangle_material.size() * sizeof(uint32_t);
    for (const auto& n : triangle_normal) bytes += n.size() * sizeof(float);
    bytes += (triangle_cull.size() + sphere_cull.size()) * sizeof(float);
    return bytes;
}

template <bool Spheres, bool Triangles, bool AnyHit, bool Cull>
bool compiled_scene::trace(const ray3f& r, float& tmax, hit_ref& best) const {
    constexpr size_t W = floatv::width;
    const floatv lanes = lane_index();
    const floatv tmin(r.tmin), zero(0.0f);

    // The nearest of the lanes that hit, if nearer than t_best: it becomes the best hit.
    auto take_closest = [&](maskv hits, floatv t, primitive_type type, uint32_t first_lane, float& t_best) {
        alignas(64) float lane_t[W];
        t.store(lane_t);
        for (unsigned mask = bits(hits); mask; mask &= mask - 1) {
            unsigned k = unsigned(__builtin_ctz(mask));
            if (lane_t[k] < t_best) {
                t_best = lane_t[k];
                best = {type, first_lane + k};
            }
        }
    };

    // Spheres: the stable test of sphere.h, W spheres at a time.
    auto sphere_leaf = [&](uint32_t first, uint32_t count, float& t_best) {
        const floatv ox(r.origin.x), oy(r.origin.y), oz(r.origin.z);
        const floatv dx(r.dir.x), dy(r.dir.y), dz(r.dir.z);
        bool found = false;
        for (uint32_t i = first; i < first + count; i += W) {
            floatv ocx = floatv::load(&sphere_x[i]) - ox, ocy = floatv::load(&sphere_y[i]) - oy,
                   ocz = floatv::load(&sphere_z[i]) - oz;
            floatv rr = floatv::load(&sphere_r2[i]);
            floatv h = dx * ocx + dy * ocy + dz * ocz;
            floatv px = ocx - h * dx, py = ocy - h * dy, pz = ocz - h * dz;
            floatv disc = rr - (px * px + py * py + pz * pz);
            maskv crosses = (disc >= zero) & (lanes < floatv(float(first + count - i)));
            if (!any(crosses)) continue;
            floatv c = (ocx * ocx + ocy * ocy + ocz * ocz) - rr;
            floatv s = sqrt(max(disc, zero));
            floatv q = select(h >= zero, h + s, h - s);
            floatv ta = c / q;
            floatv t0 = min(ta, q), t1 = max(ta, q);
            floatv t = select(t0 > tmin, t0, t1);
            // Culled: a ray that starts inside (or past) the sphere only meets its back face.
            if constexpr (Cull) t = select((t0 > tmin) | (floatv::load(&sphere_cull[i]) == zero), t, floatv(-1.0f));
            maskv hits = crosses & (t > tmin) & (t < floatv(t_best));
            if (!any(hits)) continue;
            if (AnyHit) return true;
            take_closest(hits, t, primitive_type::sphere, i, t_best);
            found = true;
        }
        return found;
    };

    // Triangles: the watertight test of triangle.h, W triangles at a time.
    detail::triangle_ray tr;
    if constexpr (Triangles) tr = detail::triangle_ray(r); // a sphere-only scene skips the set-up
    auto triangle_leaf = [&](uint32_t first, uint32_t count, float& t_best) {
        const int kx = tr.shear.kx, ky = tr.shear.ky, kz = tr.shear.kz;
        const floatv sx(tr.shear.sx), sy(tr.shear.sy), sz(tr.shear.sz);
        const floatv ox(tr.ox), oy(tr.oy), oz(tr.oz);
        bool found = false;
        for (uint32_t i = first; i < first + count; i += W) {
            auto coord = [&](int v, int axis) { return floatv::load(&triangle_vertex[size_t(3 * v + axis)][i]); };
            floatv az = coord(0, kz) - oz, bz = coord(1, kz) - oz, cz = coord(2, kz) - oz;
            floatv ax = coord(0, kx) - ox - sx * az, ay = coord(0, ky) - oy - sy * az;
            floatv bx = coord(1, kx) - ox - sx * bz, by = coord(1, ky) - oy - sy * bz;
            floatv cx = coord(2, kx) - ox - sx * cz, cy = coord(2, ky) - oy - sy * cz;
            // Each product rounded on its own (no fused multiply-add): an edge shared by two
            // triangles must give exactly opposite values in both (see rounded() in simd.h).
            floatv u = rounded(cx * by) - rounded(cy * bx), v = rounded(ax * cy) - rounded(ay * cx),
                   w = rounded(bx * ay) - rounded(by * ax);
            maskv valid = lanes < floatv(float(first + count - i));
            maskv on_edge = valid & ((u == zero) | (v == zero) | (w == zero));
            if (any(on_edge)) {
                // The ray passes exactly through an edge or vertex in float: decide in double,
                // as Woop et al. do, so the neighbouring triangles agree.
                alignas(64) float lu[W], lv[W], lw[W];
                u.store(lu);
                v.store(lv);
                w.store(lw);
                const sheared_ray<double> shear(r.dir.to_double());
                const vec3 o = r.origin.to_double();
                for (unsigned mask = bits(on_edge); mask; mask &= mask - 1) {
                    unsigned k = unsigned(__builtin_ctz(mask));
                    auto vertex = [&](int vi) {
                        return vec3(triangle_vertex[size_t(3 * vi)][i + k], triangle_vertex[size_t(3 * vi + 1)][i + k],
                                    triangle_vertex[size_t(3 * vi + 2)][i + k]) - o;
                    };
                    double du, dv, dw;
                    triangle_edge_functions(shear, vertex(0), vertex(1), vertex(2), du, dv, dw);
                    // Only the functions that were exactly zero: a zero edge is zero in the
                    // neighbouring triangle too (the float values are exact negations), so both
                    // redo it, in double; an edge that was not zero keeps its float value, which is
                    // what the neighbour, not redoing it, also has. Redoing all three would pair a
                    // double edge with its neighbour's float one, and lose rays near shared vertices.
                    if (lu[k] == 0) lu[k] = float(du);
                    if (lv[k] == 0) lv[k] = float(dv);
                    if (lw[k] == 0) lw[k] = float(dw);
                }
                u = floatv::load(lu);
                v = floatv::load(lv);
                w = floatv::load(lw);
            }
            maskv inside = ((u >= zero) & (v >= zero) & (w >= zero)) | ((u <= zero) & (v <= zero) & (w <= zero));
            maskv candidates = valid & inside;
            if (!any(candidates)) continue;
            floatv det = u + v + w;
            floatv t = (u * (sz * az) + v * (sz * bz) + w * (sz * cz)) / det; // det = 0: inf or NaN, rejected
            // The determinant is positive exactly when the ray meets the front face (the side the
            // counter-clockwise normal points to): culled triangles keep only those hits.
            if constexpr (Cull) candidates = candidates & ((det * floatv::load(&triangle_cull[i])) >= zero);
            maskv hits = candidates & (t > tmin) & (t < floatv(t_best));
            if (!any(hits)) continue;
            if (AnyHit) return true;
            take_closest(hits, t, primitive_type::triangle, i, t_best);
            found = true;
        }
        return found;
    };

    return traverse<AnyHit>(bvh, r, tmax, [&](uint32_t ref, float& t_best) {
        const uint32_t first = bvh_ref::first(ref), count = bvh_ref::count(ref);
        if constexpr (Spheres && Triangles) {
            return bvh_ref::type(ref) == primitive_type::sphere ? sphere_leaf(first, count, t_best)
                                                               : triangle_leaf(first, count, t_best);
        } else if constexpr (Spheres) {
            return sphere_leaf(first, count, t_best);
        } else {
            return triangle_leaf(first, count, t_best);
        }
    });
}

// Picks the traversal compiled for the primitive kinds this scene has.
inline bool compiled_scene::trace_any_feature(const ray3f& r, float& tmax, hit_ref& best, bool any_hit) const {
    const bool s = sphere_count > 0, t = triangle_count > 0;
    if (any_hit) {
        if (s && t) return trace<true, true, true>(r, tmax, best);
        if (s) return trace<true, false, true>(r, tmax, best);
        if (t) return trace<false, true, true>(r, tmax, best);
    } else {
        if (s && t) return trace<true, true, false>(r, tmax, best);
        if (s) return trace<true, false, false>(r, tmax, best);
        if (t) return trace<false, true, false>(r, tmax, best);
    }
    return false;
}

inline bool compiled_scene::trace_culling_back_faces(const ray3f& r, float& tmax, hit_ref& best) const {
    const bool s = sphere_count > 0, t = triangle_count > 0;
    if (s && t) return trace<true, true, false, true>(r, tmax, best);
    if (s) return trace<true, false, false, true>(r, tmax, best);
    if (t) return trace<false, true, false, true>(r, tmax, best);
    return false;
}

inline void compiled_scene::fill_hit(const ray3f& r, float t, const hit_ref& best, surface_hit& hit) const {
    const uint32_t i = best.index;
    hit.t = t;
    hit.custom_object = nullptr;
    if (best.type == primitive_type::sphere) {
        vec3f center{sphere_x[i], sphere_y[i], sphere_z[i]};
        // Re-project the hit point onto the sphere: removes the error of o + t d along the ray.
        vec3f outward = normalize(r.at(t) - center);
        hit.p = center + sphere_r[i] * outward;
        hit.front_face = dot(r.dir, outward) < 0;
        hit.normal = hit.front_face ? outward : -outward;
        hit.shading_normal = hit.normal;
        hit.offset = sphere_offset[i];
        hit.material = sphere_material[i];
        return;
    }
    // Triangle: the point from its barycentric weights lies on the triangle, unlike o + t d.
    auto vertex = [&](int v) {
        return vec3(triangle_vertex[size_t(3 * v)][i], triangle_vertex[size_t(3 * v + 1)][i],
                    triangle_vertex[size_t(3 * v + 2)][i]);
    };
    const vec3 a = vertex(0), b = vertex(1), c = vertex(2), o = r.origin.to_double();
    double u, v, w;
    triangle_edge_functions(sheared_ray<double>(r.dir.to_double()), a - o, b - o, c - o, u, v, w);
    double det = u + v + w;
    vec3 p = det != 0 ? (u * a + v * b + w * c) / det : r.at(t).to_double();
    vec3f outward = vec3f(unit_vector(cross(b - a, c - a)));
    hit.p = vec3f(p);
    hit.front_face = dot(r.dir, outward) < 0;
    hit.normal = hit.front_face ? outward : -outward;
    hit.shading_normal = hit.normal;
    if (!triangle_normal[0].empty() && det != 0) {
        // Smooth shading: the vertex normals weighted by the barycentric coordinates.
        auto normal = [&](int v) {
            return vec3(triangle_normal[size_t(3 * v)][i], triangle_normal[size_t(3 * v + 1)][i],
                        triangle_normal[size_t(3 * v + 2)][i]);
        };
        vec3 n = (u * normal(0) + v * normal(1) + w * normal(2)) / det;
        double len = n.length();
        if (len > 0) hit.shading_normal = hit.front_face ? vec3f(n / len) : vec3f(-n / len);
    }
    hit.offset = 0; // the barycentric point is within an ulp of the plane; the ray offset suffices
    hit.material = triangle_material[i];
}

inline bool compiled_scene::intersect_culling_back_faces(const ray3f& r, surface_hit& hit) const {
    if (sphere_cull.empty() && triangle_cull.empty()) return intersect(r, hit);
    float t = r.tmax;
    hit_ref best;
    bool found = trace_culling_back_faces(r, t, best);
    if (found) fill_hit(r, t, best, hit);
    hit.custom_object = nullptr;
    return found; // user-written hittables are not culled
}

template <class Predicate>
void compiled_scene::set_back_face_culling(Predicate cullable) {
    auto flags = [&](const std::vector<uint32_t>& materials, size_t count) {
        std::vector<float> f(materials.size(), 0.0f); // the padding lanes never hit anyway
        for (size_t i = 0; i < count; ++i) f[i] = cullable(materials[i]) ? 1.0f : 0.0f;
        return f;
    };
    sphere_cull = flags(sphere_material, sphere_count);
    triangle_cull = flags(triangle_material, triangle_count);
}

inline bool compiled_scene::intersect(const ray3f& r, surface_hit& hit) const {
    hit.custom_object = nullptr;
    float t = r.tmax;
    hit_ref best;
    bool found = trace_any_feature(r, t, best, false);
    if (found) fill_hit(r, t, best, hit);

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
            hit.shading_normal = hit.normal;
            hit.front_face = h.front_face;
            hit.offset = 0;
        }
    }
    return found;
}

inline bool compiled_scene::occluded(const ray3f& r) const {
    float t = r.tmax;
    hit_ref best;
    if (trace_any_feature(r, t, best, true)) return true;
    if (!custom_objects.empty()) {
        ray world_ray(origin + r.origin.to_double(), r.dir.to_double());
        hit_record rec;
        for (const hittable* object : custom_objects)
            if (object->hit(world_ray, interval(r.tmin, r.tmax), rec)) return true;
    }
    return false;
}

} // namespace rt
