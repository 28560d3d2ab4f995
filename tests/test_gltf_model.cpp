// glTF 2.0 models (rtweekend/io/gltf_model.h, io/model_scene.h): small files written here, with
// their buffers embedded as base64 or in a GLB container. Each material rule's kind and numbers;
// node transforms placing known corners where the matrices put them by hand; a mesh placed twice
// shared as instances; the camera and point lights; what renders (an emitter's radiance, its
// texture's texels the glTF way up, repeated; a normal texture in the frame TANGENT gives; vertex
// colours times the base colour, baked and in instances); a glTF and the same scene as a text scene giving
// the same image; one warning per unsupported feature, one error line per malformed file. And
// image_texture's samplers (repeat, mirror, bilinear, factor) against values worked by hand.

#include <rtweekend/io/gltf_model.h>
#include <rtweekend/io/model_scene.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/render/guides.h>
#include <rtweekend/rtweekend.h>
#include <rtweekend/scene/scene_compiler.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace test_gltf_model {

using namespace rt;

namespace {

std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t n = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out += table[(n >> (6 * k)) & 63];
    }
    if (i + 1 == bytes.size()) {
        const uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
        out += std::string{table[(n >> 18) & 63], table[(n >> 12) & 63], '=', '='};
    } else if (i + 2 == bytes.size()) {
        const uint32_t n = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += std::string{table[(n >> 18) & 63], table[(n >> 12) & 63], table[(n >> 6) & 63], '='};
    }
    return out;
}

template <class T>
std::string bytes_of(const std::vector<T>& v) {
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// The square [-1, 1]^2 at z = 0 facing +z: accessors 0 (POSITION), 1 (indices, two triangles)
// and 2 (TEXCOORD_0: (0, 0) the top left corner, the glTF way), all in buffer 0.
struct square_buffer {
    std::string bin;
    std::string views, accessors;

    square_buffer(double u_max = 1) {
        const std::vector<float> xyz = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
        const std::vector<uint16_t> index = {0, 1, 2, 0, 2, 3};
        const float u = float(u_max);
        const std::vector<float> uv = {0, 1, u, 1, u, 0, 0, 0};
        bin = bytes_of(xyz) + bytes_of(index) + std::string(4, '\0') + bytes_of(uv);
        views = R"([{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12},)"
                R"({"buffer":0,"byteOffset":64,"byteLength":32}])";
        accessors = R"([{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},)"
                    R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"},)"
                    R"({"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"}])";
    }
};

const std::string square_mesh = R"({"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2},"indices":1,"material":0}]})";

// A .gltf text with the square's buffer embedded; `rest` adds the other top-level members.
std::string gltf_text(const std::string& rest, const square_buffer& b = square_buffer()) {
    return R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + std::to_string(b.bin.size()) +
           R"(,"uri":"data:application/octet-stream;base64,)" + base64(b.bin) + R"("}],"bufferViews":)" + b.views +
           R"(,"accessors":)" + b.accessors + "," + rest + "}";
}

// The same as one GLB: the JSON chunk (without the buffer's uri) and the BIN chunk.
std::string glb_bytes(const std::string& rest, const square_buffer& b = square_buffer()) {
    std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":)" + std::to_string(b.bin.size()) +
                       R"(}],"bufferViews":)" + b.views + R"(,"accessors":)" + b.accessors + "," + rest + "}";
    while (json.size() % 4) json += ' ';
    std::string bin = b.bin;
    while (bin.size() % 4) bin += '\0';
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const uint32_t total = uint32_t(12 + 8 + json.size() + 8 + bin.size());
    return "glTF" + u32(2) + u32(total) + u32(uint32_t(json.size())) + u32(0x4E4F534A) + json + u32(uint32_t(bin.size())) +
           u32(0x004E4942) + bin;
}

const std::string one_node = R"("meshes":[)" + square_mesh + R"(],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0)";

template <class M>
const M* material_of(const gltf_model& m, size_t i) {
    const auto* mesh = dynamic_cast<const triangle_mesh*>(m.world.objects.at(i).get());
    REQUIRE(mesh);
    return dynamic_cast<const M*>(mesh->mat.get());
}

bool contains(const std::vector<std::string>& lines, const std::string& fragment) {
    for (const std::string& l : lines)
        if (l.find(fragment) != std::string::npos && l.find('\n') == std::string::npos) return true;
    return false;
}

// The first hit of the ray from `from` along `dir` with the model's world, or none.
bool hits(const gltf_model& m, const point3& from, const vec3& dir, point3* where = nullptr) {
    hit_record rec;
    if (!m.world.hit(ray(from, dir), interval(1e-6, infinity), rec)) return false;
    if (where) *where = rec.p;
    return true;
}

// The square's buffer with more float attributes per vertex (each its floats and glTF type), as
// accessors 3, 4, ... in buffer views 3, 4, ...
square_buffer with_attributes(const std::vector<std::pair<std::vector<float>, std::string>>& attributes) {
    square_buffer b;
    b.views.pop_back();
    b.accessors.pop_back();
    int view = 3;
    for (const auto& [values, type] : attributes) {
        const size_t offset = b.bin.size();
        b.bin += bytes_of(values);
        b.views += R"(,{"buffer":0,"byteOffset":)" + std::to_string(offset) + R"(,"byteLength":)" +
                   std::to_string(values.size() * 4) + "}";
        b.accessors += R"(,{"bufferView":)" + std::to_string(view++) + R"(,"componentType":5126,"count":4,"type":")" + type + R"("})";
    }
    b.views += "]";
    b.accessors += "]";
    return b;
}

