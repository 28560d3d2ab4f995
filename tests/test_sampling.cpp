// Sampling warps (rtweekend/core/sampling.h): the unit circle, uniform sphere, uniform disk,
// cosine hemisphere.
//
// Moments are checked on a stratified grid of (u1, u2) (midpoints of an n x n grid), where the
// sample mean approximates the integral deterministically with error O(1/n^2) for smooth
// integrands, so tight tolerances are safe.

#include <rtweekend/core/sampling.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

namespace test_sampling {

using namespace rt;

namespace {

template <class F>
void for_grid(int n, F f) {
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) f((i + 0.5f) / n, (j + 0.5f) / n);
}

} // namespace

TEST_CASE("unit_circle: (cos 2 pi u, sin 2 pi u) in every quarter turn") {
    // Against libm in double, at 100,003 points of [0, 1) (a prime count, so no point falls on a
    // quarter's edge by the grid alone) and at the edges and middles of the quarters and eighths,
    // where the reduction to +-pi/4 changes quadrant: within 2e-7, float's own rounding.
    const double two_pi = 2.0 * 3.14159265358979323846;
    auto check = [&](float u) {
        const vec3f c = unit_circle(u);
        CHECK(std::fabs(c.x - std::cos(two_pi * double(u))) < 2e-7);
        CHECK(std::fabs(c.y - std::sin(two_pi * double(u))) < 2e-7);
        CHECK(c.z == 0.0f);
    };
    const int n = 100003;
    double worst = 0;
    for (int i = 0; i < n; ++i) {
        const float u = float(i) / float(n);
        const vec3f c = unit_circle(u);
        worst = std::max({worst, std::fabs(c.x - std::cos(two_pi * double(u))), std::fabs(c.y - std::sin(two_pi * double(u)))});
    }
    CHECK(worst < 2e-7);
    for (int k = 0; k < 8; ++k) {
        const float edge = float(k) / 8.0f;
        check(edge);
        check(std::nextafter(edge, 1.0f));
        if (k > 0) check(std::nextafter(edge, 0.0f));
    }
    check(0x1.fffffep-1f); // the largest u below 1: a point just short of a full turn
    // The exact values at the quarter turns themselves.
    CHECK(unit_circle(0.25f).x == 0.0f);
    CHECK(unit_circle(0.25f).y == 1.0f);
    CHECK(unit_circle(0.5f).x == -1.0f);
    CHECK(unit_circle(0.75f).y == -1.0f);
}

TEST_CASE("sample_unit_sphere: unit vectors, uniform moments") {
    // Uniform on the sphere: E[x] = E[y] = E[z] = 0, E[x^2] = E[y^2] = E[z^2] = 1/3, E[xy] = 0.
    const int n = 200;
    double sx = 0, sy = 0, sz = 0, sxx = 0, syy = 0, szz = 0, sxy = 0;
    long upper = 0;
    for_grid(n, [&](float u1, float u2) {
        vec3f v = sample_unit_sphere(u1, u2);
        if (std::fabs(length(v) - 1) > 1e-6f) FAIL_CHECK("not unit");
        sx += v.x;
        sy += v.y;
        sz += v.z;
        sxx += v.x * v.x;
        syy += v.y * v.y;
        szz += v.z * v.z;
        sxy += v.x * v.y;
        if (v.z > 0.5f) ++upper;
    });
    const double N = double(n) * n;
    CHECK(std::fabs(sx / N) < 1e-4);
    CHECK(std::fabs(sy / N) < 1e-4);
    CHECK(std::fabs(sz / N) < 1e-4);
    CHECK(sxx / N == doctest::Approx(1.0 / 3).epsilon(1e-4));
    CHECK(syy / N == doctest::Approx(1.0 / 3).epsilon(1e-4));
    CHECK(szz / N == doctest::Approx(1.0 / 3).epsilon(1e-4));
    CHECK(std::fabs(sxy / N) < 1e-4);
    // The cap z > 1/2 has area fraction (1 - 1/2)/2 = 1/4 (Archimedes).
    CHECK(upper / N == doctest::Approx(0.25).epsilon(1e-3));
    // Poles: u1 = 0 -> z = 1.
    vec3f top = sample_unit_sphere(0, 0.3f);
    CHECK(top.z == 1.0f);
    CHECK(std::fabs(top.x) < 1e-7f);
}

