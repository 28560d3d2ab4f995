#pragma once
// load_gltf_model(path): a glTF 2.0 model (`.gltf` with its buffers and images, or one `.glb`),
// as models are now published, with its materials, its node hierarchy, its first camera and its
// lights.
//
//   rt::gltf_model m = rt::load_gltf_model("helmet.glb");       // throws scene_error
//   for (const std::string& w : m.warnings) ...                  // what it could not render as written
//   world.add(std::make_shared<rt::hittable_list>(m.world));
//   rt::render(cam, world, m.point_lights, m.directional_lights);
//
// tinygltf (Debian's libtinygltf-dev) parses the JSON and the buffers; the pictures are decoded
// here, as every other texture is (rtw_image::decode). The default scene's nodes are walked from
// its roots, each node's matrix (or translation * rotation * scale) times its parent's. What a
// node holds becomes (docs/models.md):
//   a mesh           one triangle_mesh per primitive (triangles, strips and fans; indexed or not),
//                    with the primitive's NORMAL (smooth shading), TEXCOORD_0, TANGENT (a normal
//                    map's frame) and COLOR_0 (multiplying the base colour); a mesh placed by
//                    one node is baked into world space, one placed by several nodes is shared, each
//                    placement a transform of it (an instance)
//   a camera         the first perspective camera met: gltf_model::view
//   a light          KHR_lights_punctual's point and spot lights: a point_light of intensity
//                    colour * intensity (candela read as the renderer's W/sr, as glTF viewers light
//                    with it), a spot's cone down its node's -z axis; directional lights: a
//                    directional_light shining down its node's -z axis, irradiance colour *
//                    intensity (lux read as W/m^2)
// A material (material_from_gltf) becomes:
//   emissive (emissiveFactor * KHR_materials_emissive_strength, times emissiveTexture) above 0
//       a diffuse_light, two-sided when the material is doubleSided
//   KHR_materials_transmission above 0
//       glass: dielectric (KHR_materials_ior, default 1.5), or rough_dielectric at its roughness
//   otherwise
//       metal_roughness(baseColorFactor * baseColorTexture, metallicFactor, roughnessFactor,
//                       metallicRoughnessTexture)
// Pictures are read with their sampler: repeated, mirrored or clamped, bilinear unless the sampler
// asks for the nearest pixel. A normalTexture makes the material normal_mapped (its frame from the
// primitive's TANGENTs, or else from the texture coordinates, smooth across a smooth mesh; the
// bitangent's handedness always from the coordinates); a metallicRoughnessTexture is
// metal_roughness's map (metallic and roughness per texel). The occlusion texture is not needed
// by a path tracer, which traces the occlusion it stands for. What is not rendered as written is
// one warning each (a rough glass's roughness texture, alpha, animation, ...).
// A malformed file (broken JSON, an index or accessor out of range, a non-finite position) is a
// scene_error naming the file and the element.

#include "../core/engine_linkage.h"
#include "../hittable_list.h"
#include "../directional_light.h"
#include "../point_light.h"
#include "../vec3.h"

#include <string>
#include <vector>

namespace rt {

struct gltf_model {
    hittable_list world;                 // the placed meshes: one triangle_mesh (or instance) per primitive
    std::vector<point_light> point_lights;
    std::vector<directional_light> directional_lights;
    std::vector<std::string> warnings;   // what was not rendered as written, one line each
    std::vector<std::string> files;      // what was read: the glTF, its buffers and images
    bool emits = false;                  // some material is an emitter
    point3 lo, hi;                       // the bounds of the placed geometry

    // The scene's first perspective camera, when it has one.
    struct camera_view {
        point3 lookfrom, lookat;         // lookat one unit in front of the camera
        vec3 vup;
        double vfov = 0;                 // degrees, vertical
        double aspect_ratio = 0;         // 0: the file gives none
    };
    bool has_view = false;
    camera_view view;
};

// Reads the glTF (or GLB) file at `path`, with the buffers and images it names beside it.
RTWEEKEND_ENGINE_FUNCTION gltf_model load_gltf_model(const std::string& path);

// The same from the file's bytes already read; `path` names it in messages, and files it names
// are looked for beside it.
RTWEEKEND_ENGINE_FUNCTION gltf_model decode_gltf_model(const std::string& bytes, const std::string& path);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/file.h"
#include "../core/scene_error.h"
#include "../material.h"
#include "../mesh.h"
#include "../texture.h"
#include "../transform.h"
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

namespace rt {

namespace detail {

// A 4x4 affine matrix, glTF's column-major order read into rows: x -> linear x + offset.
struct gltf_affine {
    mat3 linear;
    vec3 offset{0, 0, 0};

    gltf_affine then(const gltf_affine& local) const { // this * local
        return {linear * local.linear, linear * local.offset + offset};
    }
    point3 apply(const point3& p) const { return linear * p + offset; }
};

class gltf_reader {
  public:
    gltf_reader(const tinygltf::Model& m, const std::string& path, gltf_model& out) : m_(m), path_(path), out_(out) {
        dir_ = std::filesystem::path(path).parent_path().string();
    }