// The shading normal a camera 10 units up +z sees at the centre of the square, under the model.
vec3 normal_at_centre(const gltf_model& m) {
    camera cam = test::test_camera(5, 5, 1, 4);
    cam.lookfrom = point3(0, 0, 10);
    cam.lookat = point3(0, 0, 0);
    cam.vfov = 5;
    const camera_frame frame = cam.frame();
    hittable_list world;
    world.add(std::make_shared<hittable_list>(m.world));
    const compiled_scene scene = compile_scene(world, frame.position, {});
    render_settings s;
    s.samples_per_pixel = 1;
    return render_guides(scene, frame, cam.sky(), s).normal.pixel(2, 2);
}

} // namespace

TEST_CASE("glTF models: each material rule gives its kind and numbers") {
    auto with_material = [](const std::string& material) {
        return decode_gltf_model(gltf_text(R"("materials":[)" + material + "]," + one_node), "m.gltf");
    };
    {
        const gltf_model m = with_material(R"({"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,0.125,1],"metallicFactor":0.3,"roughnessFactor":0.6}})");
        const auto* mr = material_of<metal_roughness>(m, 0);
        REQUIRE(mr);
        CHECK(mr->base_colour().x() == 0.5);
        CHECK(mr->base_colour().y() == 0.25);
        CHECK(mr->base_colour().z() == 0.125);
        CHECK(mr->metallic() == 0.3);
        CHECK(mr->roughness() == 0.6);
        CHECK(m.warnings.empty());
        CHECK_FALSE(m.emits);
    }
    { // The defaults: white, metallic 1, roughness 1 (glTF's pbrMetallicRoughness defaults).
        const gltf_model m = with_material("{}");
        const auto* mr = material_of<metal_roughness>(m, 0);
        REQUIRE(mr);
        CHECK(mr->base_colour().x() == 1);
        CHECK(mr->metallic() == 1);
        CHECK(mr->roughness() == 1);
    }
    { // An emitter: emissiveFactor times KHR_materials_emissive_strength, two-sided when doubleSided.
        const gltf_model m = with_material(R"({"emissiveFactor":[0.2,0.4,0.6],"doubleSided":true,)"
                                           R"("extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":5}}})");
        const auto* light = material_of<diffuse_light>(m, 0);
        REQUIRE(light);
        CHECK(light->emission().x() == doctest::Approx(1.0));
        CHECK(light->emission().y() == doctest::Approx(2.0));
        CHECK(light->emission().z() == doctest::Approx(3.0));
        CHECK(light->two_sided());
        CHECK(m.emits);
        CHECK(contains(m.warnings, "rendered as a light"));
    }
    { // Transmission: clear glass of KHR_materials_ior's index; rough glass at its roughness.
        const gltf_model clear = with_material(R"({"pbrMetallicRoughness":{"roughnessFactor":0},"extensions":)"
                                               R"({"KHR_materials_transmission":{"transmissionFactor":1},"KHR_materials_ior":{"ior":1.33}}})");
        const auto* glass = material_of<dielectric>(clear, 0);
        REQUIRE(glass);
        CHECK(glass->refraction_index() == 1.33);
        const gltf_model rough = with_material(R"({"pbrMetallicRoughness":{"roughnessFactor":0.4},"extensions":)"
                                               R"({"KHR_materials_transmission":{"transmissionFactor":1}}})");
        const auto* frosted = material_of<rough_dielectric>(rough, 0);
        REQUIRE(frosted);
        CHECK(frosted->refraction_index() == 1.5);
        CHECK(frosted->roughness_u() == 0.4);
    }
    { // No material: glTF's default material, the same as {}.
        std::string mesh = square_mesh;
        mesh.replace(mesh.find(R"(,"material":0)"), 13, "");
        const gltf_model m = decode_gltf_model(gltf_text(R"("meshes":[)" + mesh + R"(],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}])"), "d.gltf");
        const auto* mr = material_of<metal_roughness>(m, 0);
        REQUIRE(mr);
        CHECK(mr->metallic() == 1);
    }
}

