#pragma once
// Loop subdivision of triangle meshes, and the OBJ reading and writing the subdivide tool needs.
//
//   loop_subdivide(mesh, levels)   `levels` rounds of Loop subdivision (4x the triangles each)
//   loop_beta(n)                   the weight of each neighbour of an interior vertex of valence n
//   count_edges(mesh)              distinct undirected edges (checks the mesh like loop_subdivide)
//   read_obj(path)                 positions and triangles of an OBJ file (rt::load_obj)
//   to_triangle_mesh(mesh, m)      the renderer's triangle_mesh of it, every face of material m
//   encode_obj(mesh) / write_obj(path, mesh)   "v" and "f" lines; write_obj is atomic
//
// The rules (C. Loop, "Smooth Subdivision Surfaces Based on Triangles", M.S. thesis, University
// of Utah, 1987; the boundary rules as in Hoppe et al., "Piecewise Smooth Surface
// Reconstruction", SIGGRAPH 1994):
//   - new vertex on an interior edge ab with opposite vertices c, d: 3/8 (a + b) + 1/8 (c + d);
//     on a boundary edge (one triangle): 1/2 (a + b);
//   - old interior vertex v with n neighbours p_i: (1 - n beta) v + beta sum p_i, with Loop's own
//     beta(n) = (1/n) (5/8 - (3/8 + 1/4 cos(2 pi / n))^2) (not Warren's simplification
//     3/(8n); the two agree only for n = 3 and n = 6);
//   - old boundary vertex v with boundary neighbours b1, b2: 3/4 v + 1/8 (b1 + b2);
//   - a vertex no triangle uses keeps its position (so V' = V + E still holds).
// Each triangle (v0, v1, v2) with edge vertices m0 on v0v1, m1 on v1v2, m2 on v2v0 becomes
// (v0, m0, m2), (m0, v1, m1), (m2, m1, v2), (m0, m1, m2): orientation is kept. Old vertices keep
// their indices; edge vertex e gets index V + e, edges numbered in increasing (min, max) order of
// their end points, so the output is deterministic.
//
// Topology is the index topology as given: vertices are NOT welded by position. An OBJ file that
// repeats a position under two indices (a UV seam, say) has a boundary there, and the two sides
// are subdivided as boundaries and may pull apart. Weld such files first if that is not wanted.
//
// Refused with rt::scene_error (vertex numbers counted from 1, as in OBJ): an index out of range,
// a triangle that repeats a vertex, an edge shared by more than two triangles (non-manifold
// edge), a vertex on more than two boundary edges (two fans touching at a vertex: the boundary
// rule has no single pair of neighbours), non-finite positions. A vertex where two closed fans
// touch (all its edges interior) is accepted and treated as one vertex of valence n, the sum of
// both fans' neighbours. Zero-area triangles with three distinct indices are fine.

#include <rtweekend/core/file.h>
#include <rtweekend/io/obj.h>
#include <rtweekend/mesh.h>
#include <rtweekend/core/scene_error.h>
#include <rtweekend/vec3.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>