    void read() {
        check_extensions();
        warn_unrendered();
        const std::vector<int> roots = scene_roots();
        walk(roots);
        build_meshes();
    }

  private:
    const tinygltf::Model& m_;
    std::string path_, dir_;
    gltf_model& out_;
    std::map<int, std::shared_ptr<material>> materials_;
    std::shared_ptr<material> default_material_;
    struct placement {
        int mesh;
        gltf_affine world;
    };
    std::vector<placement> placements_;
    bool saw_camera_ = false;

    [[noreturn]] void fail(const std::string& what) const { throw scene_error(path_ + ": malformed glTF file: " + what); }
    void warn(const std::string& what) {
        if (out_.warnings.size() < 50) out_.warnings.push_back(path_ + ": " + what);
    }
    template <class T>
    const T& at(const std::vector<T>& list, int index, const char* what, const std::string& from) const {
        if (index < 0 || size_t(index) >= list.size())
            fail(from + " names " + what + " " + std::to_string(index) + ", of " + std::to_string(list.size()));
        return list[size_t(index)];
    }

    // --- extensions and what is not rendered ---------------------------------------------------
    static bool supported_extension(const std::string& e) {
        return e == "KHR_lights_punctual" || e == "KHR_materials_emissive_strength" || e == "KHR_materials_ior" ||
               e == "KHR_materials_transmission" || e == "KHR_mesh_quantization";
    }
    void check_extensions() {
        for (const std::string& e : m_.extensionsRequired)
            if (!supported_extension(e))
                throw scene_error(path_ + ": the model requires the glTF extension " + token_text(e) +
                                  ", which is not supported");
        for (const std::string& e : m_.extensionsUsed)
            if (!supported_extension(e)) warn("the glTF extension " + token_text(e) + " is not supported and is ignored");
    }
    void warn_unrendered() {
        if (!m_.animations.empty()) warn("animations are not rendered: the model is shown at rest");
        if (!m_.skins.empty()) warn("skins are not applied: skinned meshes are shown in their bind pose");
    }

    // --- the node hierarchy --------------------------------------------------------------------
    std::vector<int> scene_roots() {
        if (!m_.scenes.empty()) {
            const int s = m_.defaultScene >= 0 ? m_.defaultScene : 0;
            const tinygltf::Scene& scene = at(m_.scenes, s, "scene", "the file");
            if (m_.scenes.size() > 1) warn("the file has " + std::to_string(m_.scenes.size()) + " scenes: scene " + std::to_string(s) + " is rendered");
            return scene.nodes;
        }
        // No scene: every node that is no node's child.
        std::vector<bool> child(m_.nodes.size(), false);
        for (const auto& n : m_.nodes)
            for (int c : n.children)
                if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
        std::vector<int> roots;
        for (size_t i = 0; i < child.size(); ++i)
            if (!child[i]) roots.push_back(int(i));
        return roots;
    }

    gltf_affine local_matrix(const tinygltf::Node& n, int index) const {
        const std::string where = "node " + std::to_string(index);
        auto finite = [&](const std::vector<double>& v, const char* what) {
            for (double x : v)
                if (!std::isfinite(x)) fail(where + ": its " + std::string(what) + " is not finite");
        };
        gltf_affine a;
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16) fail(where + ": a matrix has 16 numbers, got " + std::to_string(n.matrix.size()));
            finite(n.matrix, "matrix");
            const auto& c = n.matrix; // column-major
            a.linear = mat3(vec3(c[0], c[4], c[8]), vec3(c[1], c[5], c[9]), vec3(c[2], c[6], c[10]));
            a.offset = vec3(c[12], c[13], c[14]);
            return a;
        }
        vec3 t(0, 0, 0), s(1, 1, 1);
        double q[4] = {0, 0, 0, 1}; // x, y, z, w
        if (!n.translation.empty()) {
            if (n.translation.size() != 3) fail(where + ": a translation has 3 numbers");
            finite(n.translation, "translation");
            t = vec3(n.translation[0], n.translation[1], n.translation[2]);
        }
        if (!n.scale.empty()) {
            if (n.scale.size() != 3) fail(where + ": a scale has 3 numbers");
            finite(n.scale, "scale");
            s = vec3(n.scale[0], n.scale[1], n.scale[2]);
        }
        if (!n.rotation.empty()) {
            if (n.rotation.size() != 4) fail(where + ": a rotation has 4 numbers (a quaternion)");
            finite(n.rotation, "rotation");
            const double len = std::sqrt(n.rotation[0] * n.rotation[0] + n.rotation[1] * n.rotation[1] +
                                         n.rotation[2] * n.rotation[2] + n.rotation[3] * n.rotation[3]);
            if (!(len > 0)) fail(where + ": its rotation quaternion is zero");
            for (int i = 0; i < 4; ++i) q[i] = n.rotation[size_t(i)] / len;
        }
        const double x = q[0], y = q[1], z = q[2], w = q[3];
        // The rotation matrix of the unit quaternion (x, y, z, w).
        const mat3 r(vec3(1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
                     vec3(2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
                     vec3(2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)));
        a.linear = r * mat3::diagonal(s);
        a.offset = t;
        return a;
    }

