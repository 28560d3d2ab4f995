// The CENG795 reader's later homeworks (rtweekend/io/xml_scene.h, shared/formats/ceng795-later.md):
// transformation lists (points placed by hand-multiplied matrices), mesh instances and their
// chains, lookAt cameras with <Gaze>, handedness, a warning per element not read, and the JSON form
// (io/course_json.h) reading as its XML twin.

#include <rtweekend/mesh.h>
#include <rtweekend/sphere.h>
#include <rtweekend/transform.h>
#include <rtweekend/course/whitted.h>
#include <rtweekend/image/image_read.h>
#include <rtweekend/image/tonemap.h>
#include <rtweekend/io/xml_scene.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace test_course_scene {

using namespace rt;

namespace {

const char* camera_xml = R"(<Cameras><Camera id="1">
      <Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
      <NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>
      <ImageResolution>8 8</ImageResolution><ImageName>x.png</ImageName>
    </Camera></Cameras>)";

// A scene with one camera, materials 1-3, the given transformations and vertex data, and objects.
std::string scene_xml(const std::string& transformations, const std::string& vertices, const std::string& objects) {
    return std::string("<Scene>\n") + camera_xml + "\n" +
           "<Lights><PointLight id=\"1\"><Position>0 0 0</Position><Intensity>100 100 100</Intensity></PointLight></Lights>\n" +
           "<Materials><Material id=\"1\"><DiffuseReflectance>1 0 0</DiffuseReflectance></Material>"
           "<Material id=\"2\"><DiffuseReflectance>0 1 0</DiffuseReflectance></Material>"
           "<Material id=\"3\"><DiffuseReflectance>0 0 1</DiffuseReflectance></Material></Materials>\n"
           "<Transformations>" + transformations + "</Transformations>\n"
           "<VertexData>" + vertices + "</VertexData>\n<Objects>" + objects + "</Objects>\n</Scene>\n";
}

whitted_scene load_text(const std::string& text, const std::string& name = "scene.xml") {
    test::scratch_dir dir("course_scene");
    return load_xml_scene(dir.write(name, text));
}

std::string error_of(const std::string& text, const std::string& name = "bad.xml") {
    try {
        load_text(text, name);
    } catch (const scene_error& e) {
        return e.what();
    }
    return "";
}

// Where object `obj` (a transform node or a bare object) takes the object-space point p.
point3 placed(const std::shared_ptr<hittable>& obj, const point3& p) {
    if (auto t = std::dynamic_pointer_cast<transform>(obj)) return t->linear() * p + t->offset();
    return p;
}

std::shared_ptr<hittable> inner(const std::shared_ptr<hittable>& obj) {
    if (auto t = std::dynamic_pointer_cast<transform>(obj)) return t->object();
    return obj;
}

std::string replace_tmo(std::string text, const std::string& tmo) {
    const size_t at = text.find("Photographic");
    return text.replace(at, 12, tmo);
}

bool same(const vec3& a, const vec3& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); }

void check_point(const point3& got, double x, double y, double z) {
    CHECK(got.x() == doctest::Approx(x).epsilon(1e-12).scale(1));
    CHECK(got.y() == doctest::Approx(y).epsilon(1e-12).scale(1));
    CHECK(got.z() == doctest::Approx(z).epsilon(1e-12).scale(1));
}

} // namespace

TEST_CASE("course scene: a transformation list applies left to right, the first listed first") {
    const std::string transformations = "<Translation id=\"1\">1 0 0</Translation>"
                                        "<Rotation id=\"1\">90 0 0 1</Rotation>"
                                        "<Scaling id=\"1\">2 3 4</Scaling>"
                                        "<Composite id=\"1\">1 0 0 5  0 0 -1 6  0 1 0 7  0 0 0 1</Composite>"
                                        "<Rotation id=\"2\">90 -1 0 0</Rotation>";
    auto sphere_with = [&](const std::string& list) {
        whitted_scene s = load_text(scene_xml(transformations, "0 0 0",
                                              "<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius>"
                                              "<Transformations>" + list + "</Transformations></Sphere>"));
        REQUIRE(s.world.objects.size() == 1);
        return s.world.objects[0];
    };
    // t1 then r1: (1, 0, 0) turned 90 degrees about +z (counter-clockwise) is (0, 1, 0).
    check_point(placed(sphere_with("t1 r1"), point3(0, 0, 0)), 0, 1, 0);
    // r1 then t1: the origin stays, then moves to (1, 0, 0).
    check_point(placed(sphere_with("r1 t1"), point3(0, 0, 0)), 1, 0, 0);
    // s1 then t1 then r1 on (1, 1, 1): (2, 3, 4), (3, 3, 4), then (-3, 3, 4).
    check_point(placed(sphere_with("s1 t1 r1"), point3(1, 1, 1)), -3, 3, 4);
    // The composite by rows: (x, y, z) -> (x + 5, -z + 6, y + 7); on (1, 2, 3): (6, 3, 9).
    check_point(placed(sphere_with("c1"), point3(1, 2, 3)), 6, 3, 9);
    // 90 degrees about -x (the files write "90 -1 0 0"): +y goes to -z, +z to +y.
    check_point(placed(sphere_with("r2"), point3(0, 1, 0)), 0, 0, -1);
    check_point(placed(sphere_with("r2"), point3(0, 0, 1)), 0, 1, 0);
    // Letters in either case; the object keeps its own centre and radius (object space).
    auto obj = sphere_with("T1 R1");
    check_point(placed(obj, point3(0, 0, 0)), 0, 1, 0);
    auto sp = std::dynamic_pointer_cast<sphere>(inner(obj));
    REQUIRE(sp);
    CHECK(sp->radius() == 1);
}

TEST_CASE("course scene: mesh instances place their base's geometry, chained, with reset and materials") {
    // Mesh 1 (material 1) moved by t1; instance 2 of it moved further by t2 in material 2;
    // instance 3 of instance 2 with reset: s1 alone on the raw vertices, its base's material;
    // instance 4 of instance 2 without reset: t1 then t2 then t2 again, material 3.
    const std::string transformations = "<Translation id=\"1\">10 0 0</Translation>"
                                        "<Translation id=\"2\">0 5 0</Translation>"
                                        "<Scaling id=\"1\">2 2 2</Scaling>";
    const std::string objects =
        "<MeshInstance id=\"4\" baseMeshId=\"2\"><Material>3</Material><Transformations>t2</Transformations></MeshInstance>"
        "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces><Transformations>t1</Transformations></Mesh>"
        "<MeshInstance id=\"2\" baseMeshId=\"1\" resetTransform=\"false\"><Material>2</Material>"
        "<Transformations>t2</Transformations></MeshInstance>"
        "<MeshInstance id=\"3\" baseMeshId=\"2\" resetTransform=\"true\"><Transformations>s1</Transformations></MeshInstance>";
    whitted_scene s = load_text(scene_xml(transformations, "0 0 0  1 0 0  0 1 0", objects));
    REQUIRE(s.world.objects.size() == 4);
    const auto &i4 = s.world.objects[0], &m1 = s.world.objects[1], &i2 = s.world.objects[2], &i3 = s.world.objects[3];
    check_point(placed(m1, point3(1, 0, 0)), 11, 0, 0);
    check_point(placed(i2, point3(1, 0, 0)), 11, 5, 0);
    check_point(placed(i3, point3(1, 0, 0)), 2, 0, 0);
    check_point(placed(i4, point3(1, 0, 0)), 11, 10, 0);
    auto mesh = [](const std::shared_ptr<hittable>& o) {
        auto m = std::dynamic_pointer_cast<triangle_mesh>(inner(o));
        REQUIRE(m);
        return m;
    };
    auto diffuse = [&](const std::shared_ptr<hittable>& o) {
        return std::dynamic_pointer_cast<whitted_material>(mesh(o)->mat)->diffuse;
    };
    CHECK(same(diffuse(m1), color(1, 0, 0)));
    CHECK(same(diffuse(i2), color(0, 1, 0)));
    CHECK(same(diffuse(i3), color(0, 1, 0))); // no <Material>: its base's
    CHECK(same(diffuse(i4), color(0, 0, 1)));
    // One mesh read: instances in the base's material share its geometry; the others share one
    // copy per material.
    CHECK(mesh(i2) == mesh(i3));
    CHECK(mesh(m1) != mesh(i2));
    REQUIRE(mesh(m1)->positions.size() == mesh(i4)->positions.size());
    for (size_t k = 0; k < mesh(m1)->positions.size(); ++k) CHECK(same(mesh(m1)->positions[k], mesh(i4)->positions[k]));
}

