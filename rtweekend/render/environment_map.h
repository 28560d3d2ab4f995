#pragma once
// environment_map: radiance arriving from every direction at infinity, read from a lat-long
// picture (an HDR sky), and the importance sampling that lets next-event estimation find its
// bright parts (render/environment.h holds one; render/path_tracer.h samples it).
//
//   auto sky = std::make_shared<const environment_map>(read_image("sky.exr"), 1.0f);
//   path_trace(scene, frame, environment::image_based(sky), settings);
//
// Orientation (CENG795's, section 6.4 of the course text; pbrt and Mitsuba turn theirs
// differently): the texel at u = (1 + atan2(d_x, -d_z) / pi) / 2 across and v = acos(d_y) / pi
// down, the nearest one, so +y is the top row and -z the middle of the picture, in front of a
// camera looking down -z. Texels are radiance times `scale`.
//
// Sampling: a texel with probability proportional to its mean channel times sin(theta) (the solid
// angle its row spans), by a marginal distribution over rows and a conditional one over each
// row's texels, then a uniform point of it in (u, v). With dw = 2 pi^2 sin(theta) du dv, the
// solid-angle density is p(u, v) / (2 pi^2 sin theta) (Pharr, Jakob and Humphreys, Physically
// Based Rendering, 3rd ed., 14.2.4). As lookups are nearest-texel, the density follows the
// radiance texel for texel: a sun of a few texels is found as surely as a large light.

#include "../core/constants.h"
#include "../core/scene_error.h"
#include "../core/vec3f.h"
#include "../image/image.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace rt {

// The texel (x, y) = (column, row) of a w x h lat-long picture that direction d looks up, in the
// orientation above (also the course's environment lights', course/course_lights.h).
inline void latlong_texel(const vec3f& d, int w, int h, int& x, int& y) {
    const double u = (1 + std::atan2(double(d.x), -double(d.z)) / pi) / 2;
    const double v = std::acos(std::clamp(double(d.y), -1.0, 1.0)) / pi;
    // fmin and fmax before the conversion: a NaN direction gives the last texel, not undefined
    // behaviour.
    x = int(std::fmax(0.0, std::fmin(w - 1.0, std::floor(u * w))));
    y = int(std::fmax(0.0, std::fmin(h - 1.0, std::floor(v * h))));
}

class environment_map {
  public:
    // The picture's texels times scale; throws scene_error on an empty picture, a scale that is
    // negative or not finite, or a texel that is negative or not finite.
    environment_map(const image& picture, float scale);

    int width() const { return width_; }
    int height() const { return height_; }

    // The radiance arriving along -d, from direction d (unit) at infinity.
    vec3f radiance(const vec3f& d) const { return texels_[index_of(d)]; }

    // Whether some texel emits (else sample() finds nothing).
    bool emits() const { return total_ > 0; }

    // A direction wi drawn from (u1, u2) in [0, 1)^2, its solid-angle density and the radiance
    // arriving along it; false when the map is black.
    bool sample(float u1, float u2, vec3f& wi, float& pdf, vec3f& le) const;
    // The density sample() draws direction d with (0 where the map is black).
    float pdf(const vec3f& d) const;

  private:
    int width_ = 0, height_ = 0;
    std::vector<vec3f> texels_;      // row by row, top first
    std::vector<float> row_cdf_;     // height + 1 entries: the marginal over rows, 0 to 1
    std::vector<float> column_cdf_;  // (width + 1) per row: each row's conditional, 0 to 1
    std::vector<float> probability_; // of each texel: the mass sample() gives it
    double total_ = 0;

