#pragma once
// texture_table: the compiled scene's textures (book 2's texture.h) as a flat table, evaluated
// without virtual calls. A compiled_material with a texture index (bsdf.h) takes its lambertian
// albedo or diffuse_light emission from here at every hit.
//
//   uint32_t i = table.add(tex);               compiles tex (and a checker's children) once per
//                                              texture pointer; returns its index
//   vec3f c = table.eval(i, u, v, p_world);    the colour at surface coordinates (u, v), point p
//   float a = table.average(i);                the mean colour over the texture, channels averaged:
//                                              what a textured light's power is computed from
//
// Entry kinds: constant (an exact solid_color), checker (two child indices and 1 / scale), image
// (the linear float pixels, shared with the rtw_image so the table keeps them alive), noise (a
// copy of the perlin tables and the scale) and user (any other texture class, called through
// value() in double; it may call random_double(), so calls_user_code() is then true).
// eval computes in double exactly what texture::value computes, so both give the same colour.

#include "../core/scene_error.h"
#include "../texture.h"
#include "../core/vec3f.h"

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace rt {

enum class texture_kind : uint8_t { constant, checker, image, noise, user };

struct compiled_texture {
    texture_kind kind = texture_kind::constant;
    vec3f value;                         // constant
    uint32_t even = 0, odd = 0;          // checker: children
    double inv_scale = 1;                // checker
    std::shared_ptr<const std::vector<float>> pixels; // image: linear RGB, rows top to bottom
    int width = 0, height = 0;           // image
    std::shared_ptr<const perlin> noise; // noise
    double scale = 1;                    // noise
    const texture* user = nullptr;       // user; owned by the world, like the materials
    bool reads_uv = false;               // eval looks at (u, v): an image or a user texture, or a
                                         // checker with one among its children
};

class texture_table {
  public:
    std::vector<compiled_texture> entries;

    uint32_t add(const texture& tex);
    vec3f eval(uint32_t index, float u, float v, const vec3& p_world) const;
    float average(uint32_t index) const;
    // Whether eval(index, ...) depends on (u, v): where it does not (constants, 3-D checkers,
    // noise), the renderer skips computing them (a sphere's take an acos and an atan2).
    bool reads_uv(uint32_t index) const { return entries[index].reads_uv; }

    bool empty() const { return entries.empty(); }
    bool calls_user_code() const { return has_user_; }

  private:
    std::unordered_map<const texture*, uint32_t> index_;
    bool has_user_ = false;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline uint32_t texture_table::add(const texture& tex) {
    auto found = index_.find(&tex);
    if (found != index_.end()) return found->second;
    compiled_texture e;
    const std::type_info& type = typeid(tex);
    if (const solid_color* solid = exact_solid_color(&tex)) {
        e.kind = texture_kind::constant;
        e.value = vec3f(solid->albedo());
    } else if (type == typeid(checker_texture)) {
        const auto& c = static_cast<const checker_texture&>(tex);
        e.kind = texture_kind::checker;
        e.inv_scale = c.inv_scale();
        e.even = add(*c.even()); // children first: a checker's entry follows its children's
        e.odd = add(*c.odd());
        e.reads_uv = entries[e.even].reads_uv || entries[e.odd].reads_uv;
    } else if (type == typeid(image_texture)) {
        const auto& image = static_cast<const image_texture&>(tex);
        if (!image.load_error().empty()) throw scene_error(image.load_error());
        const rtw_image& img = image.image();
        e.kind = texture_kind::image;
        e.reads_uv = true;
        e.pixels = img.linear_pixels();
        e.width = img.width();
        e.height = img.height();
        if (!e.pixels) { // a default rtw_image: no pixels. A loaded image_texture always has some; be safe
            e.kind = texture_kind::constant;
            e.value = {1, 0, 1};
        }
    } else if (type == typeid(noise_texture)) {
        const auto& n = static_cast<const noise_texture&>(tex);
        e.kind = texture_kind::noise;
        e.noise = std::make_shared<const perlin>(n.noise());
        e.scale = n.scale();
    } else {
        e.kind = texture_kind::user;
        e.reads_uv = true;
        e.user = &tex;
        has_user_ = true;
    }
    const auto index = static_cast<uint32_t>(entries.size());
    entries.push_back(std::move(e));
    index_.emplace(&tex, index);
    return index;
}

inline vec3f texture_table::eval(uint32_t index, float u, float v, const vec3& p) const {
    for (;;) { // a checker hands over to one of its children
        const compiled_texture& e = entries[index];
        switch (e.kind) {
        case texture_kind::constant: return e.value;
        case texture_kind::checker: index = checker_texture::is_even(e.inv_scale, p) ? e.even : e.odd; continue;
        case texture_kind::image: {
            int i, j;
            image_texture::pixel_at(u, v, e.width, e.height, i, j);
            const float* px = &(*e.pixels)[(size_t(j) * size_t(e.width) + size_t(i)) * 3];
            return {px[0], px[1], px[2]};
        }
        case texture_kind::noise: {
            const auto grey = static_cast<float>(noise_texture::marble(*e.noise, e.scale, p));
            return {grey, grey, grey};
        }
        case texture_kind::user: return vec3f(e.user->value(u, v, p));
        }
        return {0, 0, 0};
    }
}

inline float texture_table::average(uint32_t index) const {
    const compiled_texture& e = entries[index];
    switch (e.kind) {
    case texture_kind::constant: return (e.value.x + e.value.y + e.value.z) / 3;
    // Over a surface large against the cells, half is even and half odd.
    case texture_kind::checker: return 0.5f * (average(e.even) + average(e.odd));
    case texture_kind::image: {
        double sum = 0;
        for (float c : *e.pixels) sum += c;
        return e.pixels->empty() ? 0.0f : static_cast<float>(sum / double(e.pixels->size()));
    }
    case texture_kind::noise: return 0.5f; // 0.5 (1 + sin): the sine averages to 0
    case texture_kind::user: return 1.0f;  // unknown: as a white light would be
    }
    return 1.0f;
}

} // namespace rt