TEST_CASE("glTF models: node transforms place the corners where the matrices say") {
    // Parent: translation (10, 0, 0). Child: scale (2, 1, 1), then 90 degrees about z (the unit
    // quaternion (0, 0, sin 45, cos 45)), then translation (1, 2, 3). The square's corners
    // (+-1, +-1, 0) scale to (+-2, +-1, 0), turn to (-+1, +-2, 0) ((x, y) -> (-y, x)), and move to
    // x in [0, 2], y in [0, 4], z = 3, then x in [10, 12].
    const double s45 = std::sqrt(0.5);
    const std::string nodes = R"("meshes":[)" + square_mesh + R"(],"nodes":[{"translation":[10,0,0],"children":[1]},)" +
                              R"({"mesh":0,"translation":[1,2,3],"scale":[2,1,1],"rotation":[0,0,)" + std::to_string(s45) +
                              "," + std::to_string(s45) + R"(]}],"scenes":[{"nodes":[0]}],"materials":[{}])";
    const gltf_model m = decode_gltf_model(gltf_text(nodes), "t.gltf");
    REQUIRE(m.world.objects.size() == 1);
    CHECK(m.lo.x() == doctest::Approx(10).epsilon(1e-6));
    CHECK(m.lo.y() == doctest::Approx(0).epsilon(1e-6));
    CHECK(m.lo.z() == doctest::Approx(3));
    CHECK(m.hi.x() == doctest::Approx(12).epsilon(1e-6));
    CHECK(m.hi.y() == doctest::Approx(4).epsilon(1e-6));
    CHECK(m.hi.z() == doctest::Approx(3));
    // The corner (1, 1, 0): scaled (2, 1, 0), turned (-1, 2, 0), moved (0, 4, 3), then (10, 4, 3).
    point3 p;
    CHECK(hits(m, point3(10.05, 3.9, 10), vec3(0, 0, -1), &p));
    CHECK(p.z() == doctest::Approx(3));
    CHECK_FALSE(hits(m, point3(12.05, 3.9, 10), vec3(0, 0, -1)));

    // A node's matrix (column-major): scale 3 and translation (0, 0, -5): corners at +-3, z = -5.
    const std::string matrix = R"("meshes":[)" + square_mesh +
                               R"(],"nodes":[{"mesh":0,"matrix":[3,0,0,0, 0,3,0,0, 0,0,3,0, 0,0,-5,1]}],"scenes":[{"nodes":[0]}],"materials":[{}])";
    const gltf_model mm = decode_gltf_model(gltf_text(matrix), "m.gltf");
    CHECK(mm.lo.x() == -3);
    CHECK(mm.hi.y() == 3);
    CHECK(mm.lo.z() == -5);
}

TEST_CASE("glTF models: a mesh placed by two nodes is shared, each placement an instance") {
    const std::string nodes = R"("meshes":[)" + square_mesh +
                              R"(],"nodes":[{"mesh":0,"translation":[-3,0,0]},{"mesh":0,"translation":[3,0,0]}],"scenes":[{"nodes":[0,1]}],"materials":[{}])";
    const gltf_model m = decode_gltf_model(gltf_text(nodes), "i.gltf");
    REQUIRE(m.world.objects.size() == 2);
    const auto* a = dynamic_cast<const transform*>(m.world.objects[0].get());
    const auto* b = dynamic_cast<const transform*>(m.world.objects[1].get());
    REQUIRE(a);
    REQUIRE(b);
    CHECK(a->object() == b->object()); // one mesh, two placements
    CHECK(hits(m, point3(3.5, 0.5, 5), vec3(0, 0, -1)));
    CHECK(hits(m, point3(-3.5, -0.5, 5), vec3(0, 0, -1)));
    CHECK_FALSE(hits(m, point3(0, 0, 5), vec3(0, 0, -1)));
    CHECK(m.lo.x() == -4);
    CHECK(m.hi.x() == 4);
}

TEST_CASE("glTF models: the camera and the lights") {
    // A camera at (0, 1, 4) turned 180 degrees about y (quaternion (0, 1, 0, 0)): it looks along +z.
    const std::string rest = R"("meshes":[)" + square_mesh + R"(],"materials":[{}],"cameras":[{"type":"perspective","perspective":)"
                             R"({"yfov":0.5,"znear":0.1,"aspectRatio":1.5}}],"nodes":[{"mesh":0},{"camera":0,"translation":[0,1,4],)"
                             R"("rotation":[0,1,0,0]},{"translation":[0,3,0],"extensions":{"KHR_lights_punctual":{"light":0}}},)"
                             R"({"extensions":{"KHR_lights_punctual":{"light":1}}},)"
                             R"({"rotation":[0.5,0.5,0.5,0.5],"extensions":{"KHR_lights_punctual":{"light":2}}}],)"
                             R"("scenes":[{"nodes":[0,1,2,3,4]}],)"
                             R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[)"
                             R"({"type":"point","color":[1,0.5,0.25],"intensity":4},{"type":"spot","intensity":2,"spot":{}},)"
                             R"({"type":"directional","color":[0.5,1,1],"intensity":3}]}})";
    const gltf_model m = decode_gltf_model(gltf_text(rest), "c.gltf");
    REQUIRE(m.has_view);
    CHECK(m.view.lookfrom.y() == 1);
    CHECK(m.view.lookfrom.z() == 4);
    CHECK(m.view.lookat.z() == doctest::Approx(5));
    CHECK(m.view.lookat.x() == doctest::Approx(0).epsilon(1e-12));
    CHECK(m.view.vup.y() == doctest::Approx(1));
    CHECK(m.view.vfov == doctest::Approx(0.5 * 180 / pi));
    CHECK(m.view.aspect_ratio == 1.5);
    REQUIRE(m.point_lights.size() >= 1);
    CHECK(m.point_lights[0].position.y() == 3);
    CHECK(m.point_lights[0].intensity.x() == 4);
    CHECK(m.point_lights[0].intensity.y() == 2);
    CHECK(m.point_lights[0].intensity.z() == 1);
    REQUIRE(m.point_lights.size() == 2);
    // The spot at the origin shines down its node's -z; glTF's default cones, 0 and pi / 4.
    CHECK(m.point_lights[1].spot_direction.z() == -1);
    CHECK(m.point_lights[1].inner_cone == 0);
    CHECK(m.point_lights[1].outer_cone == doctest::Approx(pi / 4));
    // The sun's node turns by 120 degrees about (1, 1, 1) (quaternion (1, 1, 1, 1) / 2), which
    // takes x to y, y to z and z to x: its -z axis, the way it shines, becomes -x.
    REQUIRE(m.directional_lights.size() == 1);
    CHECK(m.directional_lights[0].direction.x() == doctest::Approx(-1));
    CHECK(m.directional_lights[0].direction.y() == doctest::Approx(0).epsilon(1e-12));
    CHECK(m.directional_lights[0].direction.z() == doctest::Approx(0).epsilon(1e-12));
    CHECK(m.directional_lights[0].irradiance.x() == 1.5);
    CHECK(m.directional_lights[0].irradiance.y() == 3);
    CHECK(m.warnings.empty());
}

