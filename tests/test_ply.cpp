// Stanford PLY meshes (rtweekend/io/ply.h): ASCII and binary reading, skipped elements and
// properties of every type, write_ply round trips, and one error message per kind of bad input.

#include <rtweekend/material.h>
#include <rtweekend/io/ply.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include <unistd.h>

namespace test_ply {

using namespace rt;

namespace {

const std::string ply_dir = std::string(RTWEEKEND_TEST_DATA) + "/ply";

// Bytes of PLY binary data, packed by hand in either byte order.
struct packer {
    bool big_endian;
    std::string bytes;
    template <class T> packer& put(T value) {
        uint64_t bits = 0;
        if constexpr (std::is_same_v<T, float>) {
            uint32_t b;
            std::memcpy(&b, &value, 4);
            bits = b;
        } else if constexpr (std::is_same_v<T, double>) {
            std::memcpy(&bits, &value, 8);
        } else {
            bits = uint64_t(std::make_unsigned_t<T>(value));
        }
        for (size_t i = 0; i < sizeof(T); ++i) {
            size_t shift = 8 * (big_endian ? sizeof(T) - 1 - i : i);
            bytes += char((bits >> shift) & 0xFF);
        }
        return *this;
    }
};

void check_same_mesh(const triangle_mesh& a, const triangle_mesh& b) {
    REQUIRE(a.positions.size() == b.positions.size());
    for (size_t i = 0; i < a.positions.size(); ++i)
        for (int k = 0; k < 3; ++k) CHECK(a.positions[i][k] == b.positions[i][k]);
    CHECK(a.faces == b.faces);
    REQUIRE(a.normals.size() == b.normals.size());
    for (size_t i = 0; i < a.normals.size(); ++i)
        for (int k = 0; k < 3; ++k) CHECK(a.normals[i][k] == b.normals[i][k]);
    CHECK(a.face_normals == b.face_normals);
    CHECK(a.uvs == b.uvs);
    CHECK(a.face_uvs == b.face_uvs);
}

void check_point(const point3& p, double x, double y, double z) {
    CHECK(p.x() == x);
    CHECK(p.y() == y);
    CHECK(p.z() == z);
}

// The header of the typed-layout mesh, for any format line. The vertex element has a used
// property of three different types and a skipped property of every type and alias; the face
// element has skipped scalars and lists around its index list.
std::string typed_header(const std::string& format, const std::string& index_name) {
    return "ply\nformat " + format +
           " 1.0\n"
           "element vertex 4\n"
           "property char a\nproperty uchar b\nproperty short c\nproperty ushort d\n"
           "property double x\n"
           "property int e\nproperty uint f\nproperty float g\nproperty double h\n"
           "property float y\n"
           "property int8 i\nproperty uint8 j\nproperty int16 k\nproperty uint16 l\n"
           "property short z\n"
           "property int32 m\nproperty uint32 n\nproperty float32 o\nproperty float64 p\n"
           "property list uint8 float32 q\n"
           "element face 2\n"
           "property int16 flags\n"
           "property list ushort uint " +
           index_name +
           "\n"
           "property list int double r\n"
           "element extra 1\n"
           "property list uchar char s\n"
           "end_header\n";
}

// The same data as the binary packing below, as ASCII.
const std::string typed_ascii_data = "-1 255 -300 60000 0.5 -70000 4000000000 1.5 2.5 -1.25 -2 200 -3 3 7 -4 4 0.25 0.125 2 1 2\n"
                                     "1 2 3 4 1.5 5 6 7 8 -0.75 9 10 11 12 -8 13 14 15 16 0\n"
                                     "0 0 0 0 -2 0 0 0 0 0.5 0 0 0 0 0 0 0 0 0 1 9\n"
                                     "0 0 0 0 3.25 0 0 0 0 4 0 0 0 0 32767 0 0 0 0 0\n"
                                     "5 4 0 1 2 3 2 1e300 -1\n"
                                     "-6 3 3 2 1 0\n"
                                     "3 -1 0 1\n";

std::string typed_binary_data(bool big_endian) {
    packer p{big_endian, ""};
    struct row {
        double x;
        float y;
        int16_t z;
    };
    const row rows[4] = {{0.5, -1.25f, 7}, {1.5, -0.75f, -8}, {-2, 0.5f, 0}, {3.25, 4, 32767}};
    for (int v = 0; v < 4; ++v) {
        int8_t small = v == 0 ? -1 : 0;
        p.put<int8_t>(small).put<uint8_t>(255).put<int16_t>(-300).put<uint16_t>(60000);
        p.put<double>(rows[v].x);
        p.put<int32_t>(-70000).put<uint32_t>(4000000000u).put<float>(1.5f).put<double>(2.5);
        p.put<float>(rows[v].y);
        p.put<int8_t>(-2).put<uint8_t>(200).put<int16_t>(-3).put<uint16_t>(3);
        p.put<int16_t>(rows[v].z);
        p.put<int32_t>(-4).put<uint32_t>(4).put<float>(0.25f).put<double>(0.125);
        uint8_t list = v == 2 ? 1 : v == 0 ? 2 : 0;
        p.put<uint8_t>(list);
        for (uint8_t i = 0; i < list; ++i) p.put<float>(float(i + 1));
    }
    // face 0: a quad, then a list of two doubles; face 1: a triangle, an empty list
    p.put<int16_t>(5).put<uint16_t>(4).put<uint32_t>(0).put<uint32_t>(1).put<uint32_t>(2).put<uint32_t>(3);
    p.put<int32_t>(2).put<double>(1e300).put<double>(-1);
    p.put<int16_t>(-6).put<uint16_t>(3).put<uint32_t>(3).put<uint32_t>(2).put<uint32_t>(1);
    p.put<int32_t>(0);
    // extra: a list of three chars
    p.put<uint8_t>(3).put<int8_t>(-1).put<int8_t>(0).put<int8_t>(1);
    return p.bytes;
}

void check_typed_mesh(const triangle_mesh& m) {
    REQUIRE(m.positions.size() == 4);
    check_point(m.positions[0], 0.5, -1.25, 7);
    check_point(m.positions[1], 1.5, -0.75, -8);
    check_point(m.positions[2], -2, 0.5, 0);
    check_point(m.positions[3], 3.25, 4, 32767);
    REQUIRE(m.faces.size() == 3);
    CHECK(m.faces[0] == std::array<uint32_t, 3>{0, 1, 2});
    CHECK(m.faces[1] == std::array<uint32_t, 3>{0, 2, 3});
    CHECK(m.faces[2] == std::array<uint32_t, 3>{3, 2, 1});
    CHECK(m.normals.empty());
    CHECK(m.uvs.empty());
    CHECK(m.face_normals.empty());
    CHECK(m.face_uvs.empty());
}

void check_ply_error(const test::scratch_dir& dir, const std::string& bytes, const std::vector<std::string>& fragments) {
    CAPTURE(bytes);
    std::string path = dir.write("bad.ply", bytes);
    std::string message;
    try {
        load_ply(path, nullptr);
    } catch (const scene_error& e) {
        message = e.what();
    }
    CAPTURE(message);
    REQUIRE(!message.empty());
    CHECK(message.find("bad.ply") != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
    for (const auto& f : fragments) {
        CAPTURE(f);
        CHECK(message.find(f) != std::string::npos);
    }
}

const std::string triangle_header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

} // namespace

TEST_CASE("ply: an ASCII quad becomes two triangles") {
    auto mat = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    auto m = load_ply(ply_dir + "/quad.ply", mat);
    CHECK(m->mat == mat);
    REQUIRE(m->positions.size() == 4);
    check_point(m->positions[0], 0, 0, 0);
    check_point(m->positions[1], 1, 0, 0);
    check_point(m->positions[2], 1, 1, 0);
    check_point(m->positions[3], 0, 1, 0);
    REQUIRE(m->faces.size() == 2);
    CHECK(m->faces[0] == std::array<uint32_t, 3>{0, 1, 2});
    CHECK(m->faces[1] == std::array<uint32_t, 3>{0, 2, 3});
    CHECK(m->normals.empty());
    CHECK(m->face_normals.empty());
    CHECK_FALSE(m->smooth_shading);
}

TEST_CASE("ply: unknown elements and properties, including lists, are skipped, normals and s t are kept") {
    auto m = load_ply(ply_dir + "/extras.ply", nullptr);
    REQUIRE(m->positions.size() == 5);
    check_point(m->positions[0], 0, 0, 0);
    check_point(m->positions[1], 2, 0, 0);
    check_point(m->positions[2], 2, 1, 0);
    check_point(m->positions[3], 1, 2, 0);
    check_point(m->positions[4], 0, 2, 0);
    // A pentagon as a fan, then a triangle (property vertex_index, list uint uint).
    REQUIRE(m->faces.size() == 4);
    CHECK(m->faces[0] == std::array<uint32_t, 3>{0, 1, 2});
    CHECK(m->faces[1] == std::array<uint32_t, 3>{0, 2, 3});
    CHECK(m->faces[2] == std::array<uint32_t, 3>{0, 3, 4});
    CHECK(m->faces[3] == std::array<uint32_t, 3>{4, 3, 1});
    REQUIRE(m->normals.size() == 5);
    for (const auto& n : m->normals) check_point(n, 0, 0, 1);
    CHECK(m->face_normals == m->faces);
    REQUIRE(m->uvs.size() == 5);
    CHECK(m->uvs[0] == std::array<double, 2>{0, 0});
    CHECK(m->uvs[1] == std::array<double, 2>{0.5, 0});
    CHECK(m->uvs[2] == std::array<double, 2>{1, 0.5});
    CHECK(m->uvs[3] == std::array<double, 2>{0.5, 1});
    CHECK(m->uvs[4] == std::array<double, 2>{0, 1});
    CHECK(m->face_uvs == m->faces);
}

TEST_CASE("ply: hand-packed binary little- and big-endian data load to the same mesh as the ASCII twin") {
    test::scratch_dir dir("binary");
    auto ascii = load_ply(dir.write("ascii.ply", typed_header("ascii", "vertex_indices") + typed_ascii_data), nullptr);
    check_typed_mesh(*ascii);
    auto little = load_ply(dir.write("le.ply", typed_header("binary_little_endian", "vertex_indices") +
                                                   typed_binary_data(false)),
                           nullptr);
    check_typed_mesh(*little);
    check_same_mesh(*ascii, *little);
    auto big = load_ply(dir.write("be.ply", typed_header("binary_big_endian", "vertex_index") + typed_binary_data(true)),
                        nullptr);
    check_typed_mesh(*big);
    check_same_mesh(*ascii, *big);
    // CRLF header lines: the binary data starts right after end_header's line feed.
    std::string header = typed_header("binary_little_endian", "vertex_indices");
    std::string crlf;
    for (char c : header) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    check_same_mesh(*ascii, *load_ply(dir.write("crlf.ply", crlf + typed_binary_data(false)), nullptr));
}

TEST_CASE("ply: write_ply round trips, ASCII and binary, with normals and uvs") {
    test::scratch_dir dir("write");
    triangle_mesh m;
    m.positions = {point3(0, 0, 0), point3(1.5, 0, 0), point3(0, 2.25, 0), point3(0, 0, -3.125)};
    m.faces = {{0, 1, 2}, {0, 2, 3}};
    for (bool binary : {false, true}) {
        CAPTURE(binary);
        std::string path = (dir.path / (binary ? "b.ply" : "a.ply")).string();
        write_ply(path, m, binary);
        auto back = load_ply(path, nullptr);
        check_same_mesh(m, *back);
        std::ifstream in(path, std::ios::binary);
        std::string first_lines[2];
        std::getline(in, first_lines[0]);
        std::getline(in, first_lines[1]);
        CHECK(first_lines[0] == "ply");
        CHECK(first_lines[1] == (binary ? "format binary_little_endian 1.0" : "format ascii 1.0"));
    }
    // Per-vertex normals and uvs are written as they are.
    m.normals = {vec3(0, 0, 1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(1, 0, 0)};
    m.face_normals = m.faces;
    m.uvs = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}};
    m.face_uvs = m.faces;
    for (bool binary : {false, true}) {
        std::string path = (dir.path / "n.ply").string();
        write_ply(path, m, binary);
        check_same_mesh(m, *load_ply(path, nullptr));
    }
    // Per-corner normals (two per shared position) duplicate the shared vertices.
    m.normals = {vec3(0, 0, 1), vec3(-1, 0, 0)};
    m.face_normals = {{0, 0, 0}, {1, 1, 1}};
    m.uvs.clear();
    m.face_uvs.clear();
    std::string path = (dir.path / "split.ply").string();
    write_ply(path, m, true);
    auto back = load_ply(path, nullptr);
    REQUIRE(back->faces.size() == 2);
    CHECK(back->positions.size() == 6); // 0, 1, 2 with +z, then 0, 2, 3 with -x
    for (size_t f = 0; f < 2; ++f)
        for (size_t k = 0; k < 3; ++k) {
            const point3& p = back->positions[back->faces[f][k]];
            const point3& q = m.positions[m.faces[f][k]];
            check_point(p, q.x(), q.y(), q.z());
            const vec3& n = back->normals[back->face_normals[f][k]];
            check_point(n, f == 0 ? 0 : -1, 0, f == 0 ? 1 : 0);
        }
    // A face using a vertex the mesh lacks is refused, and nothing is written.
    m.faces[1][2] = 9;
    CHECK_THROWS_WITH_AS(write_ply((dir.path / "bad.ply").string(), m, false),
                         doctest::Contains("face 1 uses vertex 9"), scene_error);
    CHECK_FALSE(std::filesystem::exists(dir.path / "bad.ply"));
}

TEST_CASE("ply: files that cannot be read") {
    test::scratch_dir dir("files");
    CHECK_THROWS_WITH_AS(load_ply((dir.path / "missing.ply").string(), nullptr),
                         doctest::Contains("missing.ply: cannot open PLY file"), scene_error);
    CHECK_THROWS_WITH_AS(load_ply(dir.path.string(), nullptr), doctest::Contains("is a directory"), scene_error);
    check_ply_error(dir, "", {"not a PLY file"});
    check_ply_error(dir, "OFF\n3 1 0\n", {"not a PLY file"});
    check_ply_error(dir, "plyx\nformat ascii 1.0\n", {"not a PLY file"});
}

TEST_CASE("ply: malformed headers") {
    test::scratch_dir dir("header");
    check_ply_error(dir, "ply\nformat ascii 1.0\nelement vertex 3\n", {"no 'end_header'"});
    check_ply_error(dir, "ply\nelement vertex 0\nend_header\n", {"no 'format' line"});
    check_ply_error(dir, "ply\nformat binary_middle_endian 1.0\nend_header\n", {":2:", "unknown format"});
    check_ply_error(dir, "ply\nformat ascii 2.0\nend_header\n", {":2:", "version '2.0'"});
    check_ply_error(dir, "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", {":3:", "'-3'"});
    check_ply_error(dir, "ply\nformat ascii 1.0\nproperty float x\nend_header\n", {":3:", "before any element"});
    check_ply_error(dir, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
                    {":4:", "unknown type", "'x'"});
    check_ply_error(dir, "ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
                    {":4:", "non-integer count type"});
    check_ply_error(dir, "ply\nformat ascii 1.0\nvertices 3\nend_header\n", {":3:", "unknown keyword 'vertices'"});
    // What the mesh needs.
    check_ply_error(dir, "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 0 0\n",
                    {"no 'vertex' element"});
    check_ply_error(dir,
                    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n0 0\n3 0 0 0\n",
                    {"lacks one of x, y, z"});
    check_ply_error(dir, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
                    {"no faces"});
    check_ply_error(dir,
                    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int corners\nend_header\n0 0 0\n3 0 0 0\n",
                    {"no 'vertex_indices' list"});
    check_ply_error(dir,
                    "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n3 0 0 0\n",
                    {"not a list of integers"});
}

TEST_CASE("ply: bad ASCII data names the line, the entry and the problem") {
    test::scratch_dir dir("ascii");
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", {":13:", "face 0 uses vertex 3 but the file has 3 vertices"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", {"face 0 uses vertex -1"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", {":13:", "face 0 has 2 corners (at least 3 needed)"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0x 0\n0 1 0\n3 0 1 2\n", {":11:", "vertex 1", "'0x'", "not a number"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n", {":11:", "vertex 1", "'z'", "not a finite number"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\ninf 1 0\n3 0 1 2\n", {":12:", "vertex 2", "'x'", "not a finite number"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", {":11:", "vertex 1", "before property 'z'"});
    check_ply_error(dir, triangle_header + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n", {":10:", "vertex 0", "more values"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", {"face 0", "'1.5'", "not an integer"});
    // A list length of -3 in a uchar: refused as a value its type cannot hold (issue 14), before
    // it could be taken for a negative length.
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", {"face 0", "'-3'", "does not fit its type uchar"});
    // Counts that do not match the data: too little, too much.
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\n0 1 0\n", {"more than the", "truncated"});
    check_ply_error(dir, triangle_header + "0 0 0 1 0 0 0 1 0 3 0 1 2\n", {"vertex 0", "more values"});
    check_ply_error(dir, triangle_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", {"after the last element"});
    // Blank lines between entries and a missing final newline are fine.
    auto m = load_ply(dir.write("ok.ply", triangle_header + "0 0 0\n\n1 0 0\r\n0 1 0\n3 0 1 2"), nullptr);
    CHECK(m->faces.size() == 1);
}

TEST_CASE("ply: bad binary data: truncation, absurd counts, NaN, bad indices") {
    test::scratch_dir dir("binary_errors");
    const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n";
    auto vertices = [](float bad) {
        packer p{false, ""};
        p.put(0.f).put(0.f).put(0.f).put(1.f).put(0.f).put(0.f).put(0.f).put(1.f).put(bad);
        return p.bytes;
    };
    auto face = [](int a, int b, int c, uint8_t n = 3) {
        packer p{false, ""};
        p.put<uint8_t>(n).put(a).put(b).put(c);
        return p.bytes;
    };
    std::string good = header + vertices(0) + face(0, 1, 2);
    CHECK(load_ply(dir.write("good.ply", good), nullptr)->faces.size() == 1);
    // Truncated inside the last face: the header's counts still fit, the entry does not.
    check_ply_error(dir, good.substr(0, good.size() - 2), {"face 0", "ends before the end of this entry"});
    // Truncated earlier: the counts no longer fit the bytes.
    check_ply_error(dir, good.substr(0, header.size() + 20), {"'vertex' entries", "truncated"});
    check_ply_error(dir, good + "x", {"after the last element"});
    check_ply_error(dir, header + vertices(std::numeric_limits<float>::quiet_NaN()) + face(0, 1, 2),
                    {"vertex 2", "'z'", "not a finite number"});
    check_ply_error(dir, header + vertices(std::numeric_limits<float>::infinity()) + face(0, 1, 2),
                    {"vertex 2", "'z'", "not a finite number"});
    check_ply_error(dir, header + vertices(0) + face(0, 1, 9000), {"face 0 uses vertex 9000 but the file has 3 vertices"});
    check_ply_error(dir, header + vertices(0) + face(0, 1, 2, 2).substr(0, 9), {"face 0 has 2 corners"});
    // A list longer than the rest of the file.
    check_ply_error(dir, header + vertices(0) + face(0, 1, 2, 200), {"face 0", "ends before the end"});
    // Absurd counts are refused before anything is allocated.
    std::string huge = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000000\nproperty float x\n"
                       "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                       "end_header\n" +
                       vertices(0) + face(0, 1, 2);
    check_ply_error(dir, huge, {"4000000000000 'vertex' entries", "more than the 49 bytes"});
    std::string huge_ascii = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 18446744073709551615\n"
                             "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    check_ply_error(dir, huge_ascii, {"18446744073709551615 'face' entries", "truncated"});
}

} // namespace test_ply
