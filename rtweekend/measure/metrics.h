#pragma once
// metrics: how far an image is from a reference, in linear radiance or in 8-bit display codes.
//
//   compare_linear(a, ref)    two linear images (renders, PFM files), PSNR peak 1
//   compare_8bit(a, ref)      two linear images, each encoded first as our writers encode it:
//                             the book's int(256 * clamp(sqrt(v), 0, 0.999)); PSNR peak 255
//   compare_codes(a, ref)     two images that already hold 8-bit codes (0..255 as floats, what
//                             read_image returns for PPM, PNG and BMP); PSNR peak 255
//   compare_loaded(a, ref)    two images as read_image returns them, by the rule below
//   to_8bit_codes(linear)     the codes our writers would store, as an image of floats 0..255
//   error_shares(a, ref, n)   where the error lies: each n x n cell's share of the summed
//                             squared error (an image's error is often a few bright features);
//                             of two loaded images, in the values compare_loaded compares
//
// Every metric is a mean over all pixels and the three channels; `ref` is the reference:
//   rmse      sqrt(mean((a - ref)^2)), in the images' own units (radiance, or 8-bit codes)
//   rel_mse   mean((a - ref)^2 / (ref^2 + 0.01)) on values divided by the peak, so that the
//             0.01 means the same for codes as for radiance (where white is 1)
//   psnr      10 log10(peak^2 / mse) in dB; +inf for identical images
//   bias[c]   mean(a - ref) over channel c (R, G, B): a systematic over- or under-estimate
//
// Comparing 8-bit with linear: an 8-bit file cannot be decoded back to the radiance it came from
// (the encoding clamps at 1 and maps an interval to each code), so a linear image is compared
// with an 8-bit one by encoding the linear one, and the metrics are 8-bit metrics. Two linear
// images give both: linear metrics, and 8-bit metrics after encoding both.
//
// NaN and infinity: in a linear comparison, a channel value that is NaN or infinite in either
// image is left out of every metric (one bad pixel would otherwise make them all NaN) and counted
// in nonfinite_a / nonfinite_ref, which the caller should report; if every value is left out, the
// metrics are NaN. compare_8bit leaves nothing out: the encoding stores NaN and -inf as 0 and +inf
// as 255, and the 8-bit metrics measure that file; it still reports the linear inputs' counts.
//
// Images of different sizes, or empty ones, throw scene_error naming both sizes.

#include "../image/image_read.h"
#include "../image/image_write.h"
#include "../core/scene_error.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rt {

struct image_error {
    double rmse = 0, rel_mse = 0, psnr = 0;
    double bias[3] = {0, 0, 0};
    double peak = 1;                           // PSNR peak: 1 for linear, 255 for 8-bit
    size_t compared = 0;                       // channel values that entered the metrics
    size_t nonfinite_a = 0, nonfinite_ref = 0; // NaN or infinite channel values in each input
};

// What compare_loaded found: linear metrics only when both inputs were linear.
struct image_comparison {
    std::optional<image_error> linear;
    image_error display; // 8-bit
};

// The epsilon in rel_mse's denominator.
constexpr double rel_mse_epsilon = 1e-2;

// The image cut into cells of `cell` x `cell` pixels from the top left (those on the right and
// bottom edges smaller when cell does not divide the size), and each cell's part of the summed
// squared error, (a - ref)^2 over its pixels and channels, as a fraction of the whole image's:
// the shares sum to 1, or are all 0 when the images do not differ. Channel values that are NaN
// or infinite in either image are left out, as compare_linear leaves them out.
struct error_map {
    int cell = 0, columns = 0, rows = 0;
    bool linear = true; // false: 8-bit codes (error_shares of loaded images, one of them 8-bit)
    std::vector<double> share; // rows top to bottom, columns left to right
    double at(int column, int row) const { return share[size_t(row) * size_t(columns) + size_t(column)]; }
};

image_error compare_linear(const image& a, const image& ref);
image_error compare_8bit(const image& a, const image& ref);
image_error compare_codes(const image& a, const image& ref);
image_comparison compare_loaded(const loaded_image& a, const loaded_image& ref);
image to_8bit_codes(const image& linear);
// Throws scene_error for images compare_linear refuses, and for cell < 1.
error_map error_shares(const image& a, const image& ref, int cell);
// The same for two images as read_image returns them: linear values if both are linear, else
// 8-bit codes, the linear one encoded (compare_loaded's rule).
error_map error_shares(const loaded_image& a, const loaded_image& ref, int cell);

} // namespace rt

// --- IMPLEMENTATION ---