    // Depth first from the roots, without recursion (a chain of nodes may be deep). glTF's nodes
    // form a forest: a node met twice is malformed, which also ends any cycle.
    void walk(const std::vector<int>& roots) {
        std::vector<bool> seen(m_.nodes.size(), false);
        std::vector<std::pair<int, gltf_affine>> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, gltf_affine{}});
        while (!stack.empty()) {
            const auto [index, parent] = stack.back();
            stack.pop_back();
            const tinygltf::Node& n = at(m_.nodes, index, "node", "the scene");
            if (seen[size_t(index)]) fail("node " + std::to_string(index) + " is reached twice (glTF's nodes form a tree)");
            seen[size_t(index)] = true;
            const gltf_affine world = parent.then(local_matrix(n, index));
            if (n.mesh >= 0 || n.mesh < -1) {
                at(m_.meshes, n.mesh, "mesh", "node " + std::to_string(index));
                placements_.push_back({n.mesh, world});
            }
            if (n.camera != -1) take_camera(n, index, world);
            take_light(n, index, world);
            for (auto c = n.children.rbegin(); c != n.children.rend(); ++c) {
                at(m_.nodes, *c, "node", "node " + std::to_string(index));
                stack.push_back({*c, world});
            }
        }
    }

    void take_camera(const tinygltf::Node& n, int index, const gltf_affine& world) {
        const tinygltf::Camera& c = at(m_.cameras, n.camera, "camera", "node " + std::to_string(index));
        if (saw_camera_) return;
        saw_camera_ = true;
        if (m_.cameras.size() > 1) warn("the first camera of the scene is used (of " + std::to_string(m_.cameras.size()) + ")");
        if (c.type != "perspective") {
            warn("camera " + std::to_string(n.camera) + " is " + token_text(c.type) + ", not perspective: the default view is used");
            return;
        }
        const double yfov = c.perspective.yfov;
        if (!(std::isfinite(yfov) && yfov > 0 && yfov < pi))
            fail("camera " + std::to_string(n.camera) + ": yfov must be in (0, pi), got " + number_text(yfov));
        // A glTF camera looks down its -z axis with +y up, in its node's frame.
        const point3 eye = world.apply(point3(0, 0, 0));
        vec3 forward = world.linear * vec3(0, 0, -1), up = world.linear * vec3(0, 1, 0);
        if (!(forward.length() > 0 && up.length() > 0 && cross(forward, up).length() > 0 && std::isfinite(eye.x() + eye.y() + eye.z())))
            fail("camera node " + std::to_string(index) + ": its matrix is singular");
        out_.has_view = true;
        out_.view.lookfrom = eye;
        out_.view.lookat = eye + unit_vector(forward);
        out_.view.vup = unit_vector(up);
        out_.view.vfov = yfov * 180 / pi;
        const double aspect = c.perspective.aspectRatio;
        out_.view.aspect_ratio = std::isfinite(aspect) && aspect > 0 ? aspect : 0;
    }

    void take_light(const tinygltf::Node& n, int index, const gltf_affine& world) {
        const auto ext = n.extensions.find("KHR_lights_punctual");
        if (ext == n.extensions.end()) return;
        const tinygltf::Value& v = ext->second.Get("light");
        if (!v.IsNumber()) fail("node " + std::to_string(index) + ": KHR_lights_punctual names no light");
        // The index as a double first: tinygltf's GetNumberAsInt converts a real such as 5e77 to int,
        // which is undefined (a fuzzer's finding).
        const double number = v.GetNumberAsDouble();
        if (!(number >= 0 && number <= 2147483647.0) || number != std::floor(number))
            fail("node " + std::to_string(index) + ": KHR_lights_punctual light must be a whole number from 0, got " +
                 number_text(number));
        const int light_index = int(number);
        const tinygltf::Light& l = at(m_.lights, light_index, "light", "node " + std::to_string(index));
        const std::string name = "light " + std::to_string(light_index);
        color c(1, 1, 1);
        if (l.color.size() == 3) c = color(l.color[0], l.color[1], l.color[2]);
        else if (!l.color.empty()) fail(name + ": a colour has 3 numbers");
        for (int i = 0; i < 3; ++i)
            if (!(std::isfinite(c[i]) && c[i] >= 0)) fail(name + ": its colour must be finite and non-negative");
        if (!(std::isfinite(l.intensity) && l.intensity >= 0)) fail(name + ": its intensity must be finite and non-negative, got " + number_text(l.intensity));
        if (l.type == "directional") {
            const vec3 down = world.linear * vec3(0, 0, -1);
            if (!(down.length() > 0)) fail(name + ": its node's matrix is singular");
            out_.directional_lights.push_back({down, l.intensity * c});
            return;
        }
        point_light light{world.apply(point3(0, 0, 0)), l.intensity * c};
        if (l.type == "spot") {
            // A spot shines down its node's -z axis; glTF's cones: 0 <= inner < outer <= pi / 2.
            const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
            if (!(inner >= 0 && inner < outer && outer <= pi / 2 + 1e-9))
                fail(name + ": its cone angles must satisfy 0 <= inner < outer <= pi / 2, got " + number_text(inner) + " and " +
                     number_text(outer));
            light.spot_direction = world.linear * vec3(0, 0, -1);
            if (!(light.spot_direction.length() > 0)) fail(name + ": its node's matrix is singular");
            light.inner_cone = inner;
            light.outer_cone = outer;
        } else if (l.type != "point") {
            warn(name + " is a " + token_text(l.type) + " light, which is not supported yet: it is ignored");
            return;
        }
        out_.point_lights.push_back(light);
    }

