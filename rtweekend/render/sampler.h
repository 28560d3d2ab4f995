#pragma once
// Samplers: where the uniform numbers of one camera sample come from.
//
//   sampler_plan plan(sampler_kind::sobol, seed, samples_per_pixel);
//   pixel_sampler ps(plan, x, y, s, rng);       // sample s of pixel (x, y)
//   float t = ps.get1d(sample_dimension::camera_time);
//   uniform2 lens = ps.get2d(sample_dimension::camera_lens);
//
// Every random decision of a path draws from its own fixed dimension (sample_dimension below):
// the camera's pixel, lens and time, and per bounce the light choice, the point on the light, the
// material's lobe, its direction and Russian roulette. A dimension is 1-D or 2-D; a 2-D one is a
// pair drawn together, so that its points are stratified in the plane and not only along each
// axis. Three kinds:
//
//   independent  every number from the sample's own PCG stream (rng.h), in the order asked: the
//                numbers rtweekend drew before samplers existed
//   stratified   jittered: the N samples of a pixel fall one per stratum of each dimension (N
//                strata in 1-D, a k x k grid in 2-D with k = floor(sqrt(N)); the samples past k^2
//                are uniform), the strata shuffled per pixel and dimension so that dimensions do
//                not correlate ("padding", Kensler 2013; book 3's camera stratifies the pixel)
//   sobol        the Sobol (0, 2)-sequence, Owen-scrambled by hashing (Burley, "Practical
//                Hash-based Owen Scrambling", JCGT 2020, with Vegdahl's 2021 hash), its index
//                taken along a Morton curve over the image under a nested random scramble
//                (Ahmed and Wonka, "Screen-Space Blue-Noise Diffusion of Monte Carlo Sampling
//                Error via Hierarchical Ordering of Pixels", 2020; pbrt-v4's ZSobolSampler): each
//                pixel's samples are a stratified (0, 2)-sequence, and neighbouring pixels take
//                disjoint parts of one sequence, so their errors differ as blue noise does
//
// Every value is a pure function of (seed, pixel, sample index, dimension): the image is
// bit-identical at any thread count, and adaptive sampling may stop a pixel after any number of
// samples. Numbers a decision draws beyond its dimension (a material that asks for more than its
// block holds) come from the sample's PCG stream.

#include "../core/force_inline.h"
#include "../core/rng.h"

#if defined(__GFNI__) && defined(__SSE2__)
#include <immintrin.h> // GFNI's bit reversals (reverse_bits32, detail::lanes8)
#endif

#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

namespace rt {

enum class sampler_kind : uint8_t { independent, stratified, sobol };

inline const char* sampler_name(sampler_kind k) {
    switch (k) {
    case sampler_kind::independent: return "independent";
    case sampler_kind::stratified: return "stratified";
    case sampler_kind::sobol: return "sobol";
    }
    return "?";
}

// The sampler named `name` ("independent", "stratified" or "sobol"); false for another name.
inline bool parse_sampler(const std::string& name, sampler_kind& k) {
    for (sampler_kind candidate : {sampler_kind::independent, sampler_kind::stratified, sampler_kind::sobol})
        if (name == sampler_name(candidate)) {
            k = candidate;
            return true;
        }
    return false;
}

// The dimensions of one camera sample. A path's bounce b uses bounce(b) + one of the offsets.
namespace sample_dimension {
inline constexpr uint32_t camera_pixel = 0; // 2-D: the point in the pixel
inline constexpr uint32_t camera_lens = 1;  // 2-D: the point on the lens
inline constexpr uint32_t camera_time = 2;  // 1-D: the moment in the shutter interval
inline constexpr uint32_t light_choice = 0;   // 1-D: which light
inline constexpr uint32_t light_position = 1; // 2-D: the point on it
inline constexpr uint32_t lobe = 2;           // 1-D: the material's first choice (lobe, Fresnel)
inline constexpr uint32_t direction = 3;      // 2-D: the material's direction
inline constexpr uint32_t lobe_extra = 4;     // 1-D: a material's second 1-D number
inline constexpr uint32_t direction_extra = 5; // 2-D: a material's second pair
inline constexpr uint32_t strategy = 6;       // 1-D: the mixture estimator's light-or-material choice
inline constexpr uint32_t roulette = 7;       // 1-D: Russian roulette
inline constexpr uint32_t per_bounce = 8;
inline constexpr uint32_t bounce(int depth) { return 3 + per_bounce * uint32_t(depth); }
} // namespace sample_dimension

// What a sampler needs to know of the whole render, computed once.
struct sampler_plan {
    sampler_kind kind = sampler_kind::independent;
    uint32_t seed = 0;           // a hash of the render's seed
    uint32_t samples = 1;        // samples per pixel, N
    uint32_t grid = 1;           // stratified 2-D: k = floor(sqrt(N))
    int log2_samples = 0;        // sobol: ceil(log2 N), the bits of the sample index

