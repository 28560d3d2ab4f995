#pragma once
// ply: Stanford PLY meshes. load_ply reads one into a triangle_mesh; write_ply writes one.
//
//   auto bunny = load_ply("bunny.ply", make_shared<lambertian>(color(0.8, 0.8, 0.8)));
//   write_ply("copy.ply", *bunny, /*binary=*/true);
//
// Hand-written on purpose: no Debian package provides a C++ PLY reader except assimp, a very large
// dependency for one file format. What load_ply reads:
//   - ASCII, binary_little_endian and binary_big_endian data, any element and property layout:
//     elements and properties it does not use (scalars and lists, of any of the types char, uchar,
//     short, ushort, int, uint, float, double or their aliases int8, uint8, int16, uint16, int32,
//     uint32, float32, float64) are skipped;
//   - element `vertex`: x y z (required); nx ny nz (optional, all three: per-vertex normals);
//     u v, s t or texture_u texture_v (optional: texture coordinates);
//   - element `face`: list property `vertex_indices` (or `vertex_index`), 0-based; quads and
//     polygons are split into triangle fans (0, i, i+1).
// An ASCII file holds one element per line, as the PLY format defines it.
// Every problem is one scene_error naming the file: missing file, not a PLY file, a malformed
// header, data that ends early or goes on after the last element, a value that is not a finite
// number, an ASCII value outside its declared type (a uchar of -70000, a float beyond 3.4e38;
// unused properties too), a NUL byte in the header or in ASCII data, a face with fewer than three corners or using a vertex that does not exist, element
// counts that the file is too small to hold (checked before anything is allocated), a file
// without faces.
//
// write_ply writes positions, faces, and normals and texture coordinates when every corner of
// every face has them (vertices are duplicated where a position carries several normals or uvs),
// as float coordinates and `list uchar int vertex_indices`; ASCII or binary little-endian; to a
// temporary file renamed into place. A value a float cannot hold (1e300, NaN) is refused rather
// than written as inf or nan.

#include "../core/engine_linkage.h"
#include "../mesh.h"
#include "../core/scene_error.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rt {

// Reads a PLY file into a mesh with material `mat`. Throws scene_error "path: problem" (with the
// line for ASCII data: "path:LINE: problem").
RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> load_ply(const std::string& path,
                                                                  std::shared_ptr<material> mat);

// load_ply on a file's bytes already in memory; `path` names it in messages.
RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> decode_ply(const std::string& bytes,
                                                                    const std::string& path,
                                                                    std::shared_ptr<material> mat);

// Writes `mesh` as PLY (binary little-endian or ASCII). Throws scene_error naming the path when
// it cannot be written or a face uses a vertex the mesh does not have.
RTWEEKEND_ENGINE_FUNCTION void write_ply(const std::string& path, const triangle_mesh& mesh, bool binary);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/file.h"
#include "../core/text_lines.h"

