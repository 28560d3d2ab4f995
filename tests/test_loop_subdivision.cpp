// Loop subdivision (apps/loop_subdivision.h): counts and Euler characteristic on closed meshes,
// hand-computed positions on the regular octahedron and on open meshes, refused inputs, and the
// OBJ reading and writing of the subdivide tool.

#include "loop_subdivision.h"

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace test_loop_subdivision {

using app::tri_mesh;
using rt::vec3;

namespace {

tri_mesh tetrahedron() {
    tri_mesh m;
    m.positions = {vec3(1, 1, 1), vec3(1, -1, -1), vec3(-1, 1, -1), vec3(-1, -1, 1)};
    m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    return m;
}

// Vertices 0..5 = +x, -x, +y, -y, +z, -z; outward-facing triangles.
tri_mesh octahedron() {
    tri_mesh m;
    m.positions = {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return m;
}

long euler_characteristic(const tri_mesh& m) {
    return long(m.positions.size()) - long(app::count_edges(m)) + long(m.triangles.size());
}

void check_point(const vec3& got, const vec3& expected) {
    CAPTURE(got);
    CAPTURE(expected);
    CHECK((got - expected).length() < 1e-12);
}

// loop_subdivide(m) must throw a one-line scene_error containing `fragment`.
void check_refused(const tri_mesh& m, const std::string& fragment) {
    CAPTURE(fragment);
    bool threw = false;
    try {
        app::loop_subdivide(m, 1);
    } catch (const rt::scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find(fragment) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
    CHECK(threw);
}

namespace fs = std::filesystem;

} // namespace

TEST_CASE("loop: Loop's beta, not Warren's, for valences 3, 4 and 6") {
    // beta(n) = (1/n)(5/8 - (3/8 + 1/4 cos(2 pi / n))^2):
    // n = 3: (1/3)(5/8 - 1/16) = 3/16; n = 4: (1/4)(5/8 - 9/64) = 31/256; n = 6: (1/6)(5/8 - 1/4) = 1/16.
    CHECK(app::loop_beta(3) == doctest::Approx(3.0 / 16).epsilon(1e-14));
    CHECK(app::loop_beta(4) == doctest::Approx(31.0 / 256).epsilon(1e-14)); // Warren: 3/32
    CHECK(app::loop_beta(6) == doctest::Approx(1.0 / 16).epsilon(1e-14));
}

TEST_CASE("loop: each level gives 4F triangles and V + E vertices, and keeps a closed mesh's Euler characteristic") {
    for (const tri_mesh& start : {tetrahedron(), octahedron()}) {
        tri_mesh m = start;
        CHECK(euler_characteristic(m) == 2);
        for (int level = 1; level <= 3; ++level) {
            CAPTURE(level);
            const size_t v = m.positions.size(), e = app::count_edges(m), f = m.triangles.size();
            tri_mesh next = app::loop_subdivide(m, 1);
            CHECK(next.triangles.size() == 4 * f);
            CHECK(next.positions.size() == v + e);
            CHECK(app::count_edges(next) == 2 * e + 3 * f); // each edge splits in two, 3 new per triangle
            CHECK(euler_characteristic(next) == 2);
            m = next;
        }
    }
    // By hand for the tetrahedron: (V, E, F) = (4, 6, 4) -> (10, 24, 16) -> (34, 96, 64).
    tri_mesh two = app::loop_subdivide(tetrahedron(), 2);
    CHECK(two.positions.size() == 34);
    CHECK(two.triangles.size() == 64);
    CHECK(app::count_edges(two) == 96);
    // Zero levels: the mesh unchanged.
    tri_mesh zero = app::loop_subdivide(octahedron(), 0);
    CHECK(zero.positions.size() == 6);
    CHECK(zero.triangles == octahedron().triangles);
}

TEST_CASE("loop: one level of the regular octahedron, positions by hand") {
    tri_mesh m = app::loop_subdivide(octahedron(), 1);
    REQUIRE(m.positions.size() == 18);
    // An old vertex has valence 4 and its neighbours sum to zero: (1 - 4 * 31/256) (1, 0, 0) = (33/64, 0, 0).
    check_point(m.positions[0], vec3(33.0 / 64, 0, 0));
    check_point(m.positions[5], vec3(0, 0, -33.0 / 64));
    // Triangle 0 = (+x, +y, +z) becomes (+x, m0, m2) first, m0 on the edge +x +y, m2 on +z +x.
    // Edge +x +y has opposite vertices +z and -z: 3/8 ((1,0,0) + (0,1,0)) + 1/8 (0, 0, 0) = (3/8, 3/8, 0).
    const auto& t0 = m.triangles[0];
    CHECK(t0[0] == 0u);
    check_point(m.positions[t0[1]], vec3(3.0 / 8, 3.0 / 8, 0));
    check_point(m.positions[t0[2]], vec3(3.0 / 8, 0, 3.0 / 8));
    // The middle triangle of the four is (m0, m1, m2); m1 on the edge +y +z.
    CHECK(m.triangles[3][0] == t0[1]);
    CHECK(m.triangles[3][2] == t0[2]);
    check_point(m.positions[m.triangles[3][1]], vec3(0, 3.0 / 8, 3.0 / 8));
}

TEST_CASE("loop: a single triangle, all boundary") {
    tri_mesh m;
    m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
    m.triangles = {{0, 1, 2}};
    tri_mesh s = app::loop_subdivide(m, 1);
    REQUIRE(s.positions.size() == 6);
    // Corners: 3/4 v + 1/8 (its two neighbours).
    check_point(s.positions[0], vec3(1.0 / 8, 1.0 / 8, 0));
    check_point(s.positions[1], vec3(3.0 / 4, 1.0 / 8, 0));
    check_point(s.positions[2], vec3(1.0 / 8, 3.0 / 4, 0));
    // Edges in (min, max) order: 01 -> 3, 02 -> 4, 12 -> 5, each at its midpoint.
    check_point(s.positions[3], vec3(0.5, 0, 0));
    check_point(s.positions[4], vec3(0, 0.5, 0));
    check_point(s.positions[5], vec3(0.5, 0.5, 0));
    // (0, 1, 2) with m0 = 3 (01), m1 = 5 (12), m2 = 4 (20): orientation kept.
    using tri = std::array<uint32_t, 3>;
    CHECK(s.triangles == std::vector<tri>{{0, 3, 4}, {3, 1, 5}, {4, 5, 2}, {3, 5, 4}});
}

TEST_CASE("loop: two triangles sharing an edge: the interior edge uses the 3/8-1/8 rule, corners only boundary neighbours") {
    tri_mesh m;
    m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 1, 1)};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    tri_mesh s = app::loop_subdivide(m, 1);
    // Edges sorted: 01, 02, 03, 12, 23 -> vertices 4..8.
    REQUIRE(s.positions.size() == 9);
    // Interior edge 02, opposite 1 and 3: 3/8 (1, 1, 0) + 1/8 ((1, 0, 0) + (0, 1, 1)) = (1/2, 1/2, 1/8).
    check_point(s.positions[5], vec3(0.5, 0.5, 0.125));
    // Boundary edges: midpoints.
    check_point(s.positions[4], vec3(0.5, 0, 0));
    check_point(s.positions[7], vec3(1, 0.5, 0));
    // Vertex 0: boundary neighbours 1 and 3 (not 2, across the interior edge): 1/8 (1, 1, 1).
    check_point(s.positions[0], vec3(0.125, 0.125, 0.125));
    // Vertex 2: 3/4 (1, 1, 0) + 1/8 ((1, 0, 0) + (0, 1, 1)) = (7/8, 7/8, 1/8).
    check_point(s.positions[2], vec3(0.875, 0.875, 0.125));
    // Two levels: a 5 x 5 grid of vertices, 32 triangles.
    tri_mesh two = app::loop_subdivide(m, 2);
    CHECK(two.positions.size() == 25);
    CHECK(two.triangles.size() == 32);
}

TEST_CASE("loop: non-manifold and degenerate inputs are refused with the vertex numbers counted from 1") {
    tri_mesh fin; // three triangles on the edge 0-1
    fin.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1)};
    fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    check_refused(fin, "non-manifold edge between vertices 1 and 2: 3 triangles");

    tri_mesh bowtie; // two triangles touching only at vertex 0
    bowtie.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(-1, 0, 0), vec3(-1, -1, 0)};
    bowtie.triangles = {{0, 1, 2}, {0, 3, 4}};
    check_refused(bowtie, "non-manifold vertex 1: it lies on 4 boundary edges");

    tri_mesh repeated = tetrahedron();
    repeated.triangles[2] = {0, 2, 2};
    check_refused(repeated, "triangle 3 (vertices 1, 3, 3) repeats a vertex");

    tri_mesh out_of_range = tetrahedron();
    out_of_range.triangles[1][2] = 4;
    check_refused(out_of_range, "triangle 2 uses vertex 5 but there are only 4 vertices");

    tri_mesh nan = tetrahedron();
    nan.positions[3] = vec3(0, std::nan(""), 0);
    check_refused(nan, "vertex 4 has a non-finite coordinate");

    CHECK_THROWS_AS(app::loop_subdivide(tetrahedron(), -1), rt::scene_error);
}

