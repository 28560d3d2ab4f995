#pragma once
// triangle_set: the shape kind of triangles, single ones and meshes' (scene/shape_kinds.h says
// what a kind answers): one float array per vertex coordinate in BVH leaf order, and the SIMD
// kernel that tests a ray against one leaf of them, floatv::width triangles per instruction.
//
// The test is the watertight one of triangle.h (Woop, Benthin and Wald, JCGT 2013), in float;
// where a ray passes exactly through an edge in float, the edge is decided again in double.

#include "../../core/box3f.h"
#include "../../core/force_inline.h"
#include "../../core/scene_error.h"
#include "../../core/simd.h"
#include "../../core/vec3f.h"
#include "../../material.h"
#include "../../mesh.h"
#include "../../triangle.h"
#include "../../vec3.h"
#include "../affine_map.h"
#include "../leaf_query.h"
#include "../lights/triangle_emitter.h"
#include "../surface_hit.h"
#include "../validate.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rt {

// The ray in the frame of the watertight triangle test, for all of a leaf's lanes: the shear
// that makes it point along +z and its origin permuted to (kx, ky, kz). A query prepares it once,
// at its first triangle leaf.
struct triangle_ray {
    sheared_ray<float> shear;
    float ox = 0, oy = 0, oz = 0;

    triangle_ray() = default;
    explicit triangle_ray(const ray3f& r) : shear(r.dir) {
        ox = r.origin[shear.kx];
        oy = r.origin[shear.ky];
        oz = r.origin[shear.kz];
    }
};

struct triangle_set {
    static constexpr const char* name = "triangle";
    // Whether its shapes move with the ray's time.
    static constexpr bool moves = false;
    // A scene of these alone walks its BVH without asking each leaf its kind (shape_kinds.h).
    static constexpr bool own_walk = true;

    // --- compiling ---------------------------------------------------------------------------
    // A triangle as the compiler collects it: its corners relative to the scene origin, rounded
    // to float once in double (a vertex shared by two triangles gets the same float coordinates
    // in both, so meshes stay watertight).
    struct input {
        std::array<vec3f, 3> v;
        uint32_t material;
        std::array<vec3f, 3> n{};       // shading normals at the vertices (smooth meshes), else zero
        bool smooth = false;
        std::array<std::array<float, 2>, 3> uv{}; // texture coordinates at the vertices, else zero
        bool has_uv = false;
        std::array<vec3f, 3> dpdu{}; // smooth dp/du at the vertices (normal- or bump-mapped smooth meshes)
        bool has_dpdu = false;
        std::array<vec3f, 3> colour{vec3f(1, 1, 1), vec3f(1, 1, 1), vec3f(1, 1, 1)}; // vertex colours, else white
        bool has_colour = false;
    };
    // The book's triangle, and a triangle_mesh (mesh.h) face by face, under the map xf. A single
    // triangle of zero area is an error; a mesh's are left out and counted (degenerate).
    template <class Compiler>
    static void add(Compiler& compiler, const triangle& t, const affine_map& xf);
    template <class Compiler>
    static void add(Compiler& compiler, const triangle_mesh& mesh, const affine_map& xf);
    template <class Scene>
    static box3f bounds(const input& t, const Scene&) {
        box3f b;
        for (const vec3f& v : t.v) b.grow(v);
        return b;
    }
    // The BVH may split a triangle by planes through it (bvh.h, spatial splits): its corners.
    static constexpr bool split_by_planes = true;
    static std::array<vec3f, 3> corners(const input& t) { return t.v; }
    // In the BVH's leaf order (a split triangle once for each leaf holding a part of it), with
    // normals when some triangle is smooth and texture coordinates when some has them.
    template <class Scene>
    void lay_out(const Scene&, const std::vector<input>& inputs, const std::vector<uint32_t>& order);