TEST_CASE("course scene: an ellipsoid is a scaled sphere, seen where the sphere is not") {
    // A unit sphere at the origin scaled by (3, 1, 1), seen from (0, 0, 5) through a 2x2 plane at
    // distance 1, 80x80 pixels, lit by ambient light only (100 where it is hit, 0 elsewhere). The
    // ray through column i of row 40 has direction (dx, dy, -1), dx = -1 + (i + 0.5) / 40,
    // dy = -0.0125; it meets x^2/a^2 + y^2 + z^2 = 1 where t^2 (dx^2/a^2 + dy^2 + 1) - 10 t + 24 = 0
    // has a root: dx^2 <= a^2 (1/24 - dy^2). The sphere (a = 1): |dx| <= 0.2037, columns 32..47;
    // the ellipsoid (a = 3): |dx| <= 0.6112, columns 16..63.
    auto render_row = [](const std::string& list) {
        std::string text = R"(<Scene><BackgroundColor>0 0 0</BackgroundColor>
            <Cameras><Camera id="1"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>
            <NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>80 80</ImageResolution>
            <ImageName>e.png</ImageName></Camera></Cameras>
            <Lights><AmbientLight>100 100 100</AmbientLight></Lights>
            <Materials><Material id="1"><AmbientReflectance>1 1 1</AmbientReflectance></Material></Materials>
            <Transformations><Scaling id="1">3 1 1</Scaling></Transformations>
            <VertexData>0 0 0</VertexData>
            <Objects><Sphere id="1"><Material>1</Material><Center>1</Center><Radius>1</Radius>)" +
                           list + "</Sphere></Objects></Scene>";
        whitted_scene s = load_text(text);
        whitted_render r = render_whitted(s, 0);
        std::vector<float> row;
        for (int i = 0; i < 80; ++i) row.push_back(float(r.img.pixel(i, 40).x()));
        return row;
    };
    const std::vector<float> sphere = render_row(""), ellipsoid = render_row("<Transformations>s1</Transformations>");
    for (int i = 0; i < 80; ++i) {
        CAPTURE(i);
        CHECK(sphere[i] == (i >= 32 && i <= 47 ? 100.0f : 0.0f));
        CHECK(ellipsoid[i] == (i >= 16 && i <= 63 ? 100.0f : 0.0f));
    }
    for (int i = 0; i < 80; ++i) CHECK(ellipsoid[i] == ellipsoid[79 - i]); // symmetric
}

TEST_CASE("course scene: a lookAt camera takes <Gaze> as a direction, handedness=\"left\" mirrors") {
    auto camera = [](const std::string& attributes, const std::string& gaze) {
        std::string text = "<Scene><Cameras><Camera id=\"1\" type=\"lookAt\"" + attributes +
                           "><Position>1 2 3</Position>" + gaze +
                           "<Up>0 1 0</Up><FovY>90</FovY><NearDistance>1</NearDistance>"
                           "<ImageResolution>4 2</ImageResolution><ImageName>c.png</ImageName></Camera></Cameras></Scene>";
        whitted_scene s = load_text(text);
        REQUIRE(s.cameras.size() == 1);
        return s.cameras[0];
    };
    const view_camera by_point = camera("", "<GazePoint>1 2 -7</GazePoint>");
    const view_camera by_direction = camera("", "<Gaze>0 0 -2</Gaze>");
    CHECK(same(unit_vector(by_point.gaze), unit_vector(by_direction.gaze)));
    CHECK(by_direction.top == doctest::Approx(1));
    CHECK(by_direction.right == doctest::Approx(2));
    // Right-handed: u = up x w = (1, 0, 0), so pixel 0's centre is to the left (x < 0); left-handed:
    // u = w x up, pixel 0 to the right; v (rows) unchanged.
    const camera_frame right = view_camera_frame(camera(" handedness=\"right\"", "<Gaze>0 0 -1</Gaze>"));
    const camera_frame left = view_camera_frame(camera(" handedness=\"left\"", "<Gaze>0 0 -1</Gaze>"));
    CHECK(right.pixel00.x == doctest::Approx(-1.5f));
    CHECK(left.pixel00.x == doctest::Approx(1.5f));
    CHECK(right.pixel00.y == left.pixel00.y);
    CHECK(right.pixel00.z == left.pixel00.z);
    CHECK(right.pixel_delta_v.y == left.pixel_delta_v.y);
    CHECK(left.pixel_delta_u.x == -right.pixel_delta_u.x);
    CHECK(error_of("<Scene><Cameras><Camera id=\"1\" type=\"lookAt\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze>"
                   "<GazePoint>0 0 -1</GazePoint><Up>0 1 0</Up><FovY>90</FovY><NearDistance>1</NearDistance>"
                   "<ImageResolution>4 2</ImageResolution><ImageName>c.png</ImageName></Camera></Cameras></Scene>")
              .find("a lookAt camera takes <GazePoint> or <Gaze>, not both") != std::string::npos);
    CHECK(error_of("<Scene><Cameras><Camera id=\"1\" handedness=\"up\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze>"
                   "<Up>0 1 0</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>"
                   "<ImageResolution>4 2</ImageResolution><ImageName>c.png</ImageName></Camera></Cameras></Scene>")
              .find("handedness=\"up\" must be left or right") != std::string::npos);
}