TEST_CASE("glTF models: an emitter's radiance, its texture's texels the glTF way up and repeated") {
    test::scratch_dir dir("gltf_render");
    // A 2 x 1 picture: red on the left, blue on the right; as a data URI.
    const std::string png = encode_8bit_image(dir.file("rb.png"), 2, 1, {255, 0, 0, 0, 0, 255});
    auto scene_with = [&](const std::string& material, double u_max) {
        const std::string rest = R"("materials":[)" + material + R"(],"textures":[{"source":0,"sampler":0}],)"
                                 R"("samplers":[{"magFilter":9728,"wrapS":10497,"wrapT":10497}],)"
                                 R"("images":[{"uri":"data:image/png;base64,)" + base64(png) + R"("}],)" + one_node;
        return dir.write("s.gltf", gltf_text(rest, square_buffer(u_max)));
    };
    // The square head-on, in the dark or under a white sky, `spp` samples a pixel.
    auto render_front = [&](const std::string& path, double sky = 0, int spp = 4) {
        scene_description s = load_model_scene(path);
        CHECK(s.warnings.empty() == (sky > 0)); // the lit materials below are read as written
        s.cam = test::test_camera(16, 16, spp, 3);
        s.cam.lookfrom = point3(0, 0, 20);
        s.cam.lookat = point3(0, 0, 0);
        s.cam.vfov = 5.6; // half-height 20 tan 2.8 deg = 0.98: the square fills the view
        s.cam.background = color(sky, sky, sky);
        hittable_list world;
        world.add(std::make_shared<hittable_list>(s.world));
        return test::render_checked(s.cam, world).img;
    };
    { // Emission (1, 2, 3) in the dark: the radiance itself.
        const image img = render_front(scene_with(R"({"emissiveFactor":[0.25,0.5,0.75],"extensions":)"
                                                  R"({"KHR_materials_emissive_strength":{"emissiveStrength":4}}})", 1));
        CHECK(img.pixel(8, 8).x() == doctest::Approx(1));
        CHECK(img.pixel(8, 8).y() == doctest::Approx(2));
        CHECK(img.pixel(8, 8).z() == doctest::Approx(3));
    }
    { // The emissive texture across the square: red on the left half, blue on the right.
        const image img = render_front(scene_with(R"({"emissiveFactor":[1,1,1],"emissiveTexture":{"index":0}})", 1));
        CHECK(img.pixel(3, 8).x() == doctest::Approx(1).epsilon(1e-5));
        CHECK(img.pixel(3, 8).z() == doctest::Approx(0).epsilon(1e-5));
        CHECK(img.pixel(12, 8).x() == doctest::Approx(0).epsilon(1e-5));
        CHECK(img.pixel(12, 8).z() == doctest::Approx(1).epsilon(1e-5));
    }
    { // The base colour texture on a smooth metal (metallic 1, roughness 0) under a white sky,
      // seen head-on: Schlick's Fresnel at normal incidence is the base colour itself.
        const image img =
            render_front(scene_with(R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},"roughnessFactor":0}})", 1), 1);
        CHECK(img.pixel(3, 8).x() == doctest::Approx(1).epsilon(1e-3));
        CHECK(img.pixel(3, 8).z() == doctest::Approx(0).epsilon(1e-3));
        CHECK(img.pixel(12, 8).x() == doctest::Approx(0).epsilon(1e-3));
        CHECK(img.pixel(12, 8).z() == doctest::Approx(1).epsilon(1e-3));
    }
    { // The picture as a metallicRoughnessTexture (read as data): blue 0, green 0 on the left, a
      // smooth dielectric base (the clear coat's 0.04 head-on, the base colour c under it:
      // 0.04 + 0.96 c under a white sky); blue 1, green 0 on the right, a smooth metal of colour c.
        const image img = render_front(scene_with(R"({"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.6,0.3,1],)"
                                                  R"("metallicRoughnessTexture":{"index":0}}})", 1),
                                       1, 16);
        CHECK(img.pixel(12, 8).x() == doctest::Approx(0.9).epsilon(1e-3));
        CHECK(img.pixel(12, 8).z() == doctest::Approx(0.3).epsilon(1e-3));
        CHECK(img.pixel(3, 8).x() == doctest::Approx(0.04 + 0.96 * 0.9).epsilon(1e-2));
        CHECK(img.pixel(3, 8).z() == doctest::Approx(0.04 + 0.96 * 0.3).epsilon(1e-2));
    }
    { // u from 0 to 2, repeated: red, blue, red, blue in quarters.
        const image img = render_front(scene_with(R"({"emissiveFactor":[1,1,1],"emissiveTexture":{"index":0}})", 2));
        for (int q = 0; q < 4; ++q) {
            const color c = img.pixel(q * 4 + 2, 8);
            CHECK(c.x() == doctest::Approx(q % 2 == 0 ? 1 : 0).epsilon(1e-5));
            CHECK(c.z() == doctest::Approx(q % 2 == 0 ? 0 : 1).epsilon(1e-5));
        }
    }
}