    // --- the compiled triangles ----------------------------------------------------------------
    size_t count = 0; // triangles; the arrays hold floatv::width more when count > 0 (padding)
    // The scene's triangles: count less the copies of those the BVH split by a plane through
    // them, which are laid out once for each leaf holding a part (bvh.h, spatial splits).
    size_t distinct = 0;
    size_t degenerate = 0; // triangles of zero area the compiler left out (they can never be hit)
    // Coordinate `axis` of vertex v of triangle i is vertex[3 * v + axis][i].
    std::array<std::vector<float>, 9> vertex;
    std::vector<uint32_t> material;
    // Vertex normals, laid out like `vertex`, when some mesh has smooth_shading; else empty (and
    // the geometric normal is used).
    std::array<std::vector<float>, 9> normal;
    // Texture coordinates: coordinate c (0: u, 1: v) of vertex k of triangle i is uv[2 * k + c][i],
    // when some mesh has them; else empty (and every triangle's (u, v) is 0, as in the book).
    std::array<std::vector<float>, 6> uv;
    // Smooth dp/du at the vertices, laid out like `vertex`, when some smooth mesh with texture
    // coordinates has a normal or bump map; else empty. Each vertex's is the area-weighted mean of
    // its faces' dp/du, so that a map's frame turns smoothly across a curved mesh's triangles
    // instead of in steps (surface_tangents). Zero for the triangles that have none.
    std::array<std::vector<float>, 9> dpdu_at;
    // Vertex colours (triangle_mesh::colors), laid out like `vertex`, when some mesh has them;
    // else empty. White for the triangles that have none.
    std::array<std::vector<float>, 9> colour;
    // Back-face culling: 1 where a hit on the back face is skipped; empty until
    // mark_culled.
    std::vector<float> cull;

    void append(const std::array<vec3f, 3>& v, uint32_t material_index) {
        for (int k = 0; k < 3; ++k)
            for (int axis = 0; axis < 3; ++axis) vertex[size_t(3 * k + axis)].push_back(v[size_t(k)][axis]);
        material.push_back(material_index);
    }
    void append_normals(const std::array<vec3f, 3>& n) {
        for (int k = 0; k < 3; ++k)
            for (int axis = 0; axis < 3; ++axis) normal[size_t(3 * k + axis)].push_back(n[size_t(k)][axis]);
    }
    void append_uv(const std::array<std::array<float, 2>, 3>& t) {
        for (size_t k = 0; k < 3; ++k)
            for (size_t c = 0; c < 2; ++c) uv[2 * k + c].push_back(t[k][c]);
    }
    void append_dpdu(const std::array<vec3f, 3>& d) {
        for (int k = 0; k < 3; ++k)
            for (int axis = 0; axis < 3; ++axis) dpdu_at[size_t(3 * k + axis)].push_back(d[size_t(k)][axis]);
    }
    void append_colour(const std::array<vec3f, 3>& c) {
        for (int k = 0; k < 3; ++k)
            for (int axis = 0; axis < 3; ++axis) colour[size_t(3 * k + axis)].push_back(c[size_t(k)][axis]);
    }

    size_t size() const { return count; }
    uint32_t material_of(uint32_t i) const { return material[i]; }