namespace rt {
namespace detail {

inline std::string image_size_text(const image& img) {
    return std::to_string(img.width()) + "x" + std::to_string(img.height());
}

// An image as 8-bit codes: as it is if it holds codes already, else encoded as the writers do.
inline image as_codes(const loaded_image& img) { return img.display_encoded ? img.pixels : to_8bit_codes(img.pixels); }

inline void require_comparable(const image& a, const image& ref) {
    if (a.width() != ref.width() || a.height() != ref.height())
        throw scene_error("cannot compare images of different sizes: " + image_size_text(a) + " and reference " +
                          image_size_text(ref));
    if (a.empty()) throw scene_error("cannot compare empty images (" + image_size_text(a) + ")");
}

inline size_t count_nonfinite(const image& img) {
    size_t n = 0;
    for (float v : img.data()) n += std::isfinite(v) ? 0 : 1;
    return n;
}

inline image_error error_between(const image& a, const image& ref, double peak) {
    require_comparable(a, ref);
    image_error e;
    e.peak = peak;
    double squared = 0, relative = 0, difference[3] = {0, 0, 0};
    size_t per_channel[3] = {0, 0, 0};
    const std::vector<float>& av = a.data();
    const std::vector<float>& rv = ref.data();
    for (size_t i = 0; i < av.size(); ++i) {
        bool a_finite = std::isfinite(av[i]), ref_finite = std::isfinite(rv[i]);
        e.nonfinite_a += a_finite ? 0 : 1;
        e.nonfinite_ref += ref_finite ? 0 : 1;
        if (!a_finite || !ref_finite) continue;
        double d = double(av[i]) - double(rv[i]);
        double r = double(rv[i]) / peak;
        squared += d * d;
        relative += (d / peak) * (d / peak) / (r * r + rel_mse_epsilon);
        difference[i % 3] += d;
        ++per_channel[i % 3];
        ++e.compared;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double mse = e.compared ? squared / double(e.compared) : nan;
    e.rmse = std::sqrt(mse);
    e.rel_mse = e.compared ? relative / double(e.compared) : nan;
    e.psnr = mse > 0 ? 10 * std::log10(peak * peak / mse) : mse == 0 ? std::numeric_limits<double>::infinity() : nan;
    for (int c = 0; c < 3; ++c) e.bias[c] = per_channel[c] ? difference[c] / double(per_channel[c]) : nan;
    return e;
}

} // namespace detail

inline image to_8bit_codes(const image& linear) {
    image codes(linear.width(), linear.height());
    std::vector<unsigned char> bytes = encode_8bit(linear);
    for (size_t i = 0; i < bytes.size(); ++i) codes.data()[i] = float(bytes[i]);
    return codes;
}

inline image_error compare_linear(const image& a, const image& ref) { return detail::error_between(a, ref, 1.0); }

inline image_error compare_codes(const image& a, const image& ref) { return detail::error_between(a, ref, 255.0); }

inline image_error compare_8bit(const image& a, const image& ref) {
    detail::require_comparable(a, ref);
    image_error e = compare_codes(to_8bit_codes(a), to_8bit_codes(ref));
    e.nonfinite_a = detail::count_nonfinite(a);
    e.nonfinite_ref = detail::count_nonfinite(ref);
    return e;
}

inline error_map error_shares(const image& a, const image& ref, int cell) {
    detail::require_comparable(a, ref);
    if (cell < 1) throw scene_error("error cells must be at least 1 pixel wide, got " + std::to_string(cell));
    error_map map;
    map.cell = cell;
    map.columns = (a.width() - 1) / cell + 1;
    map.rows = (a.height() - 1) / cell + 1;
    map.share.assign(size_t(map.columns) * size_t(map.rows), 0.0);
    double total = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const size_t i = (size_t(y) * size_t(a.width()) + size_t(x)) * 3;
            double squared = 0;
            for (int c = 0; c < 3; ++c) {
                const float av = a.data()[i + c], rv = ref.data()[i + c];
                if (!std::isfinite(av) || !std::isfinite(rv)) continue;
                const double d = double(av) - double(rv);
                squared += d * d;
            }
            map.share[size_t(y / cell) * size_t(map.columns) + size_t(x / cell)] += squared;
            total += squared;
        }
    if (total > 0)
        for (double& v : map.share) v /= total;
    return map;
}

inline error_map error_shares(const loaded_image& a, const loaded_image& ref, int cell) {
    if (!a.display_encoded && !ref.display_encoded) return error_shares(a.pixels, ref.pixels, cell);
    detail::require_comparable(a.pixels, ref.pixels);
    error_map map = error_shares(detail::as_codes(a), detail::as_codes(ref), cell);
    map.linear = false;
    return map;
}

inline image_comparison compare_loaded(const loaded_image& a, const loaded_image& ref) {
    detail::require_comparable(a.pixels, ref.pixels);
    image_comparison result;
    if (!a.display_encoded && !ref.display_encoded) {
        result.linear = compare_linear(a.pixels, ref.pixels);
        result.display = compare_8bit(a.pixels, ref.pixels);
        return result;
    }
    // At least one is 8-bit: encode whichever is linear, and compare codes.
    result.display = compare_codes(detail::as_codes(a), detail::as_codes(ref));
    if (!a.display_encoded) result.display.nonfinite_a = detail::count_nonfinite(a.pixels);
    if (!ref.display_encoded) result.display.nonfinite_ref = detail::count_nonfinite(ref.pixels);
    return result;
}

} // namespace rt
