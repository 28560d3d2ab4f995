// vec3 algebra (rtweekend/vec3.h) and interval (rtweekend/interval.h).
//
// Every expected value below is worked out by hand in the comment next to it.

#include <rtweekend/interval.h>
#include <rtweekend/vec3.h>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

namespace test_vec3 {

using namespace rt;

namespace {

void check_vec(const vec3& v, double x, double y, double z, double eps = 0) {
    if (eps == 0) {
        CHECK(v.x() == x);
        CHECK(v.y() == y);
        CHECK(v.z() == z);
    } else {
        CHECK(v.x() == doctest::Approx(x).epsilon(eps));
        CHECK(v.y() == doctest::Approx(y).epsilon(eps));
        CHECK(v.z() == doctest::Approx(z).epsilon(eps));
    }
}

} // namespace

TEST_CASE("vec3: construction, access and negation") {
    vec3 zero;
    check_vec(zero, 0, 0, 0);

    vec3 v(1.5, -2, 3.25);
    CHECK(v[0] == 1.5);
    CHECK(v[1] == -2);
    CHECK(v[2] == 3.25);
    v[1] = 7;
    CHECK(v.y() == 7);
    check_vec(-v, -1.5, -7, -3.25);
}

TEST_CASE("vec3: add, subtract, scale, divide (all exact in binary floating point)") {
    vec3 a(1, 2, 3), b(4, -5, 6.5);
    check_vec(a + b, 5, -3, 9.5);
    check_vec(a - b, -3, 7, -3.5);
    check_vec(a * b, 4, -10, 19.5); // component-wise (Hadamard) product
    check_vec(2 * a, 2, 4, 6);
    check_vec(a * 2, 2, 4, 6);
    check_vec(b / 2, 2, -2.5, 3.25); // 1/2 is exact, so division by 2 is exact

    vec3 c = a;
    c += b;
    check_vec(c, 5, -3, 9.5);
    c *= 4;
    check_vec(c, 20, -12, 38);
    c /= 4;
    check_vec(c, 5, -3, 9.5);
}

TEST_CASE("vec3: dot product") {
    // (1,2,3).(4,-5,6) = 4 - 10 + 18 = 12
    CHECK(dot(vec3(1, 2, 3), vec3(4, -5, 6)) == 12);
    // orthogonal axes
    CHECK(dot(vec3(1, 0, 0), vec3(0, 1, 0)) == 0);
    // v.v = |v|^2: (2,3,6) -> 4 + 9 + 36 = 49
    CHECK(dot(vec3(2, 3, 6), vec3(2, 3, 6)) == 49);
}

TEST_CASE("vec3: cross product is right-handed, anti-commutative and orthogonal") {
    const vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    // Right-handed basis: x cross y = z, y cross z = x, z cross x = y.
    check_vec(cross(x, y), 0, 0, 1);
    check_vec(cross(y, z), 1, 0, 0);
    check_vec(cross(z, x), 0, 1, 0);
    check_vec(cross(y, x), 0, 0, -1);
    // (1,2,3) x (4,5,6) = (2*6 - 3*5, 3*4 - 1*6, 1*5 - 2*4) = (-3, 6, -3)
    check_vec(cross(vec3(1, 2, 3), vec3(4, 5, 6)), -3, 6, -3);
    // parallel vectors: zero
    check_vec(cross(vec3(1, 2, 3), vec3(-2, -4, -6)), 0, 0, 0);

    // Random pairs: a x b is orthogonal to both, anti-commutative, and |a x b|^2 = |a|^2 |b|^2 - (a.b)^2
    // (Lagrange's identity).
    std::mt19937_64 gen(12345);
    std::uniform_real_distribution<double> U(-10, 10);
    for (int i = 0; i < 200; ++i) {
        vec3 a(U(gen), U(gen), U(gen)), b(U(gen), U(gen), U(gen));
        vec3 c = cross(a, b);
        double scale = a.length() * b.length();
        CHECK(std::fabs(dot(c, a)) <= 1e-12 * scale * a.length());
        CHECK(std::fabs(dot(c, b)) <= 1e-12 * scale * b.length());
        // Anti-commutative up to rounding: with fused multiply-add contraction (-march=native)
        // a*b - c*d and c*d - a*b round differently, by at most an ulp of the products.
        vec3 d = cross(b, a);
        CHECK(std::fabs(c.x() + d.x()) <= 1e-15 * scale);
        CHECK(std::fabs(c.y() + d.y()) <= 1e-15 * scale);
        CHECK(std::fabs(c.z() + d.z()) <= 1e-15 * scale);
        double lagrange = dot(a, a) * dot(b, b) - dot(a, b) * dot(a, b);
        CHECK(c.length_squared() == doctest::Approx(lagrange).epsilon(1e-9).scale(scale * scale));
        // Right-handedness in general: (a, b, a x b) is a positively oriented frame, i.e. the
        // determinant of the matrix with rows a, b, c (expanded by Leibniz here) is positive.
        double det = a.x() * (b.y() * c.z() - b.z() * c.y()) - a.y() * (b.x() * c.z() - b.z() * c.x()) +
                     a.z() * (b.x() * c.y() - b.y() * c.x());
        CHECK(det > 0);
    }
}

TEST_CASE("vec3: length, length_squared, unit_vector") {
    // 3-4-12-13 Pythagorean quadruple: 9 + 16 + 144 = 169 = 13^2
    vec3 v(3, 4, 12);
    CHECK(v.length_squared() == 169);
    CHECK(v.length() == 13);
    vec3 u = unit_vector(v);
    check_vec(u, 3.0 / 13, 4.0 / 13, 12.0 / 13, 1e-15);
    CHECK(u.length() == doctest::Approx(1).epsilon(1e-15));

    vec3 w = unit_vector(vec3(0, -5, 0));
    check_vec(w, 0, -1, 0);

    // unit_vector of tiny and huge vectors still has unit length
    CHECK(unit_vector(vec3(1e-150, 2e-150, 2e-150)).length() == doctest::Approx(1).epsilon(1e-14));
    CHECK(unit_vector(vec3(1e150, 2e150, 2e150)).length() == doctest::Approx(1).epsilon(1e-14));
}

TEST_CASE("vec3: reflect") {
    // Mirror about the y axis normal: the normal component flips, the tangential one stays.
    // (1,-1,0) - 2 * (-1) * (0,1,0) = (1,1,0)
    check_vec(reflect(vec3(1, -1, 0), vec3(0, 1, 0)), 1, 1, 0);
    // Head-on: (0,0,-1) against normal (0,0,1) comes straight back.
    check_vec(reflect(vec3(0, 0, -1), vec3(0, 0, 1)), 0, 0, 1);
    // Parallel to the surface: unchanged.
    check_vec(reflect(vec3(2, 0, 3), vec3(0, 1, 0)), 2, 0, 3);
    // Tilted normal n = (1,1,0)/sqrt2, v = (0,-1,0): v.n = -1/sqrt2, v - 2(v.n)n = (0,-1,0) + (1,1,0) = (1,0,0)
    vec3 n = unit_vector(vec3(1, 1, 0));
    check_vec(reflect(vec3(0, -1, 0), n), 1, 0, 0, 1e-15);
    CHECK(std::fabs(reflect(vec3(0, -1, 0), n).y()) < 1e-15);

    // Length is preserved and the angle with the normal is mirrored (random cases).
    std::mt19937_64 gen(7);
    std::normal_distribution<double> N(0, 1);
    for (int i = 0; i < 100; ++i) {
        vec3 v(N(gen), N(gen), N(gen));
        vec3 m = unit_vector(vec3(N(gen), N(gen), N(gen)));
        vec3 r = reflect(v, m);
        CHECK(r.length() == doctest::Approx(v.length()).epsilon(1e-12));
        CHECK(dot(r, m) == doctest::Approx(-dot(v, m)).epsilon(1e-12).scale(v.length()));
    }
}

TEST_CASE("vec3: near_zero uses a strict 1e-8 threshold on every component") {
    CHECK(vec3(0, 0, 0).near_zero());
    CHECK(vec3(1e-9, -1e-9, 5e-9).near_zero());
    CHECK_FALSE(vec3(1e-7, 0, 0).near_zero());
    CHECK_FALSE(vec3(0, -1e-7, 0).near_zero());
    CHECK_FALSE(vec3(0, 0, 1e-8).near_zero()); // |x| < 1e-8 is strict
    CHECK_FALSE(vec3(1e-9, 1e-9, 1).near_zero());
}

TEST_CASE("vec3: operator<< prints 'x y z'") {
    std::ostringstream s;
    s << vec3(1, -2.5, 3);
    CHECK(s.str() == "1 -2.5 3");

    std::ostringstream t;
    t << vec3(0, 0.125, -100);
    CHECK(t.str() == "0 0.125 -100");
}

TEST_CASE("vec3: degrees_to_radians") {
    CHECK(degrees_to_radians(180) == doctest::Approx(3.14159265358979323846).epsilon(1e-15));
    CHECK(degrees_to_radians(90) == doctest::Approx(1.57079632679489661923).epsilon(1e-15));
    CHECK(degrees_to_radians(0) == 0);
}

TEST_CASE("vec3: random helpers stay in their domains") {
    std::srand(99); // outside a render random_double() is rand()/(RAND_MAX+1.0)
    for (int i = 0; i < 2000; ++i) {
        vec3 u = random_unit_vector();
        CHECK(u.length() == doctest::Approx(1).epsilon(1e-12));
        vec3 d = random_in_unit_disk();
        CHECK(d.z() == 0);
        CHECK(d.length_squared() < 1);
        vec3 n(0, 0, 1);
        CHECK(dot(random_on_hemisphere(n), n) >= 0);
        vec3 r = vec3::random(-2, 3);
        for (int k = 0; k < 3; ++k) {
            CHECK(r[k] >= -2);
            CHECK(r[k] < 3);
        }
    }
}

TEST_CASE("vec3: random_unit_vector and random_in_unit_disk draw the book's numbers in the book's order") {
    // The book's rejection loops written out by hand over rand() / (RAND_MAX + 1.0): a unit vector
    // from a cube point (drawn z, y, x) accepted in the ball and normalised; a disk point from a
    // square point (drawn y, x) accepted in the disk.
    auto uniform = [] { return -1 + 2 * (std::rand() / (RAND_MAX + 1.0)); };
    std::srand(2024);
    std::vector<vec3> units, disks;
    for (int i = 0; i < 200; ++i) {
        for (;;) {
            double z = uniform(), y = uniform(), x = uniform(), l2 = x * x + y * y + z * z;
            if (1e-160 < l2 && l2 <= 1) {
                units.push_back(vec3(x, y, z) / std::sqrt(l2));
                break;
            }
        }
        for (;;) {
            double y = uniform(), x = uniform();
            if (x * x + y * y < 1) {
                disks.push_back(vec3(x, y, 0));
                break;
            }
        }
    }
    std::srand(2024);
    for (int i = 0; i < 200; ++i) {
        const vec3 u = random_unit_vector(), d = random_in_unit_disk();
        for (int k = 0; k < 3; ++k) {
            CHECK(u[k] == units[size_t(i)][k]);
            CHECK(d[k] == disks[size_t(i)][k]);
        }
    }
    // Uniform on the sphere: each component has mean 0 and E[c^2] = 1/3 (variance of c^2: 1/5 -
    // 1/9 = 4/45). n = 20000: standard errors sqrt(1/3/n) = 0.0041 and sqrt(4/45/n) = 0.0021;
    // bounds at 5 sigma.
    std::srand(5);
    const int n = 20000;
    double sum[3] = {0, 0, 0}, sum_sq[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const vec3 u = random_unit_vector();
        for (int k = 0; k < 3; ++k) {
            sum[k] += u[k];
            sum_sq[k] += u[k] * u[k];
        }
    }
    for (int k = 0; k < 3; ++k) {
        CHECK(std::fabs(sum[k] / n) < 0.021);
        CHECK(std::fabs(sum_sq[k] / n - 1.0 / 3) < 0.0105);
    }
}

TEST_CASE("vec3: random_in_unit_sphere is uniform in the ball") {
    // For a uniform point in the unit ball, |p|^2 has mean 3/5 (the density of r is 3r^2, so
    // E[r^2] = integral 3r^4 dr = 3/5) and variance 3/7 - 9/25 = 12/175; every component has mean 0
    // and variance 1/5. With n = 20000 draws the standard error of the |p|^2 mean is
    // sqrt(12/175/20000) = 0.00185; 5 sigma is 0.0093. Component means: sqrt(0.2/20000) = 0.0032,
    // 5 sigma 0.016.
    std::srand(7);
    const int n = 20000;
    double sum_r2 = 0, sum[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        vec3 p = random_in_unit_sphere();
        REQUIRE(p.length_squared() < 1);
        sum_r2 += p.length_squared();
        for (int k = 0; k < 3; ++k) sum[k] += p[k];
    }
    CHECK(std::fabs(sum_r2 / n - 0.6) < 0.0093);
    for (double s : sum) CHECK(std::fabs(s / n) < 0.016);
}

TEST_CASE("vec3: random_in_hemisphere (the older books') is uniform in the half ball on the normal's side") {
    // Uniform in the half ball {|p| < 1, p.n > 0}: |p|^2 has mean 3/5 as in the whole ball (its
    // radial density is the same), and the component along n has mean 3/8 (the centroid of a
    // half ball), variance 1/5 - 9/64 = 19/320; across n, mean 0 and variance 1/5. With n = 20000
    // the standard errors are 0.00185, 0.0017 and 0.0032; 5 sigma bounds below.
    std::srand(11);
    const vec3 normal = unit_vector(vec3(1, 2, -2));
    const vec3 across = unit_vector(cross(normal, vec3(0, 0, 1)));
    const int n = 20000;
    double sum_r2 = 0, sum_along = 0, sum_across = 0;
    for (int i = 0; i < n; ++i) {
        vec3 p = random_in_hemisphere(normal);
        REQUIRE(p.length_squared() < 1);
        REQUIRE(dot(p, normal) >= 0);
        sum_r2 += p.length_squared();
        sum_along += dot(p, normal);
        sum_across += dot(p, across);
    }
    CHECK(std::fabs(sum_r2 / n - 0.6) < 0.0093);
    CHECK(std::fabs(sum_along / n - 0.375) < 0.0087);
    CHECK(std::fabs(sum_across / n) < 0.016);
}

TEST_CASE("vec3::random draws z, then y, then x (the book's g++ argument order)") {
    std::srand(2024);
    double z = std::rand() / (RAND_MAX + 1.0);
    double y = std::rand() / (RAND_MAX + 1.0);
    double x = std::rand() / (RAND_MAX + 1.0);
    std::srand(2024);
    vec3 v = vec3::random();
    CHECK(v.x() == x);
    CHECK(v.y() == y);
    CHECK(v.z() == z);
}

TEST_CASE("interval: contains, surrounds, clamp, size, expand") {
    interval i(1, 3);
    CHECK(i.size() == 2);
    // contains is closed: [1, 3]
    CHECK(i.contains(1));
    CHECK(i.contains(2));
    CHECK(i.contains(3));
    CHECK_FALSE(i.contains(0.999));
    CHECK_FALSE(i.contains(3.001));
    // surrounds is open: (1, 3)
    CHECK_FALSE(i.surrounds(1));
    CHECK(i.surrounds(2));
    CHECK_FALSE(i.surrounds(3));
    // clamp
    CHECK(i.clamp(0) == 1);
    CHECK(i.clamp(2.5) == 2.5);
    CHECK(i.clamp(10) == 3);
    // expand(delta) widens by delta/2 on each side: [1 - 0.5, 3 + 0.5]
    interval e = i.expand(1);
    CHECK(e.min == 0.5);
    CHECK(e.max == 3.5);
    CHECK(e.size() == 3);
    // NaN is in no interval
    double nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_FALSE(i.contains(nan));
    CHECK_FALSE(i.surrounds(nan));
}

TEST_CASE("interval: empty and universe") {
    interval d; // default is empty
    CHECK(d.min == infinity);
    CHECK(d.max == -infinity);
    CHECK_FALSE(d.contains(0));
    CHECK_FALSE(d.surrounds(0));
    CHECK(d.size() < 0);

    CHECK_FALSE(interval::empty.contains(0));
    CHECK_FALSE(interval::empty.contains(1e300));
    CHECK(interval::empty.size() == -infinity);

    CHECK(interval::universe.contains(0));
    CHECK(interval::universe.contains(-1e308));
    CHECK(interval::universe.surrounds(1e308));
    CHECK(interval::universe.contains(infinity)); // closed at infinity
    CHECK_FALSE(interval::universe.surrounds(infinity));
    CHECK(interval::universe.size() == infinity);
    CHECK(interval::universe.clamp(-5) == -5);
}

} // namespace test_vec3