namespace rt {

namespace detail {

enum class ply_type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

inline bool ply_type_from_name(const std::string& name, ply_type& type) {
    static const std::pair<const char*, ply_type> names[] = {
        {"char", ply_type::int8},       {"int8", ply_type::int8},       {"uchar", ply_type::uint8},
        {"uint8", ply_type::uint8},     {"short", ply_type::int16},     {"int16", ply_type::int16},
        {"ushort", ply_type::uint16},   {"uint16", ply_type::uint16},   {"int", ply_type::int32},
        {"int32", ply_type::int32},     {"uint", ply_type::uint32},     {"uint32", ply_type::uint32},
        {"float", ply_type::float32},   {"float32", ply_type::float32}, {"double", ply_type::float64},
        {"float64", ply_type::float64}};
    for (const auto& n : names)
        if (name == n.first) {
            type = n.second;
            return true;
        }
    return false;
}

inline size_t ply_type_size(ply_type t) {
    switch (t) {
    case ply_type::int8:
    case ply_type::uint8: return 1;
    case ply_type::int16:
    case ply_type::uint16: return 2;
    case ply_type::int32:
    case ply_type::uint32:
    case ply_type::float32: return 4;
    case ply_type::float64: return 8;
    }
    return 1;
}

inline bool ply_type_is_integer(ply_type t) { return t != ply_type::float32 && t != ply_type::float64; }

struct ply_property {
    std::string name;
    ply_type type = ply_type::float32; // of the value, or of a list's items
    bool is_list = false;
    ply_type count_type = ply_type::uint8;
};

struct ply_element {
    std::string name;
    uint64_t count = 0;
    std::vector<ply_property> properties;
};

// Parses a whole token as a number: a decimal integer for integer types, a decimal floating
// point number otherwise (a leading '+' is allowed). Locale-independent.
inline bool parse_ply_number(const char* begin, const char* end, bool integer, double& value) {
    if (begin != end && *begin == '+') ++begin;
    if (begin == end) return false;
    if (integer) {
        long long i = 0;
        auto r = std::from_chars(begin, end, i);
        if (r.ec != std::errc() || r.ptr != end) return false;
        value = double(i);
        return true;
    }
    auto r = std::from_chars(begin, end, value, std::chars_format::general);
    return r.ec == std::errc() && r.ptr == end;
}

// The data after the header, read value by value in either encoding. Every failure throws
// scene_error naming the file, the element entry being read and, for ASCII, the line.
class ply_data {
  public:
    enum class encoding { ascii, little_endian, big_endian };

    ply_data(const std::string& path, const std::string& text, size_t start, encoding enc, size_t line)
        : path_(path), text_(text), pos_(start), enc_(enc), line_(line) {}

    // The element entry that messages name ("vertex 3").
    void set_entry(const ply_element& e, uint64_t index) {
        element_ = &e;
        index_ = index;
    }

    // "path[:LINE]: ELEMENT INDEX: problem", or with `subject`, "... ELEMENT INDEX problem".
    [[noreturn]] void fail(const std::string& problem, bool subject = false) const {
        std::string where = path_ + (enc_ == encoding::ascii ? ":" + std::to_string(line_) : std::string()) + ": ";
        std::string entry =
            element_ ? element_->name + " " + std::to_string(index_) + (subject ? " " : ": ") : std::string();
        throw scene_error(where + entry + problem);
    }

    size_t remaining() const { return text_.size() - pos_; }

    // ASCII: an entry starts on a new line (blank lines are skipped) and must end its line.
    void begin_entry() {
        if (enc_ != encoding::ascii) return;
        while (pos_ < text_.size() && is_space(text_[pos_])) {
            if (text_[pos_] == '\n') ++line_;
            ++pos_;
        }
        if (pos_ == text_.size()) fail_ended();
    }
    void end_entry() {
        if (enc_ != encoding::ascii) return;
        skip_blanks();
        if (pos_ < text_.size() && text_[pos_] != '\n')
            fail("more values than the header declares for element '" + element_->name + "'");
    }

    // One scalar of type t.
    double read(ply_type t, const char* property) {
        if (enc_ == encoding::ascii) {
            const char *begin, *end;
            token(property, begin, end);
            double value;
            if (!parse_ply_number(begin, end, ply_type_is_integer(t), value))
                fail("'" + token_text(std::string(begin, end)) + "' (property '" + property + "') is not " +
                     (ply_type_is_integer(t) ? "an integer" : "a number"));
            // Text can say anything; a binary file could only hold what the type holds, and the
            // text must mean the same (a uchar of -70000, or a float of 1e300, is damage).
            if (!std::isfinite(value))
                fail("'" + token_text(std::string(begin, end)) + "' (property '" + property + "') is not a finite number");
            if (!fits(t, value))
                fail("'" + token_text(std::string(begin, end)) + "' (property '" + property + "') does not fit its type " +
                     ply_type_name(t) + " (" + ply_type_range(t) + ")");
            return value;
        }
        size_t size = ply_type_size(t);
        if (size > remaining()) fail_ended();
        uint64_t raw = 0;
        for (size_t i = 0; i < size; ++i) {
            uint64_t byte = static_cast<unsigned char>(text_[pos_ + i]);
            raw |= byte << (8 * (enc_ == encoding::little_endian ? i : size - 1 - i));
        }
        pos_ += size;
        switch (t) {
        case ply_type::int8: return double(static_cast<int8_t>(raw));
        case ply_type::uint8: return double(static_cast<uint8_t>(raw));
        case ply_type::int16: return double(static_cast<int16_t>(raw));
        case ply_type::uint16: return double(static_cast<uint16_t>(raw));
        case ply_type::int32: return double(static_cast<int32_t>(raw));
        case ply_type::uint32: return double(static_cast<uint32_t>(raw));
        case ply_type::float32: {
            auto bits = static_cast<uint32_t>(raw);
            float f;
            std::memcpy(&f, &bits, 4);
            return double(f);
        }
        case ply_type::float64: {
            double d;
            std::memcpy(&d, &raw, 8);
            return d;
        }
        }
        return 0;
    }

