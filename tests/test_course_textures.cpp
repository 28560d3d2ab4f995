// The course's texture maps (homework 4; course/course_textures.h, course/whitted.h, the XML
// reader; shared/formats/ceng795-later.md section 8): the texel a sphere's and a mesh's point
// picks, nearest and bilinear, with the object's transformation (rotated, mirrored and so traced
// as an instance, scaled); the decal modes; an object-space checkerboard with C truncation; the
// film's background; normal and bump maps against normals worked out by hand, in the frame the
// course uses; Perlin noise's zeros and range; JPEG images; and one-line refusals. Every expected
// value comes from the formulas in the comments beside it, not from the renderer.

#include <rtweekend/course/whitted.h>
#include <rtweekend/image/image_read.h>
#include <rtweekend/io/xml_scene.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <functional>
#include <string>

namespace test_course_textures {

using namespace rt;

namespace {

// A P3 file of w x h pixels, row 0 the top; pixel (x, y) is rgb(x, y).
std::string ppm(int w, int h, const std::function<vec3(int, int)>& rgb) {
    std::string out = "P3\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const vec3 c = rgb(x, y);
            out += std::to_string(int(c.x())) + " " + std::to_string(int(c.y())) + " " + std::to_string(int(c.z())) + "\n";
        }
    return out;
}

// The 4 x 2 test image: red 10 (x + 1) + 100 y, green 7, blue 3.
double red(int x, int y) { return 10.0 * (x + 1) + 100.0 * y; }
std::string test_image() { return ppm(4, 2, [](int x, int y) { return vec3(red(x, y), 7, 3); }); }

// One pixel looking from `from` along `gaze` through the centre of a tiny near plane: its ray
// is the gaze itself.
std::string camera(const std::string& from, const std::string& gaze, const std::string& up = "0 1 0") {
    return "<Cameras><Camera id=\"1\"><Position>" + from + "</Position><Gaze>" + gaze + "</Gaze><Up>" + up +
           "</Up><NearPlane>-0.0001 0.0001 -0.0001 0.0001</NearPlane><NearDistance>1</NearDistance>"
           "<ImageResolution>1 1</ImageResolution><ImageName>x.exr</ImageName></Camera></Cameras>";
}

std::string textures(const std::string& maps, const std::string& image = "t.ppm") {
    return "<Textures><Images><Image id=\"1\">" + image + "</Image></Images>" + maps + "</Textures>";
}

std::string map(int id, const std::string& type, const std::string& decal, const std::string& extra = "") {
    return "<TextureMap id=\"" + std::to_string(id) + "\" type=\"" + type + "\">" +
           (type == "image" ? "<ImageId>1</ImageId>" : "") + "<DecalMode>" + decal + "</DecalMode>" + extra +
           "</TextureMap>";
}

vec3 render_pixel(const test::scratch_dir& dir, const std::string& xml) {
    const whitted_scene s = load_xml_scene(dir.write("s.xml", "<Scene>" + xml + "</Scene>"));
    INFO(s.warnings.size());
    CHECK(s.warnings.empty());
    return render_whitted(s, 0).img.pixel(0, 0);
}

// The square z = 0, x and y in [-1, 1], as one mesh of two triangles (b - a) x (c - a) = +z, with
// u = (x + 1) / 2 and v = (1 - y) / 2 (v = 0 the image's top row at y = 1).
const std::string square_vertices = "<VertexData>-1 -1 0 1 -1 0 1 1 0 -1 1 0</VertexData>"
                                    "<TexCoordData>0 1 1 1 1 0 0 0</TexCoordData>";
std::string square(const std::string& textures_list, const std::string& transforms = "") {
    return "<Objects><Mesh id=\"1\"><Material>1</Material><Textures>" + textures_list + "</Textures>" +
           (transforms.empty() ? "" : "<Transformations>" + transforms + "</Transformations>") +
           "<Faces>1 2 3 1 3 4</Faces></Mesh></Objects>";
}

std::string light_at(const std::string& position, double intensity) {
    const std::string i = std::to_string(intensity);
    return "<Lights><PointLight id=\"1\"><Position>" + position + "</Position><Intensity>" + i + " " + i + " " + i +
           "</Intensity></PointLight></Lights>";
}

std::string material(const std::string& kd, const std::string& ks = "0 0 0") {
    return "<Materials><Material id=\"1\"><DiffuseReflectance>" + kd + "</DiffuseReflectance><SpecularReflectance>" +
           ks + "</SpecularReflectance><PhongExponent>10</PhongExponent></Material></Materials>";
}

} // namespace

