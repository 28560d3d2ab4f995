#pragma once
// Scene files: the plain-text format of the book-1 cover scene (see docs/scene-files.md).
//
//   scene_description s = load_scene("cover.txt");   // throws scene_error "file:line: problem"
//   s.cam.render(s.world);
//
// One directive per line; '#' starts a comment; blank lines are ignored.
//   camera <key> <values...>     keys: lookfrom x y z | lookat x y z | vup x y z | vfov_deg d |
//                                defocus_angle_deg d | focus_dist d | aspect_ratio r |
//                                image_width n | image_height n | samples_per_pixel n |
//                                max_depth n | background r g b | seed n |
//                                adaptive_error e | adaptive_min_samples n |
//                                estimator nee|bsdf|mixture | sampler sobol|stratified|independent |
//                                filter box|tent[:R]|gaussian[:SIGMA]|mitchell[:B,C] (pixel_filter.h)
//   background r g b             the same as camera background r g b
//   sky_map FILE [scale]         a lat-long picture of the sky (EXR, HDR, PFM; 8-bit pictures
//                                sRGB-decoded) times scale (1), lighting the scene and seen by rays
//                                that leave it; relative to the scene file (io/sky_map_file.h)
//   texture NAME solid r g b     a named texture, used where a colour may vary as @NAME:
//   texture NAME checker S <c> <c>      book 2's 3-D checker of cell size S; <c> is r g b or @NAME
//   texture NAME image FILE             an image (PNG, JPEG, BMP, HDR...), relative to the scene file
//   texture NAME noise S                book 2's marble (Perlin turbulence) at scale S
//   sphere cx cy cz radius <material> [<transform>...]
//   moving_sphere x1 y1 z1 x2 y2 z2 radius <material> [<transform>...]
//                                book 2's moving sphere: centre (x1,y1,z1) at time 0, (x2,y2,z2)
//                                at time 1 (the shutter is open from 0 to 1)
//   triangle ax ay az bx by bz cx cy cz <material> [<transform>...]
//   quad qx qy qz ux uy uz vx vy vz <material> [<transform>...]
//                                book 2's quad: corner Q, edges u and v; its front face is the
//                                side u x v points to
//   box ax ay az bx by bz <material> [<transform>...]
//                                book 2's box: six quads between opposite corners a and b
//   mesh file.obj <material> [smooth] [<transform>...]
//   mesh file.obj mtl [smooth] [<transform>...]
//                                the OBJ with the materials of its MTL library (obj_model.h)
//                                an OBJ mesh (or .ply: a PLY mesh); a relative path is relative to
//                                the scene file; `smooth` shades with its vertex normals (computed,
//                                area-weighted, when the file has none)
//   medium density <c> <shape line>
//                                book 2's constant_medium: fog of that density and albedo <c>
//                                inside the shape (any shape directive above, from its keyword on;
//                                its material is not used and the shape itself is not drawn)
//   group NAME ... end           the shapes between are not drawn, but kept as NAME, for
//   instance NAME [<transform>...]      placing as a whole, as many times as wanted (one copy)
//   point_light x y z r g b      a point light of intensity (r, g, b): irradiance I cos / d^2
//   directional_light dx dy dz r g b    light travelling along (dx, dy, dz) from infinity (the
//                                sun), irradiance (r, g, b) facing it: E cos at any distance
// where <material> is <kind> and five numbers (a material ignores those it does not use):
//   lambertian r g b fuzz ior    albedo (r g b may be @NAME: a texture)
//   metal r g b fuzz ior         albedo, fuzz
//   dielectric r g b fuzz ior    ior: the book's glass (Schlick)
//   glass ar ag ab 0 ior         ior and absorption per unit length (0 0 0: clear): exact
//                                Fresnel and Beer's law, dielectric(ior, absorption)
//   conductor r g b n k          tint and complex index n + ik: conductor(n, k, tint)
//   plastic r g b 0 ior          a diffuse base of albedo r g b under a clear coat of index ior
//   rough_conductor r g b rough 0    a rough metal (GGX) of albedo r g b, roughness in [0, 1]
//   rough_dielectric 0 0 0 rough ior rough glass of index ior (r g b unused)
//   metal_roughness r g b metal rough  glTF's metallic-roughness: base colour, metallic, roughness
//   isotropic r g b 0 0          the phase function of fog (for media); r g b may be @NAME
//   diffuse_light r g b 0 0      an emitter of radiance (r, g, b) from its front face (book 3);
//                                r g b may be @NAME
//   two_sided_light r g b 0 0    the same from both faces (book 2's diffuse_light)
// or, with seven numbers:
//   blinn_phong r g b sr sg sb n diffuse colour, specular colour, Blinn-Phong exponent n
// and each <transform> moves the shape, applied in the order written (book 2's instances):
//   rotate_y degrees             about the y axis, as rotate_y(object, degrees)
//   translate x y z              as translate(object, offset)
//   rotate ax ay az degrees      about the axis (ax, ay, az), as rotate(object, axis, degrees)
//   scale sx sy sz               per axis, as scale(object, factors); non-zero factors

