// CENG795 XML scenes (rtweekend/io/xml_scene.h): every level-1 element, cameras, ids and offsets,
// smooth normals, layout independence (comments, CRLF, one line), and one error per kind of bad
// input, each naming the file, the element and the problem.

#include <rtweekend/mesh.h>
#include <rtweekend/sphere.h>
#include <rtweekend/io/xml_scene.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace test_xml_scene {

using namespace rt;

namespace {

const std::string xml_dir = std::string(RTWEEKEND_TEST_DATA) + "/xml";
const double pi_ = 3.14159265358979323846;

// `text` with every `from` replaced by `to`.
std::string replace_all(std::string text, const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

// `text` with the whitespace between two numbers ("1 2", "0\n  -1") replaced by a comment.
std::string comments_between_numbers(const std::string& text) {
    auto digit = [&](size_t i) { return i < text.size() && text[i] >= '0' && text[i] <= '9'; };
    std::string out;
    for (size_t i = 0; i < text.size();) {
        size_t j = i;
        while (j < text.size() && (text[j] == ' ' || text[j] == '\t' || text[j] == '\n')) ++j;
        if (j > i && i > 0 && digit(i - 1) && (digit(j) || (text[j] == '-' && digit(j + 1)))) {
            out += "<!-- c -->";
            i = j;
        } else if (j > i) {
            out.append(text, i, j - i);
            i = j;
        } else {
            out += text[i++];
        }
    }
    return out;
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Exactly equal, or within a relative `eps` (absolute near 0).
void check_vec(const vec3& v, double x, double y, double z, double eps = 0) {
    if (eps == 0) {
        CHECK(v.x() == x);
        CHECK(v.y() == y);
        CHECK(v.z() == z);
    } else {
        CHECK(v.x() == doctest::Approx(x).epsilon(eps));
        CHECK(v.y() == doctest::Approx(y).epsilon(eps));
        CHECK(v.z() == doctest::Approx(z).epsilon(eps));
    }
}

const whitted_material& params_of(const std::shared_ptr<material>& m) {
    auto s = std::dynamic_pointer_cast<whitted_material>(m);
    REQUIRE(s);
    return *s;
}

// Everything a scene holds, as text: two scenes that dump alike are the same scene (materials
// are numbered by first use, so sharing is compared too).
std::string dump(const whitted_scene& s) {
    std::ostringstream o;
    o.precision(17);
    std::map<const material*, int> ids;
    auto mat = [&](const std::shared_ptr<material>& m) {
        auto it = ids.emplace(m.get(), int(ids.size())).first;
        const whitted_material& p = params_of(m);
        o << " material#" << it->second << " kind " << int(p.kind) << " " << p.ambient << " " << p.diffuse << " "
          << p.specular << " " << p.phong_exponent << " " << p.mirror << " " << p.refraction_index << " "
          << p.absorption_index << " " << p.absorption_coefficient;
    };
    o << "background " << s.background << " eps " << s.shadow_ray_epsilon << " " << s.intersection_test_epsilon
      << " depth " << s.max_recursion_depth << " ambient " << s.ambient_light << "\n";
    for (const auto& l : s.lights) o << "light " << l.position << " " << l.intensity << "\n";
    for (const auto& c : s.cameras)
        o << "camera " << c.position << " " << c.gaze << " " << c.up << " " << c.left << " " << c.right << " "
          << c.bottom << " " << c.top << " " << c.near_distance << " " << c.width << "x" << c.height << " "
          << c.image_name << "\n";
    for (const auto& obj : s.world.objects) {
        if (auto m = std::dynamic_pointer_cast<triangle_mesh>(obj)) {
            o << "mesh smooth " << m->smooth_shading;
            mat(m->mat);
            o << "\n";
            for (const auto& p : m->positions) o << "  p " << p << "\n";
            for (const auto& f : m->faces) o << "  f " << f[0] << " " << f[1] << " " << f[2] << "\n";
            for (const auto& n : m->normals) o << "  n " << n << "\n";
            for (const auto& f : m->face_normals) o << "  fn " << f[0] << " " << f[1] << " " << f[2] << "\n";
        } else if (auto sp = std::dynamic_pointer_cast<sphere>(obj)) {
            o << "sphere " << sp->center() << " " << sp->radius();
            mat(sp->mat());
            o << "\n";
        } else {
            o << "other\n";
        }
    }
    return o.str();
}

// The corners of face f of a mesh, as points.
std::array<point3, 3> corners(const triangle_mesh& m, size_t f) {
    return {m.positions[m.faces[f][0]], m.positions[m.faces[f][1]], m.positions[m.faces[f][2]]};
}

void check_corners(const triangle_mesh& m, size_t f, const point3& a, const point3& b, const point3& c) {
    auto k = corners(m, f);
    check_vec(k[0], a.x(), a.y(), a.z());
    check_vec(k[1], b.x(), b.y(), b.z());
    check_vec(k[2], c.x(), c.y(), c.z());
}

const std::string default_camera = R"(<Camera id="1">
      <Position>0 0 0</Position>
      <Gaze>0 0 -1</Gaze>
      <Up>0 1 0</Up>
      <NearPlane>-1 1 -1 1</NearPlane>
      <NearDistance>1</NearDistance>
      <ImageResolution>8 8</ImageResolution>
      <ImageName>x.png</ImageName>
    </Camera>)";

// A small valid scene: camera 1 (lines 4-12), materials 1-3 (lines 15-17), vertices 1-3, then
// `extra` (from line 20) and `objects` (from line 21 when there is no extra).
std::string scene_with(const std::string& objects, const std::string& camera = default_camera,
                       const std::string& extra = "") {
    return "<?xml version=\"1.0\"?>\n<Scene>\n  <Cameras>\n    " + camera + "\n  </Cameras>\n" +
           "  <Materials>\n"
           "    <Material id=\"1\"><DiffuseReflectance>1 1 1</DiffuseReflectance></Material>\n"
           "    <Material id=\"2\" type=\"mirror\"><MirrorReflectance>1 1 1</MirrorReflectance></Material>\n"
           "    <Material id=\"3\"/>\n"
           "  </Materials>\n"
           "  <VertexData>0 0 -2  1 0 -2  0 1 -2</VertexData>\n" +
           extra + "  <Objects>\n" + objects + "\n  </Objects>\n</Scene>\n";
}

// Loads `text` as bad.xml and checks the single-line message names the file (and the line, when
// given) and contains every fragment.
void check_xml_error(const std::string& text, const std::vector<std::string>& fragments, int line = 0) {
    test::scratch_dir dir("error");
    std::string path = dir.write("bad.xml", text);
    std::string message;
    try {
        load_xml_scene(path);
    } catch (const scene_error& e) {
        message = e.what();
    }
    CAPTURE(text);
    CAPTURE(message);
    REQUIRE(!message.empty());
    CHECK(message.find('\n') == std::string::npos);
    CHECK(message.rfind(path + (line ? ":" + std::to_string(line) + ":" : std::string()), 0) == 0);
    for (const auto& f : fragments) {
        CAPTURE(f);
        CHECK(message.find(f) != std::string::npos);
    }
}

} // namespace

TEST_CASE("xml scene: every level-1 element of the test scene") {
    whitted_scene s = load_xml_scene(xml_dir + "/scene.xml");
    check_vec(s.background, 10, 20, 30);
    CHECK(s.shadow_ray_epsilon == 1e-2);
    CHECK(s.intersection_test_epsilon == 1e-6); // the default
    CHECK(s.max_recursion_depth == 6);
    check_vec(s.ambient_light, 25, 25, 25);

    REQUIRE(s.lights.size() == 2);
    check_vec(s.lights[0].position, 0, 5, 0);
    check_vec(s.lights[0].intensity, 1000, 900, 800);
    check_vec(s.lights[1].position, -3, 4, 5);
    check_vec(s.lights[1].intensity, 50, 50, 50);

    REQUIRE(s.cameras.size() == 2);
    const view_camera& a = s.cameras[0];
    check_vec(a.position, 0, 0, 10);
    check_vec(a.gaze, 0, 0, -1);
    check_vec(a.up, 0, 1, 0);
    CHECK(a.left == -1);
    CHECK(a.right == 1);
    CHECK(a.bottom == -0.5);
    CHECK(a.top == 0.5); // the 5th NearPlane number is ignored
    CHECK(a.near_distance == 2);
    CHECK(a.width == 400);
    CHECK(a.height == 200);
    CHECK(a.image_name == "plain.png");
    // lookAt: gaze towards the point; a symmetric plane of aspect 640/480 at the near distance.
    const view_camera& b = s.cameras[1];
    check_vec(b.position, 1, 2, 3);
    check_vec(b.gaze, 0, 0, -10);
    check_vec(b.up, 0, 1, 0);
    double top = 1.5 * std::tan(60.0 / 2 * pi_ / 180);
    CHECK(b.top == doctest::Approx(top).epsilon(1e-15));
    CHECK(b.bottom == doctest::Approx(-top).epsilon(1e-15));
    CHECK(b.right == doctest::Approx(top * 640 / 480).epsilon(1e-15));
    CHECK(b.left == doctest::Approx(-top * 640 / 480).epsilon(1e-15));
    CHECK(b.near_distance == 1.5);
    CHECK(b.width == 640);
    CHECK(b.height == 480);
    CHECK(b.image_name == "look_at.ppm");

    // World: Mesh 1, Mesh 2 (PLY), the triangles of material 3, the sphere, the triangle of material 1.
    REQUIRE(s.world.objects.size() == 5);
    auto mesh1 = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[0]);
    auto mesh2 = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[1]);
    auto tris3 = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[2]);
    auto ball = std::dynamic_pointer_cast<sphere>(s.world.objects[3]);
    auto tris1 = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[4]);
    REQUIRE((mesh1 && mesh2 && tris3 && ball && tris1));

    const point3 v1(-1, 0, 0), v2(1, 0, 0), v3(0, 1, 0), v4(0, 0, -1), v5(5, 5, 5);
    // vertexOffset -1: ids 2 3 4 / 2 4 5 are vertices 1 2 3 / 1 3 4.
    REQUIRE(mesh1->faces.size() == 2);
    check_corners(*mesh1, 0, v1, v2, v3);
    check_corners(*mesh1, 1, v1, v3, v4);
    CHECK_FALSE(mesh1->smooth_shading);
    CHECK(mesh1->normals.empty());
    const whitted_material& m1 = params_of(mesh1->mat);
    CHECK(m1.kind == whitted_material::kind_t::plain);
    check_vec(m1.ambient, 1, 1, 1);
    check_vec(m1.diffuse, 0.5, 0.25, 0.125);
    check_vec(m1.specular, 1, 1, 1);
    CHECK(m1.phong_exponent == 50);
    CHECK(tris1->mat == mesh1->mat); // one shared surface per XML material
    REQUIRE(tris1->faces.size() == 1);
    check_corners(*tris1, 0, v1, v2, v4);

    // The PLY tetrahedron, relative to the XML file's folder; vertexOffset does not apply.
    REQUIRE(mesh2->positions.size() == 4);
    REQUIRE(mesh2->faces.size() == 4);
    check_corners(*mesh2, 0, point3(0, 0, 0), point3(0, 1, 0), point3(1, 0, 0));
    check_corners(*mesh2, 3, point3(1, 0, 0), point3(0, 1, 0), point3(0, 0, 1));
    CHECK(mesh2->smooth_shading);
    REQUIRE(mesh2->normals.size() == 4);
    // Vertex 3 (0,0,1) is in faces 1 (normal (0,-1,0), |cross| 1), 2 ((-1,0,0), 1) and 3 ((1,1,1), sqrt 3):
    // the sum of the cross products is (0,0,0) + ... = (-1+1, -1+1, 0+1) = (0, 0, 1).
    check_vec(mesh2->normals[3], 0, 0, 1, 1e-15);
    const whitted_material& m2 = params_of(mesh2->mat);
    CHECK(m2.kind == whitted_material::kind_t::mirror);
    check_vec(m2.mirror, 0.9, 0.8, 0.7);
    CHECK(m2.phong_exponent == 10);

    REQUIRE(tris3->faces.size() == 2);
    check_corners(*tris3, 0, v1, v2, v3);
    check_corners(*tris3, 1, v3, v2, v4);
    const whitted_material& m3 = params_of(tris3->mat);
    CHECK(m3.kind == whitted_material::kind_t::conductor);
    check_vec(m3.mirror, 1, 0.8, 0.5);
    CHECK(m3.refraction_index == 0.37);
    CHECK(m3.absorption_index == 2.82);

    check_vec(ball->center(), v5.x(), v5.y(), v5.z());
    CHECK(ball->radius() == 0.75);
    const whitted_material& m4 = params_of(ball->mat());
    CHECK(m4.kind == whitted_material::kind_t::dielectric);
    CHECK(m4.refraction_index == 1.5);
    check_vec(m4.absorption_coefficient, 0.01, 0.02, 0.03);
    check_vec(m4.diffuse, 0, 0, 0); // absent: the default
    CHECK(m4.phong_exponent == 1);
}