    // What a walk prepares for the kernel on demand: the sheared ray of the watertight test, made
    // at the first triangle leaf the ray reaches.
    struct ray_state {
        std::optional<triangle_ray> sheared;
    };
    // Tests triangles [first, first + n) against the ray: see leaf_query.h.
    template <query Q, shape_kind Self, class Scene>
    bool intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n, float& t_best, hit_ref& best,
                        ray_state& state) const;
    // The hit on triangle i at distance t along the ray.
    template <class Scene>
    void complete_hit(const Scene&, const ray3f& ray, float t, uint32_t i, const ray_state&, surface_hit& hit) const;
    // The texture coordinates at the hit point: the vertices' uv weighted by its barycentric
    // coordinates; 0 when the triangles have none (as the book's shapes without coordinates).
    void surface_coordinates(const surface_hit& hit, double& u, double& v) const;
    // How the point moves with the texture coordinates on triangle i at the point of coordinates
    // (u, v): dp/du and dp/dv, from its corners and their (u, v); dp/du interpolated from the
    // vertices' smooth ones where the triangle has them (dpdu_at). False when the triangles have
    // no coordinates, or triangle i's are degenerate (all on a line).
    bool surface_tangents(uint32_t i, double u, double v, vec3& dpdu, vec3& dpdv) const;
    // The vertex colours of triangle i at point p (relative to the set's origin), weighted by its
    // barycentric coordinates; false when no triangle has colours.
    bool vertex_colour(uint32_t i, const vec3& p, vec3f& c) const;

    // An emitting triangle is light-sampled by area.
    static constexpr bool light_sampled = true;
    triangle_emitter light_of(uint32_t i) const { return {vertex_f(0, i), vertex_f(1, i), vertex_f(2, i)}; }

    // Grows b by the triangles whose material `selected` accepts.
    template <class Scene, class Predicate>
    void bound_where(const Scene&, Predicate selected, box3f& b) const {
        for (uint32_t i = 0; i < count; ++i)
            if (selected(material[i]))
                for (int k = 0; k < 3; ++k) b.grow(vertex_f(k, i));
    }
    template <class Predicate>
    void mark_culled(Predicate cullable) { cull = culling_flags(material, count, cullable); }

    size_t bytes() const {
        size_t b = (material.size()) * sizeof(uint32_t) + cull.size() * sizeof(float);
        for (const auto& v : vertex) b += v.size() * sizeof(float);
        for (const auto& v : normal) b += v.size() * sizeof(float);
        for (const auto& v : uv) b += v.size() * sizeof(float);
        for (const auto& v : dpdu_at) b += v.size() * sizeof(float);
        for (const auto& v : colour) b += v.size() * sizeof(float);
        return b;
    }

  private:
    // The barycentric weights of point p (scene-origin relative) on triangle i; false when it is
    // degenerate.
    bool barycentric(uint32_t i, const vec3& p, double b[3]) const;
    vec3f vertex_f(int v, uint32_t i) const {
        return {vertex[size_t(3 * v)][i], vertex[size_t(3 * v + 1)][i], vertex[size_t(3 * v + 2)][i]};
    }
    vec3 corner(int v, uint32_t i) const {
        return vec3(vertex[size_t(3 * v)][i], vertex[size_t(3 * v + 1)][i], vertex[size_t(3 * v + 2)][i]);
    }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// Appends the triangle (a, b, c) (world points, under the map already) to the compiler's inputs;
// false when it has zero area in float (it could never be hit).
template <class Compiler>
bool add_triangle(Compiler& compiler, const point3& a, const point3& b, const point3& c, uint32_t material) {
    const vec3 origin = compiler.origin();
    for (const point3* p : {&a, &b, &c}) {
        if (!finite3(*p)) throw scene_error("triangle vertex must be finite, got " + point_text(*p));
        if (!(max_abs(*p - origin) < max_float_extent))
            throw scene_error("triangle vertex " + point_text(*p) +
                              " is out of single-precision range: it must be within 1e18 of the camera");
    }
    // Relative to the origin in double, then rounded once: a vertex shared by two triangles
    // gets the same float coordinates in both.
    triangle_set::input t{{vec3f(a - origin), vec3f(b - origin), vec3f(c - origin)}, material};
    vec3 e1 = t.v[1].to_double() - t.v[0].to_double(), e2 = t.v[2].to_double() - t.v[0].to_double();
    if (cross(e1, e2).length_squared() == 0) return false;
    compiler.template inputs<triangle_set>().push_back(t);
    return true;
}