TEST_CASE("glTF models: a normal texture tilts the shading normal the glTF way up") {
    // One texel, normal (0, 0.5, 0.87) in (x right, y up the picture, z out): tilted towards the
    // top of the picture, which the square's texture coordinates put at +y. Read as data (not
    // sRGB): green 191 is 2 191 / 255 - 1 = 0.498.
    const std::string png = encode_8bit_image("n.png", 1, 1, {128, 191, 237});
    const std::string rest = R"("materials":[{"normalTexture":{"index":0,"scale":1}}],"textures":[{"source":0}],)"
                             R"("images":[{"uri":"data:image/png;base64,)" + base64(png) + R"("}],)" + one_node;
    const gltf_model m = decode_gltf_model(gltf_text(rest), "n.gltf");
    const auto* mesh = dynamic_cast<const triangle_mesh*>(m.world.objects.at(0).get());
    REQUIRE(mesh);
    const auto* mapped = dynamic_cast<const normal_mapped*>(mesh->mat.get());
    REQUIRE(mapped);
    CHECK(dynamic_cast<const metal_roughness*>(mapped->base().get()));
    CHECK(m.warnings.empty());
    const vec3 n = normal_at_centre(m);
    const double y = 2 * 191 / 255.0 - 1, x = 2 * 128 / 255.0 - 1, z = 2 * 237 / 255.0 - 1, len = std::sqrt(x * x + y * y + z * z);
    CHECK(n.x() == doctest::Approx(x / len).epsilon(1e-4));
    CHECK(n.y() == doctest::Approx(y / len).epsilon(1e-4));
    CHECK(n.z() == doctest::Approx(z / len).epsilon(1e-4));
}

TEST_CASE("glTF models: TANGENT frames the normal texture, turned with its node") {
    // One texel tilted towards the tangent: (218, 128, 218) read as data is n = (x, y, z) =
    // (0.7098, 0.0039, 0.7098) in (T, B, N). Each vertex's TANGENT is (1, 1, 0)/sqrt 2, w = 1,
    // at 45 degrees to the texture coordinates' dp/du (+x); B = N x T = (-1, 1, 0)/sqrt 2 (on
    // dp/dv's side, +y, as w = 1 says).
    const std::string png = encode_8bit_image("t.png", 1, 1, {218, 128, 218});
    const double x = 2 * 218 / 255.0 - 1, y = 2 * 128 / 255.0 - 1, z = 2 * 218 / 255.0 - 1;
    const double r = 1 / std::sqrt(2.0);
    auto expected = [&](const vec3& t, const vec3& b) { return unit_vector(x * t + y * b + z * vec3(0, 0, 1)); };
    const float h = float(r);
    const square_buffer b = with_attributes({{{h, h, 0, 1, h, h, 0, 1, h, h, 0, 1, h, h, 0, 1}, "VEC4"},
                                             {{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3"}});
    auto model = [&](const std::string& attributes, const std::string& node) {
        const std::string rest = R"("materials":[{"normalTexture":{"index":0}}],"textures":[{"source":0}],)"
                                 R"("images":[{"uri":"data:image/png;base64,)" + base64(png) + R"("}],)"
                                 R"("meshes":[{"primitives":[{"attributes":)" + attributes + R"(,"indices":1,"material":0}]}],)"
                                 R"("nodes":[)" + node + R"(],"scenes":[{"nodes":[0]}],"scene":0)";
        gltf_model m = decode_gltf_model(gltf_text(rest, b), "t.gltf");
        CHECK(m.warnings.empty());
        return m;
    };
    // Normals +z (accessor 4): glTF ignores tangents on a mesh without normals.
    const std::string with_tangent = R"({"POSITION":0,"TEXCOORD_0":2,"NORMAL":4,"TANGENT":3})";
    const std::string without = R"({"POSITION":0,"TEXCOORD_0":2,"NORMAL":4})";
    SUBCASE("as given") {
        const vec3 n = normal_at_centre(model(with_tangent, R"({"mesh":0})"));
        const vec3 want = expected(vec3(r, r, 0), vec3(-r, r, 0));
        for (int a = 0; a < 3; ++a) CHECK(n[a] == doctest::Approx(want[a]).epsilon(1e-4));
        // Without TANGENT the frame is dp/du = +x, B = +y: a different normal.
        const vec3 plain = normal_at_centre(model(without, R"({"mesh":0})"));
        const vec3 want_plain = expected(vec3(1, 0, 0), vec3(0, 1, 0));
        for (int a = 0; a < 3; ++a) CHECK(plain[a] == doctest::Approx(want_plain[a]).epsilon(1e-4));
    }
    SUBCASE("turned 90 degrees about z by its node") {
        // The rotation takes T to (-1, 1, 0)/sqrt 2 and B to (-1, -1, 0)/sqrt 2.
        const vec3 n = normal_at_centre(model(with_tangent, R"({"mesh":0,"rotation":[0,0,0.70710678,0.70710678]})"));
        const vec3 want = expected(vec3(-r, r, 0), vec3(-r, -r, 0));
        for (int a = 0; a < 3; ++a) CHECK(n[a] == doctest::Approx(want[a]).epsilon(1e-4));
    }
}

TEST_CASE("glTF models: COLOR_0 multiplies the base colour, across the square and in instances") {
    // Vertex colours red at x = -1, blue at x = +1: at x the colour is ((1 - x)/2, 0, (1 + x)/2)
    // times the base colour (1, 0.5, 1). A smooth metal under a white sky, seen head-on, shows its
    // base colour (Schlick's Fresnel at normal incidence), so a pixel is the colour at its x.
    const square_buffer b = with_attributes({{{1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0}, "VEC3"}});
    auto model = [&](const std::string& nodes, const std::string& roots) {
        const std::string rest = R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,1,1],"roughnessFactor":0}}],)"
                                 R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":3},"indices":1,"material":0}]}],)"
                                 R"("nodes":)" + nodes + R"(,"scenes":[{"nodes":)" + roots + R"(}],"scene":0)";
        test::scratch_dir dir("gltf_colour");
        scene_description s = load_model_scene(dir.write("c.gltf", gltf_text(rest, b)));
        CHECK(s.warnings.empty());
        return s;
    };
    auto render_row = [&](scene_description s, double x_centre) {
        s.cam = test::test_camera(16, 16, 64, 3);
        s.cam.lookfrom = point3(x_centre, 0, 20);
        s.cam.lookat = point3(x_centre, 0, 0);
        s.cam.vfov = 5.6; // half-height 20 tan 2.8 deg = 0.978
        s.cam.background = color(1, 1, 1);
        hittable_list world;
        world.add(std::make_shared<hittable_list>(s.world));
        return test::render_checked(s.cam, world).img;
    };
    const double half = 20 * std::tan(degrees_to_radians(2.8));
    auto check_row = [&](const image& img, double x_shift) {
        for (int i : {2, 5, 8, 11, 13}) {
            const double x = ((i + 0.5) / 16 * 2 - 1) * half - x_shift; // in the square's own frame
            const color c = img.pixel(i, 8);
            CHECK(c.x() == doctest::Approx((1 - x) / 2).epsilon(0.01));
            CHECK(c.y() == doctest::Approx(0).epsilon(1e-4));
            CHECK(c.z() == doctest::Approx((1 + x) / 2).epsilon(0.01));
        }
    };
    SUBCASE("one placement, baked into the world") {
        check_row(render_row(model(R"([{"mesh":0}])", "[0]"), 0), 0);
    }
    SUBCASE("two placements, each an instance of one mesh") {
        const scene_description s = model(R"([{"mesh":0,"translation":[5,0,0]},{"mesh":0,"translation":[-5,0,0]}])", "[0,1]");
        check_row(render_row(s, 5), 0);
        check_row(render_row(s, -5), 0);
    }
}