TEST_CASE("xml scene: comments, CRLF, one line and element order do not change the scene") {
    const std::string pretty = read_file(xml_dir + "/scene.xml");
    const std::string expected = dump(load_xml_scene(xml_dir + "/scene.xml"));
    test::scratch_dir dir("layout");
    std::filesystem::create_directories(dir.path / "meshes");
    std::filesystem::copy_file(xml_dir + "/meshes/tetra.ply", dir.path / "meshes" / "tetra.ply");

    // A comment between every two numbers (it separates them, as whitespace does), and inside
    // elements before and after the text.
    std::string commented = comments_between_numbers(pretty);
    commented = replace_all(commented, "<Gaze>", "<Gaze><!-- looking --> ");
    commented = replace_all(commented, "</ImageName>", " <!-- the file --></ImageName>");
    REQUIRE(commented.find("1<!-- c -->0<!-- c -->0") != std::string::npos);
    std::string crlf;
    for (char c : pretty) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    std::string one_line;
    for (char c : pretty) one_line += c == '\n' ? ' ' : c;
    // Sections in reverse order: objects before vertices and materials, cameras last.
    auto section = [&](const std::string& name) {
        size_t b = pretty.find("<" + name + ">"), e = pretty.find("</" + name + ">") + name.size() + 3;
        return pretty.substr(b, e - b);
    };
    std::string reordered = "<Scene>" + section("Objects") + section("VertexData") + section("Materials") +
                            section("Lights") + "<MaxRecursionDepth>6</MaxRecursionDepth>" + section("Cameras") +
                            "<ShadowRayEpsilon>0.01</ShadowRayEpsilon><BackgroundColor>10 20 30</BackgroundColor>"
                            "</Scene>";
    // Later-level elements not read yet change nothing (each is a warning: test_course_scene.cpp),
    // nor do transformations no object names.
    std::string later = pretty;
    later.replace(later.find("<Objects>"), 9,
                  "<Transformations><Translation id=\"1\">1 2 3</Translation></Transformations>"
                  "<Textures><Images><Image id=\"1\">x.jpg</Image></Images><TextureMap id=\"1\" type=\"checkerboard\">"
                  "<DecalMode>replace_kd</DecalMode></TextureMap></Textures><Objects>"
                  "<Cylinder id=\"9\"><Material>1</Material><Transformations>t1</Transformations></Cylinder>");

    for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
             {"commented", commented}, {"crlf", crlf}, {"one_line", one_line}, {"reordered", reordered},
             {"later", later}}) {
        CAPTURE(name);
        std::string path = dir.write(name + ".xml", text);
        CHECK(dump(load_xml_scene(path)) == expected);
    }
}