#include "../core/engine_linkage.h"
#include "../camera.h"
#include "../render/pixel_filter.h"
#include "../hittable_list.h"
#include "../directional_light.h"
#include "../point_light.h"
#include "../core/scene_error.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <istream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace rt {

struct scene_description {
    camera cam;
    hittable_list world;
    std::vector<point_light> point_lights; // found by light sampling only (render with rt::render(cam, world, point_lights))
    std::vector<directional_light> directional_lights; // the same (rt::render(cam, world, point_lights, directional_lights))
    // What was read but cannot be rendered as written, one line each (a model's unsupported
    // maps: io/obj_model.h); the render apps print them.
    std::vector<std::string> warnings;
    // Every file the scene was read from: the scene file (load_scene), then its meshes and image
    // textures in the order read, as opened. What decides the image besides the settings, so what
    // a fingerprint of the scene hashes (io/slice_file.h: slices of different scenes do not merge).
    std::vector<std::string> files;
};

// Reads a scene from a stream; `name` is the file name used in error messages. Text without a
// directive (nothing, or only comments and blank lines) is refused: "<name>: scene file is empty
// (no directives)", as load_scene refuses an empty file.
RTWEEKEND_ENGINE_FUNCTION scene_description parse_scene(std::istream& in, const std::string& name);

// Throws scene_error unless the image `cam` would render is within max_render_pixels
// (core/input_limits.h): "the image is WxH = N pixels, more than the limit of ...". A side beyond
// 65536 pixels, or an aspect ratio that is not positive, is left to the camera's own check.
RTWEEKEND_ENGINE_FUNCTION void check_camera_image_size(const camera& cam);

// Reads a scene file. Besides parse_scene's checks (an empty file, or one of only comments, is
// refused there), refuses a file that places no object in the world: it would render nothing but
// the sky. And refuses an image larger than max_render_pixels (core/input_limits.h), before anything
// is allocated.
RTWEEKEND_ENGINE_FUNCTION scene_description load_scene(const std::string& path);

// load_scene on a file's text already in memory: `path` names it in messages, and relative mesh
// and texture paths are relative to its folder.
RTWEEKEND_ENGINE_FUNCTION scene_description decode_scene(const std::string& text, const std::string& path);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../constant_medium.h"
#include "../material.h"
#include "../mesh.h"
#include "../quad.h"
#include "../sphere.h"
#include "../texture.h"
#include "../transform.h"
#include "../triangle.h"
#include "../core/input_limits.h"
#include "obj.h"
#include "sky_map_file.h"
#include "obj_model.h"
#include "ply.h"

namespace rt {

namespace detail {

class scene_line {
  public:
    scene_line(const std::string& file, int number, std::vector<std::string> tokens)
        : where_(file + ":" + std::to_string(number) + ": "), tokens_(std::move(tokens)) {}

    [[noreturn]] void fail(const std::string& message) const { throw scene_error(where_ + message); }

    size_t size() const { return tokens_.size(); }
    const std::string& word(size_t i) const { return tokens_.at(i); }

    void expect_at_least(size_t n, const std::string& form) const {
        if (tokens_.size() < n)
            fail("expected '" + form + "' (at least " + std::to_string(n) + " fields), got " + std::to_string(tokens_.size()));
    }

    void expect_count(size_t n, const std::string& form) const {
        if (tokens_.size() != n)
            fail("expected '" + form + "' (" + std::to_string(n) + " fields), got " + std::to_string(tokens_.size()));
    }

    double number(size_t i, const char* what) const {
        const std::string& s = tokens_.at(i);
        errno = 0;
        char* end = nullptr;
        double v = std::strtod(s.c_str(), &end);
        // The whole token, not a prefix: strtod stops at a NUL byte inside it.
        if (end == s.c_str() || end != s.c_str() + s.size())
            fail(std::string(what) + ": '" + token_text(s) + "' is not a number");
        // ERANGE with a finite result is an underflow (1e-320): the number strtod rounded it to, a
        // subnormal or zero, is the value; what it is used for says whether it will do.
        if (std::isinf(v) && errno == ERANGE)
            fail(std::string(what) + ": '" + token_text(s) + "' is beyond the range of a double");
        if (!std::isfinite(v)) fail(std::string(what) + ": '" + token_text(s) + "' is not a finite number");
        return v;
    }