TEST_CASE("course scene: every element and attribute not read is one warning naming it and its line") {
    std::string text = scene_xml("", "0 0 0",
                                 "<Sphere id=\"1\" shadingMode=\"smooth\"><Material>1</Material><Center>1</Center>"
                                 "<Radius>1</Radius>\n<Texture>1</Texture></Sphere>\n"
                                 "<Cylinder id=\"2\"><Radius>1</Radius></Cylinder>");
    text.replace(text.find("<Camera id=\"1\">"), 15, "<Camera id=\"1\">\n<Exposure>2</Exposure>");
    whitted_scene s = load_text(text, "warn.xml");
    REQUIRE(s.warnings.size() == 4);
    // Line 3: <Exposure>, which no homework has (the camera then ends on line 7; lights, materials, transformations
    // and vertices take a line each); line 12: the sphere's attribute (not read on spheres), line
    // 13 its <Texture> (the 2018 format's, which no later homework has); line 14: a cylinder (no homework has one), whose children are not looked at.
    CHECK(s.warnings[0].find("warn.xml:3: <Exposure> is not supported yet and is ignored") != std::string::npos);
    CHECK(s.warnings[1].find("warn.xml:12: <Sphere id=\"1\">: attribute shadingMode=\"smooth\" is not supported yet") !=
          std::string::npos);
    CHECK(s.warnings[2].find("warn.xml:13: <Texture> is not supported yet") != std::string::npos);
    CHECK(s.warnings[3].find("warn.xml:14: <Cylinder id=\"2\"> is not supported yet") != std::string::npos);
    // The level-1 test scene has nothing unread.
    CHECK(load_xml_scene(std::string(RTWEEKEND_TEST_DATA) + "/xml/scene.xml").warnings.empty());
    // Many: 20 lines, then one that counts the rest.
    std::string many;
    for (int i = 0; i < 30; ++i) many += "<Unknown/>";
    whitted_scene m = load_text(scene_xml("", "0 0 0", many));
    REQUIRE(m.warnings.size() == 21);
    CHECK(m.warnings[20].find("and 10 more elements or attributes not read") != std::string::npos);
}

TEST_CASE("course scene: bad transformations and instances are one error line naming the element") {
    auto objects_error = [](const std::string& transformations, const std::string& objects) {
        std::string m = error_of(scene_xml(transformations, "0 0 0  1 0 0  0 1 0", objects));
        CHECK(m.find('\n') == std::string::npos);
        return m;
    };
    const std::string sphere_open = "<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>1</Radius>";
    CHECK(objects_error("<Translation id=\"1\">1 0 0</Translation>",
                        sphere_open + "<Transformations>t1 t2</Transformations></Sphere>")
              .find("<Sphere id=\"1\">: <Transformations>: t2: there is no <Translation id=\"2\"> (the file defines 1)") !=
          std::string::npos);
    CHECK(objects_error("", sphere_open + "<Transformations>x1</Transformations></Sphere>")
              .find("'x1' is not a transformation") != std::string::npos);
    CHECK(objects_error("<Scaling id=\"1\">1 0 1</Scaling>", sphere_open + "</Sphere>")
              .find("<Scaling id=\"1\">: <Scaling> by 0 flattens the object") != std::string::npos);
    CHECK(objects_error("<Composite id=\"1\">1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1</Composite>", sphere_open + "</Sphere>")
              .find("last row must be 0 0 0 1") != std::string::npos);
    CHECK(objects_error("<Composite id=\"1\">1 0 0 0 0 1 0 0 0 1 0 0 0 0 0 1</Composite>",
                        sphere_open + "<Transformations>c1</Transformations></Sphere>")
              .find("a singular matrix") != std::string::npos);
    CHECK(objects_error("<Rotation id=\"1\">30 0 0 0</Rotation>", sphere_open + "</Sphere>").find("a zero (or too long) axis") !=
          std::string::npos);
    CHECK(objects_error("<Translation id=\"1\">1 0 0</Translation><Translation id=\"1\">2 0 0</Translation>", "")
              .find("id 1 is defined twice") != std::string::npos);
    const std::string mesh = "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3</Faces></Mesh>";
    CHECK(objects_error("", mesh + "<MeshInstance id=\"5\" baseMeshId=\"7\"/>")
              .find("<MeshInstance id=\"5\">: baseMeshId 7: no <Mesh> or <MeshInstance> has that id (meshes 1)") !=
          std::string::npos);
    CHECK(objects_error("", mesh + "<MeshInstance id=\"5\" baseMeshId=\"6\"/><MeshInstance id=\"6\" baseMeshId=\"5\"/>")
              .find("leads back to this instance: a cycle") != std::string::npos);
    CHECK(objects_error("", mesh + "<MeshInstance id=\"5\"/>").find("missing attribute baseMeshId") != std::string::npos);
    CHECK(objects_error("", mesh + "<MeshInstance id=\"5\" baseMeshId=\"1\" resetTransform=\"yes\"/>")
              .find("resetTransform=\"yes\" must be true or false") != std::string::npos);
}

TEST_CASE("course scene: the JSON form reads as its XML twin and renders the same image") {
    const std::string xml = scene_xml("<Translation id=\"1\">0 0 -1</Translation><Scaling id=\"1\">1.5 1 1</Scaling>",
                                      "-1 -1 -3  1 -1 -3  0 1 -3  0 0 -4",
                                      "<Mesh id=\"1\"><Material>1</Material><Faces vertexOffset=\"0\">1 2 3</Faces></Mesh>"
                                      "<MeshInstance id=\"2\" baseMeshId=\"1\" resetTransform=\"false\"><Material>2</Material>"
                                      "<Transformations>t1 s1</Transformations></MeshInstance>"
                                      "<Sphere id=\"1\"><Material>3</Material><Center>4</Center><Radius>0.5</Radius></Sphere>");
    // The same scene in the course's JSON translation (section 15): attributes as "_" keys, text
    // with attributes under "_data", a repeated element as an array, every value a string.
    const std::string json = R"({"Scene": {
      "Cameras": {"Camera": {"_id": "1", "Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
                  "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "8 8", "ImageName": "x.png"}},
      "Lights": {"PointLight": {"_id": "1", "Position": "0 0 0", "Intensity": "100 100 100"}},
      "Materials": {"Material": [{"_id": "1", "DiffuseReflectance": "1 0 0"},
                                 {"_id": "2", "DiffuseReflectance": "0 1 0"},
                                 {"_id": "3", "DiffuseReflectance": "0 0 1"}]},
      "Transformations": {"Translation": {"_id": "1", "_data": "0 0 -1"}, "Scaling": {"_id": "1", "_data": "1.5 1 1"}},
      "VertexData": "-1 -1 -3  1 -1 -3  0 1 -3  0 0 -4",
      "Objects": {
        "Mesh": {"_id": "1", "Material": "1", "Faces": {"_data": "1 2 3", "_vertexOffset": "0"}},
        "MeshInstance": {"_id": "2", "_baseMeshId": "1", "_resetTransform": "false", "Material": "2",
                         "Transformations": "t1 s1"},
        "Sphere": {"_id": "1", "Material": "3", "Center": "4", "Radius": "0.5"}}}})";
    whitted_scene from_xml = load_text(xml, "twin.xml"), from_json = load_text(json, "twin.json");
    REQUIRE(from_json.world.objects.size() == from_xml.world.objects.size());
    CHECK(from_json.warnings.empty());
    for (size_t i = 0; i < from_xml.world.objects.size(); ++i) {
        check_point(placed(from_json.world.objects[i], point3(1, 2, 3)), placed(from_xml.world.objects[i], point3(1, 2, 3)).x(),
                    placed(from_xml.world.objects[i], point3(1, 2, 3)).y(), placed(from_xml.world.objects[i], point3(1, 2, 3)).z());
    }
    const image a = render_whitted(from_xml, 0).img, b = render_whitted(from_json, 0).img;
    CHECK(a.data() == b.data());
    bool lit = false;
    for (float v : a.data()) lit = lit || v > 0;
    CHECK(lit);
    // JSON errors: malformed (with its line), the wrong top, and the XML reader's own messages
    // (without a line: the elements come from the translation).
    CHECK(error_of("{\"Scene\": {\n\"Cameras\": [1,\n}}", "bad.json").find("bad.json:3: malformed JSON: ") !=
          std::string::npos);
    CHECK(error_of("[1, 2]", "top.json").find("top.json: the JSON scene must be an object holding \"Scene\"") !=
          std::string::npos);
    // A number beyond a double (nlohmann's out_of_range, which a fuzzer found escaping as an
    // exception of another kind): one line, no more than a prefix of the token.
    const std::string huge = error_of("{\"Scene\": {\"MaxRecursionDepth\": 1e" + std::string(300, '9') + "}}", "huge.json");
    CHECK(huge.find("huge.json: malformed JSON: ") != std::string::npos);
    CHECK(huge.size() < 300);
    CHECK(huge.find('\n') == std::string::npos);
    std::string bad_radius = json;
    bad_radius.replace(bad_radius.find("\"Radius\": \"0.5\""), 15, "\"Radius\": \"-2\"");
    const std::string m = error_of(bad_radius, "radius.json");
    CHECK(m.find("radius.json: <Sphere id=\"1\">: <Radius> must be positive") != std::string::npos);
    std::string deep = "{\"Scene\": ";
    for (int i = 0; i < 100; ++i) deep += "{\"A\": ";
    deep += "\"1\"" + std::string(101, '}');
    CHECK(error_of(deep, "deep.json").find("nested more than 64 levels deep") != std::string::npos);
}