TEST_CASE("glTF models: a glTF and the same scene as a text scene give the same image") {
    test::scratch_dir dir("gltf_twin");
    // The square in metal_roughness, a point light, a sun shining down -z (no rotation) and a
    // camera, both ways.
    const double yfov = 0.7;
    const std::string rest = R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,0.125,1],"metallicFactor":0.3,)"
                             R"("roughnessFactor":0.6}}],"meshes":[)" + square_mesh +
                             R"(],"cameras":[{"type":"perspective","perspective":{"yfov":0.7,"znear":0.1}}],)"
                             R"("nodes":[{"mesh":0},{"camera":0,"translation":[0.25,0.5,4]},)"
                             R"({"translation":[0.5,1,2],"extensions":{"KHR_lights_punctual":{"light":0}}},)"
                             R"({"extensions":{"KHR_lights_punctual":{"light":1}}}],"scenes":[{"nodes":[0,1,2,3]}],)"
                             R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","color":[1,0.5,0.25],"intensity":8},)"
                             R"({"type":"directional","color":[0.5,1,1],"intensity":0.5}]}})";
    const std::string gltf = dir.write("twin.gltf", gltf_text(rest));
    dir.write("square.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n");
    char vfov[64];
    std::snprintf(vfov, sizeof vfov, "%.17g", yfov * 180 / pi);
    const std::string text = dir.write("twin.txt", std::string("camera lookfrom 0.25 0.5 4\ncamera lookat 0.25 0.5 3\ncamera vup 0 1 0\n") +
                                                       "camera vfov_deg " + vfov + "\nbackground 0 0 0\n" +
                                                       "mesh square.obj metal_roughness 0.5 0.25 0.125 0.3 0.6\n" +
                                                       "point_light 0.5 1 2 8 4 2\ndirectional_light 0 0 -1 0.25 0.5 0.5\n");
    auto render_it = [](scene_description s) {
        const camera view = s.cam;
        s.cam = test::test_camera(24, 18, 8, 4);
        s.cam.lookfrom = view.lookfrom;
        s.cam.lookat = view.lookat;
        s.cam.vup = view.vup;
        s.cam.vfov = view.vfov;
        s.cam.background = view.background;
        return render(s.cam, s.world, s.point_lights, s.directional_lights).img;
    };
    const scene_description from_gltf = load_model_scene(gltf);
    CHECK(from_gltf.cam.aspect_ratio == doctest::Approx(4.0 / 3.0));
    REQUIRE(from_gltf.cam.background.has_value());
    CHECK(from_gltf.cam.background->x() == 0); // lit by its light: no sky
    const image a = render_it(from_gltf), b = render_it(load_scene(text));
    CHECK(test::same_bits(a, b));
    double sum = 0;
    for (float v : a.data()) sum += v;
    CHECK(sum > 0); // lit, not black
}