TEST_CASE("course textures: a sphere's point picks the texel of u = (pi - phi) / (2 pi), v = theta / pi") {
    test::scratch_dir dir("course_tex_sphere");
    dir.write("t.ppm", test_image());
    // A unit sphere at the origin seen from c along -c: the hit is P = c / |c|; theta = acos(P_y),
    // phi = atan2(P_z, P_x); replace_all with Normalizer 1 shows the texel as it is.
    struct probe {
        const char* from;
        const char* gaze;
        double u, v; // worked out by hand from the formula
        int x, y;    // floor(4 u), floor(2 v)
    } probes[] = {
        {"3 2 4", "-3 -2 -4", 0.3524, 0.3789, 1, 0},
        {"-3 -2 1", "3 2 -1", 0.0512, 0.6795, 0, 1},
        {"1 1 -3", "-1 -1 3", 0.6988, 0.4025, 2, 0},
        {"-2 0.5 -2", "2 -0.5 2", 0.875, 0.4443, 3, 0},
    };
    const std::string sphere = "<VertexData>0 0 0</VertexData><Materials><Material id=\"1\"></Material></Materials>"
                               "<Objects><Sphere id=\"1\"><Material>1</Material><Textures>1</Textures><Center>1</Center>"
                               "<Radius>1</Radius></Sphere></Objects>";
    for (const probe& p : probes) {
        CAPTURE(p.from);
        const vec3 c = render_pixel(dir, camera(p.from, p.gaze) + textures(map(1, "image", "replace_all", "<Normalizer>1</Normalizer>")) + sphere);
        CHECK(c.x() == red(p.x, p.y));
        CHECK(c.y() == 7);
    }
    // Bilinear at the first probe: x = 4 u = 1.4097, y = 2 v = 0.7578, between texels (1..2, 0..1):
    // 20 + 10 dx + 100 dy = 20 + 4.097 + 75.78 = 99.87.
    const vec3 b = render_pixel(dir, camera("3 2 4", "-3 -2 -4") +
                                         textures(map(1, "image", "replace_all", "<Normalizer>1</Normalizer><Interpolation>bilinear</Interpolation>")) +
                                         sphere);
    CHECK(b.x() == doctest::Approx(99.87).epsilon(2e-4));
    CHECK(b.y() == doctest::Approx(7).epsilon(1e-5));
    // Turned 90 degrees about +y (x -> z, z -> -x): the world point (1, 1, -3) / |.| is the object's
    // (-z, y, x) = (0.9045, 0.3015, 0.3015): phi = 0.3218, u = 0.4488, texel (1, 0) where the
    // unturned sphere showed (2, 0).
    const std::string turned = "<VertexData>0 0 0</VertexData><Materials><Material id=\"1\"></Material></Materials>"
                               "<Transformations><Rotation id=\"1\">90 0 1 0</Rotation></Transformations>"
                               "<Objects><Sphere id=\"1\"><Material>1</Material><Textures>1</Textures>"
                               "<Transformations>r1</Transformations><Center>1</Center><Radius>1</Radius></Sphere></Objects>";
    CHECK(render_pixel(dir, camera("1 1 -3", "-1 -1 3") + textures(map(1, "image", "replace_all", "<Normalizer>1</Normalizer>")) + turned).x() ==
          red(1, 0));
}