namespace {

// A floor (y = 0, 200 x 200, white: kd = 1, no ambient term) seen straight down from (0, 20, 0)
// through a 2x2 near plane at distance 1, n x n pixels, lit by `lights`; `camera_extra` goes
// inside the camera. Pixel (i, j)'s centre ray meets the floor at (20 a, 0, -20 b), with
// a = -1 + (i + 0.5) 2/n and b = 1 - (j + 0.5) 2/n (u = up x w = +x, v = w x u = -z).
image render_floor(const std::string& lights, int n, const std::string& camera_extra = "") {
    const std::string text = "<Scene><Cameras><Camera id=\"1\"><Position>0 20 0</Position><Gaze>0 -1 0</Gaze>"
                             "<Up>0 0 -1</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>"
                             "<ImageResolution>" + std::to_string(n) + " " + std::to_string(n) +
                             "</ImageResolution><ImageName>f.png</ImageName>" + camera_extra + "</Camera></Cameras>"
                             "<Lights>" + lights + "</Lights>"
                             "<Materials><Material id=\"1\"><DiffuseReflectance>1 1 1</DiffuseReflectance></Material></Materials>"
                             "<VertexData>-100 0 -100  100 0 -100  100 0 100  -100 0 100</VertexData>"
                             "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 3 2  1 4 3</Faces></Mesh></Objects></Scene>";
    return render_whitted(load_text(text), 0).img;
}

point3 floor_point(int i, int j, int n) {
    const double a = -1 + (i + 0.5) * 2 / n, b = 1 - (j + 0.5) * 2 / n;
    return point3(20 * a, 0, -20 * b);
}

} // namespace

TEST_CASE("course scene: a directional light lights the floor without fall-off, shadowed from any distance") {
    // Direction (1, -0.8, -1), radiance 200: towards the light l = (-1, 0.8, 1) / |...|, so on the
    // floor n.l = 0.8 / sqrt(2.64) and every pixel is 200 * 1 * 0.8 / sqrt(2.64) = 98.4652...
    const std::string light = "<DirectionalLight id=\"1\"><Direction>1 -0.8 -1</Direction><Radiance>200 200 200</Radiance>"
                              "</DirectionalLight>";
    const image img = render_floor(light, 9);
    const double expected = 200 * 0.8 / std::sqrt(2.64);
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) CHECK(img.pixel(i, j).x() == doctest::Approx(expected).epsilon(1e-5));
    // A blocker 1000 units towards the light from the floor's centre shadows the centre pixel only.
    const std::string far = "<DirectionalLight id=\"1\"><Direction>0 -1 0</Direction><Radiance>50 50 50</Radiance>"
                            "</DirectionalLight>";
    std::string text = "<Scene><Cameras><Camera id=\"1\"><Position>0 20 0</Position><Gaze>0 -1 0</Gaze><Up>0 0 -1</Up>"
                       "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>9 9</ImageResolution>"
                       "<ImageName>f.png</ImageName></Camera></Cameras><Lights>" + far + "</Lights>"
                       "<Materials><Material id=\"1\"><DiffuseReflectance>1 1 1</DiffuseReflectance></Material></Materials>"
                       "<VertexData>-100 0 -100  100 0 -100  100 0 100  -100 0 100  -1 1000 -1  1 1000 -1  0 1000 1</VertexData>"
                       "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 3 2  1 4 3  5 7 6</Faces></Mesh></Objects></Scene>";
    const image shadowed = render_whitted(load_text(text), 0).img;
    CHECK(shadowed.pixel(4, 4).x() == 0.0f); // the floor point (0, 0, 0): the blocker is straight above
    CHECK(shadowed.pixel(0, 0).x() == doctest::Approx(50).epsilon(1e-6));
}

TEST_CASE("course scene: a spot light's fall-off between half its falloff and half its coverage angle") {
    // At (0, 10, 0) pointing down, I = 1000, coverage 60 and falloff 30 degrees (full angles). A
    // floor point at distance r sees it at alpha from the axis, cos alpha = 10 / r = n.l:
    // E = I s / r^2, s = 1 for alpha <= 15, ((cos alpha - cos 30) / (cos 15 - cos 30))^4 up to 30,
    // 0 beyond; the pixel is E cos alpha (kd = 1).
    const std::string light = "<SpotLight id=\"1\"><Position>0 10 0</Position><Direction>0 -1 0</Direction>"
                              "<Intensity>1000 1000 1000</Intensity><CoverageAngle>60</CoverageAngle>"
                              "<FalloffAngle>30</FalloffAngle></SpotLight>";
    const int n = 41;
    const image img = render_floor(light, n);
    const double pi = 3.14159265358979323846;
    int inner = 0, ring = 0, dark = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const point3 x = floor_point(i, j, n);
            const double r2 = 100 + x.x() * x.x() + x.z() * x.z(), r = std::sqrt(r2), cos_a = 10 / r;
            const double alpha = std::acos(cos_a) * 180 / pi;
            double s = 0;
            if (alpha <= 15) s = 1;
            else if (alpha <= 30) s = std::pow((cos_a - std::cos(pi / 6)) / (std::cos(pi / 12) - std::cos(pi / 6)), 4);
            const double expected = 1000 * s / r2 * cos_a;
            CAPTURE(i);
            CAPTURE(j);
            CHECK(img.pixel(i, j).x() == doctest::Approx(expected).epsilon(1e-4).scale(1e-3));
            (alpha <= 15 ? inner : alpha <= 30 ? ring : dark)++;
        }
    CHECK(inner > 0);
    CHECK(ring > 0);
    CHECK(dark > 0);
    CHECK(img.pixel(n / 2, n / 2).x() == doctest::Approx(10).epsilon(1e-5)); // straight below: 1000 / 100
}