    // --- accessors -----------------------------------------------------------------------------
    // The accessor's elements, `want` components each, as doubles (normalised integers mapped to
    // [0, 1] or [-1, 1] as glTF says). Every byte read is checked to lie in its buffer first.
    std::vector<double> read_accessor(int index, int want, const std::string& from) const {
        const tinygltf::Accessor& a = at(m_.accessors, index, "accessor", from);
        const std::string where = "accessor " + std::to_string(index);
        const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        if (components != want) fail(where + " (" + from + ") has " + std::to_string(components) + " components per element, not " + std::to_string(want));
        if (size <= 0 || size > 4) fail(where + ": unknown component type " + std::to_string(a.componentType));
        if (a.sparse.isSparse) fail(where + " is sparse, which is not supported");
        std::vector<double> values;
        if (a.bufferView < 0) { // no buffer view: zeros, as glTF says
            if (a.count > (size_t(1) << 20)) fail(where + ": " + std::to_string(a.count) + " elements without data");
            values.assign(a.count * size_t(want), 0.0);
            return values;
        }
        const tinygltf::BufferView& view = at(m_.bufferViews, a.bufferView, "buffer view", where);
        const tinygltf::Buffer& buffer = at(m_.buffers, view.buffer, "buffer", "buffer view " + std::to_string(a.bufferView));
        const size_t element = size_t(size) * size_t(components);
        const size_t stride = view.byteStride ? view.byteStride : element;
        if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
            fail("buffer view " + std::to_string(a.bufferView) + " runs past the end of buffer " + std::to_string(view.buffer) +
                 " (" + std::to_string(buffer.data.size()) + " bytes)");
        if (stride < element) fail("buffer view " + std::to_string(a.bufferView) + ": stride " + std::to_string(stride) + " is less than an element of " + where);
        if (a.count > 0 && (a.byteOffset > view.byteLength || (a.count - 1) > (view.byteLength - a.byteOffset) / stride ||
                            (a.count - 1) * stride + element > view.byteLength - a.byteOffset))
            fail(where + ": " + std::to_string(a.count) + " elements run past the end of buffer view " + std::to_string(a.bufferView));
        const unsigned char* base = buffer.data.data() + view.byteOffset + a.byteOffset;
        values.resize(a.count * size_t(want));
        for (size_t e = 0; e < a.count; ++e)
            for (int k = 0; k < want; ++k) {
                const unsigned char* p = base + e * stride + size_t(k) * size_t(size);
                double x = 0;
                switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_BYTE: { int8_t v; std::memcpy(&v, p, 1); x = a.normalized ? std::max(v / 127.0, -1.0) : v; break; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { uint8_t v; std::memcpy(&v, p, 1); x = a.normalized ? v / 255.0 : v; break; }
                case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t v; std::memcpy(&v, p, 2); x = a.normalized ? std::max(v / 32767.0, -1.0) : v; break; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); x = a.normalized ? v / 65535.0 : v; break; }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); x = v; break; }
                case TINYGLTF_COMPONENT_TYPE_INT: { int32_t v; std::memcpy(&v, p, 4); x = v; break; }
                case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); x = v; break; }
                default: fail(where + ": unknown component type " + std::to_string(a.componentType));
                }
                values[e * size_t(want) + size_t(k)] = x;
            }
        return values;
    }

    // --- materials -----------------------------------------------------------------------------
    static double ext_number(const tinygltf::ExtensionMap& ext, const char* name, const char* key, double fallback, bool* present = nullptr) {
        const auto e = ext.find(name);
        if (e == ext.end()) return fallback;
        if (present) *present = true;
        const tinygltf::Value& v = e->second.Get(key);
        return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
    }

    // The picture texture `index` names, or null (with a warning) when it cannot be decoded.
    const rtw_image* picture(int index, const std::string& where, image_sampling& s) {
        const tinygltf::Texture& t = at(m_.textures, index, "texture", where);
        if (t.source < 0) {
            warn(where + ": texture " + std::to_string(index) + " has no image (or only an extension's): it is ignored");
            return nullptr;
        }
        const tinygltf::Image& img = at(m_.images, t.source, "image", "texture " + std::to_string(index));
        if (t.sampler >= 0) {
            const tinygltf::Sampler& smp = at(m_.samplers, t.sampler, "sampler", "texture " + std::to_string(index));
            auto wrap = [](int w) {
                return w == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? image_sampling::wrap_mode::clamp
                       : w == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? image_sampling::wrap_mode::mirror
                                                                    : image_sampling::wrap_mode::repeat;
            };
            s.wrap_u = wrap(smp.wrapS);
            s.wrap_v = wrap(smp.wrapT);
            s.bilinear = smp.magFilter != TINYGLTF_TEXTURE_FILTER_NEAREST;
        } else {
            s.wrap_u = s.wrap_v = image_sampling::wrap_mode::repeat;
            s.bilinear = true;
        }
        auto found = pictures_.find(t.source);
        if (found != pictures_.end()) return found->second.get();
        const std::string name = img.uri.empty() || img.uri.compare(0, 5, "data:") == 0
                                     ? path_ + " image " + std::to_string(t.source)
                                     : (std::filesystem::path(dir_) / img.uri).string();
        std::unique_ptr<rtw_image> decoded;
        if (img.image.empty()) {
            warn("image " + std::to_string(t.source) + " ('" + token_text(img.uri) + "') could not be read: the material keeps its factors");
        } else {
            try {
                decoded = std::make_unique<rtw_image>();
                decoded->decode(std::string(img.image.begin(), img.image.end()), name);
                if (!img.uri.empty() && img.uri.compare(0, 5, "data:") != 0) out_.files.push_back(name);
            } catch (const scene_error& e) {
                warn(std::string(e.what()) + ": the material keeps its factors");
                decoded.reset();
            }
        }
        const rtw_image* result = decoded.get();
        pictures_[t.source] = std::move(decoded);
        return result;
    }
    std::map<int, std::unique_ptr<rtw_image>> pictures_;

    // The texture `index` names as a colour (sRGB pictures decoded to linear), or as data (the
    // 8-bit codes / 255: normal maps) when `data`.
    std::shared_ptr<texture> textured(int index, int tex_coord, const tinygltf::ExtensionMap& extensions, const std::string& where,
                                      const color& factor, bool data = false) {
        if (index < 0) return nullptr;
        if (tex_coord != 0) warn(where + ": TEXCOORD_" + std::to_string(tex_coord) + " is not supported: TEXCOORD_0 is used");
        if (extensions.count("KHR_texture_transform")) warn(where + ": KHR_texture_transform is not supported and is ignored");
        image_sampling s;
        const rtw_image* img = picture(index, where, s);
        if (!img) return nullptr;
        s.factor = factor;
        return std::make_shared<image_texture>(data ? img->as_data() : *img, s);
    }
    std::shared_ptr<texture> textured(const tinygltf::TextureInfo& info, const std::string& where, const color& factor) {
        return textured(info.index, info.texCoord, info.extensions, where, factor);
    }

    color factor3(const std::vector<double>& f, size_t n, const std::string& where, const char* what) const {
        if (f.size() != n) fail(where + ": " + what + " has " + std::to_string(n) + " numbers, got " + std::to_string(f.size()));
        const color c(f[0], f[1], f[2]);
        for (int i = 0; i < 3; ++i)
            if (!(std::isfinite(c[i]) && c[i] >= 0)) fail(where + ": " + what + " must be finite and non-negative");
        if (!is_finite(vec3f(c))) fail(where + ": " + what + " is too large for single precision");
        return c;
    }
    double unit(double x, const std::string& where, const char* what) const {
        if (!(x >= 0 && x <= 1)) fail(where + ": " + what + " must be in [0, 1], got " + number_text(x));
        return x;
    }

    std::shared_ptr<material> material_at(int index) {
        if (index < 0) {
            // glTF's default material: metallic-roughness at its defaults.
            if (!default_material_) default_material_ = std::make_shared<metal_roughness>(color(1, 1, 1), 1.0, 1.0);
            return default_material_;
        }
        auto found = materials_.find(index);
        if (found != materials_.end()) return found->second;
        const tinygltf::Material& mat = at(m_.materials, index, "material", "a primitive");
        const std::string where = "material " + std::to_string(index) + (mat.name.empty() ? "" : " ('" + token_text(mat.name) + "')");
        std::shared_ptr<material> made = material_from_gltf(mat, where);
        const auto& nt = mat.normalTexture;
        if (nt.index >= 0) {
            if (!std::isfinite(nt.scale)) fail(where + ": the normal texture's scale must be finite");
            if (auto normals = textured(nt.index, nt.texCoord, nt.extensions, where + " normalTexture", color(1, 1, 1), true))
                made = std::make_shared<normal_mapped>(made, normals, nt.scale);
        }
        materials_[index] = made;
        return made;
    }

    std::shared_ptr<material> material_from_gltf(const tinygltf::Material& mat, const std::string& where) {
        const auto& pbr = mat.pbrMetallicRoughness;
        const color base = factor3(pbr.baseColorFactor, 4, where, "baseColorFactor");
        const double alpha = pbr.baseColorFactor[3];
        double metallic = unit(pbr.metallicFactor, where, "metallicFactor");
        double roughness = unit(pbr.roughnessFactor, where, "roughnessFactor");
        const double strength = ext_number(mat.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0);
        if (!(std::isfinite(strength) && strength >= 0)) fail(where + ": emissiveStrength must be finite and non-negative");
        const color emissive = strength * factor3(mat.emissiveFactor, 3, where, "emissiveFactor");
        if (!is_finite(vec3f(emissive)))
            fail(where + ": emissiveFactor times emissiveStrength is too large for single precision");

        if (!(alpha >= 0 && alpha <= 1)) fail(where + ": the alpha of baseColorFactor must be in [0, 1], got " + number_text(alpha));
        if (mat.alphaMode != "OPAQUE") warn(where + ": alphaMode " + token_text(mat.alphaMode) + " is not supported: the surface is opaque");
        for (const auto& e : mat.extensions)
            if (!supported_extension(e.first)) warn(where + ": the extension " + token_text(e.first) + " is ignored");

        if (emissive.x() > 0 || emissive.y() > 0 || emissive.z() > 0) {
            out_.emits = true;
            warn(where + " emits: it is rendered as a light (diffuse_light), without its reflection");
            if (auto tex = textured(mat.emissiveTexture, where + " emissiveTexture", emissive))
                return std::make_shared<diffuse_light>(tex, mat.doubleSided);
            return std::make_shared<diffuse_light>(emissive, mat.doubleSided);
        }
        const tinygltf::TextureInfo& mr = pbr.metallicRoughnessTexture;
        bool transmissive = false;
        const double transmission = ext_number(mat.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0, &transmissive);
        if (transmissive && transmission > 0) {
            double ior = ext_number(mat.extensions, "KHR_materials_ior", "ior", 1.5);
            if (!(std::isfinite(ior) && ior >= 1)) fail(where + ": ior must be at least 1, got " + number_text(ior));
            if (ior == 1) ior = 1.0 + 1e-6; // glTF's 1 means "no refraction"; the dielectric needs some
            if (transmission < 1) warn(where + ": transmission " + number_text(transmission) + " is rendered as 1 (clear glass)");
            if (mr.index >= 0) {
                // The glass takes one roughness: the texture's mean green stands for it.
                image_sampling s;
                if (const rtw_image* img = picture(mr.index, where, s)) {
                    double g = 0;
                    const double n = double(img->width()) * double(img->height());
                    for (int y = 0; y < img->height(); ++y)
                        for (int x = 0; x < img->width(); ++x) g += img->pixel_data(x, y)[1] / 255.0;
                    if (n > 0) roughness *= g / n;
                    warn(where + ": glass takes one roughness: the metallicRoughnessTexture's mean is used (roughness " +
                         number_text(roughness) + ")");
                }
            }
            if (roughness > 0) return std::make_shared<rough_dielectric>(ior, roughness);
            return std::make_shared<dielectric>(ior, color(0, 0, 0));
        }
        // Metallic (blue) and roughness (green) per texel, as data: metal_roughness's map.
        std::shared_ptr<texture> map;
        if (mr.index >= 0) map = textured(mr.index, mr.texCoord, mr.extensions, where + " metallicRoughnessTexture", color(1, 1, 1), true);
        std::shared_ptr<texture> tex = textured(pbr.baseColorTexture, where + " baseColorTexture", base);
        if (!tex && !map) return std::make_shared<metal_roughness>(base, metallic, roughness);
        if (!tex) tex = std::make_shared<solid_color>(base);
        return std::make_shared<metal_roughness>(tex, metallic, roughness, map);
    }

    // --- meshes --------------------------------------------------------------------------------
    std::shared_ptr<triangle_mesh> primitive_mesh(const tinygltf::Primitive& p, const std::string& where) {
        if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            warn(where + ": points and lines (mode " + std::to_string(p.mode) + ") are not rendered");
            return nullptr;
        }
        const auto position = p.attributes.find("POSITION");
        if (position == p.attributes.end()) fail(where + " has no POSITION");
        if (!p.targets.empty()) warn(where + ": morph targets are not applied");
        auto mesh = std::make_shared<triangle_mesh>();
        const std::vector<double> xyz = read_accessor(position->second, 3, where + " POSITION");
        const size_t count = xyz.size() / 3;
        if (count >= triangle_mesh::no_index) fail(where + ": too many vertices");
        mesh->positions.resize(count);
        for (size_t i = 0; i < count; ++i) {
            mesh->positions[i] = point3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
            if (!std::isfinite(xyz[3 * i] + xyz[3 * i + 1] + xyz[3 * i + 2])) fail(where + ": POSITION " + std::to_string(i) + " is not finite");
        }
        std::vector<uint32_t> index;
        if (p.indices >= 0) {
            const std::vector<double> raw = read_accessor(p.indices, 1, where + " indices");
            index.reserve(raw.size());
            for (double x : raw) {
                if (!(x >= 0 && x < double(count))) fail(where + ": index " + number_text(x) + " is past its " + std::to_string(count) + " vertices");
                index.push_back(uint32_t(x));
            }
        } else {
            index.resize(count);
            for (size_t i = 0; i < count; ++i) index[i] = uint32_t(i);
        }
        auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
            if (a != b && b != c && a != c) mesh->faces.push_back({a, b, c});
        };
        if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (size_t i = 2; i < index.size(); ++i)
                i % 2 == 0 ? add(index[i - 2], index[i - 1], index[i]) : add(index[i - 1], index[i - 2], index[i]);
        } else if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            for (size_t i = 2; i < index.size(); ++i) add(index[0], index[i - 1], index[i]);
        } else {
            if (index.size() % 3 != 0) warn(where + ": " + std::to_string(index.size()) + " indices are not whole triangles: the last are ignored");
            for (size_t i = 2; i < index.size(); i += 3) add(index[i - 2], index[i - 1], index[i]);
        }
        const auto normal = p.attributes.find("NORMAL");
        if (normal != p.attributes.end()) {
            const std::vector<double> n = read_accessor(normal->second, 3, where + " NORMAL");
            if (n.size() != xyz.size()) fail(where + ": NORMAL and POSITION have different counts");
            mesh->normals.resize(count);
            for (size_t i = 0; i < count; ++i) {
                const vec3 v(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
                mesh->normals[i] = std::isfinite(v.x() + v.y() + v.z()) && v.length() > 0 ? unit_vector(v) : vec3(0, 0, 0);
            }
            mesh->face_normals = mesh->faces;
            mesh->smooth_shading = true;
        }
        const auto uv = p.attributes.find("TEXCOORD_0");
        if (uv != p.attributes.end()) {
            const std::vector<double> t = read_accessor(uv->second, 2, where + " TEXCOORD_0");
            if (t.size() / 2 != count) fail(where + ": TEXCOORD_0 and POSITION have different counts");
            mesh->uvs.resize(count);
            // glTF's v runs down the picture from its top; the renderer's up from its bottom.
            for (size_t i = 0; i < count; ++i) mesh->uvs[i] = {t[2 * i], 1 - t[2 * i + 1]};
            mesh->face_uvs = mesh->faces;
        }
        // Tangents (xyz; w, the bitangent's handedness, follows from the texture coordinates here)
        // frame a normal map; glTF ignores them on a mesh without normals.
        const auto tangent = p.attributes.find("TANGENT");
        if (tangent != p.attributes.end() && normal != p.attributes.end() && uv != p.attributes.end()) {
            const std::vector<double> t = read_accessor(tangent->second, 4, where + " TANGENT");
            if (t.size() / 4 != count) fail(where + ": TANGENT and POSITION have different counts");
            mesh->tangents.resize(count);
            for (size_t i = 0; i < count; ++i) {
                const vec3 v(t[4 * i], t[4 * i + 1], t[4 * i + 2]);
                mesh->tangents[i] = std::isfinite(v.x() + v.y() + v.z()) ? v : vec3(0, 0, 0);
            }
        }
        // Vertex colours multiply the base colour (an RGBA colour's alpha is alpha, not rendered).
        const auto colour = p.attributes.find("COLOR_0");
        if (colour != p.attributes.end()) {
            const tinygltf::Accessor& a = at(m_.accessors, colour->second, "accessor", where + " COLOR_0");
            const int n = tinygltf::GetNumComponentsInType(uint32_t(a.type));
            if (n != 3 && n != 4) fail(where + ": COLOR_0 has " + std::to_string(n) + " components per element, not 3 or 4");
            if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized)
                fail(where + ": COLOR_0 of integers must be normalized");
            const std::vector<double> c = read_accessor(colour->second, n, where + " COLOR_0");
            if (c.size() / size_t(n) != count) fail(where + ": COLOR_0 and POSITION have different counts");
            mesh->colors.resize(count);
            for (size_t i = 0; i < count; ++i) {
                const color v(c[size_t(n) * i], c[size_t(n) * i + 1], c[size_t(n) * i + 2]);
                if (!(std::isfinite(v.x() + v.y() + v.z()) && v.x() >= 0 && v.y() >= 0 && v.z() >= 0))
                    fail(where + ": COLOR_0 " + std::to_string(i) + " must be finite and at least 0");
                mesh->colors[i] = v;
            }
        }
        mesh->mat = material_at(p.material);
        const auto* mapped = dynamic_cast<const normal_mapped*>(mesh->mat.get());
        if (!mesh->colors.empty() && !dynamic_cast<const metal_roughness*>(mapped ? mapped->base().get() : mesh->mat.get())) {
            warn(where + ": COLOR_0 is not applied to a glass or emitting material");
            mesh->colors.clear();
        }
        return mesh;
    }

    void grow_bounds(const point3& p) {
        if (!bounded_) {
            out_.lo = out_.hi = p;
            bounded_ = true;
            return;
        }
        out_.lo = point3(std::min(out_.lo.x(), p.x()), std::min(out_.lo.y(), p.y()), std::min(out_.lo.z(), p.z()));
        out_.hi = point3(std::max(out_.hi.x(), p.x()), std::max(out_.hi.y(), p.y()), std::max(out_.hi.z(), p.z()));
    }
    bool bounded_ = false;

    // Each mesh's primitives built once; a mesh placed once is moved into world space, one placed
    // more often is shared by its placements (instances).
    void build_meshes() {
        std::map<int, size_t> uses;
        for (const placement& p : placements_) ++uses[p.mesh];
        std::map<int, std::vector<std::shared_ptr<triangle_mesh>>> built;
        for (const placement& pl : placements_) {
            const double det = pl.world.linear.determinant();
            if (!(std::isfinite(det) && det != 0)) fail("mesh " + std::to_string(pl.mesh) + " is placed by a singular matrix");
            auto& prims = built[pl.mesh];
            if (prims.empty()) {
                const tinygltf::Mesh& mesh = m_.meshes[size_t(pl.mesh)];
                for (size_t i = 0; i < mesh.primitives.size(); ++i)
                    if (auto tm = primitive_mesh(mesh.primitives[i], "mesh " + std::to_string(pl.mesh) + " primitive " + std::to_string(i)))
                        if (!tm->faces.empty()) prims.push_back(std::move(tm));
            }
            const bool mirrored = det < 0;
            const mat3 normal_matrix = pl.world.linear.inverse().transpose();
            for (const auto& prim : prims) {
                if (uses[pl.mesh] == 1) {
                    for (point3& p : prim->positions) p = pl.world.apply(p);
                    for (vec3& n : prim->normals)
                        if (n.length_squared() > 0) n = unit_vector(normal_matrix * n);
                    for (vec3& t : prim->tangents) t = pl.world.linear * t;
                    // A mirroring matrix turns the triangles inside out; glTF keeps their fronts.
                    if (mirrored)
                        for (auto* faces : {&prim->faces, &prim->face_normals, &prim->face_uvs})
                            for (auto& f : *faces) std::swap(f[1], f[2]);
                    for (const auto& f : prim->faces)
                        for (uint32_t v : f) grow_bounds(prim->positions[v]);
                    out_.world.add(prim);
                } else {
                    const aabb box = prim->bounding_box();
                    for (double x : {box.x.min, box.x.max})
                        for (double y : {box.y.min, box.y.max})
                            for (double z : {box.z.min, box.z.max}) grow_bounds(pl.world.apply(point3(x, y, z)));
                    out_.world.add(std::make_shared<transform>(prim, pl.world.linear, pl.world.offset));
                }
            }
        }
    }
};