TEST_CASE("course textures: decal modes on a mesh with texture coordinates, placed and mirrored") {
    test::scratch_dir dir("course_tex_decal");
    dir.write("t.ppm", test_image());
    // A point light of intensity 1020 at the camera, 2 above the square: E = 1020 / 4 = 255 at
    // normal incidence, so the pixel is 255 kd + 255 ks (n . h = 1) in the course's units.
    // From (-0.6, 0.5): u = 0.2, v = 0.25, texel (0, 0); from (0.3, -0.4): u = 0.65, v = 0.7, texel (2, 1).
    struct probe {
        const char* at;
        int x, y;
    } probes[] = {{"-0.6 0.5", 0, 0}, {"0.3 -0.4", 2, 1}};
    for (const probe& p : probes) {
        CAPTURE(p.at);
        const std::string from = std::string(p.at) + " 2";
        const std::string scene = camera(from, "0 0 -1") + light_at(from, 1020) + square_vertices;
        // replace_kd: kd = texel / 255.
        vec3 c = render_pixel(dir, scene + material("0.2 0.2 0.2") + textures(map(1, "image", "replace_kd")) + square("1"));
        CHECK(c.x() == doctest::Approx(red(p.x, p.y)).epsilon(1e-5));
        CHECK(c.y() == doctest::Approx(7).epsilon(1e-5));
        // blend_kd: kd = (0.2 + texel / 255) / 2.
        c = render_pixel(dir, scene + material("0.2 0.2 0.2") + textures(map(1, "image", "blend_kd")) + square("1"));
        CHECK(c.x() == doctest::Approx((51 + red(p.x, p.y)) / 2).epsilon(1e-5));
        // replace_ks: ks = texel / 255 under a black kd.
        c = render_pixel(dir, scene + material("0 0 0", "0.9 0.9 0.9") + textures(map(1, "image", "replace_ks")) + square("1"));
        CHECK(c.x() == doctest::Approx(red(p.x, p.y)).epsilon(1e-5));
        CHECK(c.z() == doctest::Approx(3).epsilon(1e-5));
    }
    // Placed: scaled by 2 along x, the square's point (x, y) is at (2 x, y); the texel stays the
    // object's. Mirrored (x -> -x, traced as an instance): the world point (0.6, 0.5) is the
    // object's (-0.6, 0.5), texel (0, 0), where the world's u would give (3, 0).
    const std::string placed = "<Transformations><Scaling id=\"1\">2 1 1</Scaling><Scaling id=\"2\">-1 1 1</Scaling></Transformations>";
    vec3 c = render_pixel(dir, camera("-1.2 0.5 2", "0 0 -1") + light_at("-1.2 0.5 2", 1020) + square_vertices +
                                   material("0 0 0") + placed + textures(map(1, "image", "replace_kd")) + square("1", "s1"));
    CHECK(c.x() == doctest::Approx(red(0, 0)).epsilon(1e-5));
    c = render_pixel(dir, camera("0.6 0.5 2", "0 0 -1") + light_at("0.6 0.5 2", 1020) + square_vertices + material("0 0 0") +
                              placed + textures(map(1, "image", "replace_kd")) + square("1", "s2"));
    CHECK(c.x() == doctest::Approx(red(0, 0)).epsilon(1e-5));
    // The same square placed by a MeshInstance of a Mesh without textures: the instance's maps.
    const std::string instance = "<Objects><Mesh id=\"1\"><Material>1</Material><Transformations>s2</Transformations>"
                                 "<Faces>1 2 3 1 3 4</Faces></Mesh><MeshInstance id=\"2\" baseMeshId=\"1\" resetTransform=\"true\">"
                                 "<Textures>1</Textures><Transformations>s2</Transformations></MeshInstance></Objects>";
    // The base mesh (no textures) and the instance coincide: the nearest hit is either, so the
    // base is moved out of the way with a translation behind the square.
    std::string moved = instance;
    moved.replace(moved.find("<Transformations>s2</Transformations><Faces>"), 37, "<Transformations>t1</Transformations>");
    c = render_pixel(dir, camera("0.6 0.5 2", "0 0 -1") + light_at("0.6 0.5 2", 1020) + square_vertices + material("0 0 0") +
                              "<Transformations><Translation id=\"1\">0 0 -5</Translation><Scaling id=\"2\">-1 1 1</Scaling></Transformations>" +
                              textures(map(1, "image", "replace_kd")) + moved);
    CHECK(c.x() == doctest::Approx(red(0, 0)).epsilon(1e-5));
    // An instance without <Textures> of a textured Mesh is drawn with its base's maps, as it keeps
    // its base's material.
    const std::string inherited = "<Objects><Mesh id=\"1\"><Material>1</Material><Textures>1</Textures>"
                                  "<Transformations>t1</Transformations><Faces>1 2 3 1 3 4</Faces></Mesh>"
                                  "<MeshInstance id=\"2\" baseMeshId=\"1\" resetTransform=\"true\">"
                                  "<Transformations>s2</Transformations></MeshInstance></Objects>";
    c = render_pixel(dir, camera("0.6 0.5 2", "0 0 -1") + light_at("0.6 0.5 2", 1020) + square_vertices + material("0 0 0") +
                              "<Transformations><Translation id=\"1\">0 0 -5</Translation><Scaling id=\"2\">-1 1 1</Scaling></Transformations>" +
                              textures(map(1, "image", "replace_kd")) + inherited);
    CHECK(c.x() == doctest::Approx(red(0, 0)).epsilon(1e-5));
}

