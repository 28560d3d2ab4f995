#pragma once
// texture_table: the compiled scene's textures (book 2's texture.h) as a flat table, evaluated
// without virtual calls. A compiled_material with a texture index (core/material_kinds.h) takes
// its colour (a lambertian's albedo, a diffuse_light's emission) from here at every hit.
//
//   uint32_t i = table.add(tex);               compiles tex (and a checker's children) once per
//                                              texture pointer; returns its index
//   uint32_t i = table.add_constant(c);        a colour the compiler needs as a texture
//   vec3f c = table.eval(i, u, v, p_world);    the colour at surface coordinates (u, v), point p
//   float a = table.average(i);                the mean colour over the texture, channels averaged:
//                                              what a textured light's power is computed from
//
// Each entry is of a texture kind, one header of scene/textures/ and one entry in texture_kinds
// below, which answers:
//   K::compile(book_texture, table)     its entry for the books' texture class it stands for
//                                       (classify.h: book_textures)
//   k.eval(table, u, v, p)              the colour, computed in double as the book's value() does
//   k.average(table), k.reads_uv(table) its mean, and whether eval depends on (u, v) (where it does
//                                       not, the renderer skips computing them: a sphere's take
//                                       an acos and an atan2)
//   K::calls_user_code                  whether eval calls a user's value()
// A texture of any other class is a user_texture.

#include "../core/kind_list.h"
#include "../core/scene_error.h"
#include "../core/vec3f.h"
#include "../texture.h"
#include "classify.h"
#include "textures/checker_pattern.h"
#include "textures/constant_colour.h"
#include "textures/image_pixels.h"
#include "textures/marble_noise.h"
#include "textures/user_texture.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace rt {

using texture_kinds = kind_list<constant_colour, checker_pattern, image_pixels, marble_noise, user_texture>;

class texture_table {
  public:
    using entry = kind_variant<texture_kinds>;
    std::vector<entry> entries;

    uint32_t add(const texture& tex);
    // A constant colour the compiler makes itself (no book texture stands for it): a new entry.
    uint32_t add_constant(const vec3f& c);
    vec3f eval(uint32_t index, float u, float v, const vec3& p_world) const {
        return visit_value<texture_kinds>(entries[index], [&](const auto& k) { return k.eval(*this, u, v, p_world); });
    }
    float average(uint32_t index) const {
        return visit_value<texture_kinds>(entries[index], [&](const auto& k) { return k.average(*this); });
    }
    bool reads_uv(uint32_t index) const { return reads_uv_[index]; }

    bool empty() const { return entries.empty(); }
    bool calls_user_code() const { return has_user_; }

  private:
    std::unordered_map<const texture*, uint32_t> index_;
    std::vector<bool> reads_uv_;
    bool has_user_ = false;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline uint32_t texture_table::add(const texture& tex) {
    auto found = index_.find(&tex);
    if (found != index_.end()) return found->second;
    entry e = visit_book_class<book_textures>(
        tex,
        [&](const auto& known) -> entry {
            using T = std::decay_t<decltype(known)>;
            if constexpr (std::is_same_v<T, solid_color>) return constant_colour::compile(known, *this);
            else if constexpr (std::is_same_v<T, checker_texture>) return checker_pattern::compile(known, *this);
            else if constexpr (std::is_same_v<T, image_texture>) return image_pixels::compile(known, *this);
            else return marble_noise::compile(known, *this);
        },
        [&](const texture& other) -> entry { return user_texture{&other}; });
    const auto index = static_cast<uint32_t>(entries.size());
    entries.push_back(std::move(e));
    reads_uv_.push_back(visit_value<texture_kinds>(entries.back(), [&](const auto& k) { return k.reads_uv(*this); }));
    has_user_ = has_user_ || visit_value<texture_kinds>(entries.back(), [](const auto& k) {
                    return std::decay_t<decltype(k)>::calls_user_code;
                });
    index_.emplace(&tex, index);
    return index;
}

inline uint32_t texture_table::add_constant(const vec3f& c) {
    const auto index = static_cast<uint32_t>(entries.size());
    entries.push_back(constant_colour{c});
    reads_uv_.push_back(false);
    return index;
}

} // namespace rt