TEST_CASE("xml scene: optional settings take their defaults, materials may be sparse") {
    whitted_scene s = load_xml_scene(test::scratch_dir("defaults").write("d.xml", scene_with("")));
    check_vec(s.background, 0, 0, 0);
    CHECK(s.shadow_ray_epsilon == 1e-3);
    CHECK(s.intersection_test_epsilon == 1e-6);
    CHECK(s.max_recursion_depth == 0);
    check_vec(s.ambient_light, 0, 0, 0);
    CHECK(s.lights.empty());
    CHECK(s.world.objects.empty());
    REQUIRE(s.cameras.size() == 1);
}

TEST_CASE("xml scene: 1-based ids, vertexOffset and ZeroBasedIndexing") {
    test::scratch_dir dir("ids");
    const std::string vertices = "<VertexData>10 0 0  11 0 0  12 0 0  13 0 0  14 0 0  15 0 0</VertexData>";
    auto mesh_of = [&](const std::string& top, const std::string& faces) {
        std::string text = "<Scene>" + top + "<Cameras>" + default_camera + "</Cameras>" +
                           "<Materials><Material id=\"7\"/></Materials>" + vertices +
                           "<Objects><Mesh id=\"1\"><Material>7</Material>" + faces +
                           "</Mesh><Sphere id=\"1\"><Material>7</Material><Center>2</Center><Radius>1</Radius></Sphere>"
                           "</Objects></Scene>";
        whitted_scene s = load_xml_scene(dir.write("s.xml", text));
        REQUIRE(s.world.objects.size() == 2);
        auto m = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[0]);
        auto sp = std::dynamic_pointer_cast<sphere>(s.world.objects[1]);
        REQUIRE((m && sp));
        std::vector<double> xs;
        for (size_t f = 0; f < m->faces.size(); ++f)
            for (const point3& p : corners(*m, f)) xs.push_back(p.x());
        xs.push_back(sp->center().x());
        return xs;
    };
    // 1-based: id 1 is x = 10.
    CHECK(mesh_of("", "<Faces>1 2 3 4 5 6</Faces>") == std::vector<double>{10, 11, 12, 13, 14, 15, 11});
    CHECK(mesh_of("", "<Faces vertexOffset=\"3\">1 2 3</Faces>") == std::vector<double>{13, 14, 15, 11});
    CHECK(mesh_of("", "<Faces vertexOffset=\"-2\">3 8 5</Faces>") == std::vector<double>{10, 15, 12, 11});
    // vertexOffset on the <Mesh> element means the same; on both it is refused.
    {
        std::string text = "<Scene><Cameras>" + default_camera + "</Cameras><Materials><Material id=\"7\"/></Materials>" +
                           vertices + "<Objects><Mesh id=\"1\" vertexOffset=\"3\"><Material>7</Material>" +
                           "<Faces>1 2 3</Faces></Mesh></Objects></Scene>";
        whitted_scene s = load_xml_scene(dir.write("mesh_offset.xml", text));
        REQUIRE(s.world.objects.size() == 1);
        auto m = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[0]);
        REQUIRE(m);
        CHECK(corners(*m, 0)[0].x() == 13);
        std::string both = text;
        both.replace(both.find("<Faces>"), 7, "<Faces vertexOffset=\"1\">");
        CHECK_THROWS_WITH_AS(load_xml_scene(dir.write("both_offsets.xml", both)),
                             doctest::Contains("vertexOffset is given on both <Mesh> and <Faces>"), scene_error);
    }
    // Zero-based: id 0 is x = 10, and a sphere's center id 2 is x = 12.
    CHECK(mesh_of("<ZeroBasedIndexing>true</ZeroBasedIndexing>", "<Faces>0 1 5</Faces>") ==
          std::vector<double>{10, 11, 15, 12});
    CHECK(mesh_of("<ZeroBasedIndexing>false</ZeroBasedIndexing>", "<Faces>1 2 6</Faces>") ==
          std::vector<double>{10, 11, 15, 11});
}

