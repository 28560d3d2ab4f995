#pragma once
// load_obj(path, material): a triangle_mesh from a Wavefront OBJ file.
//
//   auto bunny = load_obj("bunny.obj", make_shared<lambertian>(color(0.8, 0.8, 0.8)));
//   world.add(bunny);
//
// OBJ files are read with tinyobjloader (Debian's libtinyobjloader-dev), which the rtweekend CMake
// target links. Polygons are split into triangle fans. Positions, normals and texture
// coordinates are kept; materials named in the file (mtllib/usemtl) are ignored: the mesh gets
// the material it is given.

#include "../mesh.h"
#include "../scene_error.h"
#include "file.h"
#include "text_lines.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_obj_loader.h>

namespace rt {

class material;

// Reads an OBJ file. Throws scene_error naming the file (and the line, where there is one) for a
// missing or unreadable file, a number that is not a finite number, a face with fewer than three
// corners or an index out of range, or a file without faces.
std::shared_ptr<triangle_mesh> load_obj(const std::string& path, std::shared_ptr<material> mat);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

inline std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    return line;
}

// tinyobjloader reads what it can and silently turns a malformed number into 0, so the lines
// that matter are checked first: every coordinate of v, vn and vt is a finite number, and every
// face has at least three corners whose vertex indices (1-based, or negative = relative) exist.
// Throws scene_error "path:LINE: problem".
inline void check_obj_text(const std::string& text, const std::string& path) {
    size_t vertices = 0;
    text_lines lines(text);
    for (std::string_view text_line; lines.next(text_line);) {
        std::istringstream line{std::string(text_line)};
        auto fail = [&](const std::string& what) {
            throw scene_error(path + ":" + std::to_string(lines.number()) + ": malformed OBJ file: " + what);
        };
        std::string keyword;
        if (!(line >> keyword)) continue;
        if (keyword == "v" || keyword == "vn" || keyword == "vt") {
            size_t needed = keyword == "vt" ? 1 : 3, count = 0;
            for (std::string word; line >> word; ++count) {
                char* stop = nullptr;
                double x = std::strtod(word.c_str(), &stop);
                if (stop == word.c_str() || *stop != '\0' || !std::isfinite(x))
                    fail("'" + word + "' in a '" + keyword + "' line is not a finite number");
            }
            if (count < needed) fail("a '" + keyword + "' line needs " + std::to_string(needed) + " numbers");
            if (keyword == "v") ++vertices;
        } else if (keyword == "f") {
            size_t corners = 0;
            for (std::string word; line >> word; ++corners) {
                char* stop = nullptr;
                long index = std::strtol(word.c_str(), &stop, 10);
                if (stop == word.c_str() || (*stop != '\0' && *stop != '/'))
                    fail("face corner '" + word + "' does not start with a vertex index");
                long resolved = index > 0 ? index : long(vertices) + index + 1; // negative: relative
                if (index == 0 || resolved < 1 || resolved > long(vertices))
                    fail("vertex index " + std::to_string(index) + " is out of range (" + std::to_string(vertices) +
                         " vertices so far)");
            }
            if (corners < 3) fail("a face has " + std::to_string(corners) + " corners (at least 3 needed)");
        }
    }
}

} // namespace detail

inline std::shared_ptr<triangle_mesh> load_obj(const std::string& path, std::shared_ptr<material> mat) {
    const std::string text = read_file(path, "OBJ file");
    detail::check_obj_text(text, path);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // From the text already read; material libraries are not needed (see the top of the file).
    if (!reader.ParseFromString(text, "", config)) {
        std::string why = detail::first_line(reader.Error());
        throw scene_error(path + ": malformed OBJ file" + (why.empty() ? "" : ": " + why));
    }

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    auto mesh = std::make_shared<triangle_mesh>();
    mesh->mat = std::move(mat);
    auto finite = [](const std::vector<tinyobj::real_t>& v) {
        for (auto x : v)
            if (!std::isfinite(x)) return false;
        return true;
    };
    if (!finite(attrib.vertices) || !finite(attrib.normals) || !finite(attrib.texcoords))
        throw scene_error(path + ": malformed OBJ file: a coordinate is not a finite number");
    for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        mesh->positions.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
    for (size_t i = 0; i + 2 < attrib.normals.size(); i += 3)
        mesh->normals.emplace_back(attrib.normals[i], attrib.normals[i + 1], attrib.normals[i + 2]);
    for (size_t i = 0; i + 1 < attrib.texcoords.size(); i += 2)
        mesh->uvs.push_back({double(attrib.texcoords[i]), double(attrib.texcoords[i + 1])});

    // Indices, checked against the arrays they index (tinyobjloader leaves that to the caller).
    auto checked = [&](int index, size_t size, const char* what) -> uint32_t {
        if (index < 0) return triangle_mesh::no_index;
        if (size_t(index) >= size)
            throw scene_error(path + ": malformed OBJ file: " + what + " index " + std::to_string(index + 1) +
                              " is out of range (the file has " + std::to_string(size) + ")");
        return uint32_t(index);
    };
    bool any_normals = false, any_uvs = false;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        size_t offset = 0;
        for (unsigned char corners : shape.mesh.num_face_vertices) {
            if (corners != 3) // triangulation failed: fewer than three corners
                throw scene_error(path + ": malformed OBJ file: a face in '" + shape.name + "' has " +
                                  std::to_string(corners) + " vertices");
            std::array<uint32_t, 3> f, fn, ft;
            for (int k = 0; k < 3; ++k) {
                const tinyobj::index_t& idx = shape.mesh.indices[offset + size_t(k)];
                if (idx.vertex_index < 0) throw scene_error(path + ": malformed OBJ file: a face has no vertex index");
                f[size_t(k)] = checked(idx.vertex_index, mesh->positions.size(), "vertex");
                fn[size_t(k)] = checked(idx.normal_index, mesh->normals.size(), "normal");
                ft[size_t(k)] = checked(idx.texcoord_index, mesh->uvs.size(), "texture coordinate");
                any_normals |= fn[size_t(k)] != triangle_mesh::no_index;
                any_uvs |= ft[size_t(k)] != triangle_mesh::no_index;
            }
            offset += 3;
            mesh->faces.push_back(f);
            mesh->face_normals.push_back(fn);
            mesh->face_uvs.push_back(ft);
        }
    }
    if (mesh->faces.empty()) throw scene_error(path + ": OBJ file has no faces");
    if (!any_normals) mesh->face_normals.clear();
    if (!any_uvs) mesh->face_uvs.clear();
    return mesh;
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::load_obj;
#endif
