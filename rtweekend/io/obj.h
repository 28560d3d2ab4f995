#pragma once
// load_obj(path, material): a triangle_mesh from a Wavefront OBJ file.
//
//   auto bunny = load_obj("bunny.obj", make_shared<lambertian>(color(0.8, 0.8, 0.8)));
//   world.add(bunny);
//
// OBJ files are read with tinyobjloader (Debian's libtinyobjloader-dev), which the rtweekend CMake
// target links. Polygons are split into triangle fans. Positions, normals and texture
// coordinates are kept; materials named in the file (mtllib/usemtl) are ignored: the mesh gets
// the material it is given (io/obj_model.h reads a model with its materials).

#include "../core/engine_linkage.h"
#include "../mesh.h"
#include "../core/scene_error.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rt {

class material;

// Reads an OBJ file. Throws scene_error naming the file (and the line, where there is one) for a
// missing or unreadable file, a number that is not a finite number (within float's range), a face
// with fewer than three corners or more than 1024, an index out of range, a NUL byte, or a file
// without faces (detail::check_obj_text lists every check).
RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> load_obj(const std::string& path,
                                                                  std::shared_ptr<material> mat);

// load_obj on a file's text already in memory; `path` names it in messages.
RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> decode_obj(const std::string& text, const std::string& path,
                                                                    std::shared_ptr<material> mat);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/file.h"
#include "../core/input_limits.h"
#include "../core/text_lines.h"
#include <tiny_obj_loader.h>