TEST_CASE("xml scene: smooth shading gives area-weighted vertex normals") {
    // Vertex 1 is shared by a face in the z = 0 plane (cross product (0,0,4), area 2) and one in
    // the x = 0 plane (cross product (-1,0,0), area 1/2): its normal is (-1,0,4)/sqrt(17).
    test::scratch_dir dir("smooth");
    std::string text = "<Scene><Cameras>" + default_camera +
                       "</Cameras><Materials><Material id=\"1\"/></Materials>"
                       "<VertexData>0 0 0  2 0 0  0 2 0  0 0 1  0 1 0</VertexData><Objects>"
                       "<Mesh id=\"1\" shadingMode=\"smooth\"><Material>1</Material><Faces>1 2 3  1 4 5</Faces></Mesh>"
                       "<Mesh id=\"2\" shadingMode=\"flat\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>"
                       "</Objects></Scene>";
    whitted_scene s = load_xml_scene(dir.write("s.xml", text));
    REQUIRE(s.world.objects.size() == 2);
    auto m = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[0]);
    REQUIRE(m);
    CHECK(m->smooth_shading);
    CHECK(m->face_normals == m->faces);
    auto normal_at = [&](const point3& p) {
        for (size_t f = 0; f < m->faces.size(); ++f)
            for (size_t k = 0; k < 3; ++k)
                if ((m->positions[m->faces[f][k]] - p).length_squared() == 0) return m->normals[m->face_normals[f][k]];
        FAIL("no corner at " << p);
        return vec3();
    };
    double r = std::sqrt(17.0);
    check_vec(normal_at(point3(0, 0, 0)), -1 / r, 0, 4 / r, 1e-15);
    check_vec(normal_at(point3(2, 0, 0)), 0, 0, 1);
    check_vec(normal_at(point3(0, 2, 0)), 0, 0, 1);
    check_vec(normal_at(point3(0, 0, 1)), -1, 0, 0);
    check_vec(normal_at(point3(0, 1, 0)), -1, 0, 0);
    auto flat = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[1]);
    REQUIRE(flat);
    CHECK_FALSE(flat->smooth_shading);
    CHECK(flat->normals.empty());

    // set_smooth_normals itself. Vertex 0: cross products (0,0,2), (0,0,-1), (0,0,-1) cancel, so it
    // takes its largest face's normal; vertex 2: (0,0,2) + (0,0,-1); vertex 6 is in a zero-area face
    // only, vertex 8 in none.
    triangle_mesh t;
    t.positions = {point3(0, 0, 0),  point3(2, 0, 0), point3(0, 1, 0), point3(1, 0, 0), point3(0, -1, 0),
                   point3(-1, 0, 0), point3(5, 5, 5), point3(6, 6, 6), point3(9, 9, 9)};
    t.faces = {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}, {6, 7, 6}};
    set_smooth_normals(t);
    CHECK(t.smooth_shading);
    CHECK(t.face_normals == t.faces);
    REQUIRE(t.normals.size() == 9);
    check_vec(t.normals[0], 0, 0, 1);
    check_vec(t.normals[1], 0, 0, 1);
    check_vec(t.normals[2], 0, 0, 1);
    check_vec(t.normals[3], 0, 0, -1);
    check_vec(t.normals[4], 0, 0, -1);
    check_vec(t.normals[6], 0, 0, 0);
    check_vec(t.normals[8], 0, 0, 0);
    t.faces.push_back({0, 1, 9});
    CHECK_THROWS_WITH_AS(set_smooth_normals(t), doctest::Contains("face 4 uses vertex 9"), scene_error);
}