TEST_CASE("course textures: a checkerboard in object space with C truncation") {
    test::scratch_dir dir("course_tex_checker");
    // x = trunc(p.x + Offset) * Scale % 2 != 0, y and z likewise; black where (x != y) != z. Black
    // 0.2, white 0.8: the pixel is 255 x that under the light of the decal test.
    const std::string checker = textures(map(1, "checkerboard", "replace_kd",
                                             "<BlackColor>0.2 0.2 0.2</BlackColor><WhiteColor>0.8 0.8 0.8</WhiteColor>"
                                             "<Scale>1</Scale><Offset>0</Offset>"));
    const std::string big = "<VertexData>-9 -9 0 9 -9 0 9 9 0 -9 9 0</VertexData>";
    struct probe {
        const char* at;
        bool black;
    } probes[] = {
        {"0.5 0.5", false},  // (0, 0, 0): all even
        {"-0.5 0.5", false}, // trunc(-0.5) = 0: the cell next to 0 is twice as wide (floor would make it black)
        {"1.5 0.5", true},   // x odd
        {"-1.5 0.5", true},  // trunc(-1.5) = -1, C's -1 % 2 = -1: odd
        {"1.5 1.5", false},  // x and y odd
        {"-2.5 -1.5", true}, // x even, y odd
    };
    for (const probe& p : probes) {
        CAPTURE(p.at);
        const std::string from = std::string(p.at) + " 2";
        const vec3 c = render_pixel(dir, camera(from, "0 0 -1") + light_at(from, 1020) + big + material("0 0 0") + checker + square("1"));
        CHECK(c.x() == doctest::Approx(p.black ? 51 : 204).epsilon(1e-5));
    }
    // Moved by 0.7 along x, the pattern moves with it: the world's (1.5, 0.5) is the object's
    // (0.8, 0.5), white (the world's point would be black).
    const vec3 c = render_pixel(dir, camera("1.5 0.5 2", "0 0 -1") + light_at("1.5 0.5 2", 1020) + big + material("0 0 0") +
                                         "<Transformations><Translation id=\"1\">0.7 0 0</Translation></Transformations>" +
                                         checker + square("1", "t1"));
    CHECK(c.x() == doctest::Approx(204).epsilon(1e-5));
}