    sampler_plan() = default;
    sampler_plan(sampler_kind k, uint64_t render_seed, int samples_per_pixel);

    // A 64-bit hash of (seed, dimension), kept for the first dimensions (a path of 32 bounces).
    uint64_t dimension_hash(uint32_t dimension) const {
        return dimension < hashed_dimensions ? dimension_hashes_[dimension] : hash_dimension(dimension);
    }

  private:
    static constexpr uint32_t hashed_dimensions = 3 + 8 * 32;
    uint64_t hash_dimension(uint32_t dimension) const { return mix64((uint64_t(dimension) << 32) | seed); }
    uint64_t dimension_hashes_[hashed_dimensions] = {};
};

class pixel_sampler {
  public:
    // Sample `sample` of pixel (x, y); `rng` is the sample's own PCG stream (sample_rng), which
    // the independent sampler draws from and every sampler falls back on.
    pixel_sampler(const sampler_plan& plan, int x, int y, int sample, pcg32& rng);

    float get1d(uint32_t dimension);
    uniform2 get2d(uint32_t dimension) { return dimension == held_dimension_ ? held_ : compute2d(dimension); }
    pcg32& rng() { return rng_; }

    // The pair get2d(dimension) gives, computed ahead (sample_lanes::prepare2d, for many samples
    // at once): get2d returns it without computing it again.
    void hold2d(uint32_t dimension, uniform2 value) {
        held_dimension_ = dimension;
        held_ = value;
    }

  private:
    friend class sample_lanes;
    uniform2 compute2d(uint32_t dimension);
    const sampler_plan& plan_;
    uint32_t held_dimension_ = ~0u; // hold2d's pair, or none
    uniform2 held_{0, 0};
    uint32_t pixel_hash_;    // stratified: this pixel, hashed
    uint32_t sample_;
    uint32_t reversed_index_; // sobol: the Morton-curve index (below), its bits reversed
    uint64_t high_index_hash_; // sobol: a hash of the index's bits past the 32nd, or 0
    pcg32& rng_;
};

// One dimension of several samples at once: the camera's numbers of a batch of samples
// (camera_frame::sample_rays). Lane k is samplers[k]; every lane gets exactly what its
// pixel_sampler's get1d and get2d give. With Sobol numbers that is integer arithmetic in loops over
// the lanes, which the compiler turns into SIMD instructions (sixteen samples' pairs for about
// the instructions of two taken one at a time); other samplers are asked lane by lane.
class sample_lanes {
  public:
    static constexpr int capacity = 32;
    static constexpr int block_lanes = 16; // lanes computed together (capacity is a multiple)
    // All samplers share one plan; count <= capacity.
    sample_lanes(pixel_sampler* const* samplers, int count);
    // Fill u[k] (u1[k], u2[k]) for k < count; each array holds `capacity` floats (lanes past
    // count, up to the next multiple of block_lanes, are written too, with numbers of no sample).
    void get1d(uint32_t dimension, float* u);
    void get2d(uint32_t dimension, float* u1, float* u2);
    // Whether the lanes compute their numbers together (Sobol numbers with 32-bit indices);
    // else each lane is asked in turn, which saves nothing over asking it later.
    bool vectorised() const { return vectorised_; }
    // get2d(dimension) of every lane, handed to its sampler (pixel_sampler::hold2d), where that
    // sampler's own get2d(dimension) will find it: the path tracer's bounces, whose paths all
    // draw their direction from one dimension.
    void prepare2d(uint32_t dimension);