TEST_CASE("glTF models: a GLB holds the same model as its .gltf") {
    const std::string rest = R"("materials":[{}],)" + one_node;
    const gltf_model text = decode_gltf_model(gltf_text(rest), "a.gltf");
    const gltf_model binary = decode_gltf_model(glb_bytes(rest), "a.glb");
    REQUIRE(binary.world.objects.size() == 1);
    CHECK(binary.lo.x() == text.lo.x());
    CHECK(binary.hi.y() == text.hi.y());
    const auto* a = dynamic_cast<const triangle_mesh*>(text.world.objects[0].get());
    const auto* b = dynamic_cast<const triangle_mesh*>(binary.world.objects[0].get());
    REQUIRE(a);
    REQUIRE(b);
    CHECK(a->faces == b->faces);
    CHECK(a->uvs == b->uvs);
    // The glTF's v runs down: the corner at v = 0 (the top left, (-1, 1)) has the renderer's v = 1.
    CHECK(b->uvs[3][1] == 1);
}

TEST_CASE("glTF models: one warning for what is not rendered as written, one error line for a malformed file") {
    { // Warnings: alphaMode BLEND, an unsupported extension, a picture that is missing.
        const std::string rest = R"("materials":[{"normalTexture":{"index":0},"alphaMode":"BLEND","pbrMetallicRoughness":)"
                                 R"({"baseColorTexture":{"index":0}}}],"textures":[{"source":0}],"images":[{"uri":"nowhere.png"}],)"
                                 R"("extensionsUsed":["KHR_materials_sheen"],)" + one_node;
        const gltf_model m = decode_gltf_model(gltf_text(rest), "w.gltf");
        CHECK(contains(m.warnings, "alphaMode BLEND is not supported: the surface is opaque"));
        CHECK(contains(m.warnings, "the glTF extension KHR_materials_sheen is not supported and is ignored"));
        CHECK(contains(m.warnings, "nowhere.png"));
        // The normal map's picture is missing too: no normal_mapped, the factor kept.
        REQUIRE(material_of<metal_roughness>(m, 0));
        CHECK(material_of<metal_roughness>(m, 0)->base_colour().x() == 1);
    }
    auto fails = [](const std::string& text, const std::string& fragment) {
        test::check_scene_error([&] { decode_gltf_model(text, "bad.gltf"); }, {"bad.gltf", fragment});
    };
    fails("{ not json", "malformed glTF file");
    fails(gltf_text(R"("extensionsRequired":["KHR_draco_mesh_compression"],)" + one_node),
          "requires the glTF extension KHR_draco_mesh_compression, which is not supported");
    { // An accessor past the end of its buffer view; an index past the vertices.
        square_buffer b;
        const std::string four = R"("count":4,"type":"VEC3")";
        b.accessors.replace(b.accessors.find(four), four.size(), R"("count":5,"type":"VEC3")");
        fails(gltf_text(R"("materials":[{}],)" + one_node, b), "accessor 0: 5 elements run past the end of buffer view 0");
        square_buffer c;
        const uint16_t nine = 9;
        std::memcpy(&c.bin[48], &nine, 2);
        fails(gltf_text(R"("materials":[{}],)" + one_node, c), "mesh 0 primitive 0: index 9 is past its 4 vertices");
    }
    fails(gltf_text(R"("materials":[{}],"meshes":[)" + square_mesh + R"(],"nodes":[{"mesh":0,"children":[0]}],"scenes":[{"nodes":[0]}])"),
          "node 0 is reached twice");
    fails(gltf_text(R"("materials":[{}],"meshes":[)" + square_mesh + R"(],"nodes":[{"mesh":3}],"scenes":[{"nodes":[0]}])"),
          "node 0 names mesh 3, of 1");
    fails(gltf_text(R"("materials":[{"pbrMetallicRoughness":{"metallicFactor":2}}],)" + one_node), "metallicFactor must be in [0, 1]");
    // Found by the gltf fuzzer: an emissive factor of 1.2e71 made a light of infinite power in float.
    fails(gltf_text(R"("materials":[{"emissiveFactor":[1,1,1.2e71]}],)" + one_node),
          "emissiveFactor is too large for single precision");
    fails(gltf_text(R"("materials":[{"emissiveFactor":[1,1,1e30],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":1e10}}}],)" + one_node),
          "emissiveFactor times emissiveStrength is too large for single precision");
    fails(gltf_text(R"("materials":[{}],"meshes":[)" + square_mesh + R"(],"nodes":[{"mesh":0,"scale":[0,1,1]}],"scenes":[{"nodes":[0]}])"),
          "placed by a singular matrix");
    // Found by the gltf fuzzer: a picture in a buffer view longer than its buffer (tinygltf hands
    // the view to the image loader unchecked).
    fails(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"data:application/octet-stream;base64,AAAAAA=="}],)"
          R"("bufferViews":[{"buffer":0,"byteLength":1000}],"images":[{"bufferView":0,"mimeType":"image/png"}]})",
          "image 0: its buffer view runs past the end of its buffer");
    // Found by the gltf fuzzer: a light index of 5.6e77, which tinygltf's GetNumberAsInt would
    // convert to int (undefined); and a fractional one.
    for (const char* light : {"5.6e77", "0.5", "-1"}) {
        CAPTURE(light);
        fails(gltf_text(R"("materials":[{}],"meshes":[)" + square_mesh + R"(],"nodes":[{"mesh":0},{"extensions":{"KHR_lights_punctual":{"light":)" +
                        std::string(light) + R"(}}}],"scenes":[{"nodes":[0,1]}],"extensions":{"KHR_lights_punctual":{"lights":[{"type":"point"}]}})"),
              "node 1: KHR_lights_punctual light must be a whole number from 0");
    }
    { // Vertex colours: on glass a warning (only a base colour takes them); a negative one, a
      // count that is not the vertices', two components and unnormalized integers are errors.
        const std::string coloured = R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":3},"indices":1,"material":0}]}],)"
                                     R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0)";
        const square_buffer grey = with_attributes({{{0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5}, "VEC3"}});
        const gltf_model m = decode_gltf_model(
            gltf_text(R"("materials":[{"extensions":{"KHR_materials_transmission":{"transmissionFactor":1}}}],)" + coloured, grey),
            "g.gltf");
        CHECK(contains(m.warnings, "mesh 0 primitive 0: COLOR_0 is not applied to a glass or emitting material"));
        const square_buffer negative = with_attributes({{{0.5, 0.5, 0.5, 0.5, -0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5}, "VEC3"}});
        fails(gltf_text(R"("materials":[{}],)" + coloured, negative), "mesh 0 primitive 0: COLOR_0 1 must be finite and at least 0");
        square_buffer three = grey;
        three.accessors.replace(three.accessors.rfind(R"("count":4)"), 9, R"("count":3)");
        fails(gltf_text(R"("materials":[{}],)" + coloured, three), "COLOR_0 and POSITION have different counts");
        square_buffer two = grey;
        two.accessors.replace(two.accessors.rfind("VEC3"), 4, "VEC2");
        fails(gltf_text(R"("materials":[{}],)" + coloured, two), "COLOR_0 has 2 components per element, not 3 or 4");
        square_buffer bytes = grey;
        bytes.accessors.replace(bytes.accessors.rfind("5126"), 4, "5121");
        fails(gltf_text(R"("materials":[{}],)" + coloured, bytes), "COLOR_0 of integers must be normalized");
    }
    test::check_one_line_error([] { load_gltf_model("/nonexistent/model.glb"); }, "/nonexistent/model.glb", "cannot open");
}