TEST_CASE("xml scene: a file that cannot be read or is not well-formed XML") {
    test::scratch_dir dir("files");
    CHECK_THROWS_WITH_AS(load_xml_scene((dir.path / "nope.xml").string()),
                         doctest::Contains("nope.xml: cannot open XML scene file"), scene_error);
    CHECK_THROWS_WITH_AS(load_xml_scene(dir.path.string()), doctest::Contains("is a directory"), scene_error);
    check_xml_error("", {"malformed XML", "No document element found"}, 1);
    check_xml_error("<Scene>\n<Cameras>\n</Camera>\n</Scene>\n", {"malformed XML", "Start-end tags mismatch"}, 3);
    check_xml_error("<Scene>\r\n<Cameras>\r\n<Camera>\r\n<Position>1 2 3</Position>\r\n</Scene>\r\n",
                    {"malformed XML", "mismatch"}, 5);
    check_xml_error("<Scene>\n  <!-- unclosed comment\n</Scene>\n", {"malformed XML", "Error parsing comment"}, 3);
    check_xml_error("<Scenery>\n</Scenery>\n", {"<Scenery>", "root element must be <Scene>"}, 1);
}

TEST_CASE("xml scene: a missing required element") {
    check_xml_error("<Scene>\n<Cameras/>\n</Scene>", {"<Scene>: no camera"}, 1);
    std::string camera = default_camera;
    camera.replace(camera.find("<Position>"), 26, "");
    check_xml_error(scene_with("", camera), {"<Camera id=\"1\">: missing <Position>"}, 4);
    check_xml_error(scene_with("", replace_all(default_camera, "<ImageName>x.png", "<ImageName> ")),
                    {"<Camera id=\"1\">: <ImageName> is empty"}, 11);
    check_xml_error(scene_with("<Sphere id=\"4\"><Material>1</Material><Center>1</Center></Sphere>"),
                    {"<Sphere id=\"4\">: missing <Radius>"}, 21);
    check_xml_error(scene_with("<Mesh id=\"5\">\n<Material>1</Material></Mesh>"), {"<Mesh id=\"5\">: missing <Faces>"}, 21);
    check_xml_error(scene_with("<Triangle id=\"6\"><Indices>1 2 3</Indices></Triangle>"),
                    {"<Triangle id=\"6\">: missing <Material>"});
    check_xml_error(scene_with("", default_camera, "<Lights><PointLight id=\"2\"><Position>0 0 0</Position></PointLight></Lights>"),
                    {"<PointLight id=\"2\">: missing <Intensity>"}, 20);
    check_xml_error(scene_with("", default_camera, "<Materials><Material type=\"mirror\"/></Materials>"),
                    {"<Material>: missing attribute id"}, 20);
    check_xml_error(scene_with("", default_camera, "<Materials><Material id=\"8\" type=\"dielectric\"/></Materials>"),
                    {"<Material id=\"8\">: missing <RefractionIndex>"});
    check_xml_error(scene_with("", replace_all(default_camera, "<Gaze>0 0 -1</Gaze>", "")),
                    {"<Camera id=\"1\">: missing <Gaze>"});
    check_xml_error(scene_with("", "<Camera id=\"3\" type=\"lookAt\"><Position>0 0 0</Position><Up>0 1 0</Up>"
                                   "<GazePoint>0 0 -1</GazePoint><NearDistance>1</NearDistance>"
                                   "<ImageResolution>4 4</ImageResolution><ImageName>a.png</ImageName></Camera>"),
                    {"<Camera id=\"3\">: missing <FovY>"});
}