  private:
    pixel_sampler* const* samplers_;
    int count_;
    bool vectorised_ = false; // Sobol numbers with indices of 32 bits (no high_index_hash)
    uint32_t reversed_index_[capacity] = {};
    // The lanes the loops write: count, rounded up to whole blocks.
    int written_lanes() const { return (count_ + block_lanes - 1) / block_lanes * block_lanes; }
};

// A decision's uniforms as the material contract and the light set draw them (next_float() and
// next_2d()): 1-D numbers from the dimensions dims1[0], dims1[1] in turn, pairs from dims2[0],
// dims2[1]; past those (or where a dimension is `stream`), from the sample's PCG stream.
class dimension_uniforms {
  public:
    static constexpr uint32_t stream = ~0u;
    dimension_uniforms(pixel_sampler& s, uint32_t dim1, uint32_t dim2, uint32_t dim1_extra = stream,
                       uint32_t dim2_extra = stream)
        : s_(s), dims1_{dim1, dim1_extra}, dims2_{dim2, dim2_extra} {}
    RTWEEKEND_FORCE_INLINE float next_float() {
        const uint32_t d = used1_ < 2 ? dims1_[used1_++] : stream;
        return d != stream ? s_.get1d(d) : s_.rng().next_float();
    }
    RTWEEKEND_FORCE_INLINE uniform2 next_2d() {
        const uint32_t d = used2_ < 2 ? dims2_[used2_++] : stream;
        return d != stream ? s_.get2d(d) : draw_2d(s_.rng());
    }

