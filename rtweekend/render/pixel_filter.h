#pragma once
// pixel_filter: how a pixel weighs the image around its centre (its reconstruction filter). A
// pixel's value is the filter-weighted mean of the radiance arriving through the image plane,
//   I(c) = integral f(x - c) L(x) dx / integral f,
// and each camera sample estimates it by filter importance sampling: its offset from the centre is
// drawn from |f| (a table of |f| over 256 bins per axis, sampled exactly as a piecewise-constant
// density) and it carries the weight f(t) / (p(t) integral f), so the estimate stays unbiased for
// the filter itself, negative lobes included, and each pixel still depends only on its own samples
// (the same image at any thread count; no splatting into neighbours). Filters are separable:
// f(x, y) = f(x) f(y).
//
//   pixel_filter::box()                  the books': uniform over the pixel (radius 1/2), weight 1
//   pixel_filter::tent(r)                1 - |t| / r (default r = 1)
//   pixel_filter::gaussian(s, r)         exp(-t^2 / (2 s^2)) minus its value at r, 0 beyond r
//                                        (default s = 1/2, r = 3 s; pbrt-v4's form)
//   pixel_filter::mitchell(b, c, r)      Mitchell and Netravali's cubic (SIGGRAPH 1988) over
//                                        |t| < r, t scaled by 2 / r (default b = c = 1/3, r = 2)
//   parse_pixel_filter("gaussian:0.5")   the command line's form: box, tent[:R], gaussian[:SIGMA],
//                                        mitchell[:B,C]
//
// References: Mitchell and Netravali, "Reconstruction Filters in Computer Graphics" (1988), the
// cubic's formula; Ernst et al., "Filter Importance Sampling" (2006), and pbrt-v4 section 8.8.3, the
// sampling of the filter in place of splatting.

#include "../core/scene_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace rt {

class pixel_filter {
  public:
    enum class kind_t { box, tent, gaussian, mitchell };

    static pixel_filter box() { return pixel_filter(); }
    static pixel_filter tent(double radius = 1) { return pixel_filter(kind_t::tent, radius, 0, 0, 0); }
    static pixel_filter gaussian(double sigma = 0.5, double radius = 0) {
        return pixel_filter(kind_t::gaussian, radius > 0 ? radius : 3 * sigma, sigma, 0, 0);
    }
    static pixel_filter mitchell(double b = 1.0 / 3, double c = 1.0 / 3, double radius = 2) {
        return pixel_filter(kind_t::mitchell, radius, 0, b, c);
    }

    kind_t kind() const { return kind_; }
    bool is_box() const { return kind_ == kind_t::box; }
    double radius() const { return radius_; }
    // "box", "tent:1", "gaussian:0.5", "mitchell:0.333333,0.333333": what parse_pixel_filter reads.
    std::string name() const;