TEST_CASE("xml scene: a malformed number, or too few or too many") {
    auto camera_with = [](const std::string& from, const std::string& to) {
        return scene_with("", replace_all(default_camera, from, to));
    };
    check_xml_error(camera_with("<Position>0 0 0", "<Position>1.0x 0 0"), {"<Camera id=\"1\">: <Position>: '1.0x' is not a number"}, 5);
    check_xml_error(camera_with("<Position>0 0 0", "<Position>0 nan 0"), {"<Position>: 'nan' is not a finite number"});
    check_xml_error(camera_with("<Position>0 0 0", "<Position>0 0 -inf"), {"<Position>: '-inf' is not a finite number"});
    check_xml_error(camera_with("<Position>0 0 0", "<Position>0 0 1e400"), {"<Position>: '1e400' is beyond the range of a double"});
    check_xml_error(camera_with("<Position>0 0 0", "<Position>0 0"), {"<Position> has 2 numbers, expected 3"}, 5);
    check_xml_error(camera_with("<Position>0 0 0", "<Position>0 0 0 1"), {"<Position> has 4 numbers, expected 3"});
    check_xml_error(camera_with("<NearPlane>-1 1 -1 1", "<NearPlane>-1 1 -1 1 5 6"), {"<NearPlane> has 6 numbers, expected 4 or 5"});
    check_xml_error(camera_with("<NearPlane>-1 1 -1 1", "<NearPlane>-1 1 -1"), {"<NearPlane> has 3 numbers, expected 4 or 5"});
    check_xml_error(camera_with("<ImageResolution>8 8", "<ImageResolution>8.5 8"), {"<ImageResolution>: '8.5' is not a whole number"});
    check_xml_error(camera_with("<ImageResolution>8 8", "<ImageResolution>8 8 3"), {"<ImageResolution> has 3 numbers, expected 2"});
    check_xml_error(camera_with("<Position>0 0 0", "<Position>0 <X>0</X> 0"), {"unexpected element <X> inside <Position>"});
    check_xml_error(scene_with("<Sphere id=\"1\"><Material>1.5</Material><Center>1</Center><Radius>1</Radius></Sphere>"),
                    {"<Sphere id=\"1\">: <Material>: '1.5' is not a whole number"}, 21);
}

