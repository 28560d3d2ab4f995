#pragma once
// Scene files: the plain-text format of the book-1 cover scene (see README, "Scene files").
//
//   scene_description s = load_scene("cover.txt");   // throws scene_error "file:line: problem"
//   s.cam.render(s.world);
//
// One directive per line; '#' starts a comment; blank lines are ignored.
//   camera <key> <values...>     keys: lookfrom x y z | lookat x y z | vup x y z | vfov_deg d |
//                                defocus_angle_deg d | focus_dist d | aspect_ratio r |
//                                image_width n | image_height n | samples_per_pixel n |
//                                max_depth n | background r g b | seed n |
//                                adaptive_error e | adaptive_min_samples n
//   background r g b             the same as camera background r g b
//   sphere cx cy cz radius <material> [<transform>...]
//   triangle ax ay az bx by bz cx cy cz <material> [<transform>...]
//   quad qx qy qz ux uy uz vx vy vz <material> [<transform>...]
//                                book 2's quad: corner Q, edges u and v; its front face is the
//                                side u x v points to
//   box ax ay az bx by bz <material> [<transform>...]
//                                book 2's box: six quads between opposite corners a and b
//   mesh file.obj <material> [<transform>...]
//                                an OBJ mesh (or .ply: a PLY mesh); a relative path is relative to
//                                the scene file
//   point_light x y z r g b      a point light of intensity (r, g, b): irradiance I cos / d^2
// where <material> is <kind> and always five numbers (a material ignores those it does not use):
//   lambertian r g b fuzz ior    albedo
//   metal r g b fuzz ior         albedo, fuzz
//   dielectric r g b fuzz ior    ior: the book's glass (Schlick)
//   glass ar ag ab 0 ior         ior and absorption per unit length (0 0 0: clear): exact
//                                Fresnel and Beer's law, dielectric(ior, absorption)
//   conductor r g b n k          tint and complex index n + ik: conductor(n, k, tint)
//   diffuse_light r g b 0 0      an emitter of radiance (r, g, b) from its front face (book 3)
//   two_sided_light r g b 0 0    the same from both faces (book 2's diffuse_light)
// and each <transform> moves the shape, applied in the order written (book 2's instances):
//   rotate_y degrees             about the y axis, as rotate_y(object, degrees)
//   translate x y z              as translate(object, offset)

#include "../camera.h"
#include "../hittable_list.h"
#include "../material.h"
#include "../mesh.h"
#include "../point_light.h"
#include "../quad.h"
#include "../scene_error.h"
#include "../sphere.h"
#include "../transform.h"
#include "../triangle.h"
#include "obj.h"
#include "ply.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <istream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace rt {

struct scene_description {
    camera cam;
    hittable_list world;
    std::vector<point_light> point_lights; // found by light sampling only (render with rt::render(cam, world, point_lights))
};

// Reads a scene from a stream; `name` is the file name used in error messages.
scene_description parse_scene(std::istream& in, const std::string& name);

// Reads a scene file.
scene_description load_scene(const std::string& path);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

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
        if (end == s.c_str() || *end != '\0') fail(std::string(what) + ": '" + s + "' is not a number");
        if (!std::isfinite(v) || errno == ERANGE) fail(std::string(what) + ": '" + s + "' is not a finite number");
        return v;
    }

    int integer(size_t i, const char* what, long min) const {
        const std::string& s = tokens_.at(i);
        errno = 0;
        char* end = nullptr;
        long v = std::strtol(s.c_str(), &end, 10);
        if (end == s.c_str() || *end != '\0') fail(std::string(what) + ": '" + s + "' is not an integer");
        if (errno == ERANGE || v < min || v > 1 << 30)
            fail(std::string(what) + ": " + s + " is out of range (at least " + std::to_string(min) + ")");
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
    else if (key == "adaptive_error") cam.adaptive_error = one("adaptive_error");
    else if (key == "background") {
        color bg = three("background");
        if (bg.x() < 0 || bg.y() < 0 || bg.z() < 0) line.fail("background must be non-negative");
        cam.background = bg;
    } else {
        line.expect_count(3, "camera " + key + " <integer>");
        if (key == "image_width") cam.image_width = line.integer(2, "image_width", 1);
        else if (key == "image_height") cam.image_height = line.integer(2, "image_height", 1);
        else if (key == "samples_per_pixel") cam.samples_per_pixel = line.integer(2, "samples_per_pixel", 1);
        else if (key == "max_depth") cam.max_depth = line.integer(2, "max_depth", 1);
        else if (key == "seed") cam.seed = static_cast<uint64_t>(line.integer(2, "seed", 0));
        else if (key == "adaptive_min_samples") cam.adaptive_min_samples = line.integer(2, "adaptive_min_samples", 2);
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
    } else if (key == "adaptive_error" && !(cam.adaptive_error >= 0)) {
        line.fail("adaptive_error must be 0 (off) or positive");
    }
}