    int integer(size_t i, const char* what, long min, long max = 1 << 30) const {
        const std::string& s = tokens_.at(i);
        errno = 0;
        char* end = nullptr;
        long v = std::strtol(s.c_str(), &end, 10);
        if (end == s.c_str() || end != s.c_str() + s.size())
            fail(std::string(what) + ": '" + token_text(s) + "' is not an integer");
        if (errno == ERANGE || v < min || v > max)
            fail(std::string(what) + ": " + token_text(s) + " is out of range (at least " + std::to_string(min) + ", at most " +
                 std::to_string(max) + ")");
        return static_cast<int>(v);
    }

    vec3 vector(size_t i, const char* what) const {
        return vec3(number(i, what), number(i + 1, what), number(i + 2, what));
    }

  private:
    std::string where_;
    std::vector<std::string> tokens_;
};

inline void parse_camera_line(const scene_line& line, camera& cam) {
    if (line.size() < 2) line.fail("'camera' needs a key and values");
    const std::string& key = line.word(1);
    auto one = [&](const char* what) {
        line.expect_count(3, "camera " + key + " <value>");
        return line.number(2, what);
    };
    auto three = [&](const char* what) {
        line.expect_count(5, "camera " + key + " x y z");
        return line.vector(2, what);
    };
    if (key == "lookfrom") cam.lookfrom = three("lookfrom");
    else if (key == "lookat") cam.lookat = three("lookat");
    else if (key == "vup") cam.vup = three("vup");
    else if (key == "vfov_deg" || key == "vfov") cam.vfov = one("vfov");
    else if (key == "defocus_angle_deg" || key == "defocus_angle") cam.defocus_angle = one("defocus_angle");
    else if (key == "focus_dist") cam.focus_dist = one("focus_dist");
    else if (key == "aspect_ratio") cam.aspect_ratio = one("aspect_ratio");
    else if (key == "adaptive_error") cam.settings.adaptive_error = one("adaptive_error");
    else if (key == "estimator") {
        line.expect_count(3, "camera estimator nee|bsdf|mixture");
        if (!parse_estimator(line.word(2), cam.settings.estimator))
            line.fail("estimator must be nee, bsdf or mixture, got '" + line.word(2) + "'");
    } else if (key == "sampler") {
        line.expect_count(3, "camera sampler sobol|stratified|independent");
        if (!parse_sampler(line.word(2), cam.settings.sampler))
            line.fail("sampler must be sobol, stratified or independent, got '" + line.word(2) + "'");
    } else if (key == "filter") {
        line.expect_count(3, "camera filter box|tent[:R]|gaussian[:SIGMA]|mitchell[:B,C]");
        try {
            cam.filter = parse_pixel_filter(line.word(2));
        } catch (const scene_error& e) {
            line.fail(e.what());
        }
    } else if (key == "background") {
        color bg = three("background");
        if (bg.x() < 0 || bg.y() < 0 || bg.z() < 0) line.fail("background must be non-negative");
        cam.background = bg;
    } else {
        line.expect_count(3, "camera " + key + " <integer>");
        if (key == "image_width") cam.image_width = line.integer(2, "image_width", 1);
        else if (key == "image_height") cam.image_height = line.integer(2, "image_height", 1);
        // The same limits as render's --spp and --depth (apps/app_options.h).
        else if (key == "samples_per_pixel") cam.samples_per_pixel = line.integer(2, "samples_per_pixel", 1, 1 << 24);
        else if (key == "max_depth") cam.max_depth = line.integer(2, "max_depth", 1, 1 << 16);
        else if (key == "seed") cam.settings.seed = static_cast<uint64_t>(line.integer(2, "seed", 0));
        else if (key == "adaptive_min_samples") cam.settings.adaptive_min_samples = line.integer(2, "adaptive_min_samples", 2);
        else line.fail("unknown camera key '" + key + "'");
    }
    if (key == "vfov_deg" || key == "vfov") {
        if (!(cam.vfov > 0 && cam.vfov < 180)) line.fail("vfov must be between 0 and 180 degrees");
    } else if (key == "defocus_angle_deg" || key == "defocus_angle") {
        if (!(cam.defocus_angle >= 0 && cam.defocus_angle < 180)) line.fail("defocus_angle must be in [0, 180)");
    } else if (key == "focus_dist" && !(cam.focus_dist > 0)) {
        line.fail("focus_dist must be positive");
    } else if (key == "aspect_ratio" && !(cam.aspect_ratio > 0)) {
        line.fail("aspect_ratio must be positive");
    } else if (key == "adaptive_error" && !(cam.settings.adaptive_error >= 0)) {
        line.fail("adaptive_error must be 0 (off) or positive");
    }
}

inline point_light parse_point_light_line(const scene_line& line) {
    line.expect_count(7, "point_light x y z r g b");
    point_light l{line.vector(1, "point light position"), line.vector(4, "point light intensity")};
    if (l.intensity.x() < 0 || l.intensity.y() < 0 || l.intensity.z() < 0)
        line.fail("point light intensity must be non-negative");
    return l;
}

inline directional_light parse_directional_light_line(const scene_line& line) {
    line.expect_count(7, "directional_light dx dy dz r g b");
    directional_light l{line.vector(1, "directional light direction"), line.vector(4, "directional light irradiance")};
    const double length_squared = l.direction.length_squared();
    if (!(length_squared > 0)) line.fail("directional light direction must not be zero");
    if (!std::isfinite(length_squared)) line.fail("directional light direction is too long to normalise");
    if (l.irradiance.x() < 0 || l.irradiance.y() < 0 || l.irradiance.z() < 0)
        line.fail("directional light irradiance must be non-negative");
    return l;
}

// A scene file's state between lines: the named textures and groups defined so far, and the
// group being filled (shapes go there instead of the world until `end`).
class scene_parser {
  public:
    scene_parser(scene_description& scene, const std::string& name) : scene_(scene), name_(name) {}