  private:
    pixel_sampler& s_;
    uint32_t dims1_[2], dims2_[2];
    int used1_ = 0, used2_ = 0;
};

// The uniforms of a bounce's material sample and of its light sample.
inline dimension_uniforms material_uniforms(pixel_sampler& s, int depth) {
    const uint32_t b = sample_dimension::bounce(depth);
    return {s, b + sample_dimension::lobe, b + sample_dimension::direction, b + sample_dimension::lobe_extra,
            b + sample_dimension::direction_extra};
}
inline dimension_uniforms light_uniforms(pixel_sampler& s, int depth) {
    const uint32_t b = sample_dimension::bounce(depth);
    return {s, b + sample_dimension::light_choice, b + sample_dimension::light_position};
}

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// Bit reversal by shifts and masks (and a byte swap), in any context: the form loops over many
// values vectorise (sample_lanes).
inline constexpr uint32_t reverse_bits32_by_shifts(uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
#if defined(__GNUC__)
    return __builtin_bswap32(v); // the byte order reversed in one instruction
#else
    v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
    return (v >> 16) | (v << 16);
#endif
}

// One value's bits reversed. Where the machine has GFNI (Intel since Ice Lake, AMD since Zen 4),
// one affine transform over GF(2) reverses the bits of every byte and a byte swap finishes the
// job: four instructions where the shifts and masks take fifteen, and a Sobol pair reverses
// twice.
inline constexpr uint32_t reverse_bits32(uint32_t v) {
#if defined(__GFNI__) && defined(__SSE2__) && defined(__GNUC__)
    if (!__builtin_is_constant_evaluated()) {
        const __m128i x = _mm_gf2p8affine_epi64_epi8(_mm_cvtsi32_si128(int(v)), _mm_set1_epi64x(0x8040201008040201LL), 0);
        return __builtin_bswap32(uint32_t(_mm_cvtsi128_si32(x)));
    }
#endif
    return reverse_bits32_by_shifts(v);
}

// Two words' bits reversed at once: reverse_bits64(uint64_t(a) << 32 | b) is
// uint64_t(reverse_bits32(b)) << 32 | reverse_bits32(a), for the cost of one reversal.
inline constexpr uint64_t reverse_bits64(uint64_t v) {
#if defined(__GFNI__) && defined(__SSE2__) && defined(__GNUC__) && defined(__x86_64__)
    if (!__builtin_is_constant_evaluated()) {
        const __m128i x =
            _mm_gf2p8affine_epi64_epi8(_mm_cvtsi64_si128((long long)v), _mm_set1_epi64x(0x8040201008040201LL), 0);
        return __builtin_bswap64(uint64_t(_mm_cvtsi128_si64(x)));
    }
#endif
    v = ((v >> 1) & 0x5555555555555555ull) | ((v & 0x5555555555555555ull) << 1);
    v = ((v >> 2) & 0x3333333333333333ull) | ((v & 0x3333333333333333ull) << 2);
    v = ((v >> 4) & 0x0f0f0f0f0f0f0f0full) | ((v & 0x0f0f0f0f0f0f0f0full) << 4);
#if defined(__GNUC__)
    return __builtin_bswap64(v);
#else
    v = ((v >> 8) & 0x00ff00ff00ff00ffull) | ((v & 0x00ff00ff00ff00ffull) << 8);
    v = ((v >> 16) & 0x0000ffff0000ffffull) | ((v & 0x0000ffff0000ffffull) << 16);
    return (v >> 32) | (v << 32);
#endif
}

// A 32-bit hash of two words (mix64 of their concatenation, folded).
inline constexpr uint32_t hash32(uint64_t a, uint64_t b) {
    const uint64_t h = mix64(a * 0x9e3779b97f4a7c15ULL ^ mix64(b + 0x632be59bd9b4e019ULL));
    return static_cast<uint32_t>(h ^ (h >> 32));
}

// Owen scrambling of a 32-bit fraction (bit 31 = 1/2) by hashing: each bit flipped by a function
// of the bits above it and the seed. Burley (2020) showed that a hash in which every bit depends
// only on lower bits (the Laine-Karras form), applied to the reversed bits, is exactly a nested
// uniform scramble; the multipliers are Vegdahl's improved ones ("Building a Better LK Hash",
// 2021), as pbrt-v4 uses them.
inline constexpr uint32_t laine_karras_hash(uint32_t v, uint32_t seed) {
    v ^= v * 0x3d20adeau;
    v += seed;
    v *= (seed >> 16) | 1u;
    v ^= v * 0x05526c56u;
    v ^= v * 0x53a22864u;
    return v;
}
inline constexpr uint32_t owen_scramble(uint32_t v, uint32_t seed) {
    return reverse_bits32(laine_karras_hash(reverse_bits32(v), seed));
}

// The first two dimensions of the Sobol sequence as 32-bit fractions. Dimension 0 is van der
// Corput's (the index's bits reversed); dimension 1 has the generator matrix of the primitive
// polynomial x + 1, whose columns are v_0 = 2^31, v_i = v_{i-1} xor (v_{i-1} >> 1) (Pascal's
// triangle mod 2). Together they form a (0, 2)-sequence: every power-of-two run of 2^m points
// puts one point in each of the 2^m elementary intervals of every shape.
inline constexpr uint32_t sobol_dimension0(uint32_t index) { return reverse_bits32(index); }
inline constexpr uint32_t sobol_dimension1(uint32_t index) {
    uint32_t v = 0, column = 0x80000000u;
    for (; index; index >>= 1, column ^= column >> 1)
        if (index & 1u) v ^= column;
    return v;
}

// Sobol's dimension 1 with its bits reversed, reverse(sobol_dimension1(i)), from the index in
// natural order. Column i of the generator matrix is row i of Pascal's triangle mod 2, and by
// Lucas' theorem C(i, j) is odd exactly when the bits of j are a subset of those of i: bit j of the
// reversed value is the xor of the index bits i whose positions contain j's (as 5-bit numbers).
// That superset sum takes one shift-and-xor step per bit of a position: five steps, no table, and
// the same instructions for one sample or for sixteen (sample_lanes below).
inline constexpr uint32_t sobol_dimension1_reversed(uint32_t index) {
    uint32_t v = index;
    v ^= (v >> 1) & 0x55555555u;
    v ^= (v >> 2) & 0x33333333u;
    v ^= (v >> 4) & 0x0f0f0f0fu;
    v ^= (v >> 8) & 0x00ff00ffu;
    v ^= (v >> 16) & 0x0000ffffu;
    return v;
}

inline constexpr float fraction_to_float(uint32_t v) { return static_cast<float>(v >> 8) * 0x1p-24f; }

// The bits of x (16 of them) spread to the even bit positions.
inline constexpr uint64_t spread_bits(uint32_t x) {
    uint64_t v = x & 0xffffu;
    v = (v | (v << 8)) & 0x00ff00ffULL;
    v = (v | (v << 4)) & 0x0f0f0f0fULL;
    v = (v | (v << 2)) & 0x33333333ULL;
    v = (v | (v << 1)) & 0x55555555ULL;
    return v;
}

// A permutation of [0, n), chosen by `seed`: a bijection of the smallest power-of-two range
// holding n (odd multiplications, xor-shifts and additions, each invertible modulo 2^k), walked
// until it lands inside [0, n) ("cycle walking"; fewer than two steps on average).
inline uint32_t permute_index(uint32_t i, uint32_t n, uint32_t seed) {
    if (n <= 1) return 0;
    uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    const uint32_t m1 = seed | 1u, m2 = (seed * 0x9e3779b9u) | 1u, add = (seed >> 16) * 0x85ebca6bu;
    do {
        i ^= seed & mask;
        i = (i * m1) & mask;
        i ^= (i & mask) >> 3;
        i = (i * m2 + add) & mask;
        i ^= (i & mask) >> 5;
    } while (i >= n);
    return i;
}

} // namespace detail

