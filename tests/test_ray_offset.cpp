// offset_ray_origin (rtweekend/core/ray_offset.h): spawned rays start just off the surface, on the
// side the normal points to, by 256 float ulps per unit of normal (or 2^-16 per unit near 0).

#include <rtweekend/core/ray_offset.h>

#include <doctest/doctest.h>

#include <cmath>
#include <random>

namespace test_ray_offset {

using namespace rt;

TEST_CASE("offset_ray_origin: hand-computed offsets") {
    // |p| >= 1/32: 256 ulps along a unit axis normal. The ulp of 1 is 2^-23, so
    // 1 + 256 * 2^-23 = 1 + 2^-15; the ulp of 4 is 2^-21, so -4 moved towards -inf is -4 - 2^-13.
    vec3f o = offset_ray_origin({1, 1, 1}, {1, 0, 0});
    CHECK(o.x == 1.0f + 0x1p-15f);
    CHECK(o.y == 1.0f); // zero normal component: unchanged
    CHECK(o.z == 1.0f);
    vec3f q = offset_ray_origin({-4, 2, 0.5f}, {-1, 0, 0});
    CHECK(q.x == -4.0f - 0x1p-13f);
    // Moving -4 towards zero: its magnitude drops into [2, 4), where the ulp is 2^-22, so 256 ulps
    // give -(4 - 256 * 2^-22) = -4 + 2^-14.
    vec3f w = offset_ray_origin({-4, 2, 0.5f}, {1, 0, 0});
    CHECK(w.x == -4.0f + 0x1p-14f);

    // |p| < 1/32: a fixed 2^-16 per unit of normal.
    vec3f z = offset_ray_origin({0, 0.01f, -0.02f}, {0, 0.6f, -0.8f});
    CHECK(z.x == 0.0f);
    CHECK(z.y == 0.01f + 0x1p-16f * 0.6f);
    CHECK(z.z == -0.02f + 0x1p-16f * -0.8f);

    // Negative zero (its bits are INT_MIN) is near the origin too: moved by 2^-16 per unit of
    // normal either way, and the push by ulps it does not take must not overflow on the way (the
    // sanitizer build checks that).
    vec3f m = offset_ray_origin({-0.0f, -0.0f, -0.0f}, {-1, 0, 1});
    CHECK(m.x == -0x1p-16f);
    CHECK(m.y == 0.0f);
    CHECK(m.z == 0x1p-16f);
}

TEST_CASE("offset_ray_origin: always moves to the normal's side, by a small amount") {
    std::mt19937 gen(17);
    std::uniform_real_distribution<float> U(-1, 1);
    std::uniform_real_distribution<float> E(-3, 4); // log10 of the magnitude: 1e-3 .. 1e4
    for (int i = 0; i < 20000; ++i) {
        vec3f n = normalize(vec3f(U(gen), U(gen), U(gen)));
        vec3f p(U(gen) * std::pow(10.0f, E(gen)), U(gen) * std::pow(10.0f, E(gen)), U(gen) * std::pow(10.0f, E(gen)));
        vec3f o = offset_ray_origin(p, n);
        vec3f d = o - p;
        // Strictly to the normal's side (some component of a unit n is at least 1/sqrt(3), which
        // moves by at least 147 ulps or 2^-16/sqrt3).
        CHECK(dot(d, n) > 0);
        for (int k = 0; k < 3; ++k) {
            float pk = p[k], dk = d[k], nk = n[k];
            // Each coordinate moves in the direction of its normal component (or not at all).
            CHECK(dk * nk >= 0);
            // By at most 256 ulps (ulp <= 2^-23 |p|), or 2^-16 near zero (with rounding slack).
            float bound = std::fmax(256 * 0x1p-23f * std::fabs(pk) * 1.001f, 0x1p-16f * 1.001f);
            CHECK(std::fabs(dk) <= bound);
        }
    }
}

TEST_CASE("offset_ray_origin: the three axes together give each axis's own offset, bit for bit") {
    // offset_ray_origin computes the axes side by side (in SSE lanes where there are some);
    // detail::offset_component is the same rule for one coordinate. Random points over twelve
    // orders of magnitude, and the values where the rule changes: the 1/32 threshold and its
    // neighbours, zeros of both signs, the smallest subnormal, the largest float.
    auto bits = [](float f) { return float_bits(f); };
    std::mt19937 gen(29);
    std::uniform_real_distribution<float> U(-1, 1), E(-6, 6);
    const float special[] = {0.0f, -0.0f, 1.0f / 32, -1.0f / 32, std::nextafter(1.0f / 32, 0.0f),
                             -std::nextafter(1.0f / 32, 0.0f), 0x1p-149f, -0x1p-149f, 3.4e38f, -3.4e38f};
    for (int i = 0; i < 20000; ++i) {
        vec3f p(U(gen) * std::pow(10.0f, E(gen)), U(gen) * std::pow(10.0f, E(gen)), U(gen) * std::pow(10.0f, E(gen)));
        if (i < 1000) p = {special[i % 10], special[(i / 10) % 10], special[(i / 100) % 10]};
        const vec3f n = normalize(vec3f(U(gen), U(gen), U(gen)));
        const vec3f o = offset_ray_origin(p, n);
        CAPTURE(i);
        CHECK(bits(o.x) == bits(detail::offset_component(p.x, n.x)));
        CHECK(bits(o.y) == bits(detail::offset_component(p.y, n.y)));
        CHECK(bits(o.z) == bits(detail::offset_component(p.z, n.z)));
    }
}

} // namespace test_ray_offset
