#pragma once
// texture: a colour that varies over a surface (book 2), looked up by the hit's surface
// coordinates (u, v) and its point p (in world coordinates).
//
//   solid_color(c)                           the constant one, what lambertian(color) and
//                                            diffuse_light(color) wrap
//   checker_texture(scale, even, odd)        3-D cells of side `scale`: `even` where
//   checker_texture(scale, c1, c2)           floor(x/scale) + floor(y/scale) + floor(z/scale) is even
//   image_texture("earthmap.jpg")            a picture wrapped by (u, v): u left to right, v bottom
//                                            to top; sRGB files decoded to linear (rtw_stb_image.h)
//   noise_texture(scale)                     the book's marble: 0.5 (1 + sin(scale z + 10 turb(p)))
//
//   auto mat = make_shared<lambertian>(make_shared<checker_texture>(0.32, color(.2, .3, .1), color(.9, .9, .9)));
//
// The renderer compiles these four into a flat table (scene/texture_table.h) and evaluates them
// without virtual calls; a texture of another class (a user's own) is looked up through value().

#include "color.h"
#include "core/recognise.h"
#include "interval.h"
#include "perlin.h"
#include "rtw_stb_image.h"
#include "core/scene_error.h"
#include "vec3.h"

#include <cmath>
#include <memory>
#include <string>
#include <typeinfo>

namespace rt {

class texture {
  public:
    virtual ~texture() = default;

    virtual color value(double u, double v, const point3& p) const = 0;
};

class solid_color : public texture {
  public:
    solid_color(const color& albedo) : albedo_(albedo) {}
    solid_color(double red, double green, double blue) : solid_color(color(red, green, blue)) {}

    color value(double /*u*/, double /*v*/, const point3& /*p*/) const override { return albedo_; }

    const color& albedo() const { return albedo_; }

  private:
    color albedo_;
};

class checker_texture : public texture {
  public:
    checker_texture(double scale, std::shared_ptr<texture> even, std::shared_ptr<texture> odd);
    checker_texture(double scale, const color& c1, const color& c2)
        : checker_texture(scale, std::make_shared<solid_color>(c1), std::make_shared<solid_color>(c2)) {}

    color value(double u, double v, const point3& p) const override;

    double inv_scale() const { return inv_scale_; }
    const std::shared_ptr<texture>& even() const { return even_; }
    const std::shared_ptr<texture>& odd() const { return odd_; }
    // Whether the cell holding p is an even one (exposed so the renderer tests the same rule).
    static bool is_even(double inv_scale, const point3& p);

  private:
    double inv_scale_;
    std::shared_ptr<texture> even_, odd_;
};

class image_texture : public texture {
  public:
    // A file that is missing or not an image does not throw here: the book's constructor prints
    // a message and goes on, and a book main builds its whole world before it renders. Rendering
    // a world that holds this texture then fails with load_error(), one line naming the file
    // (cam.render prints it and exits with status 1), where the book would render its cyan.
    explicit image_texture(const char* filename);

    // The pixel's colour; cyan (the book's debugging colour) when the file could not be read.
    color value(double u, double v, const point3& p) const override;

    const rtw_image& image() const { return image_; }
    // Why the file could not be read ("cannot read image texture 'x.jpg': file not found ..."),
    // or empty when it was.
    const std::string& load_error() const { return load_error_; }
    // The pixel (i, j) that (u, v) falls in: u and v clamped to [0, 1], v = 1 the top row, the
    // far edges belonging to the last pixel.
    static void pixel_at(double u, double v, int width, int height, int& i, int& j);

  private:
    rtw_image image_;
    std::string load_error_;
};

class noise_texture : public texture {
  public:
    explicit noise_texture(double scale) : scale_(scale) {}

    color value(double u, double v, const point3& p) const override;

    double scale() const { return scale_; }
    const perlin& noise() const { return noise_; }
    // The marble's grey level at p for `noise` at `scale`.
    static double marble(const perlin& noise, double scale, const point3& p) {
        return 0.5 * (1 + std::sin(scale * p.z() + 10 * noise.turb(p, 7)));
    }

  private:
    perlin noise_;
    double scale_;
};

// The texture as a solid_color if it is exactly one (not a subclass, which may override
// value()), else null: a material whose texture is one is rendered from its constant colour.
inline const solid_color* exact_solid_color(const texture* tex) {
    // dynamic_cast rather than a static_cast behind the test: g++ 12 inlines the cast into callers
    // holding another texture and warns (-Warray-bounds) about the branch never taken.
    auto* solid = dynamic_cast<const solid_color*>(tex);
    return solid && is_exactly<solid_color>(*tex) ? solid : nullptr;
}

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline checker_texture::checker_texture(double scale, std::shared_ptr<texture> even, std::shared_ptr<texture> odd)
    : inv_scale_(1.0 / scale), even_(std::move(even)), odd_(std::move(odd)) {
    if (!(std::isfinite(scale) && scale != 0)) throw scene_error("checker_texture scale must be finite and non-zero");
    if (!even_ || !odd_) throw scene_error("checker_texture needs two textures, got a null one");
}

inline bool checker_texture::is_even(double inv_scale, const point3& p) {
    // Cell indices summed as doubles: exact for any cell a float scene can hold, and no int
    // overflow far from the origin. Negative cells count too: floor(-0.5) = -1 is odd.
    // Even when half of it is a whole number: exact for any whole double (past 2^53 every double
    // is even, as it is here), and without a call of fmod (8 % of book 2's checkered spheres' time).
    // An infinite or NaN sum is neither, as fmod(sum, 2) == 0 has it.
    const double sum = std::floor(inv_scale * p.x()) + std::floor(inv_scale * p.y()) + std::floor(inv_scale * p.z());
    return std::isfinite(sum) && 2 * std::floor(0.5 * sum) == sum;
}

inline color checker_texture::value(double u, double v, const point3& p) const {
    return is_even(inv_scale_, p) ? even_->value(u, v, p) : odd_->value(u, v, p);
}

inline void image_texture::pixel_at(double u, double v, int width, int height, int& i, int& j) {
    const interval unit(0, 1);
    u = std::isnan(u) ? 0 : unit.clamp(u);
    v = 1.0 - (std::isnan(v) ? 0 : unit.clamp(v)); // image rows run top to bottom
    i = int(u * width);
    j = int(v * height);
    if (i >= width) i = width - 1;
    if (j >= height) j = height - 1;
}

inline image_texture::image_texture(const char* filename) {
    try {
        image_ = rtw_image(filename);
    } catch (const scene_error& e) {
        load_error_ = e.what();
    }
}

inline color image_texture::value(double u, double v, const point3& /*p*/) const {
    if (image_.height() <= 0) return color(0, 1, 1);
    int i, j;
    pixel_at(u, v, image_.width(), image_.height(), i, j);
    const rtw_image::rgb c = image_.linear(i, j);
    return color(c.r, c.g, c.b);
}

inline color noise_texture::value(double /*u*/, double /*v*/, const point3& p) const {
    const double grey = marble(noise_, scale_, p);
    return color(grey, grey, grey);
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::checker_texture;
using rt::image_texture;
using rt::noise_texture;
using rt::solid_color;
using rt::texture;
#endif