inline sampler_plan::sampler_plan(sampler_kind k, uint64_t render_seed, int samples_per_pixel)
    : kind(k), seed(detail::hash32(render_seed, 0x5eedULL)), samples(uint32_t(samples_per_pixel > 0 ? samples_per_pixel : 1)) {
    for (uint32_t d = 0; d < hashed_dimensions; ++d) dimension_hashes_[d] = hash_dimension(d);
    while ((grid + 1) * (grid + 1) <= samples) ++grid;
    while ((uint64_t(1) << log2_samples) < samples) ++log2_samples;
}

inline pixel_sampler::pixel_sampler(const sampler_plan& plan, int x, int y, int sample, pcg32& rng)
    : plan_(plan), pixel_hash_(0), sample_(uint32_t(sample)), reversed_index_(0), high_index_hash_(0), rng_(rng) {
    if (plan.kind == sampler_kind::stratified) pixel_hash_ = detail::hash32(plan.seed, (uint64_t(y) << 32) | uint32_t(x));
    if (plan.kind == sampler_kind::sobol) {
        // (Morton code of the pixel) * 2^log2_samples + sample.
        const uint64_t index =
            (((detail::spread_bits(uint32_t(y)) << 1) | detail::spread_bits(uint32_t(x))) << plan.log2_samples) | sample_;
        reversed_index_ = detail::reverse_bits32(static_cast<uint32_t>(index));
        if (index >> 32) high_index_hash_ = mix64(index >> 32);
    }
}

namespace detail {

// The Sobol index of a camera sample in a dimension whose hash is `salt`: the Morton-curve index
// (pixel code, then sample bits) under a nested uniform scramble, each bit flipped by a hash of
// the bits above it (Burley's shuffle, owen_scramble applied to the index). Pixels near on the
// curve share their high bits and so draw from one power-of-two block of the sequence, each from
// its own part of it (whose points are well spread: the (0, 2) property); every aligned
// power-of-two run of a pixel's own samples stays such a part, so adaptive sampling may stop at
// any power of two. Different dimensions scramble differently and do not correlate. This is
// Ahmed and Wonka's ordering with base-2 nested scrambling where pbrt-v4 permutes base-4 digits:
// one hash instead of a loop over the digits, which made sampling a fifth of the cover scene's
// time. Index bits past the 32nd (images above 2^(16 - log2(spp)/2) pixels a side) would change
// a sample below 2^-32 only; they go into the hash instead.
// Returned reversed: laine_karras_hash(reverse(index)) is reverse(scrambled index).
inline uint32_t reversed_zsobol_index(uint32_t reversed_index, uint32_t salt) {
    return laine_karras_hash(reversed_index, salt);
}

// A float uniform from a 64-bit hash.
inline float hash_to_float(uint64_t h) { return static_cast<float>(h >> 40) * 0x1p-24f; }

} // namespace detail

inline float pixel_sampler::get1d(uint32_t dimension) {
    switch (plan_.kind) {
    case sampler_kind::independent: break;
    case sampler_kind::stratified: {
        const uint32_t seed = detail::hash32(pixel_hash_, dimension);
        const uint32_t stratum = detail::permute_index(sample_ % plan_.samples, plan_.samples, seed);
        const float jitter = detail::hash_to_float(mix64((uint64_t(seed) << 32) ^ sample_ ^ 0xa5a5ULL));
        const float u = (float(stratum) + jitter) / float(plan_.samples);
        return u < 1.0f ? u : 0x1.fffffep-1f;
    }
    case sampler_kind::sobol: {
        const uint64_t h = plan_.dimension_hash(dimension) ^ high_index_hash_;
        const uint32_t reversed = detail::reversed_zsobol_index(reversed_index_, uint32_t(h));
        // owen_scramble(sobol_dimension0(index)) = reverse(lk(index)), index = reverse(reversed).
        return detail::fraction_to_float(
            detail::reverse_bits32(detail::laine_karras_hash(detail::reverse_bits32(reversed), uint32_t(h >> 32))));
    }
    }
    return rng_.next_float();
}