namespace app {

struct tri_mesh {
    std::vector<rt::vec3> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
};

// Loop's weight for each of the n neighbours of an interior vertex (see the header comment).
inline double loop_beta(int n) {
    double c = 3.0 / 8.0 + 0.25 * std::cos(2.0 * rt::pi / n);
    return (5.0 / 8.0 - c * c) / n;
}

namespace detail {

// The undirected edges of a mesh: edge e joins ends[e][0] < ends[e][1]; opposite[e] are the
// third vertices of its triangles (one for a boundary edge); edge_of_corner[3 f + k] is the edge
// from corner k to corner k + 1 of triangle f.
struct edge_table {
    std::vector<std::array<uint32_t, 2>> ends;
    std::vector<std::array<uint32_t, 2>> opposite;
    std::vector<uint8_t> face_count;
    std::vector<uint32_t> edge_of_corner;
};

inline std::string vertex_name(uint32_t v) { return std::to_string(uint64_t(v) + 1); }

inline void check_mesh(const tri_mesh& m) {
    const size_t nv = m.positions.size();
    if (nv > std::numeric_limits<uint32_t>::max())
        throw rt::scene_error("too many vertices (" + std::to_string(nv) + ") for 32-bit indices");
    for (size_t i = 0; i < nv; ++i) {
        const rt::vec3& p = m.positions[i];
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
            throw rt::scene_error("vertex " + vertex_name(uint32_t(i)) + " has a non-finite coordinate");
    }
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        const auto& t = m.triangles[f];
        for (uint32_t v : t)
            if (v >= nv)
                throw rt::scene_error("triangle " + std::to_string(f + 1) + " uses vertex " + vertex_name(v) +
                                      " but there are only " + std::to_string(nv) + " vertices");
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
            throw rt::scene_error("triangle " + std::to_string(f + 1) + " (vertices " + vertex_name(t[0]) + ", " +
                                  vertex_name(t[1]) + ", " + vertex_name(t[2]) + ") repeats a vertex");
    }
}

inline edge_table build_edges(const tri_mesh& m) {
    check_mesh(m);
    const size_t corners = 3 * m.triangles.size();
    if (corners > std::numeric_limits<uint32_t>::max())
        throw rt::scene_error("too many triangles (" + std::to_string(m.triangles.size()) + ") for 32-bit indices");

    // Sorting (edge key, corner) pairs groups the corners of each edge together and numbers the
    // edges deterministically, without a hash table.
    struct corner_edge {
        uint64_t key;
        uint32_t corner;
    };
    std::vector<corner_edge> list(corners);
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        for (int k = 0; k < 3; ++k) {
            uint32_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
            if (a > b) std::swap(a, b);
            list[3 * f + k] = {(uint64_t(a) << 32) | b, uint32_t(3 * f + k)};
        }
    }
    std::sort(list.begin(), list.end(), [](const corner_edge& x, const corner_edge& y) {
        return x.key != y.key ? x.key < y.key : x.corner < y.corner;
    });

    edge_table e;
    e.edge_of_corner.resize(corners);
    for (size_t i = 0; i < list.size();) {
        size_t j = i + 1;
        while (j < list.size() && list[j].key == list[i].key) ++j;
        const uint32_t a = uint32_t(list[i].key >> 32), b = uint32_t(list[i].key & 0xffffffffu);
        if (j - i > 2)
            throw rt::scene_error("non-manifold edge between vertices " + vertex_name(a) + " and " + vertex_name(b) +
                                  ": " + std::to_string(j - i) + " triangles share it (at most 2 may)");
        const uint32_t id = uint32_t(e.ends.size());
        std::array<uint32_t, 2> opp{};
        for (size_t s = i; s < j; ++s) {
            const uint32_t c = list[s].corner;
            e.edge_of_corner[c] = id;
            opp[s - i] = m.triangles[c / 3][(c % 3 + 2) % 3];
        }
        e.ends.push_back({a, b});
        e.opposite.push_back(opp);
        e.face_count.push_back(uint8_t(j - i));
        i = j;
    }
    return e;
}