TEST_CASE("xml scene: a value out of range") {
    auto camera_with = [](const std::string& from, const std::string& to) {
        return scene_with("", replace_all(default_camera, from, to));
    };
    check_xml_error(scene_with("<Sphere id=\"2\"><Material>1</Material><Center>1</Center><Radius>-1</Radius></Sphere>"),
                    {"<Sphere id=\"2\">: <Radius> must be positive, not -1"}, 21);
    check_xml_error(scene_with("<Sphere id=\"2\"><Material>1</Material><Center>1</Center><Radius>0</Radius></Sphere>"),
                    {"<Radius> must be positive, not 0"});
    check_xml_error(camera_with("<ImageResolution>8 8", "<ImageResolution>-8 8"),
                    {"<Camera id=\"1\">: <ImageResolution> -8 8: width and height must be between 1 and"}, 10);
    check_xml_error(camera_with("<ImageResolution>8 8", "<ImageResolution>8 0"), {"<ImageResolution> 8 0"});
    check_xml_error(camera_with("<NearDistance>1", "<NearDistance>0"), {"<NearDistance> must be positive, not 0"});
    check_xml_error(camera_with("<NearPlane>-1 1 -1 1", "<NearPlane>1 1 -1 1"), {"<NearPlane> has zero width or height"});
    check_xml_error(camera_with("<Gaze>0 0 -1", "<Gaze>0 0 0"), {"<Gaze> is the zero vector"});
    check_xml_error(camera_with("<Up>0 1 0", "<Up>0 0 2"), {"<Up> is parallel to the gaze direction"}, 7);
    check_xml_error(scene_with("", "<Camera id=\"3\" type=\"lookAt\"><Position>0 0 0</Position><Up>0 1 0</Up>"
                                   "<GazePoint>0 0 -1</GazePoint><FovY>180</FovY><NearDistance>1</NearDistance>"
                                   "<ImageResolution>4 4</ImageResolution><ImageName>a.png</ImageName></Camera>"),
                    {"<Camera id=\"3\">: <FovY> must be between 0 and 180 degrees, not 180"});
    check_xml_error(scene_with("", "<Camera id=\"3\" type=\"lookAt\"><Position>1 1 1</Position><Up>0 1 0</Up>"
                                   "<GazePoint>1 1 1</GazePoint><FovY>45</FovY><NearDistance>1</NearDistance>"
                                   "<ImageResolution>4 4</ImageResolution><ImageName>a.png</ImageName></Camera>"),
                    {"<GazePoint> is the camera's <Position>"});
    check_xml_error(camera_with("<Camera id=\"1\">", "<Camera id=\"1\" type=\"orthographic\">"),
                    {"unknown camera type 'orthographic'"}, 4);
    check_xml_error(scene_with("", default_camera, "<MaxRecursionDepth>-1</MaxRecursionDepth>"),
                    {"<Scene>: <MaxRecursionDepth> must be between 0 and 1000000, not -1"}, 20);
    check_xml_error(scene_with("", default_camera, "<BackgroundColor>0 -1 0</BackgroundColor>"),
                    {"<Scene>: <BackgroundColor> must not be negative (0 -1 0)"});
    check_xml_error(scene_with("", default_camera, "<ShadowRayEpsilon>-0.1</ShadowRayEpsilon>"),
                    {"<ShadowRayEpsilon> must be non-negative, not -0.1"});
    check_xml_error(scene_with("", default_camera, "<ZeroBasedIndexing>maybe</ZeroBasedIndexing>"),
                    {"<ZeroBasedIndexing> must be true or false, not 'maybe'"});
    check_xml_error(scene_with("", default_camera,
                               "<Materials><Material id=\"9\" type=\"conductor\"><RefractionIndex>0</RefractionIndex>"
                               "</Material></Materials>"),
                    {"<Material id=\"9\">: <RefractionIndex> must be positive, not 0"});
    check_xml_error(scene_with("", default_camera, "<Materials><Material id=\"9\" type=\"glass\"/></Materials>"),
                    {"<Material id=\"9\">: unknown material type 'glass'"});
    check_xml_error(scene_with("", default_camera,
                               "<Lights><PointLight id=\"3\"><Position>0 0 0</Position><Intensity>1 -1 1</Intensity>"
                               "</PointLight></Lights>"),
                    {"<PointLight id=\"3\">: <Intensity> must not be negative"});
}