TEST_CASE("image_texture samplers: repeat, mirror, bilinear and a factor, against values by hand") {
    // A 2 x 2 picture, linear values chosen exactly: 0.25, 0.5 (top row), 0.75, 1 (bottom row),
    // in red; green and blue 0. Pixel centres at u = 0.25, 0.75 and v = 0.75 (top), 0.25.
    std::vector<float> px = {0.25f, 0, 0, 0.5f, 0, 0, 0.75f, 0, 0, 1.0f, 0, 0};
    auto red = [&](double u, double v, image_sampling s) { return image_texture::sample(px.data(), 2, 2, u, v, s).x(); };
    image_sampling books;
    CHECK(red(0.1, 0.9, books) == 0.25);
    CHECK(red(1.3, 0.9, books) == 0.5);  // clamped to the right column
    image_sampling rep;
    rep.wrap_u = rep.wrap_v = image_sampling::wrap_mode::repeat;
    CHECK(red(1.1, 0.9, rep) == 0.25);   // 1.1 -> 0.1
    CHECK(red(-0.2, 0.9, rep) == 0.5);   // -0.2 -> 0.8
    CHECK(red(0.1, 1.9, rep) == 0.25);   // v 1.9 -> 0.9 (top row)
    image_sampling mir = rep;
    mir.wrap_u = image_sampling::wrap_mode::mirror;
    CHECK(red(1.1, 0.9, mir) == 0.5);    // 1.1 -> 0.9
    CHECK(red(2.1, 0.9, mir) == 0.25);   // 2.1 -> 0.1
    image_sampling bi = books;
    bi.bilinear = true;
    CHECK(red(0.25, 0.75, bi) == doctest::Approx(0.25)); // a pixel centre: the pixel
    CHECK(red(0.5, 0.75, bi) == doctest::Approx(0.375)); // between 0.25 and 0.5
    CHECK(red(0.5, 0.5, bi) == doctest::Approx(0.625));  // the mean of all four
    CHECK(red(0.0, 0.75, bi) == doctest::Approx(0.25));  // clamped: the edge pixel alone
    bi.wrap_u = image_sampling::wrap_mode::repeat;
    CHECK(red(0.0, 0.75, bi) == doctest::Approx(0.375)); // repeated: half the right pixel
    bi.factor = color(2, 1, 1);
    CHECK(red(0.5, 0.5, bi) == doctest::Approx(1.25));
    // value() reads as sample() does (the renderer's image kind is checked by the renders above).
    rtw_image img;
    img.decode(encode_8bit_image("x.png", 2, 1, {255, 0, 0, 0, 0, 255}), "x.png");
    image_texture tex(img, rep);
    CHECK(tex.value(1.25, 0.5, point3(0, 0, 0)).x() == doctest::Approx(1)); // 1.25 -> 0.25, the red pixel
    CHECK(tex.value(1.75, 0.5, point3(0, 0, 0)).z() == doctest::Approx(1));
}

} // namespace test_gltf_model
