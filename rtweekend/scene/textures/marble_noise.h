#pragma once
// marble_noise: a texture kind (scene/texture_table.h): book 2's noise_texture, its marble grey
// from a copy of the Perlin tables.

#include "../../core/vec3f.h"
#include "../../perlin.h"
#include "../../texture.h"
#include "../../vec3.h"

#include <memory>

namespace rt {

struct marble_noise {
    static constexpr const char* name = "noise";
    std::shared_ptr<const perlin> noise;
    double scale = 1;

    template <class Table>
    static marble_noise compile(const noise_texture& n, Table&) {
        return {std::make_shared<const perlin>(n.noise()), n.scale()};
    }
    template <class Table>
    vec3f eval(const Table&, float, float, const vec3& p) const {
        const auto grey = static_cast<float>(noise_texture::marble(*noise, scale, p));
        return {grey, grey, grey};
    }
    // 0.5 (1 + sin): the sine averages to 0.
    template <class Table>
    float average(const Table&) const { return 0.5f; }
    template <class Table>
    bool reads_uv(const Table&) const { return false; }
    static constexpr bool calls_user_code = false;
};

} // namespace rt