inline uniform2 pixel_sampler::compute2d(uint32_t dimension) {
    switch (plan_.kind) {
    case sampler_kind::independent: break;
    case sampler_kind::stratified: {
        const uint32_t seed = detail::hash32(pixel_hash_, 0x200000000ULL | dimension);
        const uint32_t k = plan_.grid, cells = k * k;
        const uint32_t cell = detail::permute_index(sample_ % plan_.samples, plan_.samples, seed);
        const uint64_t h = mix64((uint64_t(seed) << 32) ^ sample_ ^ 0x5a5aULL);
        const float j1 = detail::hash_to_float(h), j2 = detail::hash_to_float(mix64(h));
        if (cell >= cells) return {j1, j2}; // past the k x k grid: uniform
        const float a = (float(cell % k) + j1) / float(k), b = (float(cell / k) + j2) / float(k);
        return {a < 1.0f ? a : 0x1.fffffep-1f, b < 1.0f ? b : 0x1.fffffep-1f};
    }
    case sampler_kind::sobol: {
        const uint64_t h = plan_.dimension_hash(dimension) ^ high_index_hash_;
        const uint32_t reversed = detail::reversed_zsobol_index(reversed_index_, uint32_t(h));
        const uint32_t scramble0 = uint32_t(h >> 32), scramble1 = scramble0 * 0x9e3779b9u + 0x7f4a7c15u;
        // Dimension 0 reversed is the index itself; dimension 1 reversed, sobol_dimension1_reversed.
        const uint32_t index = detail::reverse_bits32(reversed);
        const uint32_t x = detail::laine_karras_hash(index, scramble0);
        const uint32_t y = detail::laine_karras_hash(detail::sobol_dimension1_reversed(index), scramble1);
        // Both scrambled coordinates back to fractions in one reversal: reverse(x) low, reverse(y) high.
        const uint64_t both = detail::reverse_bits64(uint64_t(x) << 32 | y);
        return {detail::fraction_to_float(uint32_t(both)), detail::fraction_to_float(uint32_t(both >> 32))};
    }
    }
    return draw_2d(rng_);
}

inline sample_lanes::sample_lanes(pixel_sampler* const* samplers, int count) : samplers_(samplers), count_(count) {
    vectorised_ = count > 0 && samplers[0]->plan_.kind == sampler_kind::sobol;
    for (int k = 0; k < count; ++k) {
        vectorised_ = vectorised_ && samplers[k]->high_index_hash_ == 0;
        reversed_index_[k] = samplers[k]->reversed_index_;
    }
}

namespace detail {

#if defined(__AVX2__) && defined(__GFNI__)
// Eight lanes of the Sobol steps above at once, where the machine has GFNI: a lane's bits reverse
// in two instructions (each byte's bits by one affine map over GF(2), then the bytes by one
// shuffle) where the shifts and masks take about ten, and a sample's pair needs three reversals.
// g++ vectorises the scalar loops (below) with the shifts; these are the same values, bit for bit.
struct lanes8 {
    static __m256i reverse_bits(__m256i v) {
        const __m256i bits = _mm256_gf2p8affine_epi64_epi8(v, _mm256_set1_epi64x(0x8040201008040201LL), 0);
        const __m256i bytes = _mm256_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, //
                                               3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
        return _mm256_shuffle_epi8(bits, bytes);
    }
    static __m256i times(__m256i v, uint32_t c) { return _mm256_mullo_epi32(v, _mm256_set1_epi32(int(c))); }
    static __m256i laine_karras_hash(__m256i v, uint32_t seed) {
        v = _mm256_xor_si256(v, times(v, 0x3d20adeau));
        v = _mm256_add_epi32(v, _mm256_set1_epi32(int(seed)));
        v = times(v, (seed >> 16) | 1u);
        v = _mm256_xor_si256(v, times(v, 0x05526c56u));
        return _mm256_xor_si256(v, times(v, 0x53a22864u));
    }
    template <int shift>
    static __m256i superset_step(__m256i v, uint32_t mask) {
        return _mm256_xor_si256(v, _mm256_and_si256(_mm256_srli_epi32(v, shift), _mm256_set1_epi32(int(mask))));
    }
    static __m256i sobol_dimension1_reversed(__m256i v) {
        v = superset_step<1>(v, 0x55555555u);
        v = superset_step<2>(v, 0x33333333u);
        v = superset_step<4>(v, 0x0f0f0f0fu);
        v = superset_step<8>(v, 0x00ff00ffu);
        return superset_step<16>(v, 0x0000ffffu);
    }
    // fraction_to_float: the top 24 bits, which a signed conversion takes exactly.
    static void store_fractions(float* out, __m256i v) {
        _mm256_storeu_ps(out, _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_srli_epi32(v, 8)), _mm256_set1_ps(0x1p-24f)));
    }
    static __m256i load(const uint32_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
};
#endif

} // namespace detail

