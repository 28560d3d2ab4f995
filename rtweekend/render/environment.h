#pragma once
// environment: the radiance a ray that leaves the scene sees, by its direction. The book's sky
// (white at the horizon to light blue overhead), a constant background colour, or a lat-long
// picture (environment_map.h), which the path tracer also samples as a light; or a picture of the
// film's own size behind the scene, seen by camera rays at their pixel (a course scene's
// background image).

#include "../core/vec3f.h"
#include "../image/image.h"
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
    // A picture of the film's size (width x height pixels) that a camera ray which leaves the
    // scene sees at its pixel, (x, y) for every sample of pixel (x, y): the CENG795 course's
    // replace_background. Black to every other ray. Null: none.
    std::shared_ptr<const image> film;

    static environment sky() { return {}; }
    static environment uniform(const vec3f& c) { return {true, c, false, nullptr, nullptr}; }
    static environment backdrop(const vec3f& c) { return {true, c, true, nullptr, nullptr}; }
    static environment film_backdrop(std::shared_ptr<const image> picture) {
        environment e = backdrop({0, 0, 0});
        e.film = std::move(picture);
        return e;
    }
    static environment image_based(std::shared_ptr<const environment_map> m) {
        environment e;
        e.map = std::move(m);
        return e;
    }

    // What a camera ray of pixel (x, y) that leaves the scene along unit_dir sees.
    vec3f camera_miss(const vec3f& unit_dir, int x, int y) const {
        if (film) return vec3f(film->pixel(x, y));
        return eval(unit_dir);
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