// tinygltf hands over each picture's bytes undecoded: they are decoded as the renderer's other
// textures are, and only when a material uses them. `model` is the model being read: a picture in
// a buffer view comes with the view's length unchecked against its buffer (tinygltf 2.5 does not;
// a fuzzer's finding read past the buffer), so the view is checked here first.
inline bool keep_encoded_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                               const unsigned char* bytes, int size, void* model) {
    if (image->bufferView >= 0 && model) {
        // tinygltf has checked both indices before calling.
        const auto& m = *static_cast<const tinygltf::Model*>(model);
        const tinygltf::BufferView& view = m.bufferViews[size_t(image->bufferView)];
        const size_t buffer = m.buffers[size_t(view.buffer)].data.size();
        if (view.byteOffset > buffer || view.byteLength > buffer - view.byteOffset || view.byteLength > size_t(INT32_MAX)) {
            if (err) *err += "image " + std::to_string(index) + ": its buffer view runs past the end of its buffer\n";
            return false;
        }
    }
    if (bytes && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

// Files a glTF names (buffers, images) are read as every other input is: regular files only, of
// bounded size (core/file.h).
inline bool gltf_file_exists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}
inline std::string gltf_expand_path(const std::string& path, void*) { return path; }
inline bool gltf_read_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    try {
        const std::string bytes = read_file(path, "glTF buffer or image");
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const scene_error& e) {
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
}
inline bool gltf_write_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is not supported\n";
    return false;
}

