#pragma once
// load_obj_model(path): a Wavefront OBJ model with the materials of its MTL library, as a model
// downloaded from the web comes.
//
//   rt::obj_model m = rt::load_obj_model("kitchen.obj");     // throws scene_error
//   for (const std::string& w : m.warnings) ...               // what it could not render as written
//   world.add(std::make_shared<rt::hittable_list>(m.world));  // one mesh per material
//
// The OBJ and its library (the first `mtllib`, relative to the OBJ) are read with tinyobjloader,
// each checked first as load_obj checks an OBJ (io/obj.h). Faces are grouped by their `usemtl`
// material into one triangle_mesh each. An MTL material becomes, in this order
// (material_from_mtl, docs/models.md):
//   Ke (emission) above 0           a two-sided diffuse_light of radiance Ke
//   illum 4, 6 or 7, or d below 1   glass: dielectric(Ni, clear) with the exact Fresnel equations
//   (or Tr above 0)                 (Ni 1.5 when the file gives none); rough_dielectric(Ni, Pr)
//                                   with a PBR roughness Pr
//   Pm or Pr (the PBR extension)    metal_roughness(Kd, Pm, Pr)
//   map_Kd                          lambertian with that image (relative to the MTL file)
//   Ks above 0                      blinn_phong(Kd, Ks, Ns)
//   otherwise                       lambertian(Kd)
// A `norm` normal map (tangent space, +y up the picture) makes the material normal_mapped; a
// `bump` (or `map_Bump`) height map bump_mapped, the heights (a texel's mean channel, 0 to 1)
// times its -bm multiplier (default 1) a displacement in the model's units.
// Faces without a material are grey (lambertian 0.8). Faces with normals (`vn`) are shaded
// smooth with them, as model viewers do. What is not rendered as written is one
// warning each: a missing library or texture (the face keeps Kd), a bump map beside a normal
// map, the other maps, and a textured material's Ks. A malformed file, a negative or
// non-finite colour is a scene_error naming the file (and line).

#include "../core/engine_linkage.h"
#include "../hittable_list.h"
#include "../mesh.h"
#include "../vec3.h"

#include <memory>
#include <string>
#include <vector>

namespace rt {

struct obj_model {
    hittable_list world;                // one triangle_mesh per material the faces use
    std::vector<std::string> warnings;  // what was not rendered as written, one line each
    std::vector<std::string> files;     // what was read: the OBJ, its library, its textures
    bool emits = false;                 // some material is an emitter
    point3 lo, hi;                      // the bounds of the vertices the faces use
};

// Reads the OBJ file at `path` and its material library.
RTWEEKEND_ENGINE_FUNCTION obj_model load_obj_model(const std::string& path);

// The same from texts already read: `mtl_text` is the library's (empty: none), `mtl_path` names it
// in messages and is where its textures are looked for, beside it.
RTWEEKEND_ENGINE_FUNCTION obj_model decode_obj_model(const std::string& obj_text, const std::string& path,
                                                     const std::string& mtl_text, const std::string& mtl_path);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

} // namespace rt