    // The filter's profile along one axis at offset t (pixels) from the centre.
    double eval(double t) const {
        const double a = std::fabs(t);
        if (!(a <= radius_)) return 0;
        switch (kind_) {
        case kind_t::box: return 1;
        case kind_t::tent: return 1 - a / radius_;
        case kind_t::gaussian: return double(std::exp(float(-a * a * gauss_scale_))) - gauss_floor_;
        case kind_t::mitchell: {
            const double x = 2 * a / radius_, x2 = x * x, x3 = x2 * x, b = b_, c = c_;
            if (x < 1) return ((12 - 9 * b - 6 * c) * x3 + (-18 + 12 * b + 6 * c) * x2 + (6 - 2 * b)) / 6;
            return ((-b - 6 * c) * x3 + (6 * b + 30 * c) * x2 + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6;
        }
        }
        return 0;
    }
    // The integral of eval over [-radius, radius].
    double integral() const { return integral_; }

    // One axis of a camera sample: u uniform in [0, 1) to an offset t in [-radius, radius] from the
    // pixel's centre, and the sample's weight along this axis, f(t) / (p(t) integral f). The box
    // gives t = u - 1/2 and weight 1 exactly, as the books' cameras jitter.
    float sample(float u, float& weight) const {
        if (kind_ == kind_t::box) {
            weight = 1;
            return u - 0.5f;
        }
        // The bin whose share of the cdf holds u: from the guide table's first candidate, a step or
        // two along (the cdf is normalised to 1).
        const double target = std::clamp(double(u), 0.0, 1.0);
        size_t bin = guide_[std::min(size_t(target * guides), guides - 1)];
        while (bin + 1 < bins && cdf_[bin + 1] <= target) ++bin;
        const double mass = cdf_[bin + 1] - cdf_[bin];
        const double within = mass > 0 ? (target - cdf_[bin]) / mass : 0.5;
        const double width = 2 * radius_ / bins;
        const double t = -radius_ + (double(bin) + std::clamp(within, 0.0, 1.0)) * width;
        // f(t) / (p(t) integral f), p = mass / width on the bin.
        weight = mass > 0 ? float(eval(t) * width / (mass * integral_)) : 0.0f;
        return float(t);
    }

  private:
    static constexpr size_t bins = 256, guides = 512;

    pixel_filter() = default;
    pixel_filter(kind_t kind, double radius, double sigma, double b, double c)
        : kind_(kind), radius_(radius), sigma_(sigma), b_(b), c_(c) {
        if (kind == kind_t::gaussian && !(sigma > 0 && std::isfinite(sigma))) throw scene_error("gaussian filter sigma must be positive");
        if (kind == kind_t::gaussian) {
            gauss_scale_ = 1 / (2 * sigma * sigma);
            gauss_floor_ = double(std::exp(float(-radius * radius * gauss_scale_)));
        }
        if (!(radius > 0) || !(radius <= 16)) throw scene_error("pixel filter radius must be in (0, 16] pixels");
        if (kind == kind_t::mitchell && !(std::isfinite(b) && std::isfinite(c)))
            throw scene_error("mitchell filter B and C must be finite numbers");
        // The table: the mean of |f| over each bin (16 points each), its running sum, and the
        // integral of f by the composite Simpson rule over 4096 intervals.
        const double width = 2 * radius_ / bins;
        cdf_.assign(bins + 1, 0.0);
        for (size_t i = 0; i < bins; ++i) {
            double sum = 0;
            for (int k = 0; k < 16; ++k) sum += std::fabs(eval(-radius_ + (double(i) + (k + 0.5) / 16) * width));
            cdf_[i + 1] = cdf_[i] + sum / 16 * width;
        }
        const int n = 4096;
        const double h = 2 * radius_ / n;
        double s = eval(-radius_) + eval(radius_);
        for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * eval(-radius_ + i * h);
        integral_ = s * h / 3;
        if (!(integral_ > 0) || !(cdf_.back() > 0)) throw scene_error("pixel filter " + name() + " has no positive area");
        const double total = cdf_.back();
        for (double& c : cdf_) c /= total;
        cdf_.back() = 1;
        // guide_[k]: the last bin whose cdf starts at or below k / guides.
        guide_.resize(guides);
        size_t bin = 0;
        for (size_t k = 0; k < guides; ++k) {
            while (bin + 1 < bins && cdf_[bin + 1] <= double(k) / guides) ++bin;
            guide_[k] = uint16_t(bin);
        }
    }

    kind_t kind_ = kind_t::box;
    double radius_ = 0.5, sigma_ = 0, b_ = 0, c_ = 0;
    double integral_ = 1;
    double gauss_scale_ = 0, gauss_floor_ = 0; // 1 / (2 sigma^2), and the profile's value at the radius
    std::vector<double> cdf_;     // bins + 1 running sums of |f|, normalised to end at 1
    std::vector<uint16_t> guide_; // where in cdf_ each of `guides` equal steps of u starts
};

inline std::string pixel_filter::name() const {
    auto number = [](double x) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", x);
        return std::string(buf);
    };
    switch (kind_) {
    case kind_t::box: return "box";
    case kind_t::tent: return "tent:" + number(radius_);
    case kind_t::gaussian: return "gaussian:" + number(sigma_);
    case kind_t::mitchell: return "mitchell:" + number(b_) + "," + number(c_);
    }
    return "?";
}

// "box", "tent", "tent:R", "gaussian", "gaussian:SIGMA", "mitchell", "mitchell:B,C". Throws
// scene_error naming the text for anything else.
inline pixel_filter parse_pixel_filter(const std::string& text) {
    const size_t colon = text.find(':');
    const std::string name = text.substr(0, colon), args = colon == std::string::npos ? "" : text.substr(colon + 1);
    auto numbers = [&](size_t count) {
        std::vector<double> v;
        size_t at = 0;
        while (at <= args.size() && !args.empty()) {
            const size_t end = std::min(args.find(',', at), args.size());
            const std::string word = args.substr(at, end - at);
            char* stop = nullptr;
            const double x = std::strtod(word.c_str(), &stop);
            if (word.empty() || stop != word.c_str() + word.size() || !std::isfinite(x))
                throw scene_error("filter '" + text + "': '" + word + "' is not a number");
            v.push_back(x);
            at = end + 1;
        }
        if (!v.empty() && v.size() != count)
            throw scene_error("filter '" + text + "' takes " + std::to_string(count) + (count == 1 ? " number" : " numbers"));
        return v;
    };
    if (name == "box" && args.empty() && colon == std::string::npos) return pixel_filter::box();
    if (name == "tent") {
        const auto v = numbers(1);
        return pixel_filter::tent(v.empty() ? 1 : v[0]);
    }
    if (name == "gaussian") {
        const auto v = numbers(1);
        return pixel_filter::gaussian(v.empty() ? 0.5 : v[0]);
    }
    if (name == "mitchell") {
        const auto v = numbers(2);
        return v.empty() ? pixel_filter::mitchell() : pixel_filter::mitchell(v[0], v[1]);
    }
    throw scene_error("unknown filter '" + text + "' (expected box, tent[:R], gaussian[:SIGMA] or mitchell[:B,C])");
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::parse_pixel_filter;
using rt::pixel_filter;
#endif
