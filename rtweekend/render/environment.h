#pragma once
// environment: the radiance a ray that leaves the scene sees, by its direction. The book's sky
// (white at the horizon to light blue overhead), a constant background colour, or a lat-long
// picture (environment_map.h), which the path tracer also samples as a light.

#include "../core/vec3f.h"
#include "environment_map.h"

#include <memory>

namespace rt {

struct environment {
    bool constant = false; // false: the book's sky
    vec3f color{0, 0, 0};  // the constant background
    // The course scenes' background (CENG795): seen by camera rays that miss, black to every
    // other ray, so it lights nothing.
    bool camera_rays_only = false;
    // A picture of the radiance from every direction (an HDR sky): seen by every ray that leaves,
    // and sampled by next-event estimation. Null: the sky or the colour above.
    std::shared_ptr<const environment_map> map;

    static environment sky() { return {}; }
    static environment uniform(const vec3f& c) { return {true, c, false, nullptr}; }
    static environment backdrop(const vec3f& c) { return {true, c, true, nullptr}; }
    static environment image_based(std::shared_ptr<const environment_map> m) {
        environment e;
        e.map = std::move(m);
        return e;
    }

    vec3f eval(const vec3f& unit_dir) const {
        if (map) return map->radiance(unit_dir);
        if (constant) return color;
        // The book's sky: lerp(white, (0.5, 0.7, 1.0), (y + 1) / 2).
        float a = 0.5f * (unit_dir.y + 1.0f);
        return (1.0f - a) * vec3f{1, 1, 1} + a * vec3f{0.5f, 0.7f, 1.0f};
    }
};

} // namespace rt