    size_t index_of(const vec3f& d) const {
        int x, y;
        latlong_texel(d, width_, height_, x, y);
        return size_t(y) * size_t(width_) + size_t(x);
    }
    // The index i with cdf[i] <= u < cdf[i + 1] among n intervals, skipping empty ones.
    static int interval_of(const float* cdf, int n, float u) {
        const int i = int(std::upper_bound(cdf, cdf + n + 1, u) - cdf) - 1;
        return std::clamp(i, 0, n - 1);
    }
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline environment_map::environment_map(const image& picture, float scale) {
    if (picture.empty()) throw scene_error("environment map has no pixels");
    if (!(scale >= 0) || !std::isfinite(scale)) throw scene_error("environment map scale must be finite and at least 0");
    width_ = picture.width();
    height_ = picture.height();
    texels_.resize(size_t(width_) * size_t(height_));
    probability_.assign(texels_.size(), 0.0f);
    column_cdf_.assign(size_t(width_ + 1) * size_t(height_), 0.0f);
    row_cdf_.assign(size_t(height_) + 1, 0.0f);
    std::vector<double> weight(texels_.size()), row_weight(size_t(height_), 0.0);
    for (int y = 0; y < height_; ++y) {
        const double sin_theta = std::sin(pi * (y + 0.5) / height_);
        for (int x = 0; x < width_; ++x) {
            const color c = picture.pixel(x, y) * double(scale);
            if (!(c.x() >= 0 && c.y() >= 0 && c.z() >= 0) || !std::isfinite(c.x() + c.y() + c.z()) ||
                !is_finite(vec3f(c)))
                throw scene_error("environment map texel (" + std::to_string(x) + ", " + std::to_string(y) +
                                  ") must be finite and at least 0 (times the scale)");
            const size_t i = size_t(y) * size_t(width_) + size_t(x);
            texels_[i] = vec3f(c);
            weight[i] = (c.x() + c.y() + c.z()) / 3 * sin_theta;
            row_weight[size_t(y)] += weight[i];
        }
        total_ += row_weight[size_t(y)];
    }
    if (!(total_ > 0) || !std::isfinite(total_)) {
        total_ = 0; // black (or beyond double): radiance() still answers, sample() finds nothing
        return;
    }
    double running = 0;
    for (int y = 0; y < height_; ++y) {
        float* cdf = &column_cdf_[size_t(y) * size_t(width_ + 1)];
        double in_row = 0;
        for (int x = 0; x < width_; ++x) {
            const size_t i = size_t(y) * size_t(width_) + size_t(x);
            in_row += weight[i];
            cdf[x + 1] = row_weight[size_t(y)] > 0 ? float(in_row / row_weight[size_t(y)]) : float(x + 1) / float(width_);
            probability_[i] = float(weight[i] / total_);
        }
        cdf[width_] = 1;
        running += row_weight[size_t(y)];
        row_cdf_[size_t(y) + 1] = float(running / total_);
    }
    row_cdf_[size_t(height_)] = 1;
}

inline bool environment_map::sample(float u1, float u2, vec3f& wi, float& pdf_out, vec3f& le) const {
    if (!(total_ > 0)) return false;
    // A row by the marginal, u1 reused within it for the point's v; then a texel of the row.
    const int y = interval_of(row_cdf_.data(), height_, u1);
    const float* cdf = &column_cdf_[size_t(y) * size_t(width_ + 1)];
    const int x = interval_of(cdf, width_, u2);
    const float row_span = row_cdf_[size_t(y) + 1] - row_cdf_[size_t(y)];
    const float column_span = cdf[x + 1] - cdf[x];
    const float fy = row_span > 0 ? std::clamp((u1 - row_cdf_[size_t(y)]) / row_span, 0.0f, 0.99999994f) : 0.5f;
    const float fx = column_span > 0 ? std::clamp((u2 - cdf[x]) / column_span, 0.0f, 0.99999994f) : 0.5f;
    const double u = (x + double(fx)) / width_, v = (y + double(fy)) / height_;
    const double theta = pi * v, phi = (2 * u - 1) * pi, sin_theta = std::sin(theta);
    if (!(sin_theta > 0)) return false;
    wi = vec3f(float(sin_theta * std::sin(phi)), float(std::cos(theta)), float(-sin_theta * std::cos(phi)));
    // The texel the direction looks up (rounding may move a point on a border to its neighbour):
    // its radiance and its density, so that sample() and pdf() agree.
    le = texels_[index_of(wi)];
    pdf_out = pdf(wi);
    return pdf_out > 0 && std::isfinite(pdf_out);
}

inline float environment_map::pdf(const vec3f& d) const {
    if (!(total_ > 0)) return 0;
    const double sin_theta = std::sqrt(std::fmax(0.0, 1.0 - double(d.y) * double(d.y)));
    if (!(sin_theta > 0)) return 0;
    const double p_uv = double(probability_[index_of(d)]) * width_ * height_;
    return float(p_uv / (2 * pi * pi * sin_theta));
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::environment_map;
#endif
