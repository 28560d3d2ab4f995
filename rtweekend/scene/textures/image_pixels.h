#pragma once
// image_pixels: a texture kind (scene/texture_table.h): book 2's image_texture, its linear float
// pixels shared with the rtw_image (so the table keeps them alive), looked up at (u, v) as the
// book's value() does: the nearest pixel, or as a model's sampler asks (image_sampling).

#include "../../core/scene_error.h"
#include "../../core/vec3f.h"
#include "../../texture.h"
#include "../../vec3.h"

#include <cmath>
#include <memory>
#include <vector>

namespace rt {

struct image_pixels {
    static constexpr const char* name = "image";
    std::shared_ptr<const std::vector<float>> pixels; // linear RGB, rows top to bottom
    int width = 0, height = 0;
    bool books = true;       // the book's nearest pixel, (u, v) clamped; else as `sampling` says
    image_sampling sampling;

    template <class Table>
    static image_pixels compile(const image_texture& image, Table&) {
        if (!image.load_error().empty()) throw scene_error(image.load_error());
        const color& f = image.sampling().factor;
        if (!(std::isfinite(f.x()) && std::isfinite(f.y()) && std::isfinite(f.z()) && f.x() >= 0 && f.y() >= 0 && f.z() >= 0) ||
            !is_finite(vec3f(f)))
            throw scene_error("image texture factor must be finite and non-negative in single precision");
        const rtw_image& img = image.image();
        return {img.linear_pixels(), img.width(), img.height(), image.sampling().is_books(), image.sampling()};
    }
    template <class Table>
    vec3f eval(const Table&, float u, float v, const vec3&) const {
        if (!pixels) return {1, 0, 1}; // a default rtw_image has none: the book's magenta
        if (!books) return vec3f(image_texture::sample(pixels->data(), width, height, u, v, sampling));
        int i, j;
        image_texture::pixel_at(u, v, width, height, i, j);
        const float* px = &(*pixels)[(size_t(j) * size_t(width) + size_t(i)) * 3];
        return {px[0], px[1], px[2]};
    }
    template <class Table>
    float average(const Table&) const {
        if (!pixels || pixels->empty()) return pixels ? 0.0f : 2.0f / 3.0f;
        double sum = 0;
        for (size_t k = 0; k < pixels->size(); ++k) sum += double((*pixels)[k]) * sampling.factor[int(k % 3)];
        return static_cast<float>(sum / double(pixels->size()));
    }
    template <class Table>
    bool reads_uv(const Table&) const { return true; }
    static constexpr bool calls_user_code = false;
};

} // namespace rt