TEST_CASE("course textures: the background image covers the film from the pixels' corners") {
    test::scratch_dir dir("course_tex_background");
    dir.write("t.ppm", test_image());
    // An 8 x 4 film with nothing in it: pixel (i, j) reads (u, v) = (i / 8, j / 4). Nearest: texel
    // (floor(4 i / 8), floor(2 j / 4)) = (i / 2, j / 2). Bilinear: x = i / 2, y = j / 2.
    auto film = [&](const std::string& interpolation) {
        const std::string xml =
            "<Scene><BackgroundColor>9 9 9</BackgroundColor><Cameras><Camera id=\"1\"><Position>0 0 0</Position><Gaze>0 0 -1</Gaze>"
            "<Up>0 1 0</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>8 4</ImageResolution>"
            "<ImageName>x.exr</ImageName></Camera></Cameras><VertexData>0 0 0</VertexData>" +
            textures(map(1, "image", "replace_background", "<Interpolation>" + interpolation + "</Interpolation>")) + "</Scene>";
        const whitted_scene s = load_xml_scene(dir.write("bg.xml", xml));
        CHECK(s.warnings.empty());
        return render_whitted(s, 0).img;
    };
    const image nearest = film("nearest");
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 8; ++i) {
            CAPTURE(i);
            CAPTURE(j);
            CHECK(nearest.pixel(i, j).x() == red(i / 2, j / 2));
        }
    const image bilinear = film("bilinear");
    CHECK(bilinear.pixel(1, 1).x() == doctest::Approx((10 + 20 + 110 + 120) / 4.0)); // x = y = 0.5
    CHECK(bilinear.pixel(0, 0).x() == doctest::Approx(10));
    CHECK(bilinear.pixel(7, 3).x() == doctest::Approx(140)); // x = 3.5, y = 1.5: clamped to texel (3, 1)
    CHECK(bilinear.pixel(3, 2).x() == doctest::Approx(0.5 * 20 + 0.5 * 30 + 100)); // x = 1.5, y = 1
}

TEST_CASE("course textures: a normal map turns the shading normal in the frame (T, B, N) of a square and a sphere") {
    test::scratch_dir dir("course_tex_normal");
    // Every texel (255, 128, 191): n_t = 2 c / 255 - 1 = (1, 0.003922, 0.4980). On the square,
    // T^ = dP/du / |.| = +x, B^ = dP/dv / |.| = -y (v grows downwards), N = +z:
    // n = (1, -0.003922, 0.4980) / 1.11718.
    dir.write("t.ppm", ppm(2, 2, [](int, int) { return vec3(255, 128, 191); }));
    const double len = std::sqrt(1 + 0.003922 * 0.003922 + 0.4980 * 0.4980);
    const vec3 n(1 / len, -0.003922 / len, 0.4980 / len);
    const std::string scene = camera("0 0 2", "0 0 -1") + square_vertices + material("1 1 1") +
                              textures(map(1, "image", "replace_normal")) + square("1");
    // A light at (2, 0, 2) of intensity 2040: E = 2040 / 8 = 255, l = (1, 0, 1) / sqrt 2. Without
    // the map n . l = 0.7071; with it 255 (n . l) = 255 (1 + 0.4980) / (sqrt 2 x 1.11718) = 241.8.
    const vec3 right = render_pixel(dir, scene + light_at("2 0 2", 2040));
    CHECK(right.x() == doctest::Approx(255 * dot(n, unit_vector(vec3(1, 0, 1)))).epsilon(2e-3));
    CHECK(right.x() == doctest::Approx(241.8).epsilon(2e-3));
    // From (-2, 0, 2) the tilted normal faces away: n . l = (-1 + 0.4980) / (sqrt 2 x 1.117) < 0, black.
    CHECK(render_pixel(dir, scene + light_at("-2 0 2", 2040)).x() == 0);
    // A unit sphere seen from (0, 0, 3) at P = (0, 0, 1): theta = phi = pi / 2, dP/du = 2 pi (P_z, 0,
    // -P_x) = 2 pi (1, 0, 0) and dP/dv = pi (P_y cos phi, -r sin theta, P_y sin phi) = pi (0, -1, 0):
    // the square's frame again, so the same normal and, with the lights 2 further out, the same 241.8.
    const std::string sphere = "<VertexData>0 0 0</VertexData>" + material("1 1 1") + textures(map(1, "image", "replace_normal")) +
                               "<Objects><Sphere id=\"1\"><Material>1</Material><Textures>1</Textures><Center>1</Center>"
                               "<Radius>1</Radius></Sphere></Objects>";
    CHECK(render_pixel(dir, camera("0 0 3", "0 0 -1") + sphere + light_at("2 0 3", 2040)).x() == doctest::Approx(241.8).epsilon(2e-3));
    CHECK(render_pixel(dir, camera("0 0 3", "0 0 -1") + sphere + light_at("-2 0 3", 2040)).x() == 0);
}

