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
//   image_texture(rtw_image, image_sampling) a picture already decoded, read as a model's sampler
//                                            asks: repeated or mirrored beyond [0, 1], bilinear,
//                                            each pixel times a factor (glTF, io/gltf_model.h)
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

// How an image_texture reads its picture. The default is the book's rule: the nearest pixel,
// (u, v) clamped to [0, 1]. A model's sampler (glTF's, io/gltf_model.h) may instead repeat or
// mirror the picture beyond [0, 1], blend the four nearest pixel centres (bilinear), and scale
// every pixel by a factor (glTF's baseColorFactor times its texture).
struct image_sampling {
    enum class wrap_mode { clamp, repeat, mirror };
    wrap_mode wrap_u = wrap_mode::clamp, wrap_v = wrap_mode::clamp;
    bool bilinear = false;
    color factor{1, 1, 1};

    bool is_books() const {
        return wrap_u == wrap_mode::clamp && wrap_v == wrap_mode::clamp && !bilinear && factor.x() == 1 &&
               factor.y() == 1 && factor.z() == 1;
    }
};

class image_texture : public texture {
  public:
    // A file that is missing or not an image does not throw here: the book's constructor prints
    // a message and goes on, and a book main builds its whole world before it renders. Rendering
    // a world that holds this texture then fails with load_error(), one line naming the file
    // (cam.render prints it and exits with status 1), where the book would render its cyan.
    explicit image_texture(const char* filename);
    // A picture already read (rtw_image::decode), looked up as `sampling` says.
    image_texture(rtw_image image, const image_sampling& sampling) : image_(std::move(image)), sampling_(sampling) {}

    // The pixel's colour; cyan (the book's debugging colour) when the file could not be read.
    color value(double u, double v, const point3& p) const override;

    const rtw_image& image() const { return image_; }
    // Why the file could not be read ("cannot read image texture 'x.jpg': file not found ..."),
    // or empty when it was.
    const std::string& load_error() const { return load_error_; }
    // The pixel (i, j) that (u, v) falls in: u and v clamped to [0, 1], v = 1 the top row, the
    // far edges belonging to the last pixel.
    static void pixel_at(double u, double v, int width, int height, int& i, int& j);

    const image_sampling& sampling() const { return sampling_; }
    // The colour at (u, v) of `pixels` (linear RGB, 3 floats per pixel, rows top to bottom, v = 1
    // the top row) as `s` reads it; what value() and the renderer's image kind both return.
    static color sample(const float* pixels, int width, int height, double u, double v, const image_sampling& s);

  private:
    rtw_image image_;
    std::string load_error_;
    image_sampling sampling_;
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

namespace detail {

// A texture coordinate brought into [0, 1] as `mode` wraps it (NaN reads as 0).
inline double wrap_coordinate(double t, image_sampling::wrap_mode mode) {
    if (std::isnan(t)) return 0;
    switch (mode) {
    case image_sampling::wrap_mode::repeat: return std::isfinite(t) ? t - std::floor(t) : 0;
    case image_sampling::wrap_mode::mirror: {
        if (!std::isfinite(t)) return 0;
        const double m = t - 2 * std::floor(0.5 * t); // in [0, 2): the picture, then its mirror image
        return m <= 1 ? m : 2 - m;
    }
    default: return t < 0 ? 0 : t > 1 ? 1 : t;
    }
}

// The pixel index i + k of a row of n pixels as `mode` wraps it.
inline int wrap_index(long long i, int n, image_sampling::wrap_mode mode) {
    switch (mode) {
    case image_sampling::wrap_mode::repeat: return int(((i % n) + n) % n);
    case image_sampling::wrap_mode::mirror: {
        const long long period = 2LL * n, m = ((i % period) + period) % period;
        return int(m < n ? m : period - 1 - m);
    }
    default: return i < 0 ? 0 : i >= n ? n - 1 : int(i);
    }
}

} // namespace detail

inline color image_texture::sample(const float* pixels, int width, int height, double u, double v,
                                   const image_sampling& s) {
    color c;
    if (!s.bilinear) {
        int i, j;
        pixel_at(detail::wrap_coordinate(u, s.wrap_u), detail::wrap_coordinate(v, s.wrap_v), width, height, i, j);
        const float* px = pixels + (size_t(j) * size_t(width) + size_t(i)) * 3;
        c = color(px[0], px[1], px[2]);
    } else {
        // Pixel centres at half-integers; x and y measured from the left and top edges. Far outside
        // [0, 1] the coordinates are wrapped first so that floor() stays within a long long.
        const double uu = std::isfinite(u) && std::fabs(u) < 1e6 ? u : detail::wrap_coordinate(u, s.wrap_u);
        const double vv = std::isfinite(v) && std::fabs(v) < 1e6 ? v : detail::wrap_coordinate(v, s.wrap_v);
        const double x = uu * width - 0.5, y = (1 - vv) * height - 0.5;
        const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
        const int i0 = detail::wrap_index((long long)x0, width, s.wrap_u), i1 = detail::wrap_index((long long)x0 + 1, width, s.wrap_u);
        const int j0 = detail::wrap_index((long long)y0, height, s.wrap_v), j1 = detail::wrap_index((long long)y0 + 1, height, s.wrap_v);
        auto at = [&](int i, int j) {
            const float* px = pixels + (size_t(j) * size_t(width) + size_t(i)) * 3;
            return color(px[0], px[1], px[2]);
        };
        c = (1 - fy) * ((1 - fx) * at(i0, j0) + fx * at(i1, j0)) + fy * ((1 - fx) * at(i0, j1) + fx * at(i1, j1));
    }
    return c * s.factor;
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
    if (!sampling_.is_books())
        return sample(image_.linear_pixels()->data(), image_.width(), image_.height(), u, v, sampling_);
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