TEST_CASE("sample_unit_ball: inside the unit ball, uniform by volume") {
    // Uniform in the ball: P(|p| < r) = r^3, so P(|p| < 1/2) = 1/8 and E[|p|^2] = 3/5; each
    // coordinate has mean 0 and E[x^2] = 1/5. The third uniform alone sets the radius: cbrt(u3).
    const int n = 40;
    double s_r2 = 0, sx = 0, sxx = 0;
    long inner = 0, count = 0;
    for (int k = 0; k < n; ++k) {
        float u3 = (k + 0.5f) / n;
        for_grid(n, [&](float u1, float u2) {
            vec3f p = sample_unit_ball(u1, u2, u3);
            float r2 = length_squared(p);
            if (!(r2 < 1.0f + 1e-6f)) FAIL_CHECK("outside the ball");
            s_r2 += r2;
            sx += p.x;
            sxx += p.x * p.x;
            if (r2 < 0.25f) ++inner;
            ++count;
        });
        CHECK(length(sample_unit_ball(0.3f, 0.7f, u3)) == doctest::Approx(std::cbrt(u3)).epsilon(1e-6));
    }
    const double N = double(count);
    // Midpoint sums over 40 radius strata: E[cbrt(u)^2] = 3/5 to about 1e-4.
    CHECK(s_r2 / N == doctest::Approx(0.6).epsilon(1e-3));
    CHECK(std::fabs(sx / N) < 1e-4);
    CHECK(sxx / N == doctest::Approx(0.2).epsilon(1e-3));
    // r < 1/2 <=> u3 < 1/8 = 5 of the 40 strata.
    CHECK(inner == 5L * n * n);
}

TEST_CASE("sample_unit_disk: inside the unit disk, uniform by area") {
    // Uniform on the disk: E[r^2] = 1/2, P(r < 1/2) = 1/4, E[x] = E[y] = 0, E[x^2] = 1/4.
    const int n = 200;
    double sr2 = 0, sx = 0, sy = 0, sxx = 0;
    long inner = 0;
    for_grid(n, [&](float u1, float u2) {
        vec3f p = sample_unit_disk(u1, u2);
        if (p.z != 0) FAIL_CHECK("z != 0");
        float r2 = p.x * p.x + p.y * p.y;
        if (!(r2 <= 1.0f)) FAIL_CHECK("outside the disk");
        sr2 += r2;
        sx += p.x;
        sy += p.y;
        sxx += p.x * p.x;
        if (r2 < 0.25f) ++inner;
    });
    const double N = double(n) * n;
    CHECK(sr2 / N == doctest::Approx(0.5).epsilon(1e-4));
    CHECK(std::fabs(sx / N) < 1e-4);
    CHECK(std::fabs(sy / N) < 1e-4);
    CHECK(sxx / N == doctest::Approx(0.25).epsilon(1e-4));
    CHECK(inner / N == doctest::Approx(0.25).epsilon(1e-3));
}

TEST_CASE("sample_cosine_direction: density cos(theta)/pi about the normal") {
    // mu = cos(theta) has density 2 mu: E[mu] = 2/3, E[mu^2] = 1/2, P(mu < 1/2) = 1/4.
    const vec3f n = normalize(vec3f(-2, 1, 0.5f));
    const int n_grid = 300;
    double smu = 0, smu2 = 0;
    long low = 0;
    for_grid(n_grid, [&](float u1, float u2) {
        vec3f d = sample_cosine_direction(n, u1, u2);
        if (std::fabs(length(d) - 1) > 1e-5f) FAIL_CHECK("not unit");
        float mu = dot(d, n);
        if (mu < -1e-6f) FAIL_CHECK("below the surface");
        smu += mu;
        smu2 += mu * mu;
        if (mu < 0.5f) ++low;
    });
    const double N = double(n_grid) * n_grid;
    CHECK(smu / N == doctest::Approx(2.0 / 3).epsilon(1e-3));
    CHECK(smu2 / N == doctest::Approx(0.5).epsilon(1e-3));
    CHECK(low / N == doctest::Approx(0.25).epsilon(2e-3));

    // The ends of u1: 0 is the normal itself, exactly; 1 a grazing direction (cos theta = 0),
    // still of unit length. u2 = 1/4 turns a quarter of the way round the disk: from the point
    // at u2 = 0 (x, e1 direction) to e2 = n x e1 (frame_across is right-handed).
    const vec3f d0 = sample_cosine_direction(n, 0.0f, 0.3f);
    CHECK(d0.x == n.x);
    CHECK(d0.y == n.y);
    CHECK(d0.z == n.z);
    const vec3f a = sample_cosine_direction(n, 1.0f, 0.0f), b = sample_cosine_direction(n, 1.0f, 0.25f);
    CHECK(std::fabs(dot(a, n)) < 1e-6f);
    CHECK(std::fabs(dot(b, n)) < 1e-6f);
    CHECK(std::fabs(dot(a, b)) < 1e-6f);
    const vec3f axb = cross(a, b);
    CHECK(axb.x == doctest::Approx(n.x).epsilon(1e-5));
    CHECK(axb.y == doctest::Approx(n.y).epsilon(1e-5));
    CHECK(axb.z == doctest::Approx(n.z).epsilon(1e-5));
}

} // namespace test_sampling
