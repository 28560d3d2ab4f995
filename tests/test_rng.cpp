// Random numbers (rtweekend/core/rng.h): pcg32 against the reference implementation's published
// output, per-sample generators, and random_double() inside and outside a render.

#include <rtweekend/core/rng.h>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <utility>

namespace test_rng {

using namespace rt;

TEST_CASE("pcg32 matches the reference implementation (pcg32_srandom_r(42, 54))") {
    // The first outputs of the PCG reference demo (pcg-c-basic, pcg32-demo) seeded with
    // initstate 42, initseq 54.
    pcg32 g(42, 54);
    const uint32_t expected[] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u, 0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
    for (uint32_t e : expected) CHECK(g.next_u32() == e);
}

TEST_CASE("pcg32: floats and doubles lie in 0 <= x < 1 and come from the top bits") {
    pcg32 a(7), b(7);
    for (int i = 0; i < 1000; ++i) {
        uint32_t u = b.next_u32();
        float f = a.next_float();
        // 24 high bits scaled by 2^-24: exact.
        CHECK(f == float(u >> 8) / 16777216.0f);
        CHECK(f >= 0.0f);
        CHECK(f < 1.0f);
    }
    // The largest possible float is (2^24 - 1) / 2^24 < 1.
    CHECK(float((0xffffffffu >> 8)) * 0x1p-24f < 1.0f);

    pcg32 g(123);
    const int N = 100000;
    double sum = 0, lo = 1, hi = 0;
    for (int i = 0; i < N; ++i) {
        double d = g.next_double();
        CHECK(d >= 0);
        CHECK(d < 1);
        sum += d;
        lo = std::fmin(lo, d);
        hi = std::fmax(hi, d);
    }
    // Uniform: mean 1/2, variance 1/12: 5 sigma = 5 sqrt(1/12/N) = 4.6e-3.
    CHECK(std::fabs(sum / N - 0.5) <= 5 * std::sqrt(1.0 / 12 / N));
    CHECK(lo < 1e-3);
    CHECK(hi > 1 - 1e-3);
}

TEST_CASE("sample_rng: deterministic per (seed, pixel, sample), distinct across them") {
    pcg32 a = sample_rng(1, 2, 3), b = sample_rng(1, 2, 3);
    for (int i = 0; i < 10; ++i) CHECK(a.next_u32() == b.next_u32());

    // The first 64 bits of output differ for every (seed, pixel, sample) in a grid (a collision
    // among these 3 * 4096 * 4 keys would have probability ~ n^2 / 2^65 ~ 4e-12 if they were random).
    std::set<uint64_t> seen;
    int total = 0;
    for (uint64_t seed : {0ull, 1ull, 0xdeadbeefull})
        for (uint64_t pixel = 0; pixel < 4096; ++pixel)
            for (uint64_t s = 0; s < 4; ++s) {
                pcg32 g = sample_rng(seed, pixel, s);
                uint64_t key = uint64_t(g.next_u32()) << 32 | g.next_u32();
                seen.insert(key);
                ++total;
            }
    CHECK(seen.size() == size_t(total));
}

TEST_CASE("pcg32::split: leaves its parent as it was, and the two streams do not move together") {
    pcg32 parent = sample_rng(7, 11, 13), untouched = parent;
    pcg32 child = parent.split(), again = parent.split();
    for (int i = 0; i < 10; ++i) CHECK(parent.next_u32() == untouched.next_u32()); // not advanced
    for (int i = 0; i < 10; ++i) CHECK(child.next_u32() == again.next_u32());      // deterministic
    // Parent and child, 4096 floats each: their correlation is that of independent uniforms,
    // |r| within 4 / sqrt(n) (standard deviation 1 / sqrt(n)), and neither repeats the other.
    pcg32 p = sample_rng(7, 11, 13), c = p.split();
    const int n = 4096;
    double sp = 0, sc = 0, spp = 0, scc = 0, spc = 0;
    int equal = 0;
    for (int i = 0; i < n; ++i) {
        const double x = p.next_float(), y = c.next_float();
        sp += x, sc += y, spp += x * x, scc += y * y, spc += x * y;
        equal += x == y;
    }
    const double cov = spc / n - (sp / n) * (sc / n);
    const double r = cov / std::sqrt((spp / n - (sp / n) * (sp / n)) * (scc / n - (sc / n) * (sc / n)));
    CHECK(std::fabs(r) < 4.0 / std::sqrt(double(n)));
    CHECK(equal < 8); // 24-bit floats: about n / 2^24 equal by chance
}

TEST_CASE("random_double: rand()/(RAND_MAX+1) outside a render, the sample generator inside") {
    std::srand(17);
    double r1 = std::rand() / (RAND_MAX + 1.0), r2 = std::rand() / (RAND_MAX + 1.0);
    std::srand(17);
    CHECK(random_double() == r1);
    CHECK(random_double() == r2);

    // Inside: the installed generator, and rand() is left alone.
    std::srand(17);
    pcg32 g(99), copy(99);
    {
        detail::scoped_sample_rng guard(g);
        for (int i = 0; i < 5; ++i) CHECK(random_double() == copy.next_double());
        // Nested guards restore the outer generator.
        pcg32 inner(5), inner_copy(5);
        {
            detail::scoped_sample_rng guard2(inner);
            CHECK(random_double() == inner_copy.next_double());
        }
        CHECK(random_double() == copy.next_double());
    }
    // Back outside: rand() again, from where srand(17) left it.
    CHECK(random_double() == r1);
}

TEST_CASE("random_double(min, max) stays in min <= x < max") {
    std::srand(3);
    for (int i = 0; i < 5000; ++i) {
        double d = random_double(-2.5, 4.0);
        CHECK(d >= -2.5);
        CHECK(d < 4.0);
    }
}

TEST_CASE("random_int(min, max) is uniform on the integers min..max, also for negative min") {
    // Each of the 7 values has probability 1/7; over N = 70000 draws each count is 10000 within
    // 5 sigma = 5 sqrt(N (1/7)(6/7)) = 463.
    for (int lo : {0, -3, -10}) {
        CAPTURE(lo);
        const int hi = lo + 6;
        std::srand(3);
        const long N = 70000;
        long count[7] = {0, 0, 0, 0, 0, 0, 0};
        long out_of_range = 0;
        for (long i = 0; i < N; ++i) {
            int k = random_int(lo, hi);
            if (k < lo || k > hi) ++out_of_range;
            else ++count[k - lo];
        }
        CHECK(out_of_range == 0);
        const double p = 1.0 / 7, sigma = std::sqrt(N * p * (1 - p));
        for (int v = 0; v < 7; ++v) {
            CAPTURE(lo + v);
            CHECK(std::fabs(count[v] - N * p) <= 5 * sigma);
        }
    }
}

} // namespace test_rng
