// The SIMD lanes of the leaf kernels (rtweekend/core/simd.h): the fused multiply-adds against the
// exactly rounded result worked out in double, the first-lanes mask against its definition, and
// the smallest lane against a scalar scan, at this build's width.

#include <rtweekend/core/simd.h>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace test_simd {

using namespace rt;

namespace {

constexpr size_t W = floatv::width;

floatv lanes_of(const float* values) { return floatv::load(values); }

void store(floatv v, float* out) { v.store(out); }

// A fixed spread of floats: products of very different sizes, so that fused and unfused results
// would differ in their last bits.
float value(uint32_t i) {
    uint32_t h = i * 2654435761u ^ 0x5bd1e995u;
    h ^= h >> 15;
    const float mantissa = 1.0f + float(h & 0xffffu) / 65536.0f;
    const int exponent = int((h >> 16) % 9) - 4;
    return ((h >> 28) & 1 ? -1.0f : 1.0f) * std::ldexp(mantissa, exponent);
}

} // namespace

TEST_CASE("simd: fmadd and fnmadd are a * b + c and c - a * b, rounded once where the machine fuses") {
    float a[W], b[W], c[W], r[W], s[W];
    for (uint32_t round = 0; round < 64; ++round) {
        for (size_t k = 0; k < W; ++k) {
            a[k] = value(round * 97 + uint32_t(k));
            b[k] = value(round * 89 + uint32_t(k) + 1000);
            c[k] = value(round * 83 + uint32_t(k) + 2000);
        }
        store(fmadd(lanes_of(a), lanes_of(b), lanes_of(c)), r);
        store(fnmadd(lanes_of(a), lanes_of(b), lanes_of(c)), s);
        for (size_t k = 0; k < W; ++k) {
            // A float product is exact in double, and so is the sum of it and a float here (the
            // exponents span less than double's 29 spare bits): the correctly rounded result.
            const double exact = double(a[k]) * double(b[k]) + double(c[k]);
            const double exact_n = double(c[k]) - double(a[k]) * double(b[k]);
#if defined(__FMA__) || (!defined(__AVX__) && !defined(__SSE2__))
            CHECK(r[k] == float(exact));
            CHECK(s[k] == float(exact_n));
#else
            // Unfused: the product rounded, then the sum.
            CHECK(r[k] == a[k] * b[k] + c[k]);
            CHECK(s[k] == c[k] - a[k] * b[k]);
#endif
        }
    }
}

TEST_CASE("simd: first_lanes(n) holds exactly the lanes below n") {
    for (unsigned n = 0; n <= 2 * W + 1; ++n) {
        const unsigned mask = bits(first_lanes(n));
        for (size_t k = 0; k < W; ++k) CHECK(((mask >> k) & 1u) == (k < n ? 1u : 0u));
        CHECK((mask >> W) == 0u);
    }
}

TEST_CASE("simd: reduce_min is the smallest lane, infinities and ties included") {
    const float inf = std::numeric_limits<float>::infinity();
    float v[W];
    for (uint32_t round = 0; round < 200; ++round) {
        for (size_t k = 0; k < W; ++k) v[k] = value(round * 131 + uint32_t(k));
        if (round % 3 == 0) v[round % W] = inf;
        if (round % 5 == 0)
            for (size_t k = 0; k < W; ++k) v[k] = inf;
        if (round % 7 == 0) v[(round / 7) % W] = v[0]; // a tie
        float smallest = v[0];
        for (size_t k = 1; k < W; ++k) smallest = std::fmin(smallest, v[k]);
        CHECK(reduce_min(lanes_of(v)) == smallest);
    }
    // The lane that holds it, as take_closest finds it: the first of equal ones.
    for (size_t k = 0; k < W; ++k) v[k] = 5.0f;
    v[W - 1] = -2.0f;
    if (W > 2) v[W / 2] = -2.0f;
    const float m = reduce_min(lanes_of(v));
    CHECK(m == -2.0f);
    CHECK(__builtin_ctz(bits(lanes_of(v) == floatv(m))) == int(W > 2 ? W / 2 : W - 1));
}

} // namespace test_simd