// Both follow pixel_sampler::get1d and get2d's Sobol branches step by step.
inline void sample_lanes::get1d(uint32_t dimension, float* u) {
    if (!vectorised_) {
        for (int k = 0; k < count_; ++k) u[k] = samplers_[k]->get1d(dimension);
        return;
    }
    const uint64_t h = samplers_[0]->plan_.dimension_hash(dimension);
    const uint32_t salt = uint32_t(h), scramble = uint32_t(h >> 32);
#if defined(__AVX2__) && defined(__GFNI__)
    using L = detail::lanes8;
    for (int k = 0; k < written_lanes(); k += 8) {
        const __m256i reversed = L::laine_karras_hash(L::load(reversed_index_ + k), salt);
        L::store_fractions(u + k, L::reverse_bits(L::laine_karras_hash(L::reverse_bits(reversed), scramble)));
    }
#else
    // Blocks of sixteen lanes, as many as hold count: a fixed trip count vectorises whole.
    for (int block = 0; block < count_; block += block_lanes)
        for (int k = block; k < block + block_lanes; ++k) {
            const uint32_t reversed = detail::reversed_zsobol_index(reversed_index_[k], salt);
            const uint32_t v = detail::reverse_bits32_by_shifts(
                detail::laine_karras_hash(detail::reverse_bits32_by_shifts(reversed), scramble));
            u[k] = detail::fraction_to_float(v);
        }
#endif
}

inline void sample_lanes::get2d(uint32_t dimension, float* u1, float* u2) {
    if (!vectorised_) {
        for (int k = 0; k < count_; ++k) {
            const uniform2 p = samplers_[k]->get2d(dimension);
            u1[k] = p.u1;
            u2[k] = p.u2;
        }
        return;
    }
    const uint64_t h = samplers_[0]->plan_.dimension_hash(dimension);
    const uint32_t salt = uint32_t(h), scramble0 = uint32_t(h >> 32), scramble1 = scramble0 * 0x9e3779b9u + 0x7f4a7c15u;
#if defined(__AVX2__) && defined(__GFNI__)
    using L = detail::lanes8;
    for (int k = 0; k < written_lanes(); k += 8) {
        const __m256i index = L::reverse_bits(L::laine_karras_hash(L::load(reversed_index_ + k), salt));
        L::store_fractions(u1 + k, L::reverse_bits(L::laine_karras_hash(index, scramble0)));
        L::store_fractions(u2 + k, L::reverse_bits(L::laine_karras_hash(L::sobol_dimension1_reversed(index), scramble1)));
    }
#else
    for (int block = 0; block < count_; block += block_lanes)
        for (int k = block; k < block + block_lanes; ++k) {
            const uint32_t reversed = detail::reversed_zsobol_index(reversed_index_[k], salt);
            const uint32_t index = detail::reverse_bits32_by_shifts(reversed);
            const uint32_t x = detail::laine_karras_hash(index, scramble0);
            const uint32_t y = detail::laine_karras_hash(detail::sobol_dimension1_reversed(index), scramble1);
            u1[k] = detail::fraction_to_float(detail::reverse_bits32_by_shifts(x));
            u2[k] = detail::fraction_to_float(detail::reverse_bits32_by_shifts(y));
        }
#endif
}

inline void sample_lanes::prepare2d(uint32_t dimension) {
    alignas(64) float u1[capacity], u2[capacity];
    get2d(dimension, u1, u2);
    for (int k = 0; k < count_; ++k) samplers_[k]->hold2d(dimension, {u1[k], u2[k]});
}

} // namespace rt