TEST_CASE("course scene: an area light is two-sided: L A |n_l . w_i| / d^2") {
    // A 0.01-wide square at height 5 facing up (away from the floor) of radiance 10^6: L A = 100.
    // A floor point at distance d sees it with |n_l . w_i| = 5 / d and n.l = 5 / d, so the pixel is
    // 100 (5 / d)^2 / d^2 (within the light's width: 0.2 % here). The light is invisible: the centre
    // pixel's ray passes through its centre and sees the floor, 100 / 25.
    const std::string light = "<AreaLight id=\"1\"><Position>0 5 0</Position><Normal>0 1 0</Normal><Size>0.01</Size>"
                              "<Radiance>1000000 1000000 1000000</Radiance></AreaLight>";
    const int n = 11;
    const image img = render_floor(light, n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const point3 x = floor_point(i, j, n);
            const double d2 = 25 + x.x() * x.x() + x.z() * x.z();
            CHECK(img.pixel(i, j).x() == doctest::Approx(100 * 25 / d2 / d2).epsilon(2e-3));
        }
}

TEST_CASE("course scene: NumSamples jitters inside the pixel and averages, the lens keeps the focal plane sharp") {
    // A wall at z = -10 (ambient only: ka 1, Ia 100) seen from the origin through a 2x2 near plane
    // at distance 10, 4x4 pixels: at the wall's depth pixel column 2 spans x in [0, 0.5], and the
    // wall's left edge x = 0.125 is a quarter of the way in. With 16 samples on a 4x4 grid, the 3
    // columns of cells right of the edge hit and 1 misses: the pixel is exactly 75 (and exactly 75
    // again through a lens focused on the wall, every ray of a sample meeting the same point).
    auto render_wall = [](const std::string& extra, double wall_z) {
        const std::string z = std::to_string(wall_z);
        std::string text = "<Scene><Cameras><Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                           "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>10</NearDistance><ImageResolution>4 4</ImageResolution>"
                           "<ImageName>w.png</ImageName>" + extra + "</Camera></Cameras><Lights><AmbientLight>100 100 100</AmbientLight></Lights>"
                           "<Materials><Material id=\"1\"><AmbientReflectance>1 1 1</AmbientReflectance></Material></Materials>"
                           "<VertexData>0.125 -50 " + z + "  50 -50 " + z + "  50 50 " + z + "  0.125 50 " + z + "</VertexData>"
                           "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3  1 3 4</Faces></Mesh></Objects></Scene>";
        return render_whitted(load_text(text), 0).img;
    };
    const image pinhole = render_wall("", -10), jittered = render_wall("<NumSamples>16</NumSamples>", -10);
    CHECK(pinhole.pixel(2, 1).x() == 100.0f); // its centre (x = 0.25) is right of the edge
    CHECK(jittered.pixel(1, 1).x() == 0.0f);
    CHECK(jittered.pixel(2, 1).x() == doctest::Approx(75).epsilon(1e-6));
    CHECK(jittered.pixel(3, 1).x() == 100.0f);
    const image focused = render_wall("<NumSamples>16</NumSamples><ApertureSize>2</ApertureSize><FocusDistance>10</FocusDistance>", -10);
    CHECK(focused.pixel(2, 1).x() == doctest::Approx(75).epsilon(1e-6));
    CHECK(focused.pixel(1, 1).x() == 0.0f);
    // Focused at 10 but the wall at 5 (its edge still at x = 0.125, now a quarter of a pixel
    // that covers [0, 0.25]): a lens of 2 spreads the edge over pixels on both sides.
    const image blurred = render_wall("<NumSamples>64</NumSamples><ApertureSize>2</ApertureSize><FocusDistance>10</FocusDistance>", -5);
    const image sharp = render_wall("<NumSamples>64</NumSamples>", -5);
    CHECK(sharp.pixel(1, 1).x() == 0.0f);
    CHECK(blurred.pixel(1, 1).x() > 5.0f);
    CHECK(blurred.pixel(3, 1).x() < 100.0f);
}

TEST_CASE("course scene: the course's frame and rough mirrors") {
    // d' = d with its smallest-magnitude component set to 1; u = normalize(d x d'); v = d x u.
    vec3 u, v;
    const vec3 d = unit_vector(vec3(0.2, -0.9, 0.4));
    course_frame(d, u, v);
    const vec3 expected_u = unit_vector(cross(d, vec3(1, d.y(), d.z())));
    CHECK(u.x() == doctest::Approx(expected_u.x()));
    CHECK(u.y() == doctest::Approx(expected_u.y()));
    CHECK(u.z() == doctest::Approx(expected_u.z()));
    CHECK(dot(u, d) == doctest::Approx(0).scale(1));
    CHECK(dot(v, d) == doctest::Approx(0).scale(1));
    CHECK(v.length() == doctest::Approx(1));
    // A mirror floor reflecting a wall split into lit (x > 0) and dark halves: roughness 0 keeps
    // the reflected edge as sharp as the pinhole makes it; roughness 0.5 spreads it, and the
    // reflection of the wall's middle (all rays land on the lit half) keeps its value.
    auto render_mirror = [](const std::string& roughness) {
        std::string text = "<Scene><MaxRecursionDepth>1</MaxRecursionDepth><Cameras><Camera id=\"1\"><Position>0 1 0</Position>"
                           "<Gaze>0 -1 -1</Gaze><Up>0 1 0</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>"
                           "<ImageResolution>32 32</ImageResolution><ImageName>m.png</ImageName><NumSamples>16</NumSamples>"
                           "</Camera></Cameras><Lights><AmbientLight>100 100 100</AmbientLight></Lights><Materials>"
                           "<Material id=\"1\" type=\"mirror\"><MirrorReflectance>1 1 1</MirrorReflectance>" + roughness +
                           "</Material><Material id=\"2\"><AmbientReflectance>1 1 1</AmbientReflectance></Material></Materials>"
                           "<VertexData>-50 0 50  50 0 50  50 0 -50  -50 0 -50  0 -1 -5  50 -1 -5  50 50 -5  0 50 -5</VertexData>"
                           "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3  1 3 4</Faces></Mesh>"
                           "<Mesh id=\"2\"><Material>2</Material><Faces>5 6 7  5 7 8</Faces></Mesh></Objects></Scene>";
        return render_whitted(load_text(text), 0).img;
    };
    const image smooth = render_mirror(""), rough = render_mirror("<Roughness>0.5</Roughness>");
    auto partial = [](const image& img) {
        int count = 0;
        for (int j = 16; j < 32; ++j)
            for (int i = 0; i < 32; ++i) count += img.pixel(i, j).x() > 1 && img.pixel(i, j).x() < 99;
        return count;
    };
    CHECK(partial(rough) > 2 * partial(smooth) + 10);
}