    // A list's length: a non-negative integer, small enough for the rest of the file to hold.
    uint64_t read_count(const ply_property& p) {
        double n = read(p.count_type, p.name.c_str());
        if (!(n >= 0)) fail("list '" + p.name + "' has a negative length (" + std::to_string(int64_t(n)) + ")");
        auto count = uint64_t(n);
        size_t min_item = enc_ == encoding::ascii ? 2 : ply_type_size(p.type);
        if (count > remaining() / min_item + 1) fail_ended();
        return count;
    }

    // Skips one value of property p (a scalar or a whole list). ASCII values are still checked:
    // a property the mesh does not use must hold a number of its type all the same.
    void skip(const ply_property& p) {
        uint64_t n = p.is_list ? read_count(p) : 1;
        if (enc_ == encoding::ascii) {
            for (uint64_t i = 0; i < n; ++i) read(p.type, p.name.c_str());
        } else {
            uint64_t bytes = n * ply_type_size(p.type);
            if (bytes > remaining()) fail_ended();
            pos_ += size_t(bytes);
        }
    }

    // After the last element: only whitespace may follow in ASCII, nothing in binary.
    void finish() {
        element_ = nullptr;
        if (enc_ == encoding::ascii) {
            while (pos_ < text_.size() && is_space(text_[pos_])) {
                if (text_[pos_] == '\n') ++line_;
                ++pos_;
            }
        }
        if (pos_ != text_.size())
            fail("unexpected data after the last element (" + std::to_string(remaining()) +
                 " bytes): the element counts in the header do not match the data");
    }

  private:
    // Whether `value` (a whole number for integer types) is one type t holds; a float must be
    // finite as a float, not only as the double it was parsed into.
    static bool fits(ply_type t, double value) {
        switch (t) {
        case ply_type::int8: return value >= -128 && value <= 127;
        case ply_type::uint8: return value >= 0 && value <= 255;
        case ply_type::int16: return value >= -32768 && value <= 32767;
        case ply_type::uint16: return value >= 0 && value <= 65535;
        case ply_type::int32: return value >= -2147483648.0 && value <= 2147483647.0;
        case ply_type::uint32: return value >= 0 && value <= 4294967295.0;
        case ply_type::float32: return std::fabs(value) <= double(std::numeric_limits<float>::max());
        case ply_type::float64: return std::isfinite(value);
        }
        return false;
    }
    static const char* ply_type_name(ply_type t) {
        static const char* names[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
        return names[int(t)];
    }
    static const char* ply_type_range(ply_type t) {
        static const char* ranges[] = {"-128 to 127", "0 to 255", "-32768 to 32767", "0 to 65535",
                                       "-2147483648 to 2147483647", "0 to 4294967295", "finite, at most 3.4e38",
                                       "finite"};
        return ranges[int(t)];
    }
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }
    void skip_blanks() {
        while (pos_ < text_.size() && is_space(text_[pos_]) && text_[pos_] != '\n') ++pos_;
    }
    [[noreturn]] void fail_ended() const {
        if (!element_) fail("the file ends early");
        fail("the file ends before the end of this entry (the header declares " + std::to_string(element_->count) +
             " " + element_->name + " entries)");
    }
    // The next whitespace-separated token on the current line.
    void token(const char* property, const char*& begin, const char*& end) {
        skip_blanks();
        if (pos_ == text_.size()) fail_ended();
        if (text_[pos_] == '\n')
            fail("the line ends before property '" + std::string(property) + "' (fewer values than the header declares)");
        size_t start = pos_;
        while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
        begin = text_.data() + start;
        end = text_.data() + pos_;
    }