TEST_CASE("course textures: a bump map from nearest heights, in a mesh's object frame and on a sphere") {
    test::scratch_dir dir("course_tex_bump");
    // Heights 10 x on an 8 x 2 image (R = G = B): at u = 0.5 (column 4) h_u = h(u + 1/8) - h(u) = 10,
    // h_v = 0. With T = dP/du = (2, 0, 0), B = dP/dv = (0, -2, 0), N = +z and BumpFactor 0.01:
    // n' = (B + k h_v N) x (T + k h_u N) = (0, -2, 0) x (2, 0, 0.1) = (-0.2, 0, 4): the surface rises
    // towards +x, so its normal leans to -x.
    dir.write("t.ppm", ppm(8, 2, [](int x, int) { return vec3(10 * x, 10 * x, 10 * x); }));
    const std::string bump = textures(map(1, "image", "bump_normal", "<BumpFactor>0.01</BumpFactor><Interpolation>bilinear</Interpolation>"));
    const std::string base = camera("0 0 2", "0 0 -1") + square_vertices + material("1 1 1") + bump;
    const vec3 n = unit_vector(vec3(-0.2, 0, 4));
    // Lights at (+-2, 0, 2), 2040: E = 255, l = (+-1, 0, 1) / sqrt 2 (flat: both 180.3).
    CHECK(render_pixel(dir, base + square("1") + light_at("2 0 2", 2040)).x() ==
          doctest::Approx(255 * dot(n, unit_vector(vec3(1, 0, 1)))).epsilon(1e-3)); // 171.1
    CHECK(render_pixel(dir, base + square("1") + light_at("-2 0 2", 2040)).x() ==
          doctest::Approx(255 * dot(n, unit_vector(vec3(-1, 0, 1)))).epsilon(1e-3)); // 189.1
    // Scaled by 3 along z (the plane z = 0 does not move): in the object's frame, then by M^-T,
    // n = (-0.2, 0, 4 / 3) / |.|, 255 n . l = 151.6. (Worked in the world's frame with the world's
    // T and B it would stay 171.1: the course's images follow the object's frame.)
    const vec3 scaled = unit_vector(vec3(-0.2, 0, 4.0 / 3));
    CHECK(render_pixel(dir, base + "<Transformations><Scaling id=\"1\">1 1 3</Scaling></Transformations>" + square("1", "s1") +
                                light_at("2 0 2", 2040))
              .x() == doctest::Approx(255 * dot(scaled, unit_vector(vec3(1, 0, 1)))).epsilon(1e-3));
    // A flat height field leaves a sphere's normal as it was: n' = B x T is the outward normal.
    dir.write("flat.ppm", ppm(4, 4, [](int, int) { return vec3(90, 90, 90); }));
    const std::string sphere = "<VertexData>0 0 0</VertexData>" + material("1 1 1") +
                               "<Objects><Sphere id=\"1\"><Material>1</Material><Textures>1</Textures><Center>1</Center>"
                               "<Radius>1</Radius></Sphere></Objects>";
    // From (0, 0, 3) the hit is (0, 0, 1); a light at (0, 2, 3), d^2 = 8, l = (0, 2, 2) / sqrt 8:
    // 2040 / 8 x 0.7071 = 180.3.
    const vec3 s = render_pixel(dir, camera("0 0 3", "0 0 -1") + light_at("0 2 3", 2040) +
                                         textures(map(1, "image", "bump_normal", "<BumpFactor>5</BumpFactor>"), "flat.ppm") + sphere);
    CHECK(s.x() == doctest::Approx(255 / std::sqrt(2.0)).epsilon(1e-3));
    // The ramp on the sphere: at P = (0, 0, 1), u = 0.25 (column 2, h_u = 10), v = 0.5 (h_v = 0);
    // T = 2 pi (1, 0, 0), B = pi (0, -1, 0), N = (0, 0, 1), k = 0.01: n' = B x (T + 0.1 N) =
    // (-0.1 pi, 0, 2 pi^2), n = (-0.01591, 0, 0.99987). Lights at (+-2, 0, 3): E = 255, l = (+-1, 0, 1) / sqrt 2:
    // 255 (0.99987 -+ 0.01591) / sqrt 2 = 177.4 and 183.2 (180.3 unbumped).
    const std::string ramp_sphere = camera("0 0 3", "0 0 -1") + textures(map(1, "image", "bump_normal", "<BumpFactor>0.01</BumpFactor>")) + sphere;
    const vec3 leaning = unit_vector(vec3(-0.1 * 3.14159265358979, 0, 2 * 3.14159265358979 * 3.14159265358979));
    CHECK(render_pixel(dir, ramp_sphere + light_at("2 0 3", 2040)).x() ==
          doctest::Approx(255 * dot(leaning, unit_vector(vec3(1, 0, 1)))).epsilon(1e-4)); // 177.4
    CHECK(render_pixel(dir, ramp_sphere + light_at("-2 0 3", 2040)).x() ==
          doctest::Approx(255 * dot(leaning, unit_vector(vec3(-1, 0, 1)))).epsilon(1e-4)); // 183.2
}