// The smooth dp/du of each texture-coordinate vertex of a smooth mesh with a normal or bump map
// (normal_mapped), under the map xf: the area-weighted mean of the dp/du of the faces that use it
// (triangle_set::dpdu_at). Where the mesh gives its own tangents (triangle_mesh::tangents), a
// vertex takes its tangent's direction under xf at that mean's length (a bump map's slopes scale
// with it). Empty for any other mesh, which keeps each triangle's own.
inline std::vector<vec3> vertex_dpdu(const triangle_mesh& mesh, const affine_map& xf) {
    if (!mesh.smooth_shading || mesh.face_uvs.empty() || mesh.uvs.empty() || !dynamic_cast<const normal_mapped*>(mesh.mat.get()))
        return {};
    std::vector<vec3> sum(mesh.uvs.size(), vec3(0, 0, 0));
    std::vector<double> weight(mesh.uvs.size(), 0.0);
    for (size_t i = 0; i < mesh.faces.size() && i < mesh.face_uvs.size(); ++i) {
        const auto& f = mesh.faces[i];
        const auto& fu = mesh.face_uvs[i];
        if (f[0] >= mesh.positions.size() || f[1] >= mesh.positions.size() || f[2] >= mesh.positions.size() ||
            fu[0] >= mesh.uvs.size() || fu[1] >= mesh.uvs.size() || fu[2] >= mesh.uvs.size())
            continue;
        const point3 p0 = xf.point(mesh.positions[f[0]]);
        const vec3 e1 = xf.point(mesh.positions[f[1]]) - p0, e2 = xf.point(mesh.positions[f[2]]) - p0;
        const double du1 = mesh.uvs[fu[1]][0] - mesh.uvs[fu[0]][0], dv1 = mesh.uvs[fu[1]][1] - mesh.uvs[fu[0]][1];
        const double du2 = mesh.uvs[fu[2]][0] - mesh.uvs[fu[0]][0], dv2 = mesh.uvs[fu[2]][1] - mesh.uvs[fu[0]][1];
        const double det = du1 * dv2 - du2 * dv1;
        if (!(std::fabs(det) > 0)) continue;
        const vec3 d = (dv2 * e1 - dv1 * e2) / det;
        const double area = 0.5 * cross(e1, e2).length();
        if (!finite3(d) || !(area > 0) || !std::isfinite(area)) continue;
        for (uint32_t k : fu) {
            sum[k] += area * d;
            weight[k] += area;
        }
    }
    const bool given = mesh.tangents.size() == mesh.uvs.size();
    for (size_t k = 0; k < sum.size(); ++k) {
        sum[k] = weight[k] > 0 ? sum[k] / weight[k] : vec3(0, 0, 0);
        if (given) {
            const vec3 t = xf.vector(mesh.tangents[k]);
            const double lt = t.length(), ls = sum[k].length();
            if (lt > 0 && std::isfinite(lt)) sum[k] = t * ((ls > 0 ? ls : 1) / lt);
        }
        if (!finite3(sum[k]) || !is_finite(vec3f(sum[k]))) sum[k] = vec3(0, 0, 0);
    }
    return sum;
}

} // namespace detail

template <class Compiler>
void triangle_set::add(Compiler& compiler, const triangle& t, const affine_map& xf) {
    if (!t.mat()) throw scene_error("triangle at " + point_text(t.a()) + " has no material");
    const uint32_t m = compiler.material_index(t.mat().get());
    if (!detail::add_triangle(compiler, xf.point(t.a()), xf.point(t.b()), xf.point(t.c()), m))
        throw scene_error("triangle " + point_text(t.a()) + " " + point_text(t.b()) + " " + point_text(t.c()) +
                          " has zero area");
}

