#pragma once
// triangle_mesh: many triangles sharing vertices and one material. io/obj.h (load_obj) and
// io/ply.h (load_ply) read one from a file.
//
//   auto bunny = load_obj("bunny.obj", make_shared<lambertian>(color(0.8, 0.8, 0.8)));
//   world.add(bunny);
//
// The renderer copies the triangles into its BVH with everything else (scene/scene_compiler.h), so a mesh of a
// million triangles renders about as fast as one of a thousand. The virtual hit() below tests
// every triangle in turn: it is there for code that calls world.hit() itself, and is slow for
// big meshes.

#include "color.h"
#include "hittable.h"
#include "triangle.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace rt {

class triangle_mesh : public hittable {
  public:
    static constexpr uint32_t no_index = 0xFFFFFFFFu;

    std::vector<point3> positions;
    std::vector<vec3> normals;                   // may be empty
    std::vector<std::array<double, 2>> uvs;      // texture coordinates (u, v); may be empty
    // Optional, one per entry of uvs: the direction of increasing u (dp/du) a file gives with its
    // texture coordinates (glTF's TANGENT). A smooth mesh with a normal map takes its frames from
    // these instead of working dp/du out from the coordinates; the bitangent still turns with
    // the coordinates (render: scene/surface_coordinates.h).
    std::vector<vec3> tangents;
    // Optional, one per position: colours the renderer multiplies into the surface's colour at
    // each point, weighted barycentrically (glTF's COLOR_0), leaving emitters as they are. Only
    // the renderer's compiled scene applies them; hit() below does not.
    std::vector<color> colors;
    std::vector<std::array<uint32_t, 3>> faces;  // three indices into positions per triangle
    // Per corner, indices into normals and uvs (no_index where the file gave none); either
    // vector is empty when the mesh has no such data at all.
    std::vector<std::array<uint32_t, 3>> face_normals, face_uvs;
    std::shared_ptr<material> mat;
    // Shade with the normals interpolated across each triangle (barycentrically) instead of the
    // flat geometric normal. Needs normals and face_normals (from the file, or
    // compute_vertex_normals()). Both renderers use them; the path tracer's rule for where they
    // disagree with the triangles is in render/vertex_material.h.
    bool smooth_shading = false;

    // Gives every vertex the area-weighted mean of its faces' normals (each face's cross product,
    // whose length is twice its area), replacing any normals the mesh had, and turns smooth
    // shading on. A vertex whose faces cancel out keeps no normal: its corners fall back to the
    // face normal when rendered.
    void compute_vertex_normals() {
        normals.assign(positions.size(), vec3(0, 0, 0));
        for (const auto& f : faces) {
            if (f[0] >= positions.size() || f[1] >= positions.size() || f[2] >= positions.size()) continue;
            const vec3 n = cross(positions[f[1]] - positions[f[0]], positions[f[2]] - positions[f[0]]);
            for (uint32_t v : f) normals[v] += n;
        }
        for (vec3& n : normals) {
            const double len = n.length();
            n = len > 0 ? n / len : vec3(0, 0, 0);
        }
        face_normals = faces;
        smooth_shading = true;
    }

    triangle_mesh() = default;
    triangle_mesh(std::vector<point3> positions, std::vector<std::array<uint32_t, 3>> faces,
                  std::shared_ptr<material> mat)
        : positions(std::move(positions)), faces(std::move(faces)), mat(std::move(mat)) {}

    size_t triangle_count() const { return faces.size(); }

    // The box around the vertices its faces use (empty when there are none).
    aabb bounding_box() const override {
        interval span[3];
        for (const auto& f : faces)
            for (uint32_t v : f)
                if (v < positions.size())
                    for (int a = 0; a < 3; ++a) span[a] = interval(span[a], interval(positions[v][a], positions[v][a]));
        return aabb(span[0], span[1], span[2]);
    }

    bool hit(const ray& r, interval ray_t, hit_record& rec) const override {
        bool found = false;
        for (const auto& f : faces) {
            const point3 &a = positions[f[0]], &b = positions[f[1]], &c = positions[f[2]];
            double t, bary[3];
            if (!intersect_triangle(r.origin(), r.direction(), a, b, c, ray_t.min, ray_t.max, t, bary)) continue;
            found = true;
            ray_t.max = t;
            rec.t = t;
            rec.p = bary[0] * a + bary[1] * b + bary[2] * c;
            rec.set_face_normal(r, unit_vector(cross(b - a, c - a)));
            rec.mat = mat;
            set_uv(size_t(&f - faces.data()), bary, rec);
        }
        return found;
    }
  private:
    // The hit's texture coordinates: the corners' uv weighted barycentrically; 0 without uv.
    void set_uv(size_t face, const double bary[3], hit_record& rec) const {
        rec.u = rec.v = 0;
        if (face >= face_uvs.size()) return;
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t i = face_uvs[face][k];
            if (i >= uvs.size()) continue;
            rec.u += bary[k] * uvs[i][0];
            rec.v += bary[k] * uvs[i][1];
        }
    }
};

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::triangle_mesh;
#endif