TEST_CASE("course textures: Perlin noise is zero on the lattice, continuous and bounded") {
    const course_perlin p = course_perlin::seeded(795);
    // w(t) = -6|t|^5 + 15|t|^4 - 10|t|^3 + 1: 1 at 0, 0 at 1, 1/2 at 1/2, even.
    CHECK(course_perlin::weight(0) == 1);
    CHECK(course_perlin::weight(1) == doctest::Approx(0));
    CHECK(course_perlin::weight(0.5) == doctest::Approx(0.5));
    CHECK(course_perlin::weight(-0.3) == course_perlin::weight(0.3));
    // At a lattice point every corner's term is G . 0 or has a weight w(1) = 0.
    for (int i = -3; i <= 3; ++i) CHECK(p.noise(vec3(i, 2 * i, -i)) == doctest::Approx(0).epsilon(1e-12));
    // Each corner adds at most w w w |G| |d| <= sqrt 2 sqrt 3 (and the weights sum to 1 over the
    // cell): |n| <= sqrt 6. Continuous: a step of 1e-6 moves it by less than 1e-4.
    pcg32 rng(7);
    double lo = 0, hi = 0;
    for (int k = 0; k < 2000; ++k) {
        const vec3 x(8 * rng.next_double() - 4, 8 * rng.next_double() - 4, 8 * rng.next_double() - 4);
        const double n = p.noise(x);
        lo = std::fmin(lo, n);
        hi = std::fmax(hi, n);
        CHECK(std::fabs(p.noise(x + vec3(1e-6, 1e-6, 1e-6)) - n) < 1e-4);
    }
    CHECK(lo >= -std::sqrt(6.0));
    CHECK(hi <= std::sqrt(6.0));
    CHECK(hi - lo > 0.5); // it varies
    // Its grey through replace_kd on the square: R = G = B, and absval's value is |n|.
    texture_map m;
    m.pattern = texture_map::pattern_t::perlin;
    m.absval = true;
    const vec3 at(0.3, 1.7, -2.2);
    CHECK(m.colour(0, 0, at).x == doctest::Approx(std::fabs(m.perlin.noise(at))));
    m.absval = false;
    CHECK(m.colour(0, 0, at).y == doctest::Approx((m.perlin.noise(at) + 1) / 2));
}