TEST_CASE("loop: an unused vertex keeps its position, duplicated positions are not welded") {
    tri_mesh m;
    // Two triangles forming a square, but the diagonal's vertices repeated under new indices:
    // the index topology is two separate triangles, each all boundary.
    m.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(1, 1, 0), vec3(0, 0, 0), vec3(1, 1, 0), vec3(0, 1, 0),
                   vec3(5, 5, 5)};
    m.triangles = {{0, 1, 2}, {3, 4, 5}};
    tri_mesh s = app::loop_subdivide(m, 1);
    CHECK(s.positions.size() == 7 + 6);
    check_point(s.positions[6], vec3(5, 5, 5));
    // Vertex 0 is a corner of its own triangle: 3/4 (0,0,0) + 1/8 ((1,0,0) + (1,1,0)) = (1/4, 1/8, 0);
    // welded, it would have had boundary neighbours 1 and 5 instead.
    check_point(s.positions[0], vec3(0.25, 0.125, 0));
}

TEST_CASE("loop: OBJ text out and back in") {
    tri_mesh m;
    m.positions = {vec3(0, 0.5, -1), vec3(0.1, 1e-3, 250), vec3(-3.25, 2, 0)};
    m.triangles = {{0, 1, 2}};
    // Shortest round-trip float text; 1-based faces.
    CHECK(app::encode_obj(m, "three") == "# three\nv 0 0.5 -1\nv 0.1 0.001 250\nv -3.25 2 0\nf 1 2 3\n");

    test::scratch_dir dir("obj");
    const std::string path = (dir.path / "tri.obj").string();
    app::write_obj(path, m);
    tri_mesh back = app::read_obj(path);
    REQUIRE(back.positions.size() == 3);
    CHECK(back.triangles == m.triangles);
    // Read back as floats (tinyobjloader's real_t). Float literals, not float(double) casts: GCC 12.2
    // at -O2 folds vectorized double(float(x)) pairs back to x.
    check_point(back.positions[0], vec3(0.0f, 0.5f, -1.0f));
    check_point(back.positions[1], vec3(0.1f, 1e-3f, 250.0f));
    check_point(back.positions[2], vec3(-3.25f, 2.0f, 0.0f));

    // A quad is fanned into two triangles; negative (relative) indices are resolved.
    tri_mesh quad = app::read_obj(dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n"));
    CHECK(quad.triangles.size() == 2);
    CHECK(app::count_edges(quad) == 5);
}

TEST_CASE("loop: malformed OBJ files are refused with the file name") {
    test::scratch_dir dir("badobj");
    auto check_bad = [&](const std::string& name, const std::string& text, const std::string& fragment) {
        const std::string path = dir.write(name, text);
        CAPTURE(name);
        CHECK_THROWS_WITH_AS(app::read_obj(path), doctest::Contains(fragment.c_str()), rt::scene_error);
        CHECK_THROWS_WITH_AS(app::read_obj(path), doctest::Contains(path.c_str()), rt::scene_error);
    };
    check_bad("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", ":2: malformed OBJ file: 'nan' in a 'v' line is not a finite number");
    check_bad("word.obj", "v 0 0 0\nv 1 0 0\nv 0 x1 0\nf 1 2 3\n", ":3: malformed OBJ file: 'x1'");
    check_bad("short.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", ":1: malformed OBJ file: a 'v' line needs 3 numbers");
    check_bad("edge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", ":4: malformed OBJ file: a face has 2 corners");
    check_bad("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", ":4: malformed OBJ file: vertex index 9 is out of range");
    check_bad("empty.obj", "# nothing\n", "has no faces");
    CHECK_THROWS_WITH_AS(app::read_obj((dir.path / "missing.obj").string()), doctest::Contains("missing.obj"),
                         rt::scene_error);
}

} // namespace test_loop_subdivision