inline tri_mesh subdivide_once(const tri_mesh& m) {
    const edge_table e = build_edges(m);
    const size_t nv = m.positions.size(), ne = e.ends.size();
    if (nv + ne > std::numeric_limits<uint32_t>::max() || 4 * m.triangles.size() > std::numeric_limits<uint32_t>::max())
        throw rt::scene_error("the subdivided mesh would be too large for 32-bit indices");

    // Neighbour sums over all edges (interior rule) and over boundary edges (boundary rule).
    std::vector<rt::vec3> sum(nv), boundary_sum(nv);
    std::vector<uint32_t> valence(nv, 0), boundary_valence(nv, 0);
    for (size_t i = 0; i < ne; ++i) {
        const uint32_t a = e.ends[i][0], b = e.ends[i][1];
        sum[a] += m.positions[b];
        sum[b] += m.positions[a];
        ++valence[a];
        ++valence[b];
        if (e.face_count[i] == 1) {
            boundary_sum[a] += m.positions[b];
            boundary_sum[b] += m.positions[a];
            ++boundary_valence[a];
            ++boundary_valence[b];
        }
    }

    tri_mesh out;
    out.positions.resize(nv + ne);
    for (size_t v = 0; v < nv; ++v) {
        const rt::vec3& p = m.positions[v];
        if (boundary_valence[v] == 0) {
            if (valence[v] == 0) {
                out.positions[v] = p;
            } else {
                const int n = int(valence[v]);
                const double beta = loop_beta(n);
                out.positions[v] = (1 - n * beta) * p + beta * sum[v];
            }
        } else if (boundary_valence[v] == 2) {
            out.positions[v] = 0.75 * p + 0.125 * boundary_sum[v];
        } else {
            throw rt::scene_error("non-manifold vertex " + vertex_name(uint32_t(v)) + ": it lies on " +
                                  std::to_string(boundary_valence[v]) + " boundary edges (2 expected)");
        }
    }
    for (size_t i = 0; i < ne; ++i) {
        const rt::vec3& a = m.positions[e.ends[i][0]];
        const rt::vec3& b = m.positions[e.ends[i][1]];
        out.positions[nv + i] = e.face_count[i] == 2
                                    ? 0.375 * (a + b) + 0.125 * (m.positions[e.opposite[i][0]] + m.positions[e.opposite[i][1]])
                                    : 0.5 * (a + b);
    }

    out.triangles.resize(4 * m.triangles.size());
    for (size_t f = 0; f < m.triangles.size(); ++f) {
        const auto& t = m.triangles[f];
        const uint32_t m0 = uint32_t(nv + e.edge_of_corner[3 * f + 0]);
        const uint32_t m1 = uint32_t(nv + e.edge_of_corner[3 * f + 1]);
        const uint32_t m2 = uint32_t(nv + e.edge_of_corner[3 * f + 2]);
        out.triangles[4 * f + 0] = {t[0], m0, m2};
        out.triangles[4 * f + 1] = {m0, t[1], m1};
        out.triangles[4 * f + 2] = {m2, m1, t[2]};
        out.triangles[4 * f + 3] = {m0, m1, m2};
    }
    return out;
}

} // namespace detail

inline size_t count_edges(const tri_mesh& m) { return detail::build_edges(m).ends.size(); }

inline tri_mesh loop_subdivide(const tri_mesh& mesh, int levels) {
    if (levels < 0) throw rt::scene_error("subdivision levels must be >= 0, got " + std::to_string(levels));
    detail::check_mesh(mesh);
    tri_mesh current = mesh;
    for (int level = 0; level < levels; ++level) current = detail::subdivide_once(current);
    return current;
}

// --- OBJ files -------------------------------------------------------------------------------------

// The positions and triangles of an OBJ file, read by rt::load_obj (mesh.h: polygons fanned into
// triangles, damaged lines reported with the file and line); normals, texture coordinates and
// materials are dropped. All vertices of the file are kept, used or not.
inline tri_mesh read_obj(const std::string& path) {
    std::shared_ptr<rt::triangle_mesh> mesh = rt::load_obj(path, nullptr);
    return {std::move(mesh->positions), std::move(mesh->faces)};
}

// The other way: the mesh as a shape the renderer takes, every face of `material`.
inline std::shared_ptr<rt::triangle_mesh> to_triangle_mesh(const tri_mesh& m, std::shared_ptr<rt::material> material) {
    std::vector<rt::point3> positions(m.positions.begin(), m.positions.end());
    return std::make_shared<rt::triangle_mesh>(std::move(positions), m.triangles, std::move(material));
}

// "v x y z" lines (each coordinate rounded to float, written in the shortest form that reads back
// to the same float) and "f a b c" lines (1-based), after an optional comment line.
inline std::string encode_obj(const tri_mesh& m, const std::string& comment = "") {
    std::string out;
    out.reserve(m.positions.size() * 40 + m.triangles.size() * 24 + comment.size() + 4);
    if (!comment.empty()) out += "# " + comment + "\n";
    char buf[64];
    for (const rt::vec3& p : m.positions) {
        out += 'v';
        for (int k = 0; k < 3; ++k) {
            out += ' ';
            auto r = std::to_chars(buf, buf + sizeof buf, static_cast<float>(p[k]));
            out.append(buf, r.ptr);
        }
        out += '\n';
    }
    for (const auto& t : m.triangles) {
        out += 'f';
        for (uint32_t v : t) {
            out += ' ';
            auto r = std::to_chars(buf, buf + sizeof buf, uint64_t(v) + 1);
            out.append(buf, r.ptr);
        }
        out += '\n';
    }
    return out;
}

inline void write_obj(const std::string& path, const tri_mesh& m, const std::string& comment = "") {
    rt::write_file_atomically(path, encode_obj(m, comment));
}

} // namespace app