// The material at the end of a primitive line: <kind> r g b fuzz ior (conductor: r g b n k),
// starting at field i.
inline std::shared_ptr<material> parse_material(const scene_line& line, size_t i) {
    const std::string& kind = line.word(i);
    const bool is_conductor = kind == "conductor", is_glass = kind == "glass";
    const char* rgb_name = is_conductor ? "conductor tint" : is_glass ? "glass absorption" : "albedo";
    color albedo = line.vector(i + 1, rgb_name);
    if (albedo.x() < 0 || albedo.y() < 0 || albedo.z() < 0) line.fail(std::string(rgb_name) + " must be non-negative");
    double fuzz = line.number(i + 4, is_conductor ? "conductor n" : "fuzz");
    double ior = line.number(i + 5, is_conductor ? "conductor k" : "ior");
    if (is_conductor) {
        if (!(fuzz > 0)) line.fail("conductor n must be positive, got " + line.word(i + 4));
        if (!(ior >= 0)) line.fail("conductor k must be non-negative, got " + line.word(i + 5));
        return std::make_shared<conductor>(fuzz, ior, albedo);
    }
    if (is_glass) {
        if (!(ior > 0)) line.fail("glass ior must be positive, got " + line.word(i + 5));
        return std::make_shared<dielectric>(ior, albedo);
    }
    if (kind == "lambertian") return std::make_shared<lambertian>(albedo);
    if (kind == "diffuse_light") return std::make_shared<diffuse_light>(albedo);
    if (kind == "two_sided_light") return std::make_shared<diffuse_light>(albedo, true);
    if (kind == "metal") {
        if (fuzz < 0) line.fail("metal fuzz must be non-negative, got " + line.word(i + 4));
        return std::make_shared<metal>(albedo, fuzz);
    }
    if (kind == "dielectric") {
        if (!(ior > 0)) line.fail("dielectric ior must be positive, got " + line.word(i + 5));
        return std::make_shared<dielectric>(ior);
    }
    line.fail("unknown material '" + kind +
              "' (expected lambertian, metal, dielectric, glass, conductor, diffuse_light or two_sided_light)");
}

// The transforms after field `first` (rotate_y degrees | translate x y z), applied to `object`
// in the order written.
inline std::shared_ptr<hittable> parse_transforms(const scene_line& line, size_t first, std::shared_ptr<hittable> object) {
    for (size_t i = first; i < line.size();) {
        const std::string& word = line.word(i);
        if (word == "rotate_y") {
            if (i + 1 >= line.size()) line.fail("rotate_y needs an angle in degrees");
            object = std::make_shared<rotate_y>(std::move(object), line.number(i + 1, "rotate_y angle"));
            i += 2;
        } else if (word == "translate") {
            if (i + 3 >= line.size()) line.fail("translate needs x y z");
            object = std::make_shared<translate>(std::move(object), line.vector(i + 1, "translate offset"));
            i += 4;
        } else {
            line.fail("unexpected '" + word + "' after the material (expected rotate_y or translate)");
        }
    }
    return object;
}

inline std::shared_ptr<hittable> parse_sphere_line(const scene_line& line) {
    line.expect_at_least(11, "sphere cx cy cz radius material r g b fuzz ior");
    point3 center = line.vector(1, "sphere centre");
    double radius = line.number(4, "sphere radius");
    if (!(radius > 0)) line.fail("sphere radius must be positive, got " + line.word(4));
    return parse_transforms(line, 11, std::make_shared<sphere>(center, radius, parse_material(line, 5)));
}

inline std::shared_ptr<hittable> parse_triangle_line(const scene_line& line) {
    line.expect_at_least(16, "triangle ax ay az bx by bz cx cy cz material r g b fuzz ior");
    point3 a = line.vector(1, "triangle vertex"), b = line.vector(4, "triangle vertex"), c = line.vector(7, "triangle vertex");
    if (cross(b - a, c - a).length_squared() == 0) line.fail("triangle has zero area");
    return parse_transforms(line, 16, std::make_shared<triangle>(a, b, c, parse_material(line, 10)));
}