    void line(const scene_line& line);
    void finish() const {
        if (open_group_) throw scene_error(name_ + ": group '" + open_group_name_ + "' has no 'end'");
    }

  private:
    scene_description& scene_;
    std::string name_;
    std::map<std::string, std::shared_ptr<texture>> textures_;
    std::map<std::string, std::shared_ptr<hittable_list>> groups_;
    std::shared_ptr<hittable_list> open_group_;
    std::string open_group_name_;

    void add(std::shared_ptr<hittable> object) {
        if (open_group_) open_group_->add(std::move(object));
        else scene_.world.add(std::move(object));
    }
    // A path in the file, relative to the scene file's directory unless absolute.
    std::string resolve(const std::string& file) const {
        std::filesystem::path path(file);
        if (path.is_relative()) path = std::filesystem::path(name_).parent_path() / path;
        return path.string();
    }

    // A colour at field i: three numbers, or @name for a texture defined earlier. Returns the
    // texture (a solid_color for numbers) and moves i past it.
    std::shared_ptr<texture> colour_or_texture(const scene_line& line, size_t& i, const char* what) const;
    color plain_colour(const scene_line& line, size_t& i, const char* what) const;
    std::shared_ptr<material> material_at(const scene_line& line, size_t& i) const;
    std::shared_ptr<hittable> transforms_from(const scene_line& line, size_t i, std::shared_ptr<hittable> object) const;
    // `mesh file.obj mtl [smooth] [<transform>...]`: the model with its own materials (obj_model.h).
    std::shared_ptr<hittable> model_line(const scene_line& line, const std::string& file, size_t at) const;
    // A shape directive starting at field i (sphere, moving_sphere, triangle, quad, box, mesh)
    // with its material and transforms, to the end of the line.
    std::shared_ptr<hittable> shape_at(const scene_line& line, size_t i) const;
    void texture_line(const scene_line& line);
};

inline std::shared_ptr<texture> scene_parser::colour_or_texture(const scene_line& line, size_t& i, const char* what) const {
    if (i < line.size() && line.word(i).size() > 1 && line.word(i)[0] == '@') {
        const std::string name = line.word(i).substr(1);
        auto found = textures_.find(name);
        if (found == textures_.end()) line.fail(std::string(what) + ": no texture named '" + name + "' defined above");
        ++i;
        return found->second;
    }
    return std::make_shared<solid_color>(plain_colour(line, i, what));
}

inline color scene_parser::plain_colour(const scene_line& line, size_t& i, const char* what) const {
    if (i + 3 > line.size()) line.fail(std::string(what) + ": expected r g b");
    if (line.word(i)[0] == '@') line.fail(std::string(what) + " must be three numbers, not a texture");
    color c = line.vector(i, what);
    if (c.x() < 0 || c.y() < 0 || c.z() < 0) line.fail(std::string(what) + " must be non-negative");
    i += 3;
    return c;
}

// <kind> and its fields, from field i: most kinds take r g b fuzz ior (five numbers, a kind
// ignoring those it does not use; r g b may be @texture where a colour can vary), conductor
// r g b n k, blinn_phong r g b sr sg sb exponent.
inline std::shared_ptr<material> scene_parser::material_at(const scene_line& line, size_t& i) const {
    if (i >= line.size()) line.fail("expected a material");
    const std::string kind = line.word(i++);
    auto number = [&](const char* what) {
        if (i >= line.size()) line.fail(std::string("expected ") + what + " after the material's colour");
        return line.number(i++, what);
    };
    auto textured = [&](const char* what) {
        std::shared_ptr<texture> tex = colour_or_texture(line, i, what);
        number("fuzz");
        number("ior");
        return tex;
    };
    if (kind == "lambertian") return std::make_shared<lambertian>(textured("albedo"));
    if (kind == "diffuse_light") return std::make_shared<diffuse_light>(textured("emission"));
    if (kind == "two_sided_light") return std::make_shared<diffuse_light>(textured("emission"), true);
    if (kind == "isotropic") return std::make_shared<isotropic>(textured("albedo"));
    if (kind == "blinn_phong") {
        color kd = plain_colour(line, i, "blinn_phong diffuse");
        color ks = plain_colour(line, i, "blinn_phong specular");
        double exponent = number("blinn_phong exponent");
        if (!(exponent >= 0)) line.fail("blinn_phong exponent must be non-negative");
        return std::make_shared<blinn_phong>(kd, ks, exponent);
    }
    if (kind == "rough_conductor" || kind == "rough_dielectric" || kind == "metal_roughness") {
        const bool blend = kind == "metal_roughness";
        color c = plain_colour(line, i, blend ? "base colour" : "albedo");
        const size_t first_at = i;
        const double first = number(blend ? "metallic" : "roughness");
        const double second = number(blend ? "roughness" : "ior");
        auto in_unit = [&](double v, size_t at, const char* what) {
            if (!(v >= 0 && v <= 1)) line.fail(kind + " " + what + " must be in [0, 1], got " + line.word(at));
        };
        in_unit(first, first_at, blend ? "metallic" : "roughness");
        if (blend) {
            in_unit(second, first_at + 1, "roughness");
            return std::make_shared<metal_roughness>(c, first, second);
        }
        if (kind == "rough_conductor") return std::make_shared<rough_conductor>(c, first);
        if (!(second > 0)) line.fail("rough_dielectric ior must be positive, got " + line.word(first_at + 1));
        return std::make_shared<rough_dielectric>(second, first);
    }
    const bool is_conductor = kind == "conductor", is_glass = kind == "glass";
    const char* rgb_name = is_conductor ? "conductor tint" : is_glass ? "glass absorption" : "albedo";
    color albedo = plain_colour(line, i, rgb_name);
    const size_t fuzz_at = i;
    double fuzz = number(is_conductor ? "conductor n" : "fuzz");
    double ior = number(is_conductor ? "conductor k" : "ior");
    if (is_conductor) {
        if (!(fuzz > 0)) line.fail("conductor n must be positive, got " + line.word(fuzz_at));
        if (!(ior >= 0)) line.fail("conductor k must be non-negative, got " + line.word(fuzz_at + 1));
        return std::make_shared<conductor>(fuzz, ior, albedo);
    }
    if (is_glass) {
        if (!(ior > 0)) line.fail("glass ior must be positive, got " + line.word(fuzz_at + 1));
        return std::make_shared<dielectric>(ior, albedo);
    }
    if (kind == "metal") {
        if (fuzz < 0) line.fail("metal fuzz must be non-negative, got " + line.word(fuzz_at));
        return std::make_shared<metal>(albedo, fuzz);
    }
    if (kind == "dielectric") {
        if (!(ior > 0)) line.fail("dielectric ior must be positive, got " + line.word(fuzz_at + 1));
        return std::make_shared<dielectric>(ior);
    }
    if (kind == "plastic") {
        if (!(ior > 0)) line.fail("plastic ior must be positive, got " + line.word(fuzz_at + 1));
        return std::make_shared<plastic>(albedo, ior);
    }
    line.fail("unknown material '" + kind +
              "' (expected lambertian, metal, dielectric, glass, conductor, plastic, blinn_phong, rough_conductor, "
              "rough_dielectric, metal_roughness, isotropic, diffuse_light or two_sided_light)");
}

// The transforms from field i (rotate_y degrees | translate x y z | rotate ax ay az degrees |
// scale sx sy sz), applied to `object` in the order written.
inline std::shared_ptr<hittable> scene_parser::transforms_from(const scene_line& line, size_t i,
                                                               std::shared_ptr<hittable> object) const {
    while (i < line.size()) {
        const std::string& word = line.word(i);
        if (word == "rotate_y") {
            if (i + 1 >= line.size()) line.fail("rotate_y needs an angle in degrees");
            object = std::make_shared<rotate_y>(std::move(object), line.number(i + 1, "rotate_y angle"));
            i += 2;
        } else if (word == "translate") {
            if (i + 3 >= line.size()) line.fail("translate needs x y z");
            object = std::make_shared<translate>(std::move(object), line.vector(i + 1, "translate offset"));
            i += 4;
        } else if (word == "rotate") {
            if (i + 4 >= line.size()) line.fail("rotate needs an axis x y z and an angle in degrees");
            const vec3 axis = line.vector(i + 1, "rotate axis");
            if (axis.length_squared() == 0) line.fail("rotate axis must be non-zero");
            object = std::make_shared<rotate>(std::move(object), axis, line.number(i + 4, "rotate angle"));
            i += 5;
        } else if (word == "scale") {
            if (i + 3 >= line.size()) line.fail("scale needs factors x y z");
            const vec3 factors = line.vector(i + 1, "scale factors");
            if (factors.x() == 0 || factors.y() == 0 || factors.z() == 0) line.fail("scale factors must be non-zero");
            object = std::make_shared<scale>(std::move(object), factors);
            i += 4;
        } else {
            line.fail("unexpected '" + word + "' (expected rotate_y, translate, rotate or scale)");
        }
    }
    return object;
}

inline std::shared_ptr<hittable> scene_parser::shape_at(const scene_line& line, size_t i) const {
    const std::string& kind = line.word(i);
    auto need = [&](size_t fields, const char* form) {
        if (line.size() < i + fields) line.fail(std::string("expected '") + form + "'");
    };
    if (kind == "sphere") {
        need(6, "sphere cx cy cz radius material ...");
        point3 center = line.vector(i + 1, "sphere centre");
        double radius = line.number(i + 4, "sphere radius");
        if (!(radius > 0)) line.fail("sphere radius must be positive, got " + line.word(i + 4));
        size_t at = i + 5;
        auto mat = material_at(line, at);
        return transforms_from(line, at, std::make_shared<sphere>(center, radius, std::move(mat)));
    }
    if (kind == "moving_sphere") {
        need(9, "moving_sphere x1 y1 z1 x2 y2 z2 radius material ...");
        point3 c1 = line.vector(i + 1, "moving_sphere centre at time 0");
        point3 c2 = line.vector(i + 4, "moving_sphere centre at time 1");
        double radius = line.number(i + 7, "moving_sphere radius");
        if (!(radius > 0)) line.fail("moving_sphere radius must be positive, got " + line.word(i + 7));
        size_t at = i + 8;
        auto mat = material_at(line, at);
        return transforms_from(line, at, std::make_shared<sphere>(c1, c2, radius, std::move(mat)));
    }
    if (kind == "triangle") {
        need(11, "triangle ax ay az bx by bz cx cy cz material ...");
        point3 a = line.vector(i + 1, "triangle vertex"), b = line.vector(i + 4, "triangle vertex"),
               c = line.vector(i + 7, "triangle vertex");
        if (cross(b - a, c - a).length_squared() == 0) line.fail("triangle has zero area");
        size_t at = i + 10;
        auto mat = material_at(line, at);
        return transforms_from(line, at, std::make_shared<triangle>(a, b, c, std::move(mat)));
    }
    if (kind == "quad") {
        need(11, "quad qx qy qz ux uy uz vx vy vz material ...");
        point3 q = line.vector(i + 1, "quad corner");
        vec3 u = line.vector(i + 4, "quad edge u"), v = line.vector(i + 7, "quad edge v");
        if (cross(u, v).length_squared() == 0) line.fail("quad has zero area: its edges are parallel or zero");
        size_t at = i + 10;
        auto mat = material_at(line, at);
        return transforms_from(line, at, std::make_shared<quad>(q, u, v, std::move(mat)));
    }
    if (kind == "box") {
        need(8, "box ax ay az bx by bz material ...");
        point3 a = line.vector(i + 1, "box corner"), b = line.vector(i + 4, "box corner");
        if (a.x() == b.x() || a.y() == b.y() || a.z() == b.z()) line.fail("box corners must differ in x, y and z");
        size_t at = i + 7;
        auto mat = material_at(line, at);
        return transforms_from(line, at, box(a, b, std::move(mat)));
    }
    if (kind == "mesh") {
        need(3, "mesh file.obj material ...");
        const std::string file = resolve(line.word(i + 1));
        size_t at = i + 2;
        if (line.word(at) == "mtl") return model_line(line, file, at + 1);
        std::shared_ptr<material> mat = material_at(line, at);
        std::shared_ptr<triangle_mesh> mesh;
        try {
            // By extension: Stanford PLY, or else Wavefront OBJ.
            std::string ext = std::filesystem::path(file).extension().string();
            for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
            mesh = ext == ".ply" ? load_ply(file, std::move(mat)) : load_obj(file, std::move(mat));
        } catch (const scene_error& e) {
            line.fail(e.what());
        }
        scene_.files.push_back(file);
        // `smooth`: shade with the file's vertex normals, or with computed ones if it has none.
        if (at < line.size() && line.word(at) == "smooth") {
            if (mesh->normals.empty() || mesh->face_normals.empty()) mesh->compute_vertex_normals();
            else mesh->smooth_shading = true;
            ++at;
        }
        return transforms_from(line, at, std::move(mesh));
    }
    line.fail("unknown shape '" + kind + "' (expected sphere, moving_sphere, triangle, quad, box or mesh)");
}

inline std::shared_ptr<hittable> scene_parser::model_line(const scene_line& line, const std::string& file, size_t at) const {
    if (std::filesystem::path(file).extension() == ".ply") line.fail("mtl: a PLY mesh has no material library; give a material");
    obj_model model;
    try {
        model = load_obj_model(file);
    } catch (const scene_error& e) {
        line.fail(e.what());
    }
    scene_.files.insert(scene_.files.end(), model.files.begin(), model.files.end());
    for (const std::string& w : model.warnings) scene_.warnings.push_back(w);
    if (at < line.size() && line.word(at) == "smooth") {
        for (const auto& object : model.world.objects) {
            auto* mesh = static_cast<triangle_mesh*>(object.get());
            if (mesh->normals.empty() || mesh->face_normals.empty()) mesh->compute_vertex_normals();
            else mesh->smooth_shading = true;
        }
        ++at;
    }
    return transforms_from(line, at, std::make_shared<hittable_list>(std::move(model.world)));
}

// texture NAME solid r g b | checker SCALE <colour> <colour> | image FILE | noise SCALE
inline void scene_parser::texture_line(const scene_line& line) {
    line.expect_at_least(3, "texture name kind ...");
    const std::string& name = line.word(1);
    const std::string& kind = line.word(2);
    if (textures_.count(name)) line.fail("texture '" + name + "' is already defined");
    std::shared_ptr<texture> tex;
    size_t i = 3;
    if (kind == "solid") {
        tex = std::make_shared<solid_color>(plain_colour(line, i, "solid colour"));
    } else if (kind == "checker") {
        line.expect_at_least(6, "texture name checker scale even odd");
        double scale = line.number(3, "checker scale");
        if (!(scale > 0)) line.fail("checker scale must be positive, got " + line.word(3));
        i = 4;
        auto even = colour_or_texture(line, i, "checker even colour");
        auto odd = colour_or_texture(line, i, "checker odd colour");
        tex = std::make_shared<checker_texture>(scale, even, odd);
    } else if (kind == "image") {
        line.expect_count(4, "texture name image file");
        auto image = std::make_shared<image_texture>(resolve(line.word(3)).c_str());
        if (!image->load_error().empty()) line.fail(image->load_error());
        scene_.files.push_back(image->image().path()); // where it was found ($RTW_IMAGES, images/...)
        tex = std::move(image);
        i = 4;
    } else if (kind == "noise") {
        line.expect_count(4, "texture name noise scale");
        double scale = line.number(3, "noise scale");
        if (!(scale >= 0)) line.fail("noise scale must be non-negative, got " + line.word(3));
        tex = std::make_shared<noise_texture>(scale);
        i = 4;
    } else {
        line.fail("unknown texture kind '" + kind + "' (expected solid, checker, image or noise)");
    }
    if (i != line.size()) line.fail("unexpected '" + line.word(i) + "' after the texture");
    textures_[name] = tex;
}

inline void scene_parser::line(const scene_line& line) {
    const std::string& word = line.word(0);
    if (word == "camera") {
        parse_camera_line(line, scene_.cam);
    } else if (word == "sphere" || word == "moving_sphere" || word == "triangle" || word == "quad" || word == "box" ||
               word == "mesh") {
        add(shape_at(line, 0));
    } else if (word == "texture") {
        texture_line(line);
    } else if (word == "medium") {
        // medium density <colour> <shape ...>: the shape bounds the medium (its material is not
        // used) and is not itself added to the scene.
        line.expect_at_least(6, "medium density r g b shape ...");
        double density = line.number(1, "medium density");
        if (!(density > 0)) line.fail("medium density must be positive, got " + line.word(1));
        size_t i = 2;
        auto albedo = colour_or_texture(line, i, "medium albedo");
        if (i >= line.size()) line.fail("medium needs a boundary shape after its colour");
        add(std::make_shared<constant_medium>(shape_at(line, i), density, albedo));
    } else if (word == "group") {
        line.expect_count(2, "group name");
        if (open_group_) line.fail("groups do not nest: 'end' group '" + open_group_name_ + "' first");
        if (groups_.count(line.word(1))) line.fail("group '" + line.word(1) + "' is already defined");
        open_group_ = std::make_shared<hittable_list>();
        open_group_name_ = line.word(1);
        groups_[open_group_name_] = open_group_;
    } else if (word == "end") {
        line.expect_count(1, "end");
        if (!open_group_) line.fail("'end' without a group");
        open_group_.reset();
    } else if (word == "instance") {
        line.expect_at_least(2, "instance name [transforms]");
        auto found = groups_.find(line.word(1));
        if (found == groups_.end()) line.fail("no group named '" + line.word(1) + "' defined above");
        if (found->second == open_group_) line.fail("group '" + line.word(1) + "' cannot hold an instance of itself");
        add(transforms_from(line, 2, found->second));
    } else if (word == "point_light") {
        scene_.point_lights.push_back(parse_point_light_line(line));
    } else if (word == "directional_light") {
        scene_.directional_lights.push_back(parse_directional_light_line(line));
    } else if (word == "sky_map") {
        if (line.size() != 2 && line.size() != 3) line.fail("expected: sky_map file [scale]");
        const double scale = line.size() == 3 ? line.number(2, "sky_map scale") : 1.0;
        if (!(scale >= 0)) line.fail("sky_map scale must be at least 0, got " + line.word(2));
        const std::string file = resolve(line.word(1));
        try {
            scene_.cam.sky_map = load_sky_map(file, scale);
        } catch (const scene_error& e) {
            line.fail(e.what());
        }
        scene_.files.push_back(file);
    } else if (word == "background") {
        line.expect_count(4, "background r g b");
        color bg = line.vector(1, "background");
        if (bg.x() < 0 || bg.y() < 0 || bg.z() < 0) line.fail("background must be non-negative");
        scene_.cam.background = bg;
    } else {
        line.fail("unknown directive '" + word +
                  "' (expected camera, background, sky_map, texture, sphere, moving_sphere, triangle, quad, box, "
                  "mesh, medium, group, end, instance, point_light or directional_light)");
    }
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION scene_description parse_scene(std::istream& in, const std::string& name) {
    scene_description scene;
    detail::scene_parser parser(scene, name);
    std::string text;
    int number = 0;
    bool any_directive = false;
    while (std::getline(in, text)) {
        ++number;
        // A text format holds no NUL bytes; one means a binary or damaged file, and would hide
        // the rest of a token from the number parsers.
        if (text.find('\0') != std::string::npos)
            throw scene_error(name + ":" + std::to_string(number) + ": a NUL byte (is this a binary or damaged file?)");
        auto hash = text.find('#');
        if (hash != std::string::npos) text.erase(hash);
        std::istringstream words(text);
        std::vector<std::string> tokens;
        for (std::string w; words >> w;) tokens.push_back(w);
        if (tokens.empty()) continue;
        any_directive = true;
        parser.line(detail::scene_line(name, number, std::move(tokens)));
    }
    if (in.bad()) throw scene_error(name + ": read error");
    // Nothing to render but the default sky: surely not what was meant (a missing or truncated file).
    if (!any_directive) throw scene_error(name + ": scene file is empty (no directives)");
    parser.finish();
    return scene;
}

RTWEEKEND_ENGINE_FUNCTION void check_camera_image_size(const camera& c) {
    if (c.image_width < 1 || (c.image_height < 1 && !(std::isfinite(c.aspect_ratio) && c.aspect_ratio > 0))) return;
    // In double, as the camera derives it: a tiny aspect ratio must not overflow an int here.
    const double h = c.image_height > 0 ? double(c.image_height) : std::max(1.0, std::floor(c.image_width / c.aspect_ratio));
    if (c.image_width <= 65536 && h <= 65536)
        check_render_size(uint64_t(c.image_width), uint64_t(h), "the image (camera image_width, image_height, aspect_ratio)");
}

RTWEEKEND_ENGINE_FUNCTION scene_description load_scene(const std::string& path) { return decode_scene(read_file(path,
                                                       "scene file"), path); }

RTWEEKEND_ENGINE_FUNCTION scene_description decode_scene(const std::string& text, const std::string& path) {
    std::istringstream in(text);
    scene_description scene = parse_scene(in, path);
    scene.files.insert(scene.files.begin(), path);
    // Directives that placed nothing in the world (an empty file is parse_scene's error).
    if (scene.world.objects.empty())
        throw scene_error(path + ": the scene has no objects (a group's shapes count only where an instance places "
                                 "them): it would render only the background");
    // The image is allocated at render time; its size is known now.
    try {
        check_camera_image_size(scene.cam);
    } catch (const scene_error& e) {
        throw scene_error(path + ": " + e.what());
    }
    return scene;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt
