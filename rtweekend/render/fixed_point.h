#pragma once
// Fixed-point sample sums: each pixel's samples are added as 64-bit integers, so that a pixel's
// sum is the same integer whatever order its samples arrive in and however they are split, over
// passes, threads, `render --samples` slices merged later (io/slice_file.h) or MPI ranks reduced
// with MPI_SUM (render/mpi_render.h). Summed in floating point, a split would round differently
// from one pass, and the images would differ in their last bits.
//
//   const int64_t limit = sample_limit(spp);     // per sample: no sum of spp samples overflows
//   bool clamped = false;
//   sum += to_fixed(sample.x, limit, clamped);   // exact for |sample| >= 2^-9, see below
//   float mean = fixed_mean(sum, n);
//
// The unit is 2^-32 of radiance (fixed_point_unit), chosen for these reasons:
//   - Resolution. A float v with |v| >= 2^-9 is a whole multiple of 2^-32 (its ulp is 2^(e - 23)
//     for 2^e <= |v|), so it converts exactly. A smaller sample is rounded to the nearest multiple,
//     an error of at most 2^-33 (1.2e-10) per sample and so in the mean. Nothing an output shows
//     is that small: the darkest non-zero 8-bit code stands for about 1.5e-5 (gamma 2), and a float
//     mean of 2^-9 or more has an ulp of at least 2^-32 itself.
//   - Range. An int64 holds +-2^63 units, +-2^31 (2.1e9) of radiance, in one channel's sum. A
//     sample is clamped to +-sample_limit(spp) = +-(2^63 - 1) / spp units, so that no sum of at most
//     spp samples, in any order or grouping, can leave the int64 range: the additions never
//     overflow (no undefined behaviour) and integer addition stays associative, which is what
//     makes every split give the same integer. In radiance the clamp is 2^31 / spp per sample:
//     2.1e6 at 1000 spp, 32768 at 65536, 128 at the scene files' limit of 2^24 spp; no scene of
//     this project comes near it (its brightest emitters are 15, the course scenes' white is 255).
//     A clamped sample is counted (render_stats::saturated_samples) and reported on the statistics
//     line as NaN and infinite samples are, so a clamp never goes unseen.
//   - A coarser unit buys range with resolution: 2^-24 would give 256 times the range but round
//     every sample below 0.5 (most of a dim image) by up to 3e-8, which PFM output of dark
//     pixels shows.
// The rounding is mode-independent (floor(x + 0.5), exact in double for the values it meets), so
// the integers do not depend on the floating-point environment of the thread that converts them.

#include "../image/image.h"

#if defined(__AVX512DQ__) && defined(__AVX512VL__)
#include <immintrin.h>
#endif

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace rt {

// Radiance per unit of the fixed-point sums: 2^-32.
inline constexpr double fixed_point_unit = 0x1p-32;

// The largest magnitude, in units, one sample may contribute when a pixel takes at most `samples`
// samples: then no sum of them can exceed the int64 range.
inline int64_t sample_limit(int64_t samples) {
    return std::numeric_limits<int64_t>::max() / (samples > 0 ? samples : 1);
}

// v in units of 2^-32, rounded to nearest (halves up), and clamped to [-limit, limit]; `clamped`
// is set when the clamp applied. NaN is the caller's to drop first (it is converted to 0 here,
// and counted as clamped, so that no input is undefined behaviour).
inline int64_t to_fixed(float v, int64_t limit, bool& clamped) {
    const double x = double(v) * 0x1p32; // exact: a power of two, and float's range fits double's
    const double bound = double(limit);  // may round up by less than an ulp: checked again below
    if (!(std::fabs(x) < bound)) {
        clamped = true;
        return x > 0 ? limit : (x < 0 ? -limit : 0);
    }
    // Below 2^52 adding 0.5 is exact; from there on x is already a whole number. |x| < bound <= 2^63,
    // so the conversion is defined.
    const double r = std::fabs(x) < 0x1p52 ? std::floor(x + 0.5) : x;
    int64_t n = static_cast<int64_t>(r);
    if (n > limit || n < -limit) {
        clamped = true;
        n = n > 0 ? limit : -limit;
    }
    return n;
}

// A sample's three channels converted by to_fixed and added to sum[0], sum[1], sum[2]: the same
// integers. Where the machine converts doubles to 64-bit integers in SIMD lanes (AVX-512DQ with
// VL), the three channels go through to_fixed's steps side by side when every one is below
// min(2^52, limit - 1) units in size, where no clamp applies and rounding is floor(x + 0.5);
// any other sample (out of range, NaN) channel by channel, as to_fixed has it.
inline void add_fixed3(float r, float g, float b, int64_t limit, int64_t* sum, bool& clamped) {
#if defined(__AVX512DQ__) && defined(__AVX512VL__)
    const __m256d x = _mm256_mul_pd(_mm256_cvtps_pd(_mm_setr_ps(r, g, b, 0.0f)), _mm256_set1_pd(0x1p32));
    const __m256d size = _mm256_andnot_pd(_mm256_set1_pd(-0.0), x);
    // The fast path's bound, min(2^52, limit - 1), exact (limit - 1 < 2^53 where it is the
    // smaller). A comparison, not std::fmin: g++ calls libm's fmin through the PLT for that (NaN
    // rules), with vzeroupper and the vector registers spilled around the call, once per sample.
    const double limit_less_one = double(limit) - 1.0;
    const double fast_bound = limit_less_one < 0x1p52 ? limit_less_one : 0x1p52;
    if (_mm256_cmp_pd_mask(size, _mm256_set1_pd(fast_bound), _CMP_LT_OQ) == 0xF) {
        const __m256i n = _mm256_cvttpd_epi64(_mm256_floor_pd(_mm256_add_pd(x, _mm256_set1_pd(0.5))));
        alignas(32) int64_t lanes[4];
        _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), n);
        sum[0] += lanes[0];
        sum[1] += lanes[1];
        sum[2] += lanes[2];
        return;
    }
#endif
    sum[0] += to_fixed(r, limit, clamped);
    sum[1] += to_fixed(g, limit, clamped);
    sum[2] += to_fixed(b, limit, clamped);
}

// The mean of n samples whose fixed-point sum is `sum`, as a float (0 for no samples): the
// division in double, then one rounding to float. The same integers give the same bits.
inline float fixed_mean(int64_t sum, int64_t n) {
    return n > 0 ? static_cast<float>(double(sum) * fixed_point_unit / double(n)) : 0.0f;
}

// Whether a + b fits in an int64 (and then `out` holds it): for sums read from files, which
// nothing guarantees; a render's own sums cannot overflow (see the top).
inline bool add_fixed(int64_t a, int64_t b, int64_t& out) {
    if ((b > 0 && a > std::numeric_limits<int64_t>::max() - b) || (b < 0 && a < std::numeric_limits<int64_t>::min() - b))
        return false;
    out = a + b;
    return true;
}

// The exact sums of a render's samples, pixel by pixel: what renders of parts of the sample range
// (or of the image) add up to. rgb holds 3 sums per pixel, rows top to bottom; counts the samples
// each pixel took.
struct pixel_sums {
    int width = 0, height = 0;
    std::vector<int64_t> rgb;
    std::vector<int32_t> counts;

    pixel_sums() = default;
    pixel_sums(int w, int h)
        : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0), counts(size_t(w) * size_t(h), 0) {}
    size_t pixel_count() const { return size_t(width) * size_t(height); }
};

// The image of each pixel's mean (black where a pixel took no sample).
inline image mean_image(const pixel_sums& s) {
    image img(s.width, s.height);
    std::vector<float>& out = img.data();
    for (size_t i = 0; i < s.pixel_count(); ++i)
        for (size_t k = 0; k < 3; ++k) out[i * 3 + k] = fixed_mean(s.rgb[i * 3 + k], s.counts[i]);
    return img;
}

} // namespace rt