inline std::shared_ptr<hittable> parse_quad_line(const scene_line& line) {
    line.expect_at_least(16, "quad qx qy qz ux uy uz vx vy vz material r g b fuzz ior");
    point3 q = line.vector(1, "quad corner");
    vec3 u = line.vector(4, "quad edge u"), v = line.vector(7, "quad edge v");
    if (cross(u, v).length_squared() == 0) line.fail("quad has zero area: its edges are parallel or zero");
    return parse_transforms(line, 16, std::make_shared<quad>(q, u, v, parse_material(line, 10)));
}

inline std::shared_ptr<hittable> parse_box_line(const scene_line& line) {
    line.expect_at_least(13, "box ax ay az bx by bz material r g b fuzz ior");
    point3 a = line.vector(1, "box corner"), b = line.vector(4, "box corner");
    if (a.x() == b.x() || a.y() == b.y() || a.z() == b.z()) line.fail("box corners must differ in x, y and z");
    return parse_transforms(line, 13, box(a, b, parse_material(line, 7)));
}

inline point_light parse_point_light_line(const scene_line& line) {
    line.expect_count(7, "point_light x y z r g b");
    point_light l{line.vector(1, "point light position"), line.vector(4, "point light intensity")};
    if (l.intensity.x() < 0 || l.intensity.y() < 0 || l.intensity.z() < 0)
        line.fail("point light intensity must be non-negative");
    return l;
}

// `mesh file.obj material r g b fuzz ior`; the OBJ path is relative to the scene file.
inline std::shared_ptr<hittable> parse_mesh_line(const scene_line& line, const std::string& scene_name) {
    line.expect_at_least(8, "mesh file.obj material r g b fuzz ior");
    std::filesystem::path obj(line.word(1));
    if (obj.is_relative()) obj = std::filesystem::path(scene_name).parent_path() / obj;
    std::shared_ptr<material> mat = parse_material(line, 2);
    try {
        // By extension: Stanford PLY, or else Wavefront OBJ.
        std::string ext = obj.extension().string();
        for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
        if (ext == ".ply") return parse_transforms(line, 8, load_ply(obj.string(), std::move(mat)));
        return parse_transforms(line, 8, load_obj(obj.string(), std::move(mat)));
    } catch (const scene_error& e) {
        line.fail(e.what());
    }
}

} // namespace detail

inline scene_description parse_scene(std::istream& in, const std::string& name) {
    scene_description scene;
    std::string text;
    int number = 0;
    while (std::getline(in, text)) {
        ++number;
        auto hash = text.find('#');
        if (hash != std::string::npos) text.erase(hash);
        std::istringstream words(text);
        std::vector<std::string> tokens;
        for (std::string w; words >> w;) tokens.push_back(w);
        if (tokens.empty()) continue;
        detail::scene_line line(name, number, std::move(tokens));
        if (line.word(0) == "camera") detail::parse_camera_line(line, scene.cam);
        else if (line.word(0) == "sphere") scene.world.add(detail::parse_sphere_line(line));
        else if (line.word(0) == "triangle") scene.world.add(detail::parse_triangle_line(line));
        else if (line.word(0) == "mesh") scene.world.add(detail::parse_mesh_line(line, name));
        else if (line.word(0) == "quad") scene.world.add(detail::parse_quad_line(line));
        else if (line.word(0) == "box") scene.world.add(detail::parse_box_line(line));
        else if (line.word(0) == "point_light") scene.point_lights.push_back(detail::parse_point_light_line(line));
        else if (line.word(0) == "background") {
            line.expect_count(4, "background r g b");
            color bg = line.vector(1, "background");
            if (bg.x() < 0 || bg.y() < 0 || bg.z() < 0) line.fail("background must be non-negative");
            scene.cam.background = bg;
        } else
            line.fail("unknown directive '" + line.word(0) +
                      "' (expected camera, background, sphere, triangle, quad, box, mesh or point_light)");
    }
    if (in.bad()) throw scene_error(name + ": read error");
    return scene;
}

inline scene_description load_scene(const std::string& path) {
    std::istringstream in(read_file(path, "scene file"));
    return parse_scene(in, path);
}

} // namespace rt