template <class Compiler>
void triangle_set::add(Compiler& compiler, const triangle_mesh& mesh, const affine_map& xf) {
    if (!mesh.mat) throw scene_error("triangle mesh has no material");
    if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size())
        throw scene_error("triangle mesh has " + std::to_string(mesh.colors.size()) + " vertex colours for " +
                          std::to_string(mesh.positions.size()) + " vertices");
    const uint32_t m = mesh.colors.empty() ? compiler.material_index(mesh.mat.get())
                                           : compiler.vertex_coloured_material_index(mesh.mat.get());
    std::vector<input>& inputs = compiler.template inputs<triangle_set>();
    const std::vector<vec3> smooth_dpdu = detail::vertex_dpdu(mesh, xf);
    for (size_t i = 0; i < mesh.faces.size(); ++i) {
        const auto& f = mesh.faces[i];
        for (uint32_t v : f)
            if (v >= mesh.positions.size())
                throw scene_error("triangle mesh face " + std::to_string(i) + " uses vertex " + std::to_string(v) +
                                  " of " + std::to_string(mesh.positions.size()));
        if (!detail::add_triangle(compiler, xf.point(mesh.positions[f[0]]), xf.point(mesh.positions[f[1]]),
                                  xf.point(mesh.positions[f[2]]), m)) {
            ++compiler.template set<triangle_set>().degenerate;
            continue;
        }
        input& t = inputs.back();
        if (mesh.smooth_shading && i < mesh.face_normals.size()) {
            // A smooth mesh's triangle takes its corners' normals; a corner without a usable
            // normal gets the face normal.
            const vec3f face_normal = vec3f(unit_vector(cross(t.v[1].to_double() - t.v[0].to_double(),
                                                              t.v[2].to_double() - t.v[0].to_double())));
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t index = mesh.face_normals[i][k];
                const vec3 n = index < mesh.normals.size() ? xf.normal(mesh.normals[index]) : vec3(0, 0, 0);
                const double len = n.length();
                t.n[k] = finite3(n) && len > 0 ? vec3f(n / len) : face_normal;
            }
            t.smooth = true;
        }
        if (i < mesh.face_uvs.size()) {
            // A textured mesh's triangle takes its corners' (u, v); a corner without one gets (0, 0).
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t index = mesh.face_uvs[i][k];
                if (index >= mesh.uvs.size()) continue;
                for (size_t c = 0; c < 2; ++c) {
                    const double x = mesh.uvs[index][c];
                    if (!std::isfinite(x))
                        throw scene_error("triangle mesh texture coordinate " + std::to_string(index) + " is not finite");
                    t.uv[k][c] = static_cast<float>(x);
                }
            }
            t.has_uv = true;
        }
        if (!smooth_dpdu.empty() && i < mesh.face_uvs.size()) {
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t index = mesh.face_uvs[i][k];
                if (index < smooth_dpdu.size()) t.dpdu[k] = vec3f(smooth_dpdu[index]);
            }
            t.has_dpdu = true;
        }
        if (!mesh.colors.empty()) {
            // A coloured mesh's triangle takes its corners' colours.
            for (size_t k = 0; k < 3; ++k) {
                const uint32_t index = f[k];
                const color& c = mesh.colors[index];
                if (!(finite3(c) && c.x() >= 0 && c.y() >= 0 && c.z() >= 0 && is_finite(vec3f(c))))
                    throw scene_error("triangle mesh vertex colour " + std::to_string(index) + " must be finite and at least 0, got " + point_text(c));
                t.colour[k] = vec3f(c);
            }
            t.has_colour = true;
        }
    }
}

template <class Scene>
void triangle_set::lay_out(const Scene&, const std::vector<input>& inputs, const std::vector<uint32_t>& order) {
    count = order.size();
    distinct = inputs.size();
    bool any_smooth = false, any_uv = false, any_dpdu = false, any_colour = false;
    for (const input& t : inputs)
        any_smooth = any_smooth || t.smooth, any_uv = any_uv || t.has_uv, any_dpdu = any_dpdu || t.has_dpdu,
        any_colour = any_colour || t.has_colour;
    auto push = [&](const input& t) {
        append(t.v, t.material);
        if (any_uv) append_uv(t.uv);
        if (any_dpdu) append_dpdu(t.dpdu);
        if (any_colour) append_colour(t.colour);
        if (!any_smooth) return;
        std::array<vec3f, 3> n = t.n;
        if (!t.smooth) {
            const vec3 e1 = t.v[1].to_double() - t.v[0].to_double(), e2 = t.v[2].to_double() - t.v[0].to_double();
            const vec3 c = cross(e1, e2);
            const vec3f face = c.length_squared() > 0 ? vec3f(unit_vector(c)) : vec3f(0, 0, 1); // padding: never hit
            n = {face, face, face};
        }
        append_normals(n);
    };
    for (uint32_t i : order) push(inputs[i]);
    if (count > 0)
        for (size_t k = 0; k < floatv::width; ++k) push({{vec3f(), vec3f(), vec3f()}, 0});
}