TEST_CASE("course scene: the photographic tone mapping of small images, worked by hand") {
    auto grey = [](const std::vector<double>& ys) {
        image img(int(ys.size()), 1);
        for (size_t i = 0; i < ys.size(); ++i) img.set_pixel(int(i), 0, color(ys[i], ys[i], ys[i]));
        return img;
    };
    // Two grey pixels of luminance 1 and 4: Ybar = exp((ln(1 + 1e-6) + ln(4 + 1e-6)) / 2) = 2.0000012,
    // L = 0.18 Y / Ybar = 0.0899999 and 0.3599998, Ld = L / (1 + L) = 0.0825688 and 0.2647058,
    // 255 Ld^(1/2.2) = 82.07 and 139.37, truncated.
    const std::vector<unsigned char> two = tonemap_photographic(grey({1, 4}), {0.18, 0, 1, 2.2});
    CHECK(two == std::vector<unsigned char>{82, 82, 82, 139, 139, 139});
    // Burn 40 of five pixels Y = 1, 2, 3, 4, 8: Ybar = 24^(1/5)... = 2.8619394 (with the 1e-6), the
    // 60th percentile is the pixel at index floor(5 * 0.6) = 3 (Y = 4), so Lwhite = 0.18 * 4 / Ybar =
    // 0.2515777; Ld = L (1 + L / Lwhite^2) / (1 + L) gives 0.1179745, 0.3338005, 0.6319457 for Y = 1,
    // 2, 3 (bytes 96, 154, 206), exactly 1 at Y = 4 (byte 254 or 255 by rounding) and 2.9958 at Y =
    // 8, clamped to white.
    const std::vector<unsigned char> five = tonemap_photographic(grey({1, 2, 3, 4, 8}), {0.18, 40, 1, 2.2});
    CHECK(five[0] == 96);
    CHECK(five[3] == 154);
    CHECK(five[6] == 206);
    CHECK(five[9] >= 254);
    CHECK(five[12] == 255);
    // Saturation on one pixel (2, 1, 0.5): Y = 1.1765 = Ybar, L = 0.18, Ld = 0.1525423; each channel
    // is Ld (C / Y)^s: s = 0 is grey (255 Ld^(1/2.2) = 108.9), s = 1 the colour (138, 100, 73).
    image one(1, 1);
    one.set_pixel(0, 0, color(2, 1, 0.5));
    CHECK(tonemap_photographic(one, {0.18, 0, 0, 2.2}) == std::vector<unsigned char>{108, 108, 108});
    CHECK(tonemap_photographic(one, {0.18, 0, 1, 2.2}) == std::vector<unsigned char>{138, 100, 73});
    // Black stays black (and counts in the log average); bad settings are one error.
    CHECK(tonemap_photographic(grey({0, 1}), {0.18, 0, 1, 2.2})[0] == 0);
    CHECK_THROWS_WITH_AS(tonemap_photographic(one, {0, 0, 1, 2.2}), "tone mapping: the key must be positive, got 0",
                         scene_error);
    CHECK_THROWS_AS(tonemap_photographic(one, {0.18, 100, 1, 2.2}), scene_error);
    CHECK_THROWS_AS(tonemap_photographic(one, {0.18, 0, 1, 0}), scene_error);
}

TEST_CASE("course scene: a camera's <Tonemap> writes the linear image and its tone mapping") {
    const std::string text = "<Scene><Cameras><Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                             "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>4 4</ImageResolution>"
                             "<ImageName>hdr.pfm</ImageName><Tonemap><TMO>Photographic</TMO><TMOOptions>0.18 1</TMOOptions>"
                             "<Saturation>0.8</Saturation><Gamma>2.2</Gamma></Tonemap></Camera></Cameras>"
                             "<BackgroundColor>100 400 1600</BackgroundColor></Scene>";
    const whitted_scene s = load_text(text);
    REQUIRE(s.cameras.size() == 1);
    const view_camera& c = s.cameras[0];
    CHECK(c.tonemapped);
    CHECK(c.tonemap.key == 0.18);
    CHECK(c.tonemap.burn == 1);
    CHECK(c.tonemap.saturation == 0.8);
    CHECK(s.warnings.empty());
    const image img = render_whitted(s, 0).img;
    test::scratch_dir dir("tonemap_pair");
    const std::string also = write_course_image(dir.file("hdr.pfm"), img, c);
    CHECK(also == dir.file("hdr.png"));
    const loaded_image linear = read_image(dir.file("hdr.pfm")), mapped = read_image(dir.file("hdr.png"));
    CHECK(linear.pixels.data() == img.data());
    CHECK(mapped.display_encoded);
    const std::vector<unsigned char> expected = tonemap_photographic(img, c.tonemap);
    REQUIRE(mapped.pixels.data().size() == expected.size());
    // The background (100, 400, 1600) everywhere: every pixel the same.
    for (size_t i = 3; i < expected.size(); ++i) CHECK(expected[i] == expected[i % 3]);
    CHECK(error_of(replace_tmo(text, "Reinhard")).find("<TMO> 'Reinhard' is not supported (Photographic is)") !=
          std::string::npos);
}

TEST_CASE("course scene: <MotionBlur> moves an object over the shutter, its instances stay still") {
    // A wall (ambient 100) whose left edge is at x = 0 at time 0 and moves by (1, 0, 0): seen at its
    // depth through 4 pixels across [-2, 2], the pixel [0, 1] is covered at time t where x > t, a
    // fraction 1/2 of it on average over the shutter: its mean is 50 (1024 samples, each a uniform
    // time: standard deviation 50 / 32 = 1.6). The pixel [-1, 0] never sees it, [1, 2] always.
    // An instance of the wall (reset, moved down out of view and back by its own list) without a
    // <MotionBlur> does not move.
    auto render_wall = [](const std::string& blur, const std::string& instance) {
        std::string text = "<Scene><Cameras><Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
                           "<NearPlane>-1 1 -1 1</NearPlane><NearDistance>5</NearDistance><ImageResolution>4 4</ImageResolution>"
                           "<ImageName>w.png</ImageName><NumSamples>1024</NumSamples></Camera></Cameras>"
                           "<Lights><AmbientLight>100 100 100</AmbientLight></Lights>"
                           "<Materials><Material id=\"1\"><AmbientReflectance>1 1 1</AmbientReflectance></Material></Materials>"
                           "<Transformations><Translation id=\"1\">0 -50 0</Translation><Translation id=\"2\">0 50 0</Translation>"
                           "</Transformations>"
                           "<VertexData>0 -1 -10  60 -1 -10  60 1 -10  0 1 -10</VertexData>"
                           "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 2 3  1 3 4</Faces>" + blur + "</Mesh>" +
                           instance + "</Objects></Scene>";
        return render_whitted(load_text(text), 0).img;
    };
    const image still = render_wall("", ""), blurred = render_wall("<MotionBlur>1 0 0</MotionBlur>", "");
    // At depth 10 the plane of 2 units at distance 5 spans [-2, 2]: pixel i covers [-2 + i, -1 + i].
    CHECK(still.pixel(1, 1).x() == 0.0f);
    CHECK(still.pixel(2, 1).x() == 100.0f);
    CHECK(blurred.pixel(1, 1).x() == 0.0f);
    CHECK(blurred.pixel(2, 1).x() == doctest::Approx(50).epsilon(0.1)); // within 5, about 3 standard deviations
    CHECK(blurred.pixel(3, 1).x() == 100.0f);
    // The instance: the base's matrix (identity) then t1 t2, back where the wall is, not moving.
    const image with_instance = render_wall("<MotionBlur>0 100 0</MotionBlur>",
                                            "<MeshInstance id=\"2\" baseMeshId=\"1\"><Transformations>t1 t2</Transformations>"
                                            "</MeshInstance>");
    CHECK(with_instance.pixel(2, 1).x() == 100.0f); // the still instance covers it at every time
    CHECK(with_instance.pixel(1, 1).x() == 0.0f);
}

