// The CENG795 reader's later homeworks (rtweekend/io/xml_scene.h, shared/formats/ceng795-later.md):
// transformation lists (points placed by hand-multiplied matrices), mesh instances and their
// chains, lookAt cameras with <Gaze>, handedness, a warning per element not read, and the JSON form
// (io/course_json.h) reading as its XML twin.

#include <rtweekend/mesh.h>
#include <rtweekend/sphere.h>
#include <rtweekend/transform.h>
#include <rtweekend/course/whitted.h>
#include <rtweekend/io/xml_scene.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
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
                                 "<Radius>1</Radius>\n<MotionBlur>0 0 1</MotionBlur></Sphere>\n"
                                 "<LightSphere id=\"2\"><Radiance>1 1 1</Radiance></LightSphere>");
    text.replace(text.find("<Camera id=\"1\">"), 15, "<Camera id=\"1\">\n<NumSamples>4</NumSamples>");
    whitted_scene s = load_text(text, "warn.xml");
    REQUIRE(s.warnings.size() == 4);
    // Line 3: <NumSamples> (the camera then ends on line 7; lights, materials, transformations
    // and vertices take a line each); line 12: the sphere's attribute (not read on spheres), line
    // 13 its <MotionBlur>; line 14: the light sphere, whose children are not looked at.
    CHECK(s.warnings[0].find("warn.xml:3: <NumSamples> is not supported yet and is ignored") != std::string::npos);
    CHECK(s.warnings[1].find("warn.xml:12: <Sphere id=\"1\">: attribute shadingMode=\"smooth\" is not supported yet") !=
          std::string::npos);
    CHECK(s.warnings[2].find("warn.xml:13: <MotionBlur> is not supported yet") != std::string::npos);
    CHECK(s.warnings[3].find("warn.xml:14: <LightSphere id=\"2\"> is not supported yet") != std::string::npos);
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
    std::string bad_radius = json;
    bad_radius.replace(bad_radius.find("\"Radius\": \"0.5\""), 15, "\"Radius\": \"-2\"");
    const std::string m = error_of(bad_radius, "radius.json");
    CHECK(m.find("radius.json: <Sphere id=\"1\">: <Radius> must be positive") != std::string::npos);
    std::string deep = "{\"Scene\": ";
    for (int i = 0; i < 100; ++i) deep += "{\"A\": ";
    deep += "\"1\"" + std::string(101, '}');
    CHECK(error_of(deep, "deep.json").find("nested more than 64 levels deep") != std::string::npos);
}

} // namespace test_course_scene
