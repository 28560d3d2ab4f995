#pragma once
// aov_sheet_image: a render and its guides (render/guides.h) as one picture of four panels, for
// apps/aov_sheet (which says what each panel shows). Values are linear: encode_8bit's gamma 2
// shows them as described.

#include <rtweekend/image/image.h>
#include <rtweekend/render/guides.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace app {

// The four panels in one image, linear values that the book's gamma 2 (encode_8bit) shows as
// described at the top: a panel meant to be seen as the colour c is stored as c^2.
inline rt::image aov_sheet_image(const rt::image& render, const rt::guide_images& g) {
    const int w = render.width(), h = render.height();
    rt::image out(2 * w, 2 * h);
    double nearest = std::numeric_limits<double>::infinity();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double z = g.depth.pixel(x, y).x();
            if (std::isfinite(z) && z > 0) nearest = std::min(nearest, z);
        }
    auto shown = [](double c) {
        c = std::clamp(c, 0.0, 1.0);
        return c * c;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            out.set_pixel(x, y, render.pixel(x, y));
            out.set_pixel(w + x, y, g.albedo.pixel(x, y));
            const rt::vec3 n = g.normal.pixel(x, y);
            const bool hit = n.length_squared() > 0;
            out.set_pixel(x, h + y, hit ? rt::color(shown(0.5 + 0.5 * n.x()), shown(0.5 + 0.5 * n.y()), shown(0.5 + 0.5 * n.z()))
                                      : rt::color(0, 0, 0));
            const double z = g.depth.pixel(x, y).x();
            const double v = std::isfinite(z) && z > 0 ? shown(nearest / z) : 0.0;
            out.set_pixel(w + x, h + y, rt::color(v, v, v));
        }
    return out;
}

} // namespace app