// tinygltf's first message line, printable and at most 160 characters.
inline std::string gltf_message(const std::string& text) {
    std::string line = text.substr(0, std::min(text.find('\n'), size_t(160)));
    for (char& c : line)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    if (line.size() < text.size() && text.find('\n') > 160) line += "...";
    return line.empty() ? "tinygltf gave no reason" : line;
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION gltf_model decode_gltf_model(const std::string& bytes, const std::string& path) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model m;
    loader.SetImageLoader(detail::keep_encoded_image, &m);
    loader.SetFsCallbacks({detail::gltf_file_exists, detail::gltf_expand_path, detail::gltf_read_file, detail::gltf_write_file, nullptr});
    std::string err, warn;
    const std::string dir = std::filesystem::path(path).parent_path().string();
    if (bytes.size() >= 0xFFFFFFFFull) throw scene_error(path + ": a glTF file is at most 4 GiB");
    const bool binary = bytes.compare(0, 4, "glTF") == 0;
    const bool ok = binary ? loader.LoadBinaryFromMemory(&m, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                         unsigned(bytes.size()), dir)
                           : loader.LoadASCIIFromString(&m, &err, &warn, bytes.data(), unsigned(bytes.size()), dir);
    if (!ok) throw scene_error(path + ": malformed glTF file: " + detail::gltf_message(err.empty() ? warn : err));
    gltf_model model;
    model.files.push_back(path);
    for (const auto& b : m.buffers)
        if (!b.uri.empty() && b.uri.compare(0, 5, "data:") != 0) model.files.push_back((std::filesystem::path(dir) / b.uri).string());
    std::istringstream notes(warn);
    for (std::string note; std::getline(notes, note) && model.warnings.size() < 20;)
        if (!note.empty()) model.warnings.push_back(path + ": " + token_text(note));
    detail::gltf_reader(m, path, model).read();
    return model;
}

RTWEEKEND_ENGINE_FUNCTION gltf_model load_gltf_model(const std::string& path) {
    return decode_gltf_model(read_file(path, "glTF file"), path);
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::gltf_model;
using rt::load_gltf_model;
#endif