template <query Q, shape_kind Self, class Scene>
RTWEEKEND_FORCE_INLINE bool triangle_set::intersect_leaf(const Scene&, const ray3f& ray, uint32_t first, uint32_t n,
                                                         float& t_best, hit_ref& best, ray_state& state) const {
    if (!state.sheared) state.sheared.emplace(ray); // the ray's first triangle leaf
    const triangle_ray& tr = *state.sheared;
    constexpr size_t W = floatv::width;
    const floatv tmin(ray.tmin), zero(0.0f);
    const int kx = tr.shear.kx, ky = tr.shear.ky, kz = tr.shear.kz;
    const floatv sx(tr.shear.sx), sy(tr.shear.sy), sz(tr.shear.sz);
    const floatv ox(tr.ox), oy(tr.oy), oz(tr.oz);
    bool found = false;
    for (uint32_t i = first; i < first + n; i += W) {
        auto coord = [&](int v, int axis) { return floatv::load(&vertex[size_t(3 * v + axis)][i]); };
        floatv az = coord(0, kz) - oz, bz = coord(1, kz) - oz, cz = coord(2, kz) - oz;
        floatv ax = coord(0, kx) - ox - sx * az, ay = coord(0, ky) - oy - sy * az;
        floatv bx = coord(1, kx) - ox - sx * bz, by = coord(1, ky) - oy - sy * bz;
        floatv cx = coord(2, kx) - ox - sx * cz, cy = coord(2, ky) - oy - sy * cz;
        // Each product rounded on its own (no fused multiply-add): an edge shared by two
        // triangles must give exactly opposite values in both (see rounded() in simd.h).
        floatv u = rounded(cx * by) - rounded(cy * bx), v = rounded(ax * cy) - rounded(ay * cx),
               w = rounded(bx * ay) - rounded(by * ax);
        maskv valid = first_lanes(first + n - i);
        maskv on_edge = valid & ((u == zero) | (v == zero) | (w == zero));
        if (any(on_edge)) {
            // The ray passes exactly through an edge or vertex in float: decide in double, as
            // Woop et al. do, so the neighbouring triangles agree.
            alignas(64) float lu[W], lv[W], lw[W];
            u.store(lu);
            v.store(lv);
            w.store(lw);
            const sheared_ray<double> shear(ray.dir.to_double());
            const vec3 o = ray.origin.to_double();
            for (unsigned mask = bits(on_edge); mask; mask &= mask - 1) {
                unsigned k = unsigned(__builtin_ctz(mask));
                double du, dv, dw;
                triangle_edge_functions(shear, corner(0, i + k) - o, corner(1, i + k) - o, corner(2, i + k) - o, du, dv,
                                        dw);
                // Only the functions that were exactly zero: a zero edge is zero in the
                // neighbouring triangle too (the float values are exact negations), so both redo
                // it, in double; an edge that was not zero keeps its float value, which is what the
                // neighbour, not redoing it, also has. Redoing all three would pair a double edge
                // with its neighbour's float one, and lose rays near shared vertices.
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
        if constexpr (Q == query::closest_culled) candidates = candidates & ((det * floatv::load(&cull[i])) >= zero);
        maskv hits = candidates & within_range<Q>(t, tmin, t_best);
        if (!any(hits)) continue;
        if constexpr (Q == query::any) return true;
        found |= take_closest(hits, t, Self, i, t_best, best);
    }
    return found;
}

template <class Scene>
void triangle_set::complete_hit(const Scene&, const ray3f& ray, float t, uint32_t i, const ray_state&,
                                surface_hit& hit) const {
    // The point from its barycentric weights lies on the triangle, unlike o + t d.
    const vec3 a = corner(0, i), b = corner(1, i), c = corner(2, i), o = ray.origin.to_double();
    double u, v, w;
    triangle_edge_functions(sheared_ray<double>(ray.dir.to_double()), a - o, b - o, c - o, u, v, w);
    double det = u + v + w;
    vec3 p = det != 0 ? (u * a + v * b + w * c) / det : ray.at(t).to_double();
    vec3f outward = vec3f(unit_vector(cross(b - a, c - a)));
    hit.p = vec3f(p);
    hit.set_face_normal(ray.dir, outward);
    if (!normal[0].empty() && det != 0) {
        // Smooth shading: the vertex normals weighted by the barycentric coordinates.
        auto vertex_normal = [&](int k) {
            return vec3(normal[size_t(3 * k)][i], normal[size_t(3 * k + 1)][i], normal[size_t(3 * k + 2)][i]);
        };
        vec3 n = (u * vertex_normal(0) + v * vertex_normal(1) + w * vertex_normal(2)) / det;
        double len = n.length();
        if (len > 0) hit.shading_normal = hit.front_face ? vec3f(n / len) : vec3f(-n / len);
    }
    hit.offset = 0; // the barycentric point is within an ulp of the plane; the ray offset suffices
    hit.material = material[i];
}

inline bool triangle_set::surface_tangents(uint32_t i, double u, double v, vec3& dpdu, vec3& dpdv) const {
    if (uv[0].empty()) return false;
    // p - p0 = (u - u0) dp/du + (v - v0) dp/dv across the triangle: two edges, two equations each.
    const vec3 e1 = corner(1, i) - corner(0, i), e2 = corner(2, i) - corner(0, i);
    const double du1 = double(uv[2][i]) - uv[0][i], dv1 = double(uv[3][i]) - uv[1][i];
    const double du2 = double(uv[4][i]) - uv[0][i], dv2 = double(uv[5][i]) - uv[1][i];
    const double det = du1 * dv2 - du2 * dv1;
    if (!(std::fabs(det) > 0)) return false;
    dpdu = (dv2 * e1 - dv1 * e2) / det;
    dpdv = (du1 * e2 - du2 * e1) / det;
    if (!dpdu_at[0].empty()) {
        // The point's barycentric weights from its (u, v): (u - u0, v - v0) = b1 (du1, dv1) + b2 (du2, dv2).
        const double b1 = ((u - uv[0][i]) * dv2 - (v - uv[1][i]) * du2) / det;
        const double b2 = ((v - uv[1][i]) * du1 - (u - uv[0][i]) * dv1) / det;
        auto at = [&](int k) {
            return vec3(dpdu_at[size_t(3 * k)][i], dpdu_at[size_t(3 * k + 1)][i], dpdu_at[size_t(3 * k + 2)][i]);
        };
        const vec3 smooth = (1 - b1 - b2) * at(0) + b1 * at(1) + b2 * at(2);
        if (smooth.length_squared() > 0 && finite3(smooth)) dpdu = smooth;
    }
    return std::isfinite(dpdu.x() + dpdu.y() + dpdu.z() + dpdv.x() + dpdv.y() + dpdv.z());
}

inline bool triangle_set::barycentric(uint32_t i, const vec3& p, double b[3]) const {
    // By least squares in the triangle's plane (Ericson, Real-Time Collision Detection, 3.4): p is
    // on the plane, up to rounding.
    const vec3 a = corner(0, i), e1 = corner(1, i) - a, e2 = corner(2, i) - a, d = p - a;
    const double d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2), d20 = dot(d, e1), d21 = dot(d, e2);
    const double det = d00 * d11 - d01 * d01;
    if (!(det > 0)) return false;
    b[1] = (d11 * d20 - d01 * d21) / det;
    b[2] = (d00 * d21 - d01 * d20) / det;
    b[0] = 1 - b[1] - b[2];
    return true;
}

inline void triangle_set::surface_coordinates(const surface_hit& hit, double& u, double& v) const {
    u = v = 0;
    const uint32_t i = hit.index;
    double b[3];
    if (uv[0].empty() || !barycentric(i, hit.p.to_double(), b)) return;
    u = b[0] * uv[0][i] + b[1] * uv[2][i] + b[2] * uv[4][i];
    v = b[0] * uv[1][i] + b[1] * uv[3][i] + b[2] * uv[5][i];
}

inline bool triangle_set::vertex_colour(uint32_t i, const vec3& p, vec3f& c) const {
    if (colour[0].empty()) return false;
    double b[3];
    if (!barycentric(i, p, b)) b[0] = b[1] = b[2] = 1.0 / 3;
    vec3 sum(0, 0, 0);
    for (int k = 0; k < 3; ++k)
        sum += std::max(b[k], 0.0) * vec3(colour[size_t(3 * k)][i], colour[size_t(3 * k + 1)][i], colour[size_t(3 * k + 2)][i]);
    const double total = std::max(b[0], 0.0) + std::max(b[1], 0.0) + std::max(b[2], 0.0);
    c = vec3f(total > 0 ? sum / total : sum);
    return true;
}

} // namespace rt