    const std::string& path_;
    const std::string& text_;
    size_t pos_;
    encoding enc_;
    size_t line_;
    const ply_element* element_ = nullptr;
    uint64_t index_ = 0;
};

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> load_ply(const std::string& path,
                                                                  std::shared_ptr<material> mat) {
    return decode_ply(read_file(path, "PLY file"), path, std::move(mat));
}

RTWEEKEND_ENGINE_FUNCTION std::shared_ptr<triangle_mesh> decode_ply(const std::string& text, const std::string& path,
                                                                    std::shared_ptr<material> mat) {
    using detail::ply_element;
    using detail::ply_property;
    using detail::ply_type;
    // A NUL byte has no place in the header, nor anywhere in an ASCII file (found below, once the
    // format is known); it would hide the rest of a token from the number parsers.
    auto refuse_nul = [&](size_t end) {
        size_t nul = text.find('\0');
        if (nul < end)
            throw scene_error(path + ":" + std::to_string(line_index(text).line_of(nul)) +
                              ": a NUL byte in PLY text (is this a binary or damaged file?)");
    };

    // --- header: lines up to end_header ---
    auto not_ply = [&] { return scene_error(path + ": not a PLY file (it does not start with a 'ply' line)"); };
    if (text.compare(0, 4, "ply\n") != 0 && text.compare(0, 5, "ply\r\n") != 0) throw not_ply();
    std::vector<ply_element> elements;
    bool have_format = false, ended = false;
    auto enc = detail::ply_data::encoding::ascii;
    text_lines lines(text);
    while (!ended) {
        std::string_view header_line;
        if (!lines.next(header_line)) throw scene_error(path + ": PLY header has no 'end_header' line");
        std::istringstream line{std::string(header_line)};
        const size_t line_number = lines.number();
        auto fail = [&](const std::string& what) {
            throw scene_error(path + ":" + std::to_string(line_number) + ": malformed PLY header: " + what);
        };
        std::string keyword;
        if (!(line >> keyword)) continue;
        if (line_number == 1) continue; // "ply"
        if (keyword == "comment" || keyword == "obj_info") continue;
        std::vector<std::string> words;
        for (std::string w; line >> w;) words.push_back(w);
        if (keyword == "format") {
            if (words.size() != 2) fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
            if (words[0] == "ascii") enc = detail::ply_data::encoding::ascii;
            else if (words[0] == "binary_little_endian") enc = detail::ply_data::encoding::little_endian;
            else if (words[0] == "binary_big_endian") enc = detail::ply_data::encoding::big_endian;
            else fail("unknown format '" + words[0] + "'");
            if (words[1] != "1.0" && words[1] != "1") fail("unsupported PLY version '" + words[1] + "'");
            have_format = true;
        } else if (keyword == "element") {
            if (words.size() != 2) fail("expected 'element NAME COUNT'");
            ply_element e;
            e.name = words[0];
            const std::string& c = words[1];
            auto r = std::from_chars(c.data(), c.data() + c.size(), e.count);
            if (r.ec != std::errc() || r.ptr != c.data() + c.size())
                fail("element '" + e.name + "' has count '" + c + "', not a non-negative integer");
            elements.push_back(e);
        } else if (keyword == "property") {
            if (elements.empty()) fail("a property before any element");
            ply_property p;
            bool ok;
            if (!words.empty() && words[0] == "list") {
                if (words.size() != 4) fail("expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
                p.is_list = true;
                ok = detail::ply_type_from_name(words[1], p.count_type) && detail::ply_type_from_name(words[2], p.type);
                if (ok && !detail::ply_type_is_integer(p.count_type))
                    fail("list '" + words[3] + "' has a non-integer count type '" + words[1] + "'");
                p.name = words[3];
            } else {
                if (words.size() != 2) fail("expected 'property TYPE NAME'");
                ok = detail::ply_type_from_name(words[0], p.type);
                p.name = words[1];
            }
            if (!ok) fail("unknown type in property '" + p.name + "'");
            elements.back().properties.push_back(p);
        } else if (keyword == "end_header") {
            ended = true;
        } else {
            fail("unknown keyword '" + keyword + "'");
        }
    }
    if (!have_format) throw scene_error(path + ": malformed PLY header: no 'format' line");
    refuse_nul(enc == detail::ply_data::encoding::ascii ? text.size() : lines.offset());

    // --- what the mesh needs from the header ---
    const ply_element *vertex_el = nullptr, *face_el = nullptr;
    for (const auto& e : elements) {
        if (e.name == "vertex" && !vertex_el) vertex_el = &e;
        if (e.name == "face" && !face_el) face_el = &e;
    }
    if (!vertex_el) throw scene_error(path + ": PLY file has no 'vertex' element");
    if (!face_el || face_el->count == 0) throw scene_error(path + ": PLY file has no faces");
    // Roles of the vertex properties: 0-2 position, 3-5 normal, 6-7 uv; -1 unused.
    std::vector<int> role(vertex_el->properties.size(), -1);
    auto find = [](const ply_element& e, const char* name) -> int {
        for (size_t i = 0; i < e.properties.size(); ++i)
            if (e.properties[i].name == name) return int(i);
        return -1;
    };
    auto assign = [&](std::initializer_list<const char*> names, int first_role) {
        std::vector<int> found;
        for (const char* n : names) found.push_back(find(*vertex_el, n));
        for (int f : found)
            if (f < 0) return false;
        for (size_t k = 0; k < found.size(); ++k) {
            if (vertex_el->properties[size_t(found[k])].is_list)
                throw scene_error(path + ": PLY vertex property '" + vertex_el->properties[size_t(found[k])].name +
                                  "' is a list, not a number");
            role[size_t(found[k])] = first_role + int(k);
        }
        return true;
    };
    if (!assign({"x", "y", "z"}, 0)) throw scene_error(path + ": PLY vertex element lacks one of x, y, z");
    bool has_normals = assign({"nx", "ny", "nz"}, 3);
    bool has_uvs = assign({"u", "v"}, 6) || assign({"s", "t"}, 6) || assign({"texture_u", "texture_v"}, 6) ||
                   assign({"texture_s", "texture_t"}, 6);
    int index_prop = find(*face_el, "vertex_indices");
    if (index_prop < 0) index_prop = find(*face_el, "vertex_index");
    if (index_prop < 0) throw scene_error(path + ": PLY face element has no 'vertex_indices' list");
    const ply_property& indices = face_el->properties[size_t(index_prop)];
    if (!indices.is_list || !detail::ply_type_is_integer(indices.type))
        throw scene_error(path + ": PLY face property '" + indices.name + "' is not a list of integers");

    // Counts against the file's size, before allocating anything: an entry takes at least the sum
    // of its scalars' sizes and its lists' count sizes (binary), or two characters per value (ASCII).
    const size_t data_start = lines.offset();
    size_t data_bytes = text.size() - data_start;
    uint64_t needed = 0;
    for (const auto& e : elements) {
        uint64_t entry = 0;
        for (const auto& p : e.properties)
            entry += enc == detail::ply_data::encoding::ascii ? 2 : detail::ply_type_size(p.is_list ? p.count_type : p.type);
        if (entry == 0) continue;
        if (e.count > (uint64_t(data_bytes) + 1) / entry || needed + e.count * entry > uint64_t(data_bytes) + 1)
            throw scene_error(path + ": PLY header declares " + std::to_string(e.count) + " '" + e.name +
                              "' entries, more than the " + std::to_string(data_bytes) +
                              " bytes after the header can hold (the file is truncated or damaged)");
        needed += e.count * entry;
    }

    // --- data ---
    auto mesh = std::make_shared<triangle_mesh>();
    mesh->mat = std::move(mat);
    const uint64_t vertex_count = vertex_el->count;
    mesh->positions.reserve(size_t(vertex_count));
    if (has_normals) mesh->normals.reserve(size_t(vertex_count));
    if (has_uvs) mesh->uvs.reserve(size_t(vertex_count));
    mesh->faces.reserve(size_t(face_el->count));
    detail::ply_data data(path, text, data_start, enc, lines.number() + 1);
    std::vector<uint32_t> polygon;
    for (const auto& e : elements) {
        const bool is_vertex = &e == vertex_el, is_face = &e == face_el;
        if (e.properties.empty()) continue;
        for (uint64_t i = 0; i < e.count; ++i) {
            data.set_entry(e, i);
            data.begin_entry();
            if (is_vertex) {
                double v[8] = {0, 0, 0, 0, 0, 0, 0, 0};
                for (size_t k = 0; k < e.properties.size(); ++k) {
                    const ply_property& p = e.properties[k];
                    if (role[k] < 0) {
                        data.skip(p);
                        continue;
                    }
                    v[role[k]] = data.read(p.type, p.name.c_str());
                    if (!std::isfinite(v[role[k]]))
                        data.fail("property '" + p.name + "' is " + std::to_string(v[role[k]]) + ", not a finite number");
                }
                mesh->positions.emplace_back(v[0], v[1], v[2]);
                if (has_normals) mesh->normals.emplace_back(v[3], v[4], v[5]);
                if (has_uvs) mesh->uvs.push_back({v[6], v[7]});
            } else if (is_face) {
                for (size_t k = 0; k < e.properties.size(); ++k) {
                    const ply_property& p = e.properties[k];
                    if (int(k) != index_prop) {
                        data.skip(p);
                        continue;
                    }
                    uint64_t corners = data.read_count(p);
                    if (corners < 3)
                        data.fail("has " + std::to_string(corners) + " corners (at least 3 needed)", true);
                    polygon.clear();
                    for (uint64_t c = 0; c < corners; ++c) {
                        double index = data.read(p.type, p.name.c_str());
                        if (!(index >= 0 && index < double(vertex_count)))
                            data.fail("uses vertex " + std::to_string(int64_t(index)) + " but the file has " +
                                          std::to_string(vertex_count) + " vertices",
                                      true);
                        polygon.push_back(uint32_t(index));
                    }
                    for (size_t c = 1; c + 1 < polygon.size(); ++c)
                        mesh->faces.push_back({polygon[0], polygon[c], polygon[c + 1]});
                }
            } else {
                for (const auto& p : e.properties) data.skip(p);
            }
            data.end_entry();
        }
    }
    data.finish();
    if (has_normals) mesh->face_normals = mesh->faces;
    if (has_uvs) mesh->face_uvs = mesh->faces;
    return mesh;
}

RTWEEKEND_ENGINE_FUNCTION void write_ply(const std::string& path, const triangle_mesh& mesh, bool binary) {
    const uint32_t none = triangle_mesh::no_index;
    const size_t n_faces = mesh.faces.size();
    auto corner_has = [&](const std::vector<std::array<uint32_t, 3>>& per_corner, size_t size) {
        if (per_corner.size() != n_faces || size == 0) return false;
        for (const auto& f : per_corner)
            for (uint32_t i : f)
                if (i == none || i >= size) return false;
        return true;
    };
    const bool normals = n_faces > 0 && corner_has(mesh.face_normals, mesh.normals.size());
    const bool uvs = n_faces > 0 && corner_has(mesh.face_uvs, mesh.uvs.size());

    // One output vertex per distinct (position, normal, uv) used by a corner; a mesh whose normals
    // and uvs are indexed like its positions keeps its vertex order.
    bool same_indexing = (!normals || (mesh.face_normals == mesh.faces && mesh.normals.size() >= mesh.positions.size())) &&
                         (!uvs || (mesh.face_uvs == mesh.faces && mesh.uvs.size() >= mesh.positions.size()));
    std::vector<std::array<uint32_t, 3>> vertices; // (position, normal, uv) indices
    std::vector<std::array<uint32_t, 3>> faces(n_faces);
    for (size_t i = 0; i < n_faces; ++i)
        for (uint32_t v : mesh.faces[i])
            if (v >= mesh.positions.size())
                throw scene_error("cannot write '" + path + "': face " + std::to_string(i) + " uses vertex " +
                                  std::to_string(v) + " but the mesh has " + std::to_string(mesh.positions.size()));
    if (same_indexing) {
        for (uint32_t v = 0; v < mesh.positions.size(); ++v) vertices.push_back({v, normals ? v : 0, uvs ? v : 0});
        faces = mesh.faces;
    } else {
        std::map<std::array<uint32_t, 3>, uint32_t> index;
        for (size_t i = 0; i < n_faces; ++i)
            for (size_t k = 0; k < 3; ++k) {
                std::array<uint32_t, 3> key = {mesh.faces[i][k], normals ? mesh.face_normals[i][k] : 0,
                                               uvs ? mesh.face_uvs[i][k] : 0};
                auto it = index.emplace(key, uint32_t(vertices.size())).first;
                if (it->second == vertices.size()) vertices.push_back(key);
                faces[i][k] = it->second;
            }
    }
    if (vertices.size() > 0x7FFFFFFFu)
        throw scene_error("cannot write '" + path + "': too many vertices for 32-bit PLY indices");
    // The file stores floats: a value beyond float's range would be written as inf (and NaN as
    // nan), which no reader, this one included, accepts back.
    auto check_float = [&](double x, const char* what, size_t index) {
        if (!(std::fabs(x) <= double(std::numeric_limits<float>::max()))) {
            std::ostringstream value;
            value << x;
            throw scene_error("cannot write '" + path + "': " + what + " " + std::to_string(index) + " has the value " +
                              value.str() + ", which a PLY float cannot hold (finite, at most 3.4e38)");
        }
    };
    for (const auto& v : vertices) {
        for (int k = 0; k < 3; ++k) check_float(mesh.positions[v[0]][k], "position", v[0]);
        if (normals)
            for (int k = 0; k < 3; ++k) check_float(mesh.normals[v[1]][k], "normal", v[1]);
        if (uvs)
            for (size_t k = 0; k < 2; ++k) check_float(mesh.uvs[v[2]][k], "texture coordinate", v[2]);
    }

    std::string out = "ply\nformat ";
    out += binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
    out += "comment written by rtweekend\nelement vertex " + std::to_string(vertices.size()) + "\n";
    out += "property float x\nproperty float y\nproperty float z\n";
    if (normals) out += "property float nx\nproperty float ny\nproperty float nz\n";
    if (uvs) out += "property float u\nproperty float v\n";
    out += "element face " + std::to_string(n_faces) + "\nproperty list uchar int vertex_indices\nend_header\n";

    auto put_float = [&](double x) {
        float f = static_cast<float>(x);
        if (binary) {
            uint32_t bits;
            std::memcpy(&bits, &f, 4);
            for (int b = 0; b < 4; ++b) out += char((bits >> (8 * b)) & 0xFF);
        } else {
            char buf[32];
            auto r = std::to_chars(buf, buf + sizeof buf, f);
            out.append(buf, r.ptr);
            out += ' ';
        }
    };
    auto put_int = [&](uint32_t v) {
        if (binary) {
            for (int b = 0; b < 4; ++b) out += char((v >> (8 * b)) & 0xFF);
        } else {
            out += std::to_string(v);
            out += ' ';
        }
    };
    auto end_line = [&] {
        if (!binary) out.back() = '\n';
    };
    for (const auto& v : vertices) {
        const point3& p = mesh.positions[v[0]];
        for (int k = 0; k < 3; ++k) put_float(p[k]);
        if (normals)
            for (int k = 0; k < 3; ++k) put_float(mesh.normals[v[1]][k]);
        if (uvs)
            for (size_t k = 0; k < 2; ++k) put_float(mesh.uvs[v[2]][k]);
        end_line();
    }
    for (const auto& f : faces) {
        if (binary) out += char(3);
        else out += "3 ";
        for (uint32_t i : f) put_int(i);
        end_line();
    }
    write_file_atomically(path, out);
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::load_ply;
using rt::write_ply;
#endif