TEST_CASE("course scene: a LightMesh and a LightSphere light the floor and are seen as their radiance") {
    // One pixel seeing the floor point X = (4, 0, 0) from straight above through a tiny plane; the
    // light's centre is (0, 5, 0): d^2 = 41, and the floor's cos = 5 / d.
    auto render_point = [](const std::string& vertices, const std::string& objects, int samples,
                           const std::string& transformations = "") {
        const std::string text = "<Scene><Cameras><Camera id=\"1\"><Position>4 20 0</Position><Gaze>0 -1 0</Gaze>"
                                 "<Up>0 0 -1</Up><NearPlane>-0.001 0.001 -0.001 0.001</NearPlane><NearDistance>1</NearDistance>"
                                 "<ImageResolution>1 1</ImageResolution><ImageName>p.png</ImageName><NumSamples>" +
                                 std::to_string(samples) + "</NumSamples></Camera></Cameras>"
                                 "<Materials><Material id=\"1\"><DiffuseReflectance>1 1 1</DiffuseReflectance></Material>"
                                 "<Material id=\"2\"/></Materials><Transformations>" + transformations + "</Transformations>"
                                 "<VertexData>-100 0 -100  100 0 -100  100 0 100  -100 0 100  " + vertices + "</VertexData>"
                                 "<Objects><Mesh id=\"1\"><Material>1</Material><Faces>1 3 2  1 4 3</Faces></Mesh>" + objects +
                                 "</Objects></Scene>";
        const whitted_scene s = load_text(text);
        CHECK(s.warnings.empty());
        return render_whitted(s, 0).img.pixel(0, 0).x();
    };
    // A LightMesh square of side 0.01 (A = 1e-4) facing down, L = 1e6: L A cos_y cos_x / d^2 =
    // 100 * (25 / 41) / 41 = 1.4872.
    const std::string square = "-0.005 5 -0.005  0.005 5 -0.005  0.005 5 0.005  -0.005 5 0.005";
    const std::string light_mesh = "<LightMesh id=\"1\"><Material>2</Material><Faces>5 6 7  5 7 8</Faces>"
                                   "<Radiance>1000000 1000000 1000000</Radiance></LightMesh>";
    CHECK(render_point(square, light_mesh, 1) == doctest::Approx(100.0 * 25 / 41 / 41).epsilon(2e-3));
    // A LightSphere of radius 0.05, L = 10^4: a sphere wholly above the horizon gives exactly
    // E = L pi r^2 cos_x / d^2 = 10^4 pi 0.0025 (5 / sqrt 41) / 41 = 1.4958. One point of it per
    // sample (its far half hidden by itself): about 1.3 / sqrt(N) relative noise, so 40000 samples.
    const double sphere_expected = 1e4 * 3.14159265358979 * 0.0025 * (5 / std::sqrt(41.0)) / 41;
    const std::string light_sphere = "<LightSphere id=\"1\"><Material>2</Material><Center>5</Center><Radius>0.05</Radius>"
                                     "<Radiance>10000 10000 10000</Radiance></LightSphere>";
    CHECK(render_point("0 5 0", light_sphere, 40000) == doctest::Approx(sphere_expected).epsilon(0.04));
    // The same sphere as half its size at half the height, scaled by 2 about the origin: the
    // area density carries the map's stretch J = |det M| |M^-T n| = 8 / 2 = 4.
    const std::string scaled = "<LightSphere id=\"1\"><Material>2</Material><Center>5</Center><Radius>0.025</Radius>"
                               "<Radiance>10000 10000 10000</Radiance><Transformations>s1</Transformations></LightSphere>";
    CHECK(render_point("0 2.5 0", scaled, 40000, "<Scaling id=\"1\">2 2 2</Scaling>") ==
          doctest::Approx(sphere_expected).epsilon(0.04));
    // Seen straight on, a light is its radiance (its black material adds nothing).
    const std::string text = "<Scene><Cameras><Camera id=\"1\"><Position>0 20 0</Position><Gaze>0 -1 0</Gaze>"
                             "<Up>0 0 -1</Up><NearPlane>-0.0001 0.0001 -0.0001 0.0001</NearPlane><NearDistance>1</NearDistance>"
                             "<ImageResolution>1 1</ImageResolution><ImageName>p.png</ImageName></Camera></Cameras>"
                             "<Materials><Material id=\"2\"/></Materials><VertexData>" + square + "</VertexData><Objects>"
                             "<LightMesh id=\"1\"><Material>2</Material><Faces>1 2 3  1 3 4</Faces>"
                             "<Radiance>7 8 9</Radiance></LightMesh></Objects></Scene>";
    const color seen = render_whitted(load_text(text), 0).img.pixel(0, 0);
    CHECK(seen.x() == doctest::Approx(7));
    CHECK(seen.y() == doctest::Approx(8));
    CHECK(seen.z() == doctest::Approx(9));
}

TEST_CASE("course scene: binary vertex and face files read as their text twins") {
    test::scratch_dir dir("binary_geometry");
    auto le32 = [](uint32_t v) {
        std::string b(4, '\0');
        for (int k = 0; k < 4; ++k) b[size_t(k)] = char((v >> (8 * k)) & 0xff);
        return b;
    };
    auto f32 = [&](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return le32(u);
    };
    // Four vertices and two faces (ids from 1, as the text's).
    const float xyz[] = {-1, -1, -3, 1, -1, -3, 1, 1, -3, -1, 1, -3.5f};
    std::string vertices = le32(4);
    for (float c : xyz) vertices += f32(c);
    std::string faces = le32(2);
    for (uint32_t i : {1u, 2u, 3u, 1u, 3u, 4u}) faces += le32(i);
    dir.write("v.bin", vertices);
    dir.write("f.bin", faces);
    auto scene_text = [](const std::string& vertex_data, const std::string& face_data) {
        return std::string("<Scene>") + camera_xml + "<Materials><Material id=\"1\"><DiffuseReflectance>1 1 1</DiffuseReflectance>"
               "</Material></Materials>" + vertex_data + "<Objects><Mesh id=\"1\"><Material>1</Material>" + face_data +
               "</Mesh></Objects></Scene>";
    };
    const whitted_scene binary =
        load_xml_scene(dir.write("binary.xml", scene_text("<VertexData binaryFile=\"v.bin\"/>", "<Faces binaryFile=\"f.bin\"/>")));
    const whitted_scene text = load_xml_scene(
        dir.write("text.xml", scene_text("<VertexData>-1 -1 -3 1 -1 -3 1 1 -3 -1 1 -3.5</VertexData>", "<Faces>1 2 3 1 3 4</Faces>")));
    auto mesh = [](const whitted_scene& s) {
        REQUIRE(s.world.objects.size() == 1);
        auto m = std::dynamic_pointer_cast<triangle_mesh>(s.world.objects[0]);
        REQUIRE(m);
        return m;
    };
    REQUIRE(mesh(binary)->positions.size() == 4);
    for (size_t k = 0; k < 4; ++k) CHECK(same(mesh(binary)->positions[k], mesh(text)->positions[k]));
    CHECK(mesh(binary)->faces == mesh(text)->faces);
    CHECK(binary.warnings.empty());
    CHECK(binary.files.size() == 3); // the scene and both binary files
    // Texture coordinates the same way (homework 4's form of sponza): a count, then u v float32
    // pairs, one per vertex; the mesh's corners take them by their vertex ids.
    std::string uv = le32(4);
    for (float c : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f, 0.125f, 0.375f, 0.625f}) uv += f32(c);
    dir.write("t.bin", uv);
    const whitted_scene with_uv = load_xml_scene(dir.write(
        "uv.xml", scene_text("<VertexData binaryFile=\"v.bin\"/><TexCoordData binaryFile=\"t.bin\"/>", "<Faces>3 1 4</Faces>")));
    REQUIRE(mesh(with_uv)->face_uvs.size() == 1);
    const auto& corner = mesh(with_uv)->face_uvs[0];
    CHECK(mesh(with_uv)->uvs[corner[0]] == std::array<double, 2>{1.0, 0.125});   // vertex 3
    CHECK(mesh(with_uv)->uvs[corner[1]] == std::array<double, 2>{0.0, 0.25});    // vertex 1
    CHECK(mesh(with_uv)->uvs[corner[2]] == std::array<double, 2>{0.375, 0.625}); // vertex 4
    // A file whose size does not match its count, and one that is missing: one line each.
    dir.write("short.bin", le32(3) + f32(1));
    const std::string short_error = error_of(scene_text("<VertexData binaryFile=\"" + dir.file("short.bin") + "\"/>", "<Faces>1 2 3</Faces>"));
    CHECK(short_error.find("holds 8 bytes, but its count 3 needs 4 + 12 x count") != std::string::npos);
    CHECK(error_of(scene_text("<VertexData binaryFile=\"" + dir.file("none.bin") + "\"/>", "<Faces>1 2 3</Faces>"))
              .find("cannot") != std::string::npos);
}