#include "../core/file.h"
#include "../core/scene_error.h"
#include "../core/text_lines.h"
#include "../material.h"
#include "../texture.h"
#include "obj.h"
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace rt {

namespace detail {

// tinyobjloader reads an MTL file's numbers as it reads an OBJ's (obj.h): a number it would
// overflow on, an integer beyond an int, or a NUL byte is refused first, "path:LINE: malformed MTL
// file: ...".
inline void check_mtl_text(const std::string& text, const std::string& path) {
    for_each_obj_line(text, path, "MTL", [&](std::istringstream& line, size_t number) {
        for (std::string word; line >> word;)
            if (!obj_number_tame(word) || !obj_int_prefix_fits(word))
                throw scene_error(path + ":" + std::to_string(number) + ": malformed MTL file: '" + token_text(word) +
                                  "' is out of range (of an int, or has more digits than a number needs)");
    });
}

// The names of the libraries an OBJ's `mtllib` lines give, in order.
inline std::vector<std::string> obj_material_libraries(const std::string& text) {
    std::vector<std::string> names;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string keyword;
        if (!(words >> keyword) || keyword != "mtllib") continue;
        for (std::string name; words >> name;) names.push_back(name);
    }
    return names;
}

// A file named in a model (a texture, a library) relative to the directory `dir`; Windows
// separators read as '/'.
inline std::string model_file(const std::string& dir, std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    const std::filesystem::path p(name);
    return p.is_absolute() || dir.empty() ? name : (std::filesystem::path(dir) / p).string();
}

inline color mtl_colour(const tinyobj::real_t (&c)[3], const std::string& where, const char* key) {
    const color v(c[0], c[1], c[2]);
    for (int i = 0; i < 3; ++i)
        if (!(std::isfinite(v[i]) && v[i] >= 0))
            throw scene_error(where + ": " + key + " must be finite and non-negative, got " + std::to_string(v[i]));
    return v;
}

inline std::shared_ptr<material> material_from_mtl_colours(const tinyobj::material_t& m, const std::string& mtl_path,
                                                           obj_model& model);

// The material an MTL entry becomes (the rules at the top of the file), with its `norm` normal
// map or its `bump` height map.
inline std::shared_ptr<material> material_from_mtl(const tinyobj::material_t& m, const std::string& mtl_path,
                                                   obj_model& model) {
    std::shared_ptr<material> made = material_from_mtl_colours(m, mtl_path, model);
    const bool normals = !m.normal_texname.empty(), heights = !m.bump_texname.empty();
    if (!normals && !heights) return made;
    const std::string where = mtl_path + ": material '" + m.name + "'";
    if (normals && heights)
        model.warnings.push_back(where + ": it has a normal map and a bump map: the normal map is used, the bump map '" +
                                 token_text(m.bump_texname) + "' is ignored");
    const std::string& name = normals ? m.normal_texname : m.bump_texname;
    const char* what = normals ? "normal map" : "bump map";
    const std::string file = model_file(std::filesystem::path(mtl_path).parent_path().string(), name);
    rtw_image picture;
    try {
        if (!picture.load(file)) {
            model.warnings.push_back(where + ": " + what + " '" + token_text(name) + "' not found; the faces are flat");
            return made;
        }
    } catch (const scene_error& e) {
        model.warnings.push_back(where + ": " + e.what() + "; the faces are flat");
        return made;
    }
    model.files.push_back(file);
    image_sampling s;
    s.wrap_u = s.wrap_v = image_sampling::wrap_mode::repeat;
    s.bilinear = true;
    auto map = std::make_shared<image_texture>(picture.as_data(), s);
    if (normals) return std::make_shared<normal_mapped>(made, map);
    const double scale = m.bump_texopt.bump_multiplier;
    if (!std::isfinite(scale)) {
        model.warnings.push_back(where + ": its bump multiplier (-bm) is not finite; the faces are flat");
        return made;
    }
    return std::make_shared<bump_mapped>(made, map, scale);
}

// The material of an MTL entry's colours and maps (all the rules but `norm` and `bump`).
inline std::shared_ptr<material> material_from_mtl_colours(const tinyobj::material_t& m, const std::string& mtl_path,
                                                           obj_model& model) {
    const std::string where = mtl_path + ": material '" + m.name + "'";
    const std::string dir = std::filesystem::path(mtl_path).parent_path().string();
    const color kd = mtl_colour(m.diffuse, where, "Kd"), ks = mtl_colour(m.specular, where, "Ks");
    const color ke = mtl_colour(m.emission, where, "Ke");
    auto unsupported = [&](const std::string& file, const char* what) {
        if (!file.empty()) model.warnings.push_back(where + ": " + what + " '" + file + "' is not supported yet and is ignored");
    };
    unsupported(m.displacement_texname, "displacement map");
    unsupported(m.specular_texname, "map_Ks");
    unsupported(m.specular_highlight_texname, "map_Ns");
    unsupported(m.alpha_texname, "map_d");
    unsupported(m.reflection_texname, "refl map");
    unsupported(m.roughness_texname, "map_Pr");
    unsupported(m.metallic_texname, "map_Pm");
    unsupported(m.emissive_texname, "map_Ke");
    const double roughness = std::clamp(double(m.roughness), 0.0, 1.0), metallic = std::clamp(double(m.metallic), 0.0, 1.0);

    if (ke.x() > 0 || ke.y() > 0 || ke.z() > 0) {
        model.emits = true;
        return std::make_shared<diffuse_light>(ke, true);
    }
    const bool glass = m.illum == 4 || m.illum == 6 || m.illum == 7 || m.dissolve < 1;
    if (glass) {
        const double ior = std::isfinite(m.ior) && m.ior > 1 ? double(m.ior) : 1.5;
        if (roughness > 0) return std::make_shared<rough_dielectric>(ior, roughness);
        return std::make_shared<dielectric>(ior, color(0, 0, 0));
    }
    if (m.metallic > 0 || m.roughness > 0) return std::make_shared<metal_roughness>(kd, metallic, roughness);
    if (!m.diffuse_texname.empty()) {
        const std::string file = model_file(dir, m.diffuse_texname);
        auto image = std::make_shared<image_texture>(file.c_str());
        if (image->load_error().empty()) {
            model.files.push_back(image->image().path());
            if (ks.x() > 0 || ks.y() > 0 || ks.z() > 0)
                model.warnings.push_back(where + ": Ks is ignored: a textured material is Lambertian");
            return std::make_shared<lambertian>(image);
        }
        model.warnings.push_back(where + ": " + image->load_error() + "; the faces keep Kd");
    }
    if (ks.x() > 0 || ks.y() > 0 || ks.z() > 0)
        return std::make_shared<blinn_phong>(kd, ks, std::isfinite(m.shininess) && m.shininess > 0 ? double(m.shininess) : 0.0);
    return std::make_shared<lambertian>(kd);
}

// The faces of `all` whose material number is `id`, as a mesh of their own: the vertices,
// normals and texture coordinates they use, renumbered in order of first use. `remap` is scratch
// (as large as the largest array, filled with no_index), left as it was found.
inline std::shared_ptr<triangle_mesh> faces_with_material(const triangle_mesh& all, const std::vector<int>& face_material,
                                                          int id, std::shared_ptr<material> mat,
                                                          std::vector<uint32_t>& remap) {
    auto mesh = std::make_shared<triangle_mesh>();
    mesh->mat = std::move(mat);
    std::vector<uint32_t> used;
    auto take = [&](uint32_t index, auto& out, const auto& from) {
        if (index == triangle_mesh::no_index) return index;
        if (remap[index] == triangle_mesh::no_index) {
            remap[index] = uint32_t(out.size());
            out.push_back(from[index]);
            used.push_back(index);
        }
        return remap[index];
    };
    auto reset = [&] {
        for (uint32_t i : used) remap[i] = triangle_mesh::no_index;
        used.clear();
    };
    // The faces' corners of one kind (positions, normals or texture coordinates), renumbered.
    auto renumber = [&](const auto& corners, auto& out_corners, auto& out, const auto& from) {
        for (size_t f = 0; f < all.faces.size(); ++f)
            if (face_material[f] == id) {
                std::array<uint32_t, 3> face;
                for (size_t k = 0; k < 3; ++k) face[k] = take(corners[f][k], out, from);
                out_corners.push_back(face);
            }
        reset();
    };
    renumber(all.faces, mesh->faces, mesh->positions, all.positions);
    if (!all.face_normals.empty()) renumber(all.face_normals, mesh->face_normals, mesh->normals, all.normals);
    if (!all.face_uvs.empty()) renumber(all.face_uvs, mesh->face_uvs, mesh->uvs, all.uvs);
    return mesh;
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION obj_model decode_obj_model(const std::string& obj_text, const std::string& path,
                                                     const std::string& mtl_text, const std::string& mtl_path) {
    detail::check_mtl_text(mtl_text, mtl_path);
    tinyobj::ObjReader reader;
    detail::parse_obj(reader, obj_text, path, mtl_text);
    obj_model model;
    model.files.push_back(path);
    if (!mtl_path.empty() && !mtl_text.empty()) model.files.push_back(mtl_path);
    // tinyobjloader's own notes (a usemtl naming no material of the library, ...), one line each.
    std::istringstream notes(reader.Warning());
    for (std::string note; std::getline(notes, note) && model.warnings.size() < 20;)
        if (!note.empty()) model.warnings.push_back(path + ": " + token_text(note));
    std::vector<std::shared_ptr<material>> materials;
    for (const tinyobj::material_t& m : reader.GetMaterials()) materials.push_back(detail::material_from_mtl(m, mtl_path, model));
    std::vector<int> face_material;
    const std::shared_ptr<triangle_mesh> all = detail::mesh_of_obj(reader, path, nullptr, &face_material);
    const auto grey = std::make_shared<lambertian>(color(0.8, 0.8, 0.8));
    std::vector<uint32_t> remap(std::max({all->positions.size(), all->normals.size(), all->uvs.size()}), triangle_mesh::no_index);
    std::vector<int> ids = face_material;
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (int id : ids) {
        const bool known = id >= 0 && size_t(id) < materials.size();
        auto mesh = detail::faces_with_material(*all, face_material, id, known ? materials[size_t(id)] : grey, remap);
        mesh->smooth_shading = !mesh->normals.empty();
        model.world.add(std::move(mesh));
    }
    bool first = true;
    for (const auto& face : all->faces)
        for (uint32_t v : face) {
            const point3& p = all->positions[v];
            model.lo = first ? p : point3(std::min(model.lo.x(), p.x()), std::min(model.lo.y(), p.y()), std::min(model.lo.z(), p.z()));
            model.hi = first ? p : point3(std::max(model.hi.x(), p.x()), std::max(model.hi.y(), p.y()), std::max(model.hi.z(), p.z()));
            first = false;
        }
    return model;
}

RTWEEKEND_ENGINE_FUNCTION obj_model load_obj_model(const std::string& path) {
    const std::string text = read_file(path, "OBJ file");
    const std::vector<std::string> libraries = detail::obj_material_libraries(text);
    std::string mtl_text, mtl_path;
    std::vector<std::string> notes;
    if (!libraries.empty()) {
        mtl_path = detail::model_file(std::filesystem::path(path).parent_path().string(), libraries[0]);
        try {
            mtl_text = read_file(mtl_path, "MTL file");
        } catch (const scene_error& e) {
            notes.push_back(std::string(e.what()) + ": every face is grey");
        }
        if (libraries.size() > 1)
            notes.push_back(path + ": only the first material library is read ('" + token_text(libraries[0]) + "' of " +
                            std::to_string(libraries.size()) + ")");
    }
    obj_model model = decode_obj_model(text, path, mtl_text, mtl_path);
    model.warnings.insert(model.warnings.begin(), notes.begin(), notes.end());
    return model;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::load_obj_model;
using rt::obj_model;
#endif
