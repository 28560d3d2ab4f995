#pragma once
// xml_scene: reads a CENG795 / CENG477 scene into a whitted_scene: the XML of homework 1 (level
// 1, the recursive ray tracer; shared/formats/ceng795-xml.md) with the later homeworks' geometry
// (shared/formats/ceng795-later.md, sections 1-3 and 7), and the same scenes in the course's JSON
// form (a file ending .json, section 15; io/course_json.h turns it into the XML it translates).
//
//   whitted_scene s = load_xml_scene("scenes/simple.xml");   // throws scene_error
//   for (const std::string& w : s.warnings) ...              // elements it did not read
//   for (const view_camera& cam : s.cameras) ...              // one image per camera
//
// What it reads:
//   <Scene>: BackgroundColor (default 0 0 0), ShadowRayEpsilon (1e-3), IntersectionTestEpsilon
//     (1e-6), MaxRecursionDepth (0), ZeroBasedIndexing (true|false, default false: ids from 1);
//   <Cameras>: <Camera> plain (Position, Gaze, Up, NearPlane l r b t [a 5th number is ignored],
//     NearDistance, ImageResolution, ImageName) or type="lookAt" (GazePoint, or Gaze as a
//     direction, and FovY in degrees instead of NearPlane: a symmetric image plane of aspect nx/ny
//     at NearDistance); handedness="left" mirrors the image left to right ("right", the default);
//   <Lights>: at most one <AmbientLight>, any number of <PointLight> (Position, Intensity);
//   <Materials>: <Material id type="mirror|conductor|dielectric"> (no type: plain) with
//     AmbientReflectance, DiffuseReflectance, SpecularReflectance, PhongExponent,
//     MirrorReflectance, RefractionIndex (required by conductor and dielectric), AbsorptionIndex,
//     AbsorptionCoefficient; each optional, defaulting as whitted_material does (a plain
//     material's MirrorReflectance is ignored, with a warning: the course's rule). One shared
//     whitted_material per material; BRDF="k" names an entry of <BRDFs>;
//   <BRDFs>: <OriginalPhong>, <ModifiedPhong normalized>, <OriginalBlinnPhong>,
//     <ModifiedBlinnPhong normalized>, <TorranceSparrow kdfresnel>, each with an id (one numbering
//     for all) and <Exponent> (course_brdf_bsdf.h; it replaces the material's PhongExponent);
//   <VertexData>: x y z triples;
//   <Transformations>: <Translation id> dx dy dz, <Scaling id> sx sy sz, <Rotation id> degrees
//     x y z (counter-clockwise about the axis through the origin), <Composite id> 16 numbers of a
//     4x4 matrix by rows (its last row 0 0 0 1); each kind numbers its own ids;
//   <Objects>: <Triangle> (Indices, Material): the single triangles of one material (and one
//     transformation list) become one triangle_mesh; <Mesh shadingMode="smooth|flat"> (Material,
//     <Faces vertexOffset="N" plyFile="path">; vertexOffset may also sit on <Mesh>): one
//     triangle_mesh each, a plyFile read by load_ply relative to the XML file's folder
//     (vertexOffset does not apply to it); smooth meshes get area-weighted vertex normals
//     (set_smooth_normals below, replacing any normals of a PLY file); <Sphere> (Material,
//     Center = a vertex id, Radius); <MeshInstance baseMeshId="k" resetTransform="true|false">
//     (Material, optional: the base's otherwise): the geometry of Mesh k (or, when no Mesh has
//     that id, of MeshInstance k, so instances chain) placed by its own transformations after the
//     base's whole matrix, or by its own alone, on the base Mesh's raw vertices, with reset.
//     Every object may carry <Transformations>t1 r2 s1 c1</Transformations>: letters t, s, r, c
//     and ids, applied left to right (the first listed acts first), the matrix M on points, M^-T
//     on normals (a transform node, transform.h; spheres under a non-uniform scale are
//     ellipsoids, a mirroring M keeps each surface's front face). One instance shares its base's
//     geometry (the compiler traces it in its own frame); one with another material, a copy.
// Zero-area triangles are kept (the renderer leaves them out). Numbers are whitespace-separated,
// and a comment between numbers separates them. Elements may come in any order.
//
// Distribution ray tracing (homework 3) and the new lights (homeworks 3 and 5): a camera's
// <NumSamples> (1 to 2^24), <ApertureSize> and <FocusDistance> (view_camera.h); a material's
// <Roughness> (whitted_material.h); <Lights> with <DirectionalLight> (Direction, Radiance),
// <SpotLight> (Position, Direction, Intensity, CoverageAngle, FalloffAngle: full angles in
// degrees, falloff <= coverage <= 360) and <AreaLight> (Position, Normal, Size, Radiance):
// course/course_lights.h. A camera's <Tonemap> (homework 5: TMO Photographic, TMOOptions key and
// burn, Saturation, Gamma) writes its image linear and tone mapped (write_course_image).
//
// <LightMesh> and <LightSphere> (homework 6): a Mesh or Sphere with a <Radiance>, seen by the rays
// that hit it and sampled as a light (course_lights.h: light_mesh, light_sphere).
// <MotionBlur>x y z</MotionBlur> on a Mesh, Sphere or MeshInstance moves it by t (x, y, z) at the
// ray's time t, after its transformations (transform.h: moving); cameras with NumSamples give each
// sample its own time. <BRDFs> and a material's BRDF="k" (homework 6, above); a camera's
// <Renderer>PathTracing</Renderer> and <RendererParams> (view_camera::path_tracing; the course's
// path tracer of course/whitted.h).
//
// Textures (homework 4): <Textures> with <Images> and <TextureMap id type degamma> (DecalMode,
// ImageId, Interpolation, Normalizer, BumpFactor, NoiseScale, NoiseConversion, Scale, Offset,
// BlackColor, WhiteColor: course/course_textures.h); an object's <Textures>k1 k2</Textures> gives it
// a material of its own and records it in whitted_scene::textured_objects; <TexCoordData> (u v per
// vertex, numbered like the vertices; binaryFile too) with <Faces textureOffset="k">.
// <SphericalDirectionalLight><ImageId> (homework 5) is an environment light.
//
// Anything else: each element the lists above do not name, and any attribute they do not name, is one warning
// (whitted_scene::warnings: "scene.xml:12: <Cylinder id="2"> is not supported yet and is ignored"; at
// most 20, then a count of the rest); the scene renders without it. <VertexData binaryFile="f">
// and <Faces binaryFile="f"> (homework 6's sponza) read a little-endian int32 count and then that
// many float32 x y z or int32 index triples, relative to the scene's folder; any other size of
// file is refused.
//
// Errors: every problem is one scene_error "file:LINE: <Element id="N">: problem", e.g.
//   scene.xml:14: <Sphere id="2">: <Material> 7 does not exist (the file defines materials 1-3)
// for a missing or unreadable file, malformed XML (pugixml's description and line), no <Scene>
// root, no camera, a missing required element, an element given twice, a value that is not a
// finite number (or a whole number where one is needed) or has too few or too many numbers, a
// negative colour, a non-positive radius, resolution, near distance or refraction index, a
// degenerate camera (zero gaze, up parallel to gaze, empty image plane, FovY outside (0, 180)),
// a material or vertex id that does not exist (after vertexOffset; an id plus vertexOffset beyond
// a 64-bit integer), a transformation or base mesh that does not exist, instances whose bases
// form a cycle, a transformation list whose matrix is singular (a scale of 0) or a <Composite>
// whose last row is not 0 0 0 1, a <Faces> list that is empty or not a multiple of 3, an
// <ImageResolution> of more than 2^26 pixels (core/input_limits.h), an <ImageName> that is absolute or has a '..'
// component (image_name_problem below), a NUL byte anywhere in the file, and any problem of a PLY
// file (its own message follows).
//
// The XML is parsed by pugixml (Debian's libpugixml-dev), which the rtweekend CMake target links;
// JSON by nlohmann/json (Debian's nlohmann-json3-dev). A JSON scene's messages name no line: the
// elements come from a translation (io/course_json.h), and its element and id say where.

#include "../core/engine_linkage.h"
#include "../mesh.h"
#include "../core/scene_error.h"
#include "../course/whitted_scene.h"

#include <algorithm>
#include <cstdio>
#include <array>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace rt {

// Reads a CENG795 scene, XML or (a name ending .json, any case) JSON. Throws scene_error (see above).
RTWEEKEND_ENGINE_FUNCTION whitted_scene load_xml_scene(const std::string& path);

// load_xml_scene on a file's text already in memory: `path` names it in messages (and says, by its
// extension, whether the text is JSON), and a plyFile is read relative to its folder.
RTWEEKEND_ENGINE_FUNCTION whitted_scene decode_xml_scene(const std::string& text, const std::string& path);

// What is wrong with a camera's ImageName as a file name inside the output directory, "" if
// nothing: it must be a relative path without a ".." component (and not empty), so that the image
// lands inside the directory the user chose (render -o DIR), never beside or above it; and it may
// hold no control character (a line break would also split every message that names the file).
RTWEEKEND_ENGINE_FUNCTION std::string image_name_problem(const std::string& image_name);

// Gives `mesh` area-weighted vertex normals and turns on smooth shading: each vertex's normal is
// the normalised sum of the (unnormalised, so area-weighted) cross products (b - a) x (c - a) of
// the faces that use it. A vertex whose sum vanishes takes the normal of its largest face; one
// used only by zero-area faces, or by none, gets (0, 0, 0). Replaces normals and face_normals.
RTWEEKEND_ENGINE_FUNCTION void set_smooth_normals(triangle_mesh& mesh);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../scene/affine_map.h"
#include "../sphere.h"
#include "../transform.h"
#include "../vec3.h"
#include "../whitted_material.h"
#include "../core/file.h"
#include "course_json.h"
#include "../core/input_limits.h"
#include "ply.h"
#include "../image/image_read.h"
#include "../render/render_settings.h"
#include "../core/text_lines.h"
#include <pugixml.hpp>
#include <cstring>
#include <set>
#include <unordered_set>