TEST_CASE("course scene: a MirrorReflectance without type=\"mirror\" is ignored, with a warning") {
    // A square at z = -5 facing the camera at the origin, of MirrorReflectance 0.5 and nothing
    // else; behind the camera a wall of ambient reflectance (1, 0.5, 0.25) under Ia = 100. Typed a
    // mirror, the centre pixel shows the wall: 0.5 x 100 x (1, 0.5, 0.25) = (50, 25, 12.5).
    // Untyped (as Blender-exported course scenes write plain materials), the course's renderer
    // shows no reflection: the square's own shading, 0.
    auto scene = [](const std::string& type) {
        return "<Scene><MaxRecursionDepth>1</MaxRecursionDepth><Cameras><Camera id=\"1\"><Position>0 0 0</Position>"
               "<Gaze>0 0 -1</Gaze><Up>0 1 0</Up><NearPlane>-0.001 0.001 -0.001 0.001</NearPlane><NearDistance>1</NearDistance>"
               "<ImageResolution>1 1</ImageResolution><ImageName>x.exr</ImageName></Camera></Cameras>"
               "<Lights><AmbientLight>100 100 100</AmbientLight></Lights><Materials><Material id=\"1\"" + type +
               "><MirrorReflectance>0.5 0.5 0.5</MirrorReflectance></Material><Material id=\"2\">"
               "<AmbientReflectance>1 0.5 0.25</AmbientReflectance></Material></Materials>"
               "<VertexData>-3 -3 -5 3 -3 -5 3 3 -5 -3 3 -5 -3 -3 5 3 -3 5 3 3 5 -3 3 5</VertexData><Objects>"
               "<Mesh id=\"1\"><Material>1</Material><Faces>1 2 3 1 3 4</Faces></Mesh>"
               "<Mesh id=\"2\"><Material>2</Material><Faces>5 7 6 5 8 7</Faces></Mesh></Objects></Scene>";
    };
    const whitted_scene mirror = load_text(scene(" type=\"mirror\""));
    CHECK(mirror.warnings.empty());
    const vec3 seen = render_whitted(mirror, 0).img.pixel(0, 0);
    CHECK(seen.x() == doctest::Approx(50));
    CHECK(seen.z() == doctest::Approx(12.5));
    const whitted_scene plain = load_text(scene(""));
    REQUIRE(plain.warnings.size() == 1);
    CHECK(plain.warnings[0].find("<Material id=\"1\">: <MirrorReflectance> of a material without type=\"mirror\"") !=
          std::string::npos);
    CHECK(render_whitted(plain, 0).img.pixel(0, 0).x() == 0);
}

TEST_CASE("course scene: a camera's lens in the path tracer's frame meets the course's focal plane") {
    // ApertureSize 0.5, FocusDistance 4, near plane at 1 (ceng795-later.md 3.2): a pixel's pinhole
    // ray dir meets the focal plane at p = e + (4 / dot(dir, -w)) dir; the frame's ray from any
    // lens point through that pixel must pass through p, and start within 0.25 of e in the
    // plane perpendicular to the gaze.
    view_camera c;
    c.position = vec3(1, 2, 3);
    c.gaze = vec3(0.2, -0.1, -1);
    c.up = vec3(0, 1, 0);
    c.left = -0.5, c.right = 0.5, c.bottom = -0.4, c.top = 0.4;
    c.near_distance = 1;
    c.width = 10, c.height = 8;
    c.aperture = 0.5;
    c.focus_distance = 4;
    const camera_frame frame = view_camera_frame(c).placed_in(point3(0, 0, 0));
    CHECK(frame.thin_lens);
    const vec3 w = -unit_vector(c.gaze), u = unit_vector(cross(c.up, w)), v = cross(w, u);
    for (const auto& [i, j] : {std::pair<int, int>{0, 0}, {9, 7}, {3, 5}})
        for (const auto& [lu, lv] : {std::pair<float, float>{0, 0}, {0.9f, 0}, {0, -0.9f}, {0.5f, 0.6f}}) {
            CAPTURE(i);
            CAPTURE(j);
            CAPTURE(lu);
            const vec3 q = c.position - c.near_distance * w + (c.left + (i + 0.5) * (c.right - c.left) / c.width) * u +
                           (c.top - (j + 0.5) * (c.top - c.bottom) / c.height) * v;
            const vec3 dir = unit_vector(q - c.position);
            const vec3 p = c.position + (c.focus_distance / dot(dir, -w)) * dir;
            const ray3f r = frame.generate(float(i) + 0.5f, float(j) + 0.5f, lu, lv);
            const vec3 o = r.origin.to_double(), d = r.dir.to_double();
            CHECK(std::fabs(dot(o - c.position, w)) < 1e-6);
            CHECK((o - c.position).length() <= 0.25 * std::hypot(lu, lv) + 1e-6);
            CHECK((o - c.position).length() == doctest::Approx(0.25 * std::hypot(lu, lv)).epsilon(1e-5));
            CHECK(cross(p - o, d).length() < 1e-4 * (p - o).length());
            CHECK(dot(p - o, d) > 0);
        }
    // A pinhole camera keeps the near plane's grid, no lens.
    c.aperture = 0;
    CHECK_FALSE(view_camera_frame(c).thin_lens);
}

} // namespace test_course_scene