TEST_CASE("xml scene: an id that does not exist, or is defined twice") {
    check_xml_error(scene_with("<Sphere id=\"2\">\n<Material>7</Material><Center>1</Center><Radius>1</Radius></Sphere>"),
                    {"<Sphere id=\"2\">: <Material> 7 does not exist (the file defines materials 1-3)"}, 22);
    check_xml_error(scene_with("<Sphere id=\"2\"><Material>1</Material><Center>4</Center><Radius>1</Radius></Sphere>"),
                    {"<Sphere id=\"2\">: <Center> vertex 4 does not exist (the file defines vertices 1-3)"}, 21);
    check_xml_error(scene_with("<Triangle id=\"3\"><Indices>1 0 2</Indices><Material>1</Material></Triangle>"),
                    {"<Triangle id=\"3\">: <Indices> vertex 0 does not exist (the file defines vertices 1-3)"});
    check_xml_error(scene_with("<Triangle id=\"3\"><Indices>1 2</Indices><Material>1</Material></Triangle>"),
                    {"<Indices> has 2 numbers, expected 3"});
    check_xml_error(scene_with("<Mesh id=\"4\"><Material>1</Material>\n<Faces vertexOffset=\"-1\">2 3 4  1 2 3</Faces></Mesh>"),
                    {"<Mesh id=\"4\">: <Faces> vertex 1 + vertexOffset -1 = 0 (triangle 2) does not exist (the file "
                     "defines vertices 1-3)"},
                    22);
    check_xml_error(scene_with("<Mesh id=\"4\"><Material>1</Material><Faces vertexOffset=\"two\">1 2 3</Faces></Mesh>"),
                    {"<Faces>: attribute vertexOffset=\"two\" is not a whole number"});
    check_xml_error(scene_with("", default_camera, "<Materials>\n<Material id=\"2\"/></Materials>"),
                    {"<Material id=\"2\">: material id 2 is defined twice (first on line 16)"}, 21);
    check_xml_error(scene_with("", default_camera, "<Lights><AmbientLight>1 1 1</AmbientLight></Lights><Lights>\n"
                                                   "<AmbientLight>2 2 2</AmbientLight></Lights>"),
                    {"<Lights>: <AmbientLight> appears twice"}, 21);
    check_xml_error(scene_with("<Sphere id=\"2\"><Material>1</Material><Center>1</Center><Radius>1</Radius>\n"
                               "<Radius>2</Radius></Sphere>"),
                    {"<Sphere id=\"2\">: <Radius> appears twice"}, 22);
    check_xml_error(scene_with("", default_camera, "<VertexData>1 2 3</VertexData>"), {"<VertexData> appears twice"});
    // No materials, no vertices at all.
    check_xml_error("<Scene><Cameras>" + default_camera +
                        "</Cameras><Objects><Sphere id=\"1\"><Material>1</Material></Sphere></Objects></Scene>",
                    {"<Material> 1 does not exist (the file defines no materials)"});
    check_xml_error("<Scene><Cameras>" + default_camera +
                        "</Cameras><Materials><Material id=\"1\"/><Material id=\"2\"/><Material id=\"5\"/></Materials>"
                        "<Objects><Sphere id=\"2\"><Material>3</Material></Sphere></Objects></Scene>",
                    {"<Sphere id=\"2\">: <Material> 3 does not exist (the file defines materials 1-2, 5)"});
    check_xml_error("<Scene><Cameras>" + default_camera +
                        "</Cameras><Materials><Material id=\"1\"/></Materials>"
                        "<Objects><Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere>"
                        "</Objects></Scene>",
                    {"<Center> vertex 1 does not exist (the file has no <VertexData>)"});
}

TEST_CASE("xml scene: bad faces and PLY files") {
    check_xml_error(scene_with("<Mesh id=\"1\"><Material>1</Material>\n<Faces>1 2 3 1</Faces></Mesh>"),
                    {"<Mesh id=\"1\">: <Faces> has 4 vertex ids, not a multiple of 3"}, 22);
    check_xml_error(scene_with("<Mesh id=\"1\"><Material>1</Material><Faces> <!-- none --> </Faces></Mesh>"),
                    {"<Mesh id=\"1\">: <Faces> is empty"});
    check_xml_error(scene_with("<Mesh id=\"1\"><Material>1</Material><Faces>1 2 x</Faces></Mesh>"),
                    {"<Faces>: 'x' is not a whole number"});
    check_xml_error(scene_with("<Mesh id=\"1\" shadingMode=\"phong\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>"),
                    {"<Mesh id=\"1\">: unknown shadingMode 'phong'"});
    check_xml_error(scene_with("<Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"missing.ply\"/></Mesh>"),
                    {"<Mesh id=\"1\">: <Faces plyFile=\"missing.ply\">: ", "missing.ply: cannot open PLY file"}, 21);
    check_xml_error(scene_with("<Mesh id=\"1\"><Material>1</Material><Faces plyFile=\" \"/></Mesh>"),
                    {"<Faces plyFile=\"\"> names no file"});
    check_xml_error(scene_with("<Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"a.ply\">1 2 3</Faces></Mesh>"),
                    {"<Faces> has both a plyFile and indices"});
    // A damaged PLY file beside the XML file: both files and the PLY's own problem are named.
    test::scratch_dir dir("ply");
    dir.write("broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    std::string path = dir.write(
        "scene.xml", scene_with("<Mesh id=\"1\"><Material>1</Material><Faces plyFile=\"broken.ply\"/></Mesh>"));
    CHECK_THROWS_WITH_AS(load_xml_scene(path),
                         (path + ":21: <Mesh id=\"1\">: <Faces plyFile=\"broken.ply\">: " +
                          (dir.path / "broken.ply").string() + ":13: face 0 uses vertex 7 but the file has 3 vertices")
                             .c_str(),
                         scene_error);
}

} // namespace test_xml_scene