namespace rt {

RTWEEKEND_ENGINE_FUNCTION std::string image_name_problem(const std::string& image_name) {
    if (image_name.empty()) return "is empty";
    for (char c : image_name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            return "has a control character (a line break, say): is the file damaged?";
    // '/' and '\\' both count as separators, so that a name means the same on every system.
    const std::filesystem::path p(image_name);
    if (p.is_absolute() || p.has_root_name() || image_name[0] == '/' || image_name[0] == '\\')
        return "is an absolute path: it must name a file inside the output directory";
    for (size_t start = 0; start <= image_name.size();) {
        size_t end = image_name.find_first_of("/\\", start);
        if (end == std::string::npos) end = image_name.size();
        if (end - start == 2 && image_name.compare(start, 2, "..") == 0)
            return "has a '..' component: it must name a file inside the output directory";
        start = end + 1;
    }
    return {};
}

RTWEEKEND_ENGINE_FUNCTION void set_smooth_normals(triangle_mesh& mesh) {
    const size_t n = mesh.positions.size();
    std::vector<vec3> sum(n, vec3(0, 0, 0)), largest(n, vec3(0, 0, 0));
    std::vector<double> magnitude(n, 0.0);
    for (size_t i = 0; i < mesh.faces.size(); ++i)
        for (uint32_t v : mesh.faces[i])
            if (v >= n)
                throw scene_error("set_smooth_normals: face " + std::to_string(i) + " uses vertex " + std::to_string(v) +
                                  " but the mesh has " + std::to_string(n));
    for (const auto& f : mesh.faces) {
        const point3 &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
        vec3 normal = cross(b - a, c - a);
        for (uint32_t v : f) {
            sum[v] += normal;
            magnitude[v] += normal.length();
            if (normal.length_squared() > largest[v].length_squared()) largest[v] = normal;
        }
    }
    mesh.normals.assign(n, vec3(0, 0, 0));
    for (size_t v = 0; v < n; ++v) {
        double len = sum[v].length();
        if (len > 1e-12 * magnitude[v] && len > 0) mesh.normals[v] = sum[v] / len;
        else if (largest[v].length_squared() > 0) mesh.normals[v] = unit_vector(largest[v]);
    }
    mesh.face_normals = mesh.faces;
    mesh.smooth_shading = true;
}

namespace detail {

class xml_scene_reader {
  public:
    xml_scene_reader(const std::string& path, const std::string& text, bool json)
        : path_(path), text_(text), lines_(text_), json_(json) {
        dir_ = std::filesystem::path(path_).parent_path();
    }

    whitted_scene read() {
        // pugixml would end a text at a NUL byte and read "0.5\0junk" as 0.5; a text file has none.
        if (size_t nul = text_.find('\0'); nul != std::string::npos)
            throw scene_error(path_ + ":" + std::to_string(line_at(ptrdiff_t(nul))) +
                              ": a NUL byte (is this a binary or damaged file?)");
        if (json_) {
            course_json_translator(text_, path_).translate(doc_);
        } else {
            pugi::xml_parse_result parsed = doc_.load_buffer(text_.data(), text_.size(), pugi::parse_default);
            if (!parsed)
                throw scene_error(path_ + ":" + std::to_string(line_at(parsed.offset)) +
                                  ": malformed XML: " + parsed.description());
        }
        pugi::xml_node root = doc_.document_element();
        if (std::string(root.name()) != "Scene")
            fail(root, "<" + std::string(root.name()) + ">", "the root element must be <Scene>");
        mark(root);
        whitted_scene scene;
        scene.files.push_back(path_);
        read_settings(root, scene);
        read_vertices(root);
        read_brdfs(root);
        read_materials(root);
        read_transformations(root);
        read_cameras(root, scene);
        read_images(root);
        read_tex_coords(root);
        read_texture_maps(root, scene);
        read_lights(root, scene);
        read_objects(root, scene);
        scene.files.insert(scene.files.end(), ply_files_.begin(), ply_files_.end());
        if (scene.cameras.empty()) fail(root, "<Scene>", "no camera: a scene needs a <Camera> inside <Cameras>");
        warn_runaway_roulette(scene);
        scene.warnings = notes_;
        warn_unread(root, scene.warnings);
        return scene;
    }

  private:
    using node = pugi::xml_node;

    // --- messages ---
    size_t line_at(ptrdiff_t offset) const { return offset < 0 ? 0 : lines_.line_of(size_t(offset)); }
    // The line of an element, 0 for none (a JSON scene's elements have no line).
    size_t line_of(node at) const { return at && !json_ ? line_at(at.offset_debug()) : 0; }
    [[noreturn]] void fail(node at, const std::string& owner, const std::string& problem) const {
        size_t line = line_of(at);
        // Values quoted from the file may hold line breaks (&#10;): the message stays one line.
        throw scene_error(one_line(path_ + (line ? ":" + std::to_string(line) : std::string()) + ": " + owner + ": " + problem));
    }
    static std::string tag(node n) { return "<" + std::string(n.name()) + ">"; }

    // --- what was read: every element and attribute the reader looks at is marked; the rest are
    // warned about (warn_unread), so that nothing in a file is dropped without a word.
    void mark(node n) const {
        if (n) read_.insert(n.internal_object());
    }
    pugi::xml_attribute attr(node n, const char* name) const {
        pugi::xml_attribute a = n.attribute(name);
        if (a) read_.insert(a.internal_object());
        return a;
    }
    bool was_read(node n) const { return read_.count(n.internal_object()) != 0; }
    bool was_read(pugi::xml_attribute a) const { return read_.count(a.internal_object()) != 0; }
    // One warning per element not read (its children are not looked at) and per attribute not
    // read on an element that was (ids are names, never warned about); at most max_warnings lines,
    // then one that counts the rest.
    void warn_unread(node root, std::vector<std::string>& warnings) const {
        constexpr size_t max_warnings = 20;
        size_t more = 0;
        auto warn = [&](node at, const std::string& what) {
            if (warnings.size() >= max_warnings) {
                ++more;
                return;
            }
            const size_t line = line_of(at);
            warnings.push_back(one_line(path_ + (line ? ":" + std::to_string(line) : std::string()) + ": " + what));
        };
        auto warn_attributes = [&](node n) {
            for (pugi::xml_attribute a : n.attributes())
                if (!was_read(a) && std::string(a.name()) != "id")
                    warn(n, element_name(n) + ": attribute " + token_text(a.name()) + "=\"" + token_text(a.value()) +
                                "\" is not supported yet and is ignored");
        };
        // Depth first in the file's order, with a stack of (element, its next child) rather than
        // recursion: pugixml reads elements nested as deep as a file likes.
        warn_attributes(root);
        std::vector<std::pair<node, node>> open{{root, root.first_child()}};
        while (!open.empty()) {
            node c = open.back().second;
            if (!c) {
                open.pop_back();
                continue;
            }
            open.back().second = c.next_sibling();
            if (c.type() != pugi::node_element) continue;
            if (!was_read(c)) {
                warn(c, token_text(element_name(c)) + " is not supported yet and is ignored");
                continue;
            }
            warn_attributes(c);
            open.emplace_back(c, c.first_child());
        }
        if (more > 0)
            warnings.push_back(path_ + ": and " + std::to_string(more) + " more elements or attributes not read");
    }
    // <Name id="N">, or <Name> without an id.
    static std::string element_name(node n) {
        pugi::xml_attribute id = n.attribute("id");
        return id ? "<" + std::string(n.name()) + " id=\"" + id.value() + "\">" : tag(n);
    }
    static std::string lower(std::string s) {
        for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
        return s;
    }
    static std::string trim(const std::string& s) {
        const char* space = " \t\r\n\v\f";
        size_t b = s.find_first_not_of(space);
        if (b == std::string::npos) return "";
        return s.substr(b, s.find_last_not_of(space) - b + 1);
    }
    static std::string number_text(double x) {
        std::ostringstream s;
        s << x;
        return s.str();
    }
    // "1-3, 5, 7-9"
    static std::string id_ranges(const std::vector<long long>& sorted) {
        std::string out;
        for (size_t i = 0; i < sorted.size();) {
            size_t j = i;
            while (j + 1 < sorted.size() && sorted[j + 1] == sorted[j] + 1) ++j;
            if (!out.empty()) out += ", ";
            out += std::to_string(sorted[i]);
            if (j > i) out += "-" + std::to_string(sorted[j]);
            i = j + 1;
        }
        return out;
    }

    // --- elements and values ---
    // The one child `name` of `parent`: an error if it appears twice, or is required and absent.
    node child(node parent, const char* name, bool required) const {
        node found;
        for (node c : parent.children(name)) {
            if (found) fail(c, element_name(parent), "<" + std::string(name) + "> appears twice");
            found = c;
        }
        mark(found);
        if (!found && required) fail(parent, element_name(parent), "missing <" + std::string(name) + ">");
        return found;
    }
    // The character data of an element: its text pieces (split by comments) joined by spaces.
    std::string text(node el, const std::string& owner) const {
        std::string out;
        for (node c : el.children()) {
            if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) {
                out += c.value();
                out += ' ';
            } else if (c.type() == pugi::node_element) {
                fail(c, owner, "unexpected element " + tag(c) + " inside " + tag(el));
            }
        }
        return out;
    }
    // The words of a text: runs between whitespace and commas (some course files write
    // "0.5, 0.5, 0.5"; a decimal comma such as "1,5" then reads as two numbers, which no element
    // takes where it wants one, so it is still an error).
    static std::vector<std::string> words(const std::string& s) {
        std::vector<std::string> out;
        size_t i = 0;
        while (i < s.size()) {
            auto separator = [&](char c) { return c == ',' || std::isspace(static_cast<unsigned char>(c)); };
            while (i < s.size() && separator(s[i])) ++i;
            const size_t start = i;
            while (i < s.size() && !separator(s[i])) ++i;
            if (i > start) out.emplace_back(s, start, i - start);
        }
        return out;
    }
    double parse_number(const std::string& word, node el, const std::string& owner) const {
        const char* b = word.data();
        const char* e = b + word.size();
        if (b != e && *b == '+') ++b;
        double x = 0;
        auto r = std::from_chars(b, e, x, std::chars_format::general);
        if (b != e && r.ec == std::errc::result_out_of_range && r.ptr == e) {
            // Beyond double's range, or an underflow (1e-320): strtod tells which, and rounds an
            // underflow to the subnormal or zero that is then the value.
            x = std::strtod(std::string(b, e).c_str(), nullptr);
            if (std::isinf(x)) fail(el, owner, tag(el) + ": '" + token_text(word) + "' is beyond the range of a double");
        } else if (b == e || r.ec != std::errc() || r.ptr != e) {
            fail(el, owner, tag(el) + ": '" + token_text(word) + "' is not a number");
        }
        if (!std::isfinite(x)) fail(el, owner, tag(el) + ": '" + token_text(word) + "' is not a finite number");
        return x;
    }
    long long parse_integer(const std::string& word, node el, const std::string& owner) const {
        const char* b = word.data();
        const char* e = b + word.size();
        if (b != e && *b == '+') ++b;
        long long i = 0;
        auto r = std::from_chars(b, e, i);
        if (b == e || r.ec != std::errc() || r.ptr != e)
            fail(el, owner, tag(el) + ": '" + token_text(word) + "' is not a whole number");
        return i;
    }
    std::vector<double> numbers(node el, const std::string& owner, size_t min_count, size_t max_count) const {
        std::vector<double> out;
        for (const std::string& w : words(text(el, owner))) out.push_back(parse_number(w, el, owner));
        if (out.size() < min_count || out.size() > max_count) {
            std::string expected = min_count == max_count
                                       ? std::to_string(min_count)
                                       : std::to_string(min_count) + " or " + std::to_string(max_count);
            fail(el, owner, tag(el) + " has " + std::to_string(out.size()) + " number" + (out.size() == 1 ? "" : "s") +
                                ", expected " + expected);
        }
        return out;
    }
    std::vector<long long> integers(node el, const std::string& owner) const {
        std::vector<long long> out;
        for (const std::string& w : words(text(el, owner))) out.push_back(parse_integer(w, el, owner));
        return out;
    }
    long long integer(node el, const std::string& owner) const {
        std::vector<long long> v = integers(el, owner);
        if (v.size() != 1)
            fail(el, owner, tag(el) + " has " + std::to_string(v.size()) + " numbers, expected 1");
        return v[0];
    }
    double scalar(node el, const std::string& owner) const { return numbers(el, owner, 1, 1)[0]; }
    vec3 triple(node el, const std::string& owner) const {
        std::vector<double> v = numbers(el, owner, 3, 3);
        return vec3(v[0], v[1], v[2]);
    }
    vec3 nonzero(node el, const std::string& owner) const {
        const vec3 d = triple(el, owner);
        if (!(d.length_squared() > 0) || !std::isfinite(d.length_squared()))
            fail(el, owner, tag(el) + " must be a non-zero direction (and not overflow when squared)");
        return d;
    }
    color colour(node el, const std::string& owner) const {
        vec3 c = triple(el, owner);
        if (c.x() < 0 || c.y() < 0 || c.z() < 0)
            fail(el, owner, tag(el) + " must not be negative (" + number_text(c.x()) + " " + number_text(c.y()) + " " +
                                number_text(c.z()) + ")");
        return c;
    }
    // A required or optional number with a lower bound (`strict`: above it; otherwise at least it).
    double bounded(node el, const std::string& owner, double bound, bool strict) const {
        double x = scalar(el, owner);
        if (strict ? !(x > bound) : !(x >= bound))
            fail(el, owner,
                 tag(el) + " must be " + (strict ? (bound == 0 ? "positive" : "greater than " + number_text(bound))
                                                 : (bound == 0 ? "non-negative" : "at least " + number_text(bound))) +
                     ", not " + number_text(x));
        return x;
    }
    long long attribute_integer(node el, const char* name, long long fallback) const {
        pugi::xml_attribute a = attr(el, name);
        if (!a) return fallback;
        std::string w = trim(a.value());
        const char* b = w.data();
        const char* e = b + w.size();
        if (b != e && *b == '+') ++b;
        long long i = 0;
        auto r = std::from_chars(b, e, i);
        if (b == e || r.ec != std::errc() || r.ptr != e)
            fail(el, element_name(el), "attribute " + std::string(name) + "=\"" + a.value() + "\" is not a whole number");
        return i;
    }

    // --- sections ---
    void read_settings(node root, whitted_scene& scene) {
        const std::string owner = "<Scene>";
        if (node n = child(root, "BackgroundColor", false)) scene.background = colour(n, owner);
        if (node n = child(root, "ShadowRayEpsilon", false)) scene.shadow_ray_epsilon = bounded(n, owner, 0, false);
        if (node n = child(root, "IntersectionTestEpsilon", false))
            scene.intersection_test_epsilon = bounded(n, owner, 0, false);
        if (node n = child(root, "MaxRecursionDepth", false)) {
            long long d = integer(n, owner);
            if (d < 0 || d > 1000000) fail(n, owner, tag(n) + " must be between 0 and 1000000, not " + std::to_string(d));
            scene.max_recursion_depth = int(d);
        }
        if (node n = child(root, "ZeroBasedIndexing", false)) {
            std::string v = lower(trim(text(n, owner)));
            if (v == "true" || v == "1") zero_based_ = true;
            else if (v == "false" || v == "0") zero_based_ = false;
            else fail(n, owner, tag(n) + " must be true or false, not '" + trim(text(n, owner)) + "'");
        }
    }

    void read_vertices(node root) {
        node data = child(root, "VertexData", false);
        if (!data) return;
        if (attr(data, "binaryFile")) {
            const std::vector<double> xyz = binary_values<float, double>(data, "<Scene>", 12);
            for (size_t i = 0; i < xyz.size(); i += 3) {
                for (size_t c = 0; c < 3; ++c)
                    if (!std::isfinite(xyz[i + c]))
                        fail(data, "<Scene>", "<VertexData binaryFile>: vertex " + std::to_string(i / 3 + 1) + " is not finite");
                vertices_.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
            }
            return;
        }
        std::vector<double> v = numbers(data, "<Scene>", 0, static_cast<size_t>(-1));
        if (v.size() % 3 != 0)
            fail(data, "<Scene>", "<VertexData> has " + std::to_string(v.size()) +
                                      " numbers, not a multiple of 3 (x y z per vertex)");
        for (size_t i = 0; i < v.size(); i += 3) vertices_.emplace_back(v[i], v[i + 1], v[i + 2]);
    }

    // The bytes of an element's binaryFile (sponza's form, homework 6): a little-endian int32 count,
    // then count records of `record` bytes (3 float32 per vertex, 3 int32 per face), nothing more.
    // Read relative to the scene's folder and listed among the scene's files.
    std::string binary_file(node el, const std::string& owner, size_t record) {
        const std::string file = trim(attr(el, "binaryFile").value());
        if (file.empty()) fail(el, owner, tag(el) + ": binaryFile=\"\" names no file");
        const std::filesystem::path p(file);
        const std::string resolved = p.is_absolute() ? p.string() : (dir_ / p).string();
        std::string bytes;
        try {
            bytes = read_file(resolved, "binary geometry file");
        } catch (const scene_error& e) {
            fail(el, owner, tag(el) + ": " + e.what());
        }
        if (bytes.size() < 4) fail(el, owner, tag(el) + ": " + token_text(file) + " is shorter than its 4-byte count");
        const uint8_t* b = reinterpret_cast<const uint8_t*>(bytes.data());
        const int32_t count = int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
        if (count < 0 || uint64_t(bytes.size() - 4) != uint64_t(count) * record)
            fail(el, owner, tag(el) + ": " + token_text(file) + " holds " + std::to_string(bytes.size()) +
                                " bytes, but its count " + std::to_string(count) + " needs 4 + " + std::to_string(record) +
                                " x count");
        ply_files_.push_back(resolved); // hashed with the scene's files (the list's name is older than this)
        // Native float and int32 below: refuse a big-endian machine rather than misread.
        static_assert(sizeof(float) == 4, "float32");
        const uint16_t probe = 1;
        if (*reinterpret_cast<const uint8_t*>(&probe) != 1) fail(el, owner, "binary geometry files need a little-endian machine");
        return bytes;
    }

    // The values of an element's binaryFile after its count (4 bytes each, float32 or int32 as
    // Stored), as Out; refused when the element has numbers of its own as well.
    template <class Stored, class Out>
    std::vector<Out> binary_values(node el, const std::string& owner, size_t record) {
        static_assert(sizeof(Stored) == 4, "4-byte values");
        if (!words(text(el, owner)).empty()) fail(el, owner, tag(el) + " has both a binaryFile and numbers");
        const std::string bytes = binary_file(el, owner, record);
        std::vector<Out> out((bytes.size() - 4) / 4);
        for (size_t k = 0; k < out.size(); ++k) {
            Stored x;
            std::memcpy(&x, bytes.data() + 4 + 4 * k, 4);
            out[k] = Out(x);
        }
        return out;
    }

    // An element's id: required, and not yet taken in `defined` (`what` names the kind).
    template <class Map>
    long long new_id(node el, const std::string& owner, const Map& defined, const std::string& what) const {
        if (!attr(el, "id")) fail(el, owner, "missing attribute id");
        const long long id = attribute_integer(el, "id", 0);
        if (defined.count(id)) fail(el, owner, what + " id " + std::to_string(id) + " is defined twice");
        return id;
    }

    // A true|false attribute (absent: false).
    bool flag(node el, const char* name, const std::string& owner) const {
        pugi::xml_attribute a = attr(el, name);
        if (!a) return false;
        const std::string v = lower(trim(a.value()));
        if (v == "true" || v == "1") return true;
        if (v != "false" && v != "0")
            fail(el, owner, std::string(name) + "=\"" + token_text(a.value()) + "\" must be true or false");
        return false;
    }

    // <BRDFs> (homework 6): the models materials name with BRDF="k".
    void read_brdfs(node root) {
        using model = course_brdf_bsdf::model_t;
        for (node section : root.children("BRDFs")) {
            mark(section);
            for (node b : section.children()) {
                if (b.type() != pugi::node_element) continue;
                const std::string name = b.name();
                course_brdf_bsdf brdf;
                if (name == "OriginalPhong") brdf.model = model::original_phong;
                else if (name == "ModifiedPhong") brdf.model = model::modified_phong;
                else if (name == "OriginalBlinnPhong") brdf.model = model::original_blinn_phong;
                else if (name == "ModifiedBlinnPhong") brdf.model = model::modified_blinn_phong;
                else if (name == "TorranceSparrow") brdf.model = model::torrance_sparrow;
                else continue; // warned about as unread
                mark(b);
                const std::string owner = element_name(b);
                const long long id = new_id(b, owner, brdfs_, "BRDF");
                if (brdf.model == model::modified_phong || brdf.model == model::modified_blinn_phong)
                    brdf.normalized = flag(b, "normalized", owner);
                if (brdf.model == model::torrance_sparrow) brdf.kd_fresnel = flag(b, "kdfresnel", owner);
                brdf.exponent = float(bounded(child(b, "Exponent", true), owner, 0, false));
                brdfs_[id] = brdf;
            }
        }
    }

    void read_materials(node root) {
        for (node section : root.children("Materials")) {
            mark(section);
            for (node m : section.children("Material")) {
                mark(m);
                const std::string owner = element_name(m);
                if (!attr(m, "id")) fail(m, owner, "missing attribute id");
                long long id = attribute_integer(m, "id", 0);
                if (materials_.count(id))
                    fail(m, owner, "material id " + std::to_string(id) + " is defined twice" +
                                       (json_ ? std::string() : " (first on line " + std::to_string(material_lines_[id]) + ")"));
                auto material = std::make_shared<whitted_material>();
                whitted_material& p = *material;
                std::string type = lower(trim(attr(m, "type").value()));
                using kind = whitted_material::kind_t;
                if (type.empty()) p.kind = kind::plain;
                else if (type == "mirror") p.kind = kind::mirror;
                else if (type == "conductor") p.kind = kind::conductor;
                else if (type == "dielectric") p.kind = kind::dielectric;
                else
                    fail(m, owner, "unknown material type '" + std::string(attr(m, "type").value()) +
                                       "' (expected mirror, conductor or dielectric, or no type)");
                if (node n = child(m, "AmbientReflectance", false)) p.ambient = colour(n, owner);
                if (node n = child(m, "DiffuseReflectance", false)) p.diffuse = colour(n, owner);
                if (node n = child(m, "SpecularReflectance", false)) p.specular = colour(n, owner);
                if (node n = child(m, "PhongExponent", false)) p.phong_exponent = bounded(n, owner, 0, false);
                if (node n = child(m, "MirrorReflectance", false)) {
                    p.mirror = colour(n, owner);
                    // The course's rule (its homework-1 text; the instructor's images of Blender-
                    // exported scenes, galactica's ship and Veach Ajar's floor, show no mirror):
                    // only a mirror, conductor or dielectric reflects. An untyped material's
                    // MirrorReflectance is read, said, and not used.
                    if (type.empty() && (p.mirror.x() > 0 || p.mirror.y() > 0 || p.mirror.z() > 0)) {
                        p.mirror = color(0, 0, 0);
                        const size_t line = line_of(n);
                        notes_.push_back(one_line(path_ + (line ? ":" + std::to_string(line) : std::string()) + ": " +
                                                  owner + ": <MirrorReflectance> of a material without type=\"mirror\" "
                                                  "(or conductor or dielectric) is ignored, as the course's renderer ignores it"));
                    }
                }
                bool needs_index = p.kind == kind::conductor || p.kind == kind::dielectric;
                if (node n = child(m, "RefractionIndex", needs_index)) p.refraction_index = bounded(n, owner, 0, true);
                if (node n = child(m, "AbsorptionIndex", false)) p.absorption_index = bounded(n, owner, 0, false);
                if (node n = child(m, "AbsorptionCoefficient", false)) p.absorption_coefficient = colour(n, owner);
                if (node n = child(m, "Roughness", false)) p.roughness = bounded(n, owner, 0, false);
                if (flag(m, "degamma", owner)) {
                    // degamma="true" (homework 5): the colours are display values; each reflectance
                    // c is read as c^2.2, the gamma every course <Tonemap> uses (the course says no
                    // more: docs/course.md).
                    auto linear = [](color& c) {
                        for (int k = 0; k < 3; ++k) c[k] = std::pow(c[k], 2.2);
                    };
                    linear(p.ambient);
                    linear(p.diffuse);
                    linear(p.specular);
                    linear(p.mirror);
                }
                if (attr(m, "BRDF")) {
                    const long long b = attribute_integer(m, "BRDF", 0);
                    auto it = brdfs_.find(b);
                    if (it == brdfs_.end())
                        fail(m, owner, "BRDF=\"" + std::to_string(b) + "\" names no entry of <BRDFs>");
                    p.brdf = it->second;
                    p.phong_exponent = it->second.exponent;
                }
                materials_[id] = material;
                material_lines_[id] = line_of(m);
            }
        }
    }

    // <Renderer>PathTracing</Renderer> and <RendererParams> (homework 6): any of the words
    // NextEventEstimation, ImportanceSampling, RussianRoulette (none: uniform sampling, no NEE, the
    // depth limit).
    void read_renderer(node c, const std::string& owner, view_camera& cam) {
        node renderer = child(c, "Renderer", false);
        if (renderer) {
            const std::string name = trim(text(renderer, owner));
            // DirectLighting: the classic renderer, as no <Renderer> is.
            if (lower(name) == "pathtracing") cam.path_tracing.on = true;
            else if (lower(name) != "directlighting")
                fail(renderer, owner, "<Renderer> '" + token_text(name) +
                                          "' is not supported (PathTracing or DirectLighting, the classic ray tracer)");
        }
        node params = child(c, "RendererParams", false);
        if (!params) return;
        for (const std::string& w : words(text(params, owner))) {
            const std::string word = lower(w);
            if (word == "nexteventestimation") cam.path_tracing.next_event_estimation = true;
            else if (word == "importancesampling") cam.path_tracing.importance_sampling = true;
            else if (word == "russianroulette") cam.path_tracing.russian_roulette = true;
            else
                fail(params, owner, "<RendererParams>: '" + token_text(w) +
                                        "' is not one of NextEventEstimation, ImportanceSampling, RussianRoulette");
        }
        if (!cam.path_tracing.on) {
            const size_t line = line_of(params);
            notes_.push_back(one_line(path_ + (line ? ":" + std::to_string(line) : std::string()) + ": " + owner +
                                      ": <RendererParams> without <Renderer>PathTracing</Renderer> is ignored (the classic ray tracer takes none)"));
        }
    }

    // <Tonemap>: <TMO>Photographic</TMO> (the only operator the course uses), <TMOOptions>key
    // burn</TMOOptions>, <Saturation>, <Gamma>.
    void read_tonemap(node t, const std::string& owner, view_camera& cam) const {
        node tmo = child(t, "TMO", true);
        const std::string name = trim(text(tmo, owner));
        if (lower(name) != "photographic")
            fail(tmo, owner, "<TMO> '" + token_text(name) + "' is not supported (Photographic is)");
        photographic_tonemap& m = cam.tonemap;
        node options = child(t, "TMOOptions", true);
        const std::vector<double> kb = numbers(options, owner, 2, 2);
        if (!(kb[0] > 0)) fail(options, owner, "<TMOOptions>: the key must be positive, not " + number_text(kb[0]));
        if (!(kb[1] >= 0 && kb[1] < 100))
            fail(options, owner, "<TMOOptions>: burn must be a percentage in [0, 100), not " + number_text(kb[1]));
        m.key = kb[0];
        m.burn = kb[1];
        if (node n = child(t, "Saturation", false)) m.saturation = bounded(n, owner, 0, false);
        if (node n = child(t, "Gamma", false)) m.gamma = bounded(n, owner, 0, true);
        cam.tonemapped = true;
    }

    // <Transformations> at the scene's level: the numbered translations, scalings, rotations and
    // composites that objects name (t1, s2, r3, c4).
    void read_transformations(node root) {
        for (node section : root.children("Transformations")) {
            mark(section);
            for (node t : section.children()) {
                if (t.type() != pugi::node_element) continue;
                const std::string name = t.name();
                const char letter = name == "Translation" ? 't'
                                    : name == "Scaling"   ? 's'
                                    : name == "Rotation"  ? 'r'
                                    : name == "Composite" ? 'c'
                                                          : 0;
                if (!letter) continue; // warned about as unread
                mark(t);
                const std::string owner = element_name(t);
                auto& kind = transformations_[letter];
                const long long id = new_id(t, owner, kind, "<" + name + ">");
                affine_map m;
                if (letter == 't') {
                    m = affine_map::linear(mat3(), triple(t, owner));
                } else if (letter == 's') {
                    const vec3 f = triple(t, owner);
                    if (f.x() == 0 || f.y() == 0 || f.z() == 0)
                        fail(t, owner, "<Scaling> by 0 flattens the object: every factor must be non-zero");
                    m = affine_map::linear(mat3::diagonal(f), vec3(0, 0, 0));
                } else if (letter == 'r') {
                    const std::vector<double> v = numbers(t, owner, 4, 4);
                    const vec3 axis(v[1], v[2], v[3]);
                    if (!(axis.length_squared() > 0) || !std::isfinite(axis.length_squared()))
                        fail(t, owner, "<Rotation> has a zero (or too long) axis: expected degrees x y z");
                    m = affine_map::linear(mat3::rotation(axis, v[0]), vec3(0, 0, 0));
                } else {
                    const std::vector<double> v = numbers(t, owner, 16, 16);
                    if (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1)
                        fail(t, owner, "<Composite>'s last row must be 0 0 0 1 (an affine matrix, by rows), not " +
                                           number_text(v[12]) + " " + number_text(v[13]) + " " + number_text(v[14]) +
                                           " " + number_text(v[15]));
                    m = affine_map::linear(mat3(vec3(v[0], v[1], v[2]), vec3(v[4], v[5], v[6]), vec3(v[8], v[9], v[10])),
                                           vec3(v[3], v[7], v[11]));
                }
                kind[id] = m;
            }
        }
    }

    // The matrix of an object's <Transformations> list ("t1 r2 s1": t1 acts first), the identity
    // without one.
    affine_map object_transform(node object, const std::string& owner) const {
        affine_map m;
        node list = child(object, "Transformations", false);
        if (!list) return m;
        for (const std::string& w : words(text(list, owner))) {
            const char letter = char(std::tolower(static_cast<unsigned char>(w[0])));
            const char* kind_name = letter == 't'   ? "Translation"
                                    : letter == 's' ? "Scaling"
                                    : letter == 'r' ? "Rotation"
                                    : letter == 'c' ? "Composite"
                                                    : nullptr;
            if (!kind_name || w.size() < 2)
                fail(list, owner, "<Transformations>: '" + token_text(w) +
                                      "' is not a transformation (a letter t, s, r or c and an id: t1)");
            const long long id = parse_integer(w.substr(1), list, owner);
            auto kind = transformations_.find(letter);
            const bool found = kind != transformations_.end() && kind->second.count(id);
            if (!found) {
                std::vector<long long> ids;
                if (kind != transformations_.end())
                    for (const auto& kv : kind->second) ids.push_back(kv.first);
                fail(list, owner, "<Transformations>: " + token_text(w) + ": there is no <" + kind_name + " id=\"" +
                                      std::to_string(id) + "\"> (" +
                                      (ids.empty() ? std::string("the file defines none")
                                                   : "the file defines " + id_ranges(ids)) + ")");
            }
            m = kind->second.at(id).then(m);
        }
        check_invertible(m, list, owner);
        return m;
    }
    void check_invertible(const affine_map& m, node at, const std::string& owner) const {
        if (m.identity) return;
        const double det = m.m.determinant();
        bool finite = std::isfinite(det);
        for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(m.t[i]);
        if (!finite) fail(at, owner, "<Transformations> give a matrix beyond the range of a double");
        if (det == 0) fail(at, owner, "<Transformations> give a singular matrix: the object would be flat");
    }
    // The placed object moving by its <MotionBlur> x y z (homework 3: world space, after every
    // transformation; at time t in [0, 1] it is displaced by t (x, y, z)), or as it is without one.
    // An instance does not inherit its base's motion (the instructor's dragon_dynamic image).
    std::shared_ptr<hittable> blurred(node o, const std::string& owner, std::shared_ptr<hittable> placed) const {
        node blur = child(o, "MotionBlur", false);
        if (!blur) return placed;
        const vec3 d = triple(blur, owner);
        if (d.x() == 0 && d.y() == 0 && d.z() == 0) return placed;
        return std::make_shared<moving>(std::move(placed), d);
    }
    // The object as placed by m.
    static std::shared_ptr<hittable> place(std::shared_ptr<hittable> object, const affine_map& m) {
        if (m.identity) return object;
        return std::make_shared<transform>(std::move(object), m.m, m.t);
    }

    void read_cameras(node root, whitted_scene& scene) {
        for (node section : root.children("Cameras")) {
            mark(section);
            for (node c : section.children("Camera")) {
                mark(c);
                const std::string owner = element_name(c);
                view_camera cam;
                std::string type = lower(trim(attr(c, "type").value()));
                if (!type.empty() && type != "lookat")
                    fail(c, owner, "unknown camera type '" + std::string(attr(c, "type").value()) +
                                       "' (expected lookAt, or no type)");
                cam.position = triple(child(c, "Position", true), owner);
                node up = child(c, "Up", true);
                cam.up = triple(up, owner);
                if (cam.up.length_squared() == 0) fail(up, owner, "<Up> is the zero vector");
                cam.near_distance = bounded(child(c, "NearDistance", true), owner, 0, true);
                node res = child(c, "ImageResolution", true);
                std::vector<long long> wh = integers(res, owner);
                if (wh.size() != 2)
                    fail(res, owner, "<ImageResolution> has " + std::to_string(wh.size()) + " numbers, expected 2");
                if (wh[0] <= 0 || wh[1] <= 0 || wh[0] > 1000000 || wh[1] > 1000000)
                    fail(res, owner, "<ImageResolution> " + std::to_string(wh[0]) + " " + std::to_string(wh[1]) +
                                         ": width and height must be between 1 and 1000000");
                if (uint64_t(wh[0]) * uint64_t(wh[1]) > max_render_pixels)
                    fail(res, owner, "<ImageResolution> " + std::to_string(wh[0]) + " " + std::to_string(wh[1]) + " is " +
                                         std::to_string(uint64_t(wh[0]) * uint64_t(wh[1])) +
                                         " pixels, more than the limit of " + std::to_string(max_render_pixels) +
                                         " (2^26) pixels for a render");
                cam.width = int(wh[0]);
                cam.height = int(wh[1]);
                node name = child(c, "ImageName", true);
                cam.image_name = trim(text(name, owner));
                if (cam.image_name.empty()) fail(name, owner, "<ImageName> is empty");
                std::string unsafe = image_name_problem(cam.image_name);
                if (!unsafe.empty()) fail(name, owner, "<ImageName> '" + cam.image_name + "' " + unsafe);
                if (type.empty()) {
                    node gaze = child(c, "Gaze", true);
                    cam.gaze = triple(gaze, owner);
                    if (cam.gaze.length_squared() == 0) fail(gaze, owner, "<Gaze> is the zero vector");
                    node plane = child(c, "NearPlane", true);
                    std::vector<double> lrbt = numbers(plane, owner, 4, 5); // a 5th number is ignored
                    cam.left = lrbt[0];
                    cam.right = lrbt[1];
                    cam.bottom = lrbt[2];
                    cam.top = lrbt[3];
                    if (cam.left == cam.right || cam.bottom == cam.top)
                        fail(plane, owner, "<NearPlane> has zero width or height");
                } else {
                    // A point to look at, or (as hw6's lookAt cameras give it) the direction.
                    node at = child(c, "GazePoint", false), gaze = child(c, "Gaze", false);
                    if (at && gaze) fail(gaze, owner, "a lookAt camera takes <GazePoint> or <Gaze>, not both");
                    if (!at && !gaze) fail(c, owner, "missing <GazePoint> (or <Gaze>)");
                    if (at) {
                        cam.gaze = triple(at, owner) - cam.position;
                        if (cam.gaze.length_squared() == 0) fail(at, owner, "<GazePoint> is the camera's <Position>");
                    } else {
                        cam.gaze = triple(gaze, owner);
                        if (cam.gaze.length_squared() == 0) fail(gaze, owner, "<Gaze> is the zero vector");
                    }
                    node fov = child(c, "FovY", true);
                    double fovy = scalar(fov, owner);
                    if (!(fovy > 0 && fovy < 180))
                        fail(fov, owner, "<FovY> must be between 0 and 180 degrees, not " + number_text(fovy));
                    cam.top = cam.near_distance * std::tan(fovy * 3.14159265358979323846 / 360);
                    cam.bottom = -cam.top;
                    cam.right = cam.top * double(cam.width) / double(cam.height);
                    cam.left = -cam.right;
                }
                if (cross(cam.up, cam.gaze).length_squared() == 0)
                    fail(up, owner, "<Up> is parallel to the gaze direction");
                if (node n = child(c, "NumSamples", false)) {
                    const long long k = integer(n, owner);
                    if (k < 1 || k > (1 << 24)) fail(n, owner, "<NumSamples> must be between 1 and 16777216, not " + std::to_string(k));
                    cam.samples = int(k);
                }
                if (node n = child(c, "ApertureSize", false)) cam.aperture = bounded(n, owner, 0, false);
                if (node n = child(c, "FocusDistance", false)) cam.focus_distance = bounded(n, owner, 0, true);
                if (cam.aperture > 0 && cam.focus_distance == 0)
                    fail(c, owner, "an <ApertureSize> needs a <FocusDistance>");
                if (node t = child(c, "Tonemap", false)) read_tonemap(t, owner, cam);
                read_renderer(c, owner, cam);
                if (pugi::xml_attribute hand = attr(c, "handedness")) {
                    const std::string h = lower(trim(hand.value()));
                    if (h == "left") cam.left_handed = true;
                    else if (h != "right")
                        fail(c, owner, "handedness=\"" + token_text(hand.value()) + "\" must be left or right");
                }
                scene.cameras.push_back(cam);
            }
        }
    }

    void read_lights(node root, whitted_scene& scene) {
        node ambient;
        for (node section : root.children("Lights")) {
            mark(section);
            for (node a : section.children("AmbientLight")) {
                mark(a);
                if (ambient) fail(a, "<Lights>", "<AmbientLight> appears twice");
                ambient = a;
                scene.ambient_light = colour(a, "<Lights>");
            }
            for (node l : section.children("PointLight")) {
                mark(l);
                const std::string owner = element_name(l);
                point_light light;
                light.position = triple(child(l, "Position", true), owner);
                light.intensity = colour(child(l, "Intensity", true), owner);
                scene.lights.push_back(light);
            }
            for (node l : section.children("DirectionalLight")) {
                mark(l);
                const std::string owner = element_name(l);
                directional_light light;
                light.direction = nonzero(child(l, "Direction", true), owner);
                light.irradiance = colour(child(l, "Radiance", true), owner);
                scene.directional_lights.push_back(light);
            }
            for (node l : section.children("SpotLight")) {
                mark(l);
                const std::string owner = element_name(l);
                spot_light light;
                light.position = triple(child(l, "Position", true), owner);
                light.direction = nonzero(child(l, "Direction", true), owner);
                light.intensity = colour(child(l, "Intensity", true), owner);
                node coverage = child(l, "CoverageAngle", true), falloff = child(l, "FalloffAngle", true);
                light.coverage_degrees = bounded(coverage, owner, 0, false);
                light.falloff_degrees = bounded(falloff, owner, 0, false);
                if (light.coverage_degrees > 360) fail(coverage, owner, "<CoverageAngle> must be at most 360 degrees");
                if (light.falloff_degrees > light.coverage_degrees)
                    fail(falloff, owner, "<FalloffAngle> must not be larger than <CoverageAngle>");
                scene.spot_lights.push_back(light);
            }
            for (node l : section.children("AreaLight")) {
                mark(l);
                const std::string owner = element_name(l);
                area_light light;
                light.position = triple(child(l, "Position", true), owner);
                light.normal = nonzero(child(l, "Normal", true), owner);
                light.size = bounded(child(l, "Size", true), owner, 0, true);
                light.radiance = colour(child(l, "Radiance", true), owner);
                scene.area_lights.push_back(light);
            }
            for (node l : section.children("SphericalDirectionalLight")) {
                mark(l);
                const std::string owner = element_name(l);
                if (pugi::xml_attribute type = attr(l, "type")) {
                    const std::string t = lower(trim(type.value()));
                    if (t != "latlong")
                        fail(l, owner, "type=\"" + token_text(type.value()) + "\" is not supported (latlong is)");
                }
                node id = child(l, "ImageId", true);
                environment_light light;
                light.map = image_of(id, owner, light.path);
                scene.environment_lights.push_back(light);
            }
        }
    }

    // <Textures><Images><Image id="k">path</Image>...: the images, by id, as the file names them
    // (relative to its folder). Environment lights and texture maps read theirs (image_of).
    void read_images(node root) {
        for (node section : root.children("Textures")) {
            mark(section);
            for (node images : section.children("Images")) {
                mark(images);
                for (node i : images.children("Image")) {
                    mark(i);
                    const std::string owner = element_name(i);
                    const long long id = new_id(i, owner, images_, "image");
                    images_[id] = i;
                }
            }
        }
    }

    // A path-traced camera with RussianRoulette keeps a path going while its throughput is 1 or
    // more (the course's rule, section 11): on a plain material that reflects more than it
    // receives, as the level-1 model's f = kd does for kd above 1/pi (albedo pi kd), no path ends
    // before the renderer's cap (whitted_settings::max_branch_rays). Said once per such material.
    void warn_runaway_roulette(const whitted_scene& scene) {
        bool roulette = false;
        for (const view_camera& c : scene.cameras) roulette = roulette || (c.path_tracing.on && c.path_tracing.russian_roulette);
        if (!roulette) return;
        for (const auto& [id, m] : materials_) {
            if (m->kind != whitted_material::kind_t::plain || m->effective_kind() != whitted_material::kind_t::plain) continue;
            const double kd = std::max({m->diffuse.x(), m->diffuse.y(), m->diffuse.z()});
            const bool per_pi = m->brdf && (m->brdf->normalized || m->brdf->model == course_brdf_bsdf::model_t::torrance_sparrow);
            const double albedo = per_pi ? kd : pi * kd;
            if (!(albedo > 1)) continue;
            char text[48];
            std::snprintf(text, sizeof text, "%.3g", albedo);
            notes_.push_back(one_line(path_ + (json_ ? std::string() : ":" + std::to_string(material_lines_[id])) +
                                      ": <Material id=\"" + std::to_string(id) + "\">: reflects " + text +
                                      " times the light it receives in the course's path tracer (" +
                                      (per_pi ? "its BRDF's diffuse albedo kd" : "f = kd, albedo pi kd") +
                                      "): under RussianRoulette its paths do not end and are cut at " +
                                      std::to_string(whitted_settings{}.max_branch_rays) + " rays"));
        }
    }

    // <TexCoordData>: u v per vertex, indexed like <VertexData> (a binaryFile: an int32 count, then
    // count pairs of float32).
    void read_tex_coords(node root) {
        node data = child(root, "TexCoordData", false);
        if (!data) return;
        const std::vector<double> v = attr(data, "binaryFile") ? binary_values<float, double>(data, "<Scene>", 8)
                                                               : numbers(data, "<Scene>", 0, static_cast<size_t>(-1));
        if (v.size() % 2 != 0)
            fail(data, "<Scene>", "<TexCoordData> has " + std::to_string(v.size()) + " numbers, not a multiple of 2 (u v per vertex)");
        for (size_t i = 0; i < v.size(); i += 2) {
            if (!std::isfinite(v[i]) || !std::isfinite(v[i + 1]))
                fail(data, "<Scene>", "<TexCoordData>: texture coordinate " + std::to_string(i / 2 + 1) + " is not finite");
            tex_coords_.push_back({v[i], v[i + 1]});
        }
    }

    // <Textures><TextureMap id type="image|perlin|checkerboard" degamma>: see course_textures.h
    // for what each child means. A replace_background map is the scene's background texture.
    void read_texture_maps(node root, whitted_scene& scene) {
        for (node section : root.children("Textures"))
            for (node t : section.children("TextureMap")) {
                mark(t);
                const std::string owner = element_name(t);
                const long long id = new_id(t, owner, texture_maps_, "texture map");
                texture_map map;
                using pattern = texture_map::pattern_t;
                using decal = texture_map::decal_t;
                const std::string type = lower(trim(attr(t, "type").value()));
                if (type == "image") map.pattern = pattern::image;
                else if (type == "perlin") map.pattern = pattern::perlin;
                else if (type == "checkerboard") map.pattern = pattern::checkerboard;
                else
                    fail(t, owner, type.empty() ? "missing attribute type (image, perlin or checkerboard)"
                                                : "unknown type \"" + token_text(attr(t, "type").value()) +
                                                      "\" (expected image, perlin or checkerboard)");
                map.degamma = flag(t, "degamma", owner);
                node mode = child(t, "DecalMode", true);
                const std::string m = lower(trim(text(mode, owner)));
                static const std::pair<const char*, decal> modes[] = {
                    {"replace_kd", decal::replace_kd},         {"blend_kd", decal::blend_kd},
                    {"replace_ks", decal::replace_ks},         {"replace_all", decal::replace_all},
                    {"replace_normal", decal::replace_normal}, {"bump_normal", decal::bump_normal},
                    {"replace_background", decal::replace_background}};
                bool known = false;
                for (const auto& [name, value] : modes)
                    if (m == name) map.decal = value, known = true;
                if (!known)
                    fail(mode, owner, "unknown <DecalMode> '" + token_text(trim(text(mode, owner))) +
                                          "' (expected replace_kd, blend_kd, replace_ks, replace_all, replace_normal, "
                                          "bump_normal or replace_background)");
                const bool needs_image = map.decal == decal::replace_normal || map.decal == decal::replace_background;
                if (needs_image && map.pattern != pattern::image)
                    fail(mode, owner, m + " needs an image map, not " + type);
                if (map.decal == decal::bump_normal && map.pattern == pattern::checkerboard)
                    fail(mode, owner, "bump_normal needs an image or perlin map, not a checkerboard");
                if (map.pattern == pattern::image) {
                    std::string path;
                    node ref = child(t, "ImageId", true);
                    map.picture = image_of(ref, owner, path);
                    const bool encoded = image_encoded_[integer(ref, owner)];
                    map.normalizer = encoded ? 255.0f : 1.0f; // 8-bit codes, or radiance as it is
                    if (node n = child(t, "Normalizer", false)) map.normalizer = float(bounded(n, owner, 0, true));
                    if (node n = child(t, "Interpolation", false)) map.bilinear = either(n, owner, "nearest", "bilinear");
                }
                if (node n = child(t, "BumpFactor", false)) map.bump_factor = float(finite(n, owner));
                if (map.pattern == pattern::perlin) {
                    if (node n = child(t, "NoiseScale", false)) map.noise_scale = float(finite(n, owner));
                    if (node n = child(t, "NoiseConversion", false)) map.absval = either(n, owner, "linear", "absval");
                }
                if (map.pattern == pattern::checkerboard) {
                    if (node n = child(t, "Scale", false)) map.scale = finite(n, owner);
                    if (node n = child(t, "Offset", false)) map.offset = finite(n, owner);
                    if (node n = child(t, "BlackColor", false)) map.black = vec3f(colour(n, owner));
                    if (node n = child(t, "WhiteColor", false)) map.white = vec3f(colour(n, owner));
                }
                if (map.decal == decal::replace_background) {
                    if (scene.background_texture)
                        fail(t, owner, "a second replace_background map (one background per scene)");
                    scene.background_texture = map;
                }
                texture_maps_[id] = std::move(map);
            }
    }
    // An element whose text is one of two words (case aside): false for `first`, true for `second`.
    bool either(node el, const std::string& owner, const char* first, const char* second) const {
        const std::string w = lower(trim(text(el, owner)));
        if (w == second) return true;
        if (w != first)
            fail(el, owner, "unknown " + tag(el) + " '" + token_text(trim(text(el, owner))) + "' (expected " + first +
                                " or " + second + ")");
        return false;
    }
    // A number that must be finite (any sign).
    double finite(node el, const std::string& owner) const {
        const double x = scalar(el, owner);
        if (!std::isfinite(x)) fail(el, owner, tag(el) + " must be a finite number");
        return x;
    }

    // An object's <Textures>k1 k2</Textures> (homework 4): nullptr without one; else a copy of its
    // material that only this object uses, with the object's maps recorded in the scene (the
    // renderer finds the object by that material: course_textures.h).
    std::shared_ptr<whitted_material> textured(node o, const std::string& owner, const std::shared_ptr<whitted_material>& given,
                                               textured_object::shape_t shape, const affine_map& placed,
                                               whitted_scene& scene, const point3& center = point3(0, 0, 0),
                                               double radius = 1) {
        node list = child(o, "Textures", false);
        if (!list) return nullptr;
        textured_object t;
        for (long long id : integers(list, owner)) {
            auto it = texture_maps_.find(id);
            if (it == texture_maps_.end())
                fail(list, owner, "<Textures> names texture map " + std::to_string(id) + ", which <Textures> does not define");
            if (it->second.decal != texture_map::decal_t::replace_background) t.maps.push_back(it->second);
        }
        auto copy = std::make_shared<whitted_material>(*given);
        t.surface = copy;
        t.shape = shape;
        t.center = center;
        t.radius = radius;
        t.linear = placed.m;
        t.offset = placed.t;
        scene.textured_objects.push_back(std::move(t));
        return copy;
    }

    // The image `ref` (an <ImageId>) names, read once: linear values as the file holds them (an
    // 8-bit file's codes 0-255). Refused: a missing id or file, or texels that are not finite and
    // non-negative radiance.
    std::shared_ptr<const image> image_of(node ref, const std::string& owner, std::string& path) {
        const long long id = integer(ref, owner);
        auto it = images_.find(id);
        if (it == images_.end()) fail(ref, owner, tag(ref) + " " + std::to_string(id) + " names no <Image> of <Textures>");
        const std::string file = trim(text(it->second, element_name(it->second)));
        if (file.empty()) fail(it->second, element_name(it->second), "names no file");
        const std::filesystem::path fp(file);
        path = fp.is_absolute() ? fp.string() : (dir_ / fp).string();
        auto cached = loaded_images_.find(id);
        if (cached != loaded_images_.end()) return cached->second;
        loaded_image loaded;
        try {
            loaded = read_image(path);
        } catch (const scene_error& e) {
            fail(ref, owner, tag(ref) + " " + std::to_string(id) + ": " + e.what());
        }
        for (float c : loaded.pixels.data())
            if (!(c >= 0) || !std::isfinite(c))
                fail(ref, owner, tag(ref) + " " + std::to_string(id) + ": " + token_text(file) +
                                     " holds a texel that is negative or not a finite number");
        ply_files_.push_back(path); // hashed with the scene's files
        image_encoded_[id] = loaded.display_encoded;
        auto img = std::make_shared<const image>(std::move(loaded.pixels));
        loaded_images_[id] = img;
        return img;
    }

    std::shared_ptr<whitted_material> material_of(node object, const std::string& owner) const {
        node m = child(object, "Material", true);
        long long id = integer(m, owner);
        auto it = materials_.find(id);
        if (it == materials_.end()) {
            std::vector<long long> ids;
            for (const auto& kv : materials_) ids.push_back(kv.first);
            fail(m, owner, "<Material> " + std::to_string(id) + " does not exist (" +
                               (ids.empty() ? "the file defines no materials" : "the file defines materials " + id_ranges(ids)) +
                               ")");
        }
        return it->second;
    }

    // The index in <TexCoordData> of face index `id` plus `offset` (textureOffset), numbered like
    // the vertices. Out of range: refused when `required` (the object has <Textures>), else
    // UINT32_MAX (the mesh gets no texture coordinates).
    uint32_t tex_coord_index(long long id, node at, const std::string& owner, long long offset, bool required) const {
        const long long first = zero_based_ ? 0 : 1;
        const bool overflows = offset > 0 ? id > LLONG_MAX - offset : id < LLONG_MIN - offset;
        const long long shifted = overflows ? first - 1 : id + offset;
        if (shifted >= first && shifted - first < (long long)tex_coords_.size()) return uint32_t(shifted - first);
        if (!required) return UINT32_MAX;
        fail(at, owner, "texture coordinate " + std::to_string(id) +
                            (offset != 0 ? " + textureOffset " + std::to_string(offset) : std::string()) +
                            " does not exist (<TexCoordData> has " + std::to_string(tex_coords_.size()) + ")");
    }

    // The 0-based index of vertex id `id` (as the file gives it, `offset` already added).
    uint32_t vertex_index(long long id, node at, const std::string& owner, const std::string& what) const {
        // Compared before subtracting: id - 1 would overflow for the smallest long long.
        const long long first = zero_based_ ? 0 : 1;
        if (id < first || id - first >= (long long)vertices_.size()) {
            std::string has = vertices_.empty() ? "the file has no <VertexData>"
                                                : "the file defines vertices " + std::to_string(first) + "-" +
                                                      std::to_string(first + (long long)vertices_.size() - 1);
            fail(at, owner, what + " does not exist (" + has + ")");
        }
        return uint32_t(id - first);
    }

    void read_objects(node root, whitted_scene& scene) {
        remap_.assign(vertices_.size(), triangle_mesh::no_index);
        // Meshes and instances by id first: an instance may name one defined after it.
        for (node section : root.children("Objects"))
            for (node o : section.children()) {
                const std::string name = o.name();
                if (name != "Mesh" && name != "MeshInstance") continue;
                if (!o.attribute("id")) continue; // nothing can name it
                auto& by_id = name == "Mesh" ? meshes_by_id_ : instances_by_id_;
                by_id.emplace(attribute_integer(o, "id", 0), o); // the first of a repeated id
            }
        // Single triangles, by material and transformation list (placed once all are read).
        std::map<std::pair<const whitted_material*, std::string>, std::shared_ptr<triangle_mesh>> single;
        std::map<std::pair<const whitted_material*, std::string>, affine_map> single_transform;
        std::vector<std::pair<const whitted_material*, std::string>> single_order;
        for (node section : root.children("Objects")) {
            mark(section);
            for (node o : section.children()) {
                if (o.type() != pugi::node_element) continue;
                const std::string name = o.name(), owner = element_name(o);
                if (name == "Triangle") {
                    mark(o);
                    auto mat = material_of(o, owner);
                    const affine_map m = object_transform(o, owner);
                    if (auto mapped = textured(o, owner, mat, textured_object::shape_t::mesh, m, scene)) mat = mapped;
                    node idx = child(o, "Indices", true);
                    std::vector<long long> ids = integers(idx, owner);
                    if (ids.size() != 3)
                        fail(idx, owner, "<Indices> has " + std::to_string(ids.size()) + " numbers, expected 3");
                    node list = child(o, "Transformations", false);
                    const auto key = std::make_pair(mat.get(), list ? lower(trim(text(list, owner))) : std::string());
                    auto& mesh = single[key];
                    if (!mesh) {
                        mesh = std::make_shared<triangle_mesh>();
                        mesh->mat = mat;
                        // Untransformed triangles go in where the first is (level 1's order).
                        if (m.identity) scene.world.add(mesh);
                        else single_order.push_back(key);
                        single_transform[key] = m;
                    }
                    auto first = uint32_t(mesh->positions.size());
                    for (long long id : ids)
                        mesh->positions.push_back(
                            vertices_[vertex_index(id, idx, owner, "<Indices> vertex " + std::to_string(id))]);
                    mesh->faces.push_back({first, first + 1, first + 2});
                    if (child(o, "Textures", false) && !tex_coords_.empty()) {
                        // A textured triangle has a mesh of its own: its corners' texture coordinates.
                        for (long long id : ids) mesh->uvs.push_back(tex_coords_[tex_coord_index(id, idx, owner, 0, true)]);
                        mesh->face_uvs.push_back({first, first + 1, first + 2});
                    }
                } else if (name == "Mesh") {
                    mark(o);
                    const placed_mesh& p = resolve_mesh(o);
                    auto mapped = textured(o, owner, p.material, textured_object::shape_t::mesh, p.matrix, scene);
                    scene.world.add(blurred(o, owner, place(mapped ? with_material(p.geometry, mapped) : p.geometry, p.matrix)));
                } else if (name == "MeshInstance") {
                    mark(o);
                    std::set<const void*> visiting;
                    const placed_mesh p = resolve_instance(o, visiting);
                    auto mapped = p.textures ? textured(p.textures, element_name(p.textures), p.material,
                                                        textured_object::shape_t::mesh, p.matrix, scene)
                                             : nullptr;
                    scene.world.add(blurred(o, owner, place(with_material(p.geometry, mapped ? mapped : p.material), p.matrix)));
                } else if (name == "Sphere") {
                    mark(o);
                    auto mat = material_of(o, owner);
                    node center = child(o, "Center", true);
                    long long id = integer(center, owner);
                    point3 c = vertices_[vertex_index(id, center, owner, "<Center> vertex " + std::to_string(id))];
                    double radius = bounded(child(o, "Radius", true), owner, 0, true);
                    const affine_map m = object_transform(o, owner);
                    if (auto mapped = textured(o, owner, mat, textured_object::shape_t::sphere, m, scene, c, radius)) mat = mapped;
                    scene.world.add(blurred(o, owner, place(std::make_shared<sphere>(c, radius, mat), m)));
                } else if (name == "LightMesh" || name == "LightSphere") {
                    mark(o);
                    read_light_object(o, owner, name == "LightMesh", scene);
                }
                // Anything else belongs to a later homework: warned about.
            }
        }
        for (const auto& key : single_order) scene.world.add(place(single[key], single_transform[key]));
    }

    // <LightMesh> and <LightSphere> (homework 6): a Mesh or Sphere with a <Radiance> L. The shape
    // goes into the world in a copy of its material that emits L (seen by the rays that hit it), and
    // into the scene's light list, which the Whitted integrator samples (course_lights.h).
    void read_light_object(node o, const std::string& owner, bool is_mesh, whitted_scene& scene) {
        const color radiance = colour(child(o, "Radiance", true), owner);
        const affine_map m = object_transform(o, owner);
        auto emitting = [&](const std::shared_ptr<material>& given) {
            auto copy = std::make_shared<whitted_material>(*std::static_pointer_cast<whitted_material>(given));
            copy->radiance = radiance;
            return copy;
        };
        if (is_mesh) {
            std::shared_ptr<triangle_mesh> mesh = read_mesh(o, owner, remap_);
            mesh->mat = emitting(mesh->mat);
            light_mesh light;
            light.radiance = radiance;
            for (const auto& f : mesh->faces)
                light.triangles.push_back({m.point(mesh->positions[f[0]]), m.point(mesh->positions[f[1]]),
                                           m.point(mesh->positions[f[2]])});
            light.shape = place(mesh, m);
            scene.world.add(light.shape);
            scene.light_meshes.push_back(std::move(light));
            return;
        }
        auto mat = emitting(material_of(o, owner));
        node center = child(o, "Center", true);
        const long long id = integer(center, owner);
        const point3 c = vertices_[vertex_index(id, center, owner, "<Center> vertex " + std::to_string(id))];
        const double radius = bounded(child(o, "Radius", true), owner, 0, true);
        light_sphere light;
        light.center = c;
        light.radius = radius;
        light.linear = m.m;
        light.offset = m.t;
        light.radiance = radiance;
        light.shape = place(std::make_shared<sphere>(c, radius, mat), m);
        scene.world.add(light.shape);
        scene.light_spheres.push_back(light);
    }

    // A mesh's raw geometry (with the material its <Mesh> gives), where it is placed and the
    // material it is drawn with.
    struct placed_mesh {
        std::shared_ptr<triangle_mesh> geometry;
        affine_map matrix;
        std::shared_ptr<whitted_material> material;
        // The element whose <Textures> list it is drawn with: its own, else its base's (an
        // instance copies its base, maps included, as it keeps its material); none without.
        node textures;
    };

    // A <Mesh>: read once, however many instances name it.
    const placed_mesh& resolve_mesh(node o) {
        auto it = resolved_.find(o.internal_object());
        if (it != resolved_.end()) return it->second;
        const std::string owner = element_name(o);
        placed_mesh p;
        p.geometry = read_mesh(o, owner, remap_);
        p.material = std::static_pointer_cast<whitted_material>(p.geometry->mat);
        p.matrix = object_transform(o, owner);
        if (child(o, "Textures", false)) p.textures = o;
        return resolved_.emplace(o.internal_object(), std::move(p)).first->second;
    }

    // A <MeshInstance>: its base (a Mesh of that id, else a MeshInstance), its own matrix after the
    // base's (or alone, with resetTransform="true", on the base Mesh's raw vertices) and its own
    // material or the base's.
    placed_mesh resolve_instance(node o, std::set<const void*>& visiting) {
        auto it = resolved_.find(o.internal_object());
        if (it != resolved_.end()) return it->second;
        const std::string owner = element_name(o);
        pugi::xml_attribute base_attr = attr(o, "baseMeshId");
        if (!base_attr) fail(o, owner, "missing attribute baseMeshId");
        const long long base_id = attribute_integer(o, "baseMeshId", 0);
        bool reset = false;
        if (pugi::xml_attribute r = attr(o, "resetTransform")) {
            const std::string v = lower(trim(r.value()));
            if (v == "true" || v == "1") reset = true;
            else if (v != "false" && v != "0")
                fail(o, owner, "resetTransform=\"" + token_text(r.value()) + "\" must be true or false");
        }
        if (!visiting.insert(o.internal_object()).second)
            fail(o, owner, "baseMeshId " + std::to_string(base_id) + " leads back to this instance: a cycle");
        // Each link is a call: a chain as long as a hostile file likes would overflow the stack
        // (the course's longest is 8).
        constexpr size_t max_chain = 256;
        if (visiting.size() > max_chain)
            fail(o, owner, "a chain of more than " + std::to_string(max_chain) + " instances of instances");
        placed_mesh base;
        if (auto m = meshes_by_id_.find(base_id); m != meshes_by_id_.end()) {
            mark(m->second);
            base = resolve_mesh(m->second);
        } else if (auto i = instances_by_id_.find(base_id); i != instances_by_id_.end()) {
            mark(i->second);
            base = resolve_instance(i->second, visiting);
        } else {
            std::vector<long long> ids;
            for (const auto& kv : meshes_by_id_) ids.push_back(kv.first);
            fail(o, owner, "baseMeshId " + std::to_string(base_id) + ": no <Mesh> or <MeshInstance> has that id (" +
                               (ids.empty() ? std::string("the file defines no meshes") : "meshes " + id_ranges(ids)) +
                               ")");
        }
        placed_mesh p;
        p.geometry = base.geometry;
        const affine_map own = object_transform(o, owner);
        p.matrix = reset ? own : own.then(base.matrix);
        check_invertible(p.matrix, o, owner);
        p.material = child(o, "Material", false) ? material_of(o, owner) : base.material;
        p.textures = child(o, "Textures", false) ? o : base.textures;
        return resolved_.emplace(o.internal_object(), std::move(p)).first->second;
    }

    // `geometry` drawn with `material`: itself when that is its own, else one shared copy per
    // material (the compiler instances a mesh placed several times only when the placements share
    // the mesh, material and all).
    std::shared_ptr<triangle_mesh> with_material(const std::shared_ptr<triangle_mesh>& geometry,
                                                 const std::shared_ptr<whitted_material>& material) {
        if (geometry->mat.get() == material.get()) return geometry;
        auto& copy = recoloured_[{geometry.get(), material.get()}];
        if (!copy) {
            copy = std::make_shared<triangle_mesh>(*geometry);
            copy->mat = material;
        }
        return copy;
    }

    std::shared_ptr<triangle_mesh> read_mesh(node o, const std::string& owner, std::vector<uint32_t>& remap) {
        auto mat = material_of(o, owner);
        std::string shading = lower(trim(attr(o, "shadingMode").value()));
        if (!shading.empty() && shading != "smooth" && shading != "flat")
            fail(o, owner, "unknown shadingMode '" + std::string(attr(o, "shadingMode").value()) +
                               "' (expected smooth or flat)");
        node faces = child(o, "Faces", true);
        std::shared_ptr<triangle_mesh> mesh;
        if (pugi::xml_attribute ply = attr(faces, "plyFile")) {
            std::string file = trim(ply.value());
            if (file.empty()) fail(faces, owner, "<Faces plyFile=\"\"> names no file");
            if (!words(text(faces, owner)).empty())
                fail(faces, owner, "<Faces> has both a plyFile and indices");
            attr(faces, "vertexOffset"); // read, and by level 1's rule not applied to a PLY file's faces
            std::filesystem::path p(file);
            std::string resolved = p.is_absolute() ? p.string() : (dir_ / p).string();
            try {
                mesh = load_ply(resolved, mat);
            } catch (const scene_error& e) {
                fail(faces, owner, "<Faces plyFile=\"" + file + "\">: " + e.what());
            }
            ply_files_.push_back(resolved);
        } else {
            // The course's files put vertexOffset on <Faces>; a <Mesh vertexOffset> means the same.
            if (attr(o, "vertexOffset") && attr(faces, "vertexOffset"))
                fail(faces, owner, "vertexOffset is given on both <Mesh> and <Faces>");
            long long offset = attr(o, "vertexOffset") ? attribute_integer(o, "vertexOffset", 0)
                                                           : attribute_integer(faces, "vertexOffset", 0);
            const std::vector<long long> ids = attr(faces, "binaryFile") ? binary_values<int32_t, long long>(faces, owner, 12)
                                                                         : integers(faces, owner);
            if (ids.empty()) fail(faces, owner, "<Faces> is empty");
            if (ids.size() % 3 != 0)
                fail(faces, owner, "<Faces> has " + std::to_string(ids.size()) +
                                       " vertex ids, not a multiple of 3 (three per triangle)");
            mesh = std::make_shared<triangle_mesh>();
            mesh->mat = mat;
            // Texture coordinates (homework 4): face index n names <TexCoordData> entry
            // n + textureOffset, when the file has them and every corner's is there.
            const long long tex_offset = attribute_integer(faces, "textureOffset", 0);
            if (!tex_coords_.empty()) {
                const bool required = bool(child(o, "Textures", false));
                std::map<uint32_t, uint32_t> slot;
                std::vector<uint32_t> corner;
                for (long long id : ids) {
                    const uint32_t t = tex_coord_index(id, faces, owner, tex_offset, required);
                    if (t == UINT32_MAX) break;
                    auto [it, added] = slot.emplace(t, uint32_t(mesh->uvs.size()));
                    if (added) mesh->uvs.push_back(tex_coords_[t]);
                    corner.push_back(it->second);
                }
                if (corner.size() == ids.size())
                    for (size_t i = 0; i < ids.size(); i += 3) mesh->face_uvs.push_back({corner[i], corner[i + 1], corner[i + 2]});
                else
                    mesh->uvs.clear();
            }
            // Only the vertices the mesh uses, in order of first use.
            std::vector<uint32_t> used;
            mesh->faces.reserve(ids.size() / 3);
            for (size_t i = 0; i < ids.size(); i += 3) {
                std::array<uint32_t, 3> f;
                for (size_t k = 0; k < 3; ++k) {
                    long long id = ids[i + k];
                    // id + offset in 64 bits, checked: both come from the file and may be anything
                    // a long long holds, and signed overflow is undefined behaviour.
                    const bool overflows = offset > 0 ? id > LLONG_MAX - offset : id < LLONG_MIN - offset;
                    const long long shifted = overflows ? 0 : id + offset;
                    std::string what = "<Faces> vertex " + std::to_string(id);
                    if (offset != 0)
                        what += " + vertexOffset " + std::to_string(offset) +
                                (overflows ? " overflows a 64-bit integer" : " = " + std::to_string(shifted));
                    what += " (triangle " + std::to_string(i / 3 + 1) + ")";
                    if (overflows) fail(faces, owner, what);
                    uint32_t v = vertex_index(shifted, faces, owner, what);
                    if (remap[v] == triangle_mesh::no_index) {
                        remap[v] = uint32_t(used.size());
                        used.push_back(v);
                    }
                    f[k] = remap[v];
                }
                mesh->faces.push_back(f);
            }
            mesh->positions.reserve(used.size());
            for (uint32_t v : used) {
                mesh->positions.push_back(vertices_[v]);
                remap[v] = triangle_mesh::no_index;
            }
        }
        if (shading == "smooth") set_smooth_normals(*mesh);
        return mesh;
    }

    const std::string& path_;
    const std::string& text_;
    line_index lines_;
    std::filesystem::path dir_;
    pugi::xml_document doc_;
    bool zero_based_ = false;
    std::vector<point3> vertices_;
    std::map<long long, std::shared_ptr<whitted_material>> materials_;
    std::map<long long, course_brdf_bsdf> brdfs_;
    std::vector<std::string> notes_; // warnings besides the unread elements
    std::map<long long, node> images_; // <Image> by id
    std::map<long long, std::shared_ptr<const image>> loaded_images_;
    std::map<long long, bool> image_encoded_; // whether the file holds 8-bit codes (PNG, JPEG, ...)
    std::map<long long, texture_map> texture_maps_;
    std::vector<std::array<double, 2>> tex_coords_; // <TexCoordData>
    std::map<long long, size_t> material_lines_;
    std::map<char, std::map<long long, affine_map>> transformations_; // by letter t, s, r, c, then id
    std::map<long long, node> meshes_by_id_, instances_by_id_;
    std::map<const void*, placed_mesh> resolved_; // meshes and instances by element
    std::map<std::pair<const triangle_mesh*, const whitted_material*>, std::shared_ptr<triangle_mesh>> recoloured_;
    std::vector<uint32_t> remap_; // read_mesh's scratch: vertex id -> index in the mesh being read
    bool json_ = false;
    mutable std::unordered_set<const void*> read_; // elements and attributes read (warn_unread)
    std::vector<std::string> ply_files_; // the PLY meshes read, in order (whitted_scene::files)
};

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION whitted_scene load_xml_scene(const std::string& path) {
    return decode_xml_scene(read_file(path, "XML scene file"), path);
}

RTWEEKEND_ENGINE_FUNCTION whitted_scene decode_xml_scene(const std::string& text, const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return detail::xml_scene_reader(path, text, ext == ".json").read();
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::image_name_problem;
using rt::load_xml_scene;
using rt::set_smooth_normals;
#endif