TEST_CASE("course textures: a JPEG image is read as 8-bit codes") {
    const loaded_image img = read_image(std::string(RTWEEKEND_TEST_DATA) + "/fuzz/jpeg_16x16.jpg");
    CHECK(img.format == "JPEG");
    CHECK(img.display_encoded);
    CHECK(img.pixels.width() == 16);
    CHECK(img.pixels.height() == 16);
    for (float c : img.pixels.data()) {
        CHECK(c >= 0);
        CHECK(c <= 255);
        CHECK(c == std::floor(c));
    }
}

TEST_CASE("course textures: one line for what cannot be read") {
    test::scratch_dir dir("course_tex_bad");
    dir.write("t.ppm", test_image());
    auto error_of = [&](const std::string& body) -> std::string {
        try {
            load_xml_scene(dir.write("bad.xml", "<Scene>" + camera("0 0 2", "0 0 -1") + body + "</Scene>"));
        } catch (const scene_error& e) {
            CHECK(std::string(e.what()).find('\n') == std::string::npos);
            return e.what();
        }
        return "";
    };
    const std::string mesh = square_vertices + material("1 1 1");
    CHECK(error_of(mesh + textures(map(1, "image", "replace_kd")) + square("1")).empty());
    CHECK(error_of(mesh + textures(map(1, "image", "replace_kd")) + square("2")).find("names texture map 2") != std::string::npos);
    CHECK(error_of(mesh + textures(map(1, "image", "decal_kd")) + square("1")).find("unknown <DecalMode> 'decal_kd'") != std::string::npos);
    CHECK(error_of(mesh + textures(map(1, "marble", "replace_kd")) + square("1")).find("unknown type \"marble\"") != std::string::npos);
    CHECK(error_of(mesh + textures(map(1, "image", "replace_kd", "<Interpolation>cubic</Interpolation>")) + square("1"))
              .find("unknown <Interpolation> 'cubic'") != std::string::npos);
    CHECK(error_of(mesh + textures(map(1, "image", "replace_kd", "<Normalizer>0</Normalizer>")) + square("1"))
              .find("<Normalizer> must be positive") != std::string::npos);
    CHECK(error_of(mesh + textures(map(1, "checkerboard", "replace_normal")) + square("1"))
              .find("replace_normal needs an image map") != std::string::npos);
    CHECK(error_of(mesh + textures(map(1, "image", "replace_kd"), "missing.png") + square("1")).find("missing.png") != std::string::npos);
    CHECK(error_of(mesh + textures(map(1, "image", "replace_background") + map(2, "image", "replace_background")))
              .find("a second replace_background map") != std::string::npos);
    // Texture coordinates: an odd count, and a face whose corner has none.
    std::string odd = mesh + textures(map(1, "image", "replace_kd")) + square("1");
    odd.replace(odd.find("0 1 1 1 1 0 0 0"), 15, "0 1 1 1 1 0 0");
    CHECK(error_of(odd).find("not a multiple of 2") != std::string::npos);
    std::string short_uv = mesh + textures(map(1, "image", "replace_kd")) + square("1");
    short_uv.replace(short_uv.find("0 1 1 1 1 0 0 0"), 15, "0 1 1 1 1 0");
    CHECK(error_of(short_uv).find("texture coordinate 4 does not exist (<TexCoordData> has 3)") != std::string::npos);
}

} // namespace test_course_textures