namespace rt {

namespace detail {

inline std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    return line;
}

// Whether the integer prefix atoi would read from `part` (sign and digits) fits an int: atoi
// is undefined beyond that, and tinyobjloader reads indices, smoothing groups and tag counts
// with it.
inline bool obj_int_prefix_fits(const std::string& part) {
    size_t i = 0;
    if (i < part.size() && (part[i] == '+' || part[i] == '-')) ++i;
    uint64_t v = 0;
    for (; i < part.size() && part[i] >= '0' && part[i] <= '9'; ++i) {
        v = v * 10 + uint64_t(part[i] - '0');
        if (v > uint64_t(INT_MAX)) return false;
    }
    return true;
}

// Whether `word` is a number, whole, that a float holds: tinyobjloader parses in double and
// converts to float, which is undefined beyond float's range.
inline bool obj_float_fits(const std::string& word) {
    char* stop = nullptr;
    double x = std::strtod(word.c_str(), &stop);
    return stop != word.c_str() && stop == word.c_str() + word.size() && std::fabs(x) <= double(FLT_MAX);
}

// Whether tinyobjloader reads the number at the start of `word` without overflowing: it adds up
// the mantissa's digits in a double and the exponent's in an int, then scales by pow(5, exponent),
// so 400 digits make an infinite mantissa, e500 an infinite power (0e500 is NaN), and ten exponent
// digits overflow the int. At most 64 digits before the exponent and an exponent of at most 300
// keep every step finite (a value beyond float's range is refused by the range checks).
inline bool obj_number_tame(const std::string& word) {
    size_t i = 0, digits = 0;
    if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
    for (; i < word.size() && ((word[i] >= '0' && word[i] <= '9') || word[i] == '.'); ++i) digits += word[i] != '.';
    if (digits > 64) return false;
    if (i >= word.size() || (word[i] != 'e' && word[i] != 'E')) return true;
    ++i;
    if (i < word.size() && (word[i] == '+' || word[i] == '-')) ++i;
    int exponent = 0, exponent_digits = 0;
    for (; i < word.size() && word[i] >= '0' && word[i] <= '9'; ++i, ++exponent_digits)
        if (exponent_digits < 4) exponent = exponent * 10 + (word[i] - '0');
    return exponent_digits <= 3 && exponent <= 300;
}

// Calls f(line, number) for each line of an OBJ or MTL file's text as tinyobjloader splits them
// (at "\n", "\r\n" or a lone "\r"), `line` a stream of its words, numbers from 1; after refusing a
// NUL byte anywhere (a text format holds none): "path:LINE: malformed <kind> file: a NUL byte".
template <class F>
void for_each_obj_line(const std::string& text, const std::string& path, const char* kind, F&& f) {
    if (size_t nul = text.find('\0'); nul != std::string::npos)
        throw scene_error(path + ":" + std::to_string(line_index(text).line_of(nul)) + ": malformed " + kind +
                          " file: a NUL byte (is this a binary or damaged file?)");
    size_t next = 0, number = 0;
    while (next < text.size()) {
        const size_t end = std::min(text.find_first_of("\r\n", next), text.size());
        std::istringstream line{text.substr(next, end - next)};
        next = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
        f(line, ++number);
    }
}

// tinyobjloader reads what it can and silently turns a malformed number into 0, converts numbers
// with undefined behaviour when they are out of range, and splits a polygon into triangles in
// time quadratic in its corners; so the lines that matter are checked first, split as
// tinyobjloader splits them (a lone carriage return ends a line too). Throws scene_error
// "path:LINE: problem" for:
//   - a NUL byte anywhere (a text format holds none);
//   - a coordinate of v, vn or vt that is not a number, whole, within float's range;
//   - a number on a v, vn, vt, s, t or vw line that tinyobjloader would overflow on
//     (obj_number_tame: more than 64 digits, or an exponent above 300);
//   - a face (f) with fewer than three corners or more than max_obj_face_corners (1024), and any
//     index of f, l or p (vertex, texture coordinate or normal: "v/vt/vn", 1-based, or negative
//     = relative) that is 0, does not exist (so far in the file), or is beyond an int;
//   - a number on an s, t or vw line that is beyond an int (on a vw line, once rounded to a float).
inline void check_obj_text(const std::string& text, const std::string& path) {
    size_t counts[3] = {0, 0, 0}; // v, vt, vn lines so far
    const char* count_names[3] = {"vertex", "texture coordinate", "normal"};
    const char* plural_names[3] = {"vertices", "texture coordinates", "normals"};
    for_each_obj_line(text, path, "OBJ", [&](std::istringstream& line, size_t number) {
        auto fail = [&](const std::string& what) {
            throw scene_error(path + ":" + std::to_string(number) + ": malformed OBJ file: " + what);
        };
        std::string keyword;
        if (!(line >> keyword)) return;
        if (keyword == "v" || keyword == "vn" || keyword == "vt") {
            size_t needed = keyword == "vt" ? 1 : 3, count = 0;
            for (std::string word; line >> word; ++count) {
                if (!obj_float_fits(word))
                    fail("'" + token_text(word) + "' in a '" + keyword + "' line is not a finite number within float's range");
                if (!obj_number_tame(word))
                    fail("'" + token_text(word) + "' in a '" + keyword + "' line has more digits than a number needs (at most 64, " +
                         "and an exponent of at most 300)");
            }
            if (count < needed) fail("a '" + keyword + "' line needs " + std::to_string(needed) + " numbers");
            ++counts[keyword == "v" ? 0 : keyword == "vt" ? 1 : 2];
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
            size_t corners = 0;
            for (std::string word; line >> word; ++corners) {
                if (keyword == "f" && corners == max_obj_face_corners)
                    fail("a face has more than " + std::to_string(max_obj_face_corners) +
                         " corners, the limit (split it into smaller polygons)");
                // v, v/vt, v//vn or v/vt/vn: each index present is checked against its own list.
                size_t start = 0;
                for (int part = 0; part < 3 && start <= word.size(); ++part) {
                    size_t slash = std::min(word.find('/', start), word.size());
                    const std::string index_text = word.substr(start, slash - start);
                    start = slash + 1;
                    if (index_text.empty() && part > 0) continue; // "v//vn": no texture coordinate
                    char* stop = nullptr;
                    errno = 0;
                    long long index = std::strtoll(index_text.c_str(), &stop, 10);
                    if (stop == index_text.c_str() || stop != index_text.c_str() + index_text.size())
                        fail("face corner '" + word + "' has '" + index_text + "', not an index");
                    const long long n = (long long)counts[part];
                    const long long resolved = index > 0 ? index : n + index + 1; // negative: relative
                    if (errno == ERANGE || index > INT_MAX || index < -INT_MAX || index == 0 || resolved < 1 ||
                        resolved > n)
                        fail(std::string(count_names[part]) + " index " + index_text + " is out of range (" +
                             std::to_string(n) + " " + (n == 1 ? count_names[part] : plural_names[part]) + " so far)");
                }
            }
            if (keyword == "f" && corners < 3)
                fail("a face has " + std::to_string(corners) + " corners (at least 3 needed)");
        } else if (keyword == "s" || keyword == "t" || keyword == "vw") {
            // tinyobjloader reads these with atoi (group ids, tag counts, joint ids) or as floats.
            for (std::string word; line >> word;)
                for (size_t start = 0; start <= word.size();) {
                    size_t slash = std::min(word.find('/', start), word.size());
                    const std::string part = word.substr(start, slash - start);
                    start = slash + 1;
                    char* stop = nullptr;
                    const double x = std::strtod(part.c_str(), &stop);
                    const bool is_number = stop != part.c_str() && stop == part.c_str() + part.size();
                    // A vw line's joint ids are read as floats (of the number at the start of the
                    // word, whatever follows it), then converted to int: kept well inside an int.
                    const bool vw_joint_fits = keyword != "vw" || stop == part.c_str() || std::fabs(x) < 2147483000.0;
                    if (!obj_int_prefix_fits(part) || (is_number && !(std::fabs(x) <= double(FLT_MAX))) ||
                        !vw_joint_fits || !obj_number_tame(part))
                        fail("'" + token_text(word) + "' in a '" + keyword + "' line is out of range (of an int, or of a float)");
                }
        }
    });
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> load_obj(const std::string& path,
                                                                  std::shared_ptr<material> mat) {
    return decode_obj(read_file(path, "OBJ file"), path, std::move(mat));
}

namespace detail {

// tinyobjloader's reading of an OBJ file's text (checked first: check_obj_text) with the text of
// its material library (empty: none); throws scene_error "path: malformed OBJ file: ..." when it
// fails.
inline void parse_obj(tinyobj::ObjReader& reader, const std::string& text, const std::string& path,
                      const std::string& mtl_text) {
    check_obj_text(text, path);
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    if (!reader.ParseFromString(text, mtl_text, config)) {
        std::string why = first_line(reader.Error());
        throw scene_error(path + ": malformed OBJ file" + (why.empty() ? "" : ": " + why));
    }
}

// The triangle mesh of what `reader` read, all of its faces with material `mat`; with
// `face_materials`, each face's material number in the file's library (-1: none) too.
inline std::shared_ptr<triangle_mesh> mesh_of_obj(const tinyobj::ObjReader& reader, const std::string& path,
                                                  std::shared_ptr<material> mat, std::vector<int>* face_materials) {
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
        size_t offset = 0, face = 0;
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
            if (face_materials)
                face_materials->push_back(face < shape.mesh.material_ids.size() ? shape.mesh.material_ids[face] : -1);
            ++face;
        }
    }
    if (mesh->faces.empty()) throw scene_error(path + ": OBJ file has no faces");
    if (!any_normals) mesh->face_normals.clear();
    if (!any_uvs) mesh->face_uvs.clear();
    return mesh;
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> decode_obj(const std::string& text, const std::string& path,
                                                                    std::shared_ptr<material> mat) {
    tinyobj::ObjReader reader;
    // From the text already read; material libraries are not needed (see the top of the file).
    detail::parse_obj(reader, text, path, "");
    return detail::mesh_of_obj(reader, path, std::move(mat), nullptr);
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::load_obj;
#endif
