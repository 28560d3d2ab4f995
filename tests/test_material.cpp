// Materials: Schlick's approximation, refraction (Snell's law), and the scattering of the three
// book materials, both through the renderer's material contract (rtweekend/core/bsdf.h: sample()) and
// the book's virtual scatter() (rtweekend/material.h).
//
// Statistical checks use fixed seeds and 5-sigma bounds, derived in the comments: for a fraction
// with success probability p over N independent draws the count has standard deviation
// sqrt(N p (1 - p)); for a mean of N draws of a variable with variance V the standard error is
// sqrt(V / N).

#include <rtweekend/core/bsdf.h>
#include <rtweekend/material.h>
#include <rtweekend/core/rng.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <cstdlib>

namespace test_material {

using namespace rt;

namespace {

constexpr double deg = 3.14159265358979323846 / 180.0;

compiled_material make_dielectric(float ior) { return compiled_material::of(dielectric_bsdf{ior}); }

compiled_material make_metal(vec3f albedo, float fuzz) { return compiled_material::of(metal_bsdf{albedo, fuzz}); }

compiled_material make_lambertian(vec3f albedo) { return compiled_material::of(lambertian_bsdf{albedo}); }

// A unit direction travelling downwards at angle theta from the -y axis, in the xy plane; the
// surface normal facing it is +y.
vec3 incident(double theta) { return vec3(std::sin(theta), -std::cos(theta), 0); }

// The binomial 5-sigma check: |count - N p| <= 5 sqrt(N p (1 - p)).
void check_binomial(long count, long n, double p) {
    double mean = n * p, sigma = std::sqrt(n * p * (1 - p));
    INFO("count " << count << " of " << n << ", expected " << mean << " +- " << sigma);
    CHECK(std::fabs(double(count) - mean) <= 5 * sigma);
}

} // namespace

// ------------------------------------------------------------------------------------------------
// Schlick

TEST_CASE("schlick_reflectance: normal incidence, grazing, and a hand-computed middle value") {
    // Normal incidence (cos = 1): r0 = ((1 - n)/(1 + n))^2; for n = 1.5: (-0.5/2.5)^2 = 0.04.
    CHECK(schlick_reflectance(1.0, 1.5) == doctest::Approx(0.04).epsilon(1e-14));
    // r0 is symmetric in n <-> 1/n: ((1 - 2/3)/(1 + 2/3))^2 = (1/5)^2 = 0.04.
    CHECK(schlick_reflectance(1.0, 1.0 / 1.5) == doctest::Approx(0.04).epsilon(1e-14));
    // n = 1.33: (0.33/2.33)^2 = 0.0200593...
    CHECK(schlick_reflectance(1.0, 1.33) == doctest::Approx((0.33 / 2.33) * (0.33 / 2.33)).epsilon(1e-14));
    // Matched indices: no reflection at normal incidence.
    CHECK(schlick_reflectance(1.0, 1.0) == 0);
    // Grazing (cos = 0): r0 + (1 - r0) * 1 = 1 for any index.
    CHECK(schlick_reflectance(0.0, 1.5) == doctest::Approx(1).epsilon(1e-15));
    CHECK(schlick_reflectance(0.0, 1.0 / 1.5) == doctest::Approx(1).epsilon(1e-15));
    CHECK(schlick_reflectance(0.0, 2.4) == doctest::Approx(1).epsilon(1e-15));
    // cos = 0.5, ri = 1/1.5: r0 = 0.04, (1 - 0.5)^5 = 0.03125, 0.04 + 0.96 * 0.03125 = 0.04 + 0.03 = 0.07.
    CHECK(schlick_reflectance(0.5, 1.0 / 1.5) == doctest::Approx(0.07).epsilon(1e-14));

    // The same function in float, as the float kernels use it, agrees to float precision.
    CHECK(schlick_reflectance(1.0f, 1.5f) == doctest::Approx(0.04).epsilon(1e-6));
    CHECK(schlick_reflectance(0.0f, 1.5f) == doctest::Approx(1).epsilon(1e-6));
    CHECK(schlick_reflectance(0.5f, 1.0f / 1.5f) == doctest::Approx(0.07).epsilon(1e-6));
}

// ------------------------------------------------------------------------------------------------
// Refraction

TEST_CASE("refract obeys Snell's law and returns a unit vector") {
    const vec3 n(0, 1, 0);
    // eta = n1 / n2. Into glass, into water, out of glass (below the critical angle), and matched.
    const double etas[] = {1 / 1.5, 1 / 1.33, 1.5, 1.0};
    const double angles[] = {0, 10, 20, 30, 40, 45, 60, 75, 89};
    for (double eta : etas) {
        for (double a : angles) {
            double theta1 = a * deg;
            double sin2 = eta * std::sin(theta1);
            if (sin2 >= 1) continue; // beyond the critical angle: no refracted ray
            CAPTURE(eta);
            CAPTURE(a);
            vec3 uv = incident(theta1);
            vec3 r = refract(uv, n, eta);
            CHECK(r.length() == doctest::Approx(1).epsilon(1e-12));
            // Snell: n1 sin(theta1) = n2 sin(theta2)  <=>  sin(theta2) = eta sin(theta1).
            CHECK(r.x() == doctest::Approx(sin2).epsilon(1e-12).scale(1e-12));
            CHECK(r.y() == doctest::Approx(-std::sqrt(1 - sin2 * sin2)).epsilon(1e-12)); // goes through
            CHECK(r.z() == 0); // stays in the plane of incidence

            vec3f rf = refract_f(vec3f(uv), vec3f(n), float(std::cos(theta1)), float(eta));
            CHECK(length(rf) == doctest::Approx(1).epsilon(1e-5));
            CHECK(rf.x == doctest::Approx(sin2).epsilon(1e-5).scale(1e-6));
            CHECK(rf.y == doctest::Approx(-std::sqrt(1 - sin2 * sin2)).epsilon(1e-5));
        }
    }
    // eta = 1: the ray is unchanged.
    vec3 uv = incident(37 * deg), r = refract(uv, n, 1.0);
    CHECK(r.x() == doctest::Approx(uv.x()).epsilon(1e-14));
    CHECK(r.y() == doctest::Approx(uv.y()).epsilon(1e-14));
}

TEST_CASE("refract in general position: coplanar with the incident ray and the normal, Snell holds") {
    std::srand(4);
    for (int i = 0; i < 500; ++i) {
        vec3 n = random_unit_vector();
        vec3 uv = random_unit_vector();
        if (dot(uv, n) > 0) uv = -uv; // the normal faces the incident ray
        if (dot(uv, n) > -1e-3) continue;
        double eta = 0.5 + random_double(); // 0.5 .. 1.5
        double cos1 = -dot(uv, n), sin1 = std::sqrt(1 - cos1 * cos1);
        if (eta * sin1 >= 0.999) continue;
        vec3 r = refract(uv, n, eta);
        CHECK(r.length() == doctest::Approx(1).epsilon(1e-10));
        // Coplanar: r has no component along n x uv.
        CHECK(std::fabs(dot(r, unit_vector(cross(n, uv)))) < 1e-10);
        double cos2 = -dot(r, n);
        CHECK(cos2 > 0);
        double sin2 = std::sqrt(std::fmax(0.0, 1 - cos2 * cos2));
        CHECK(sin2 == doctest::Approx(eta * sin1).epsilon(1e-8).scale(1e-8));
    }
}

// ------------------------------------------------------------------------------------------------
// Dielectric

TEST_CASE("dielectric: total internal reflection beyond the critical angle, always the mirror direction") {
    // From inside glass (front_face false, ri = 1.5) the critical angle is asin(1/1.5) = 41.81 deg.
    // Beyond it ri * sin(theta) > 1 and every draw must reflect: the outgoing direction is the
    // mirror image (sin theta, cos theta, 0) of the incident (sin theta, -cos theta, 0).
    const compiled_material glass = make_dielectric(1.5f);
    const vec3f n(0, 1, 0);
    pcg32 rng(2718);
    for (double a : {42.0, 45.0, 60.0, 80.0, 89.0}) {
        CAPTURE(a);
        CHECK(1.5 * std::sin(a * deg) > 1); // really beyond the critical angle
        vec3f wi(incident(a * deg));
        long mirrors = 0;
        const long N = 2000;
        for (long i = 0; i < N; ++i) {
            vec3f dir, att;
            REQUIRE(test::sample_direction(glass, wi, n, /*front_face=*/false, rng, dir, att));
            CHECK(att.x == 1);
            CHECK(att.y == 1);
            CHECK(att.z == 1);
            if (std::fabs(dir.x - std::sin(a * deg)) < 1e-6 && std::fabs(dir.y - std::cos(a * deg)) < 1e-6 &&
                std::fabs(dir.z) < 1e-6)
                ++mirrors;
        }
        CHECK(mirrors == N);
    }

    // The book's virtual dielectric::scatter does the same (it draws from rand() here).
    std::srand(11);
    dielectric book_glass(1.5);
    hit_record rec;
    rec.p = point3(0, 0, 0);
    rec.normal = vec3(0, 1, 0);
    rec.front_face = false;
    for (double a : {42.0, 70.0}) {
        for (int i = 0; i < 500; ++i) {
            color att;
            ray out;
            REQUIRE(book_glass.scatter(ray(point3(0, 1, 0), incident(a * deg)), rec, att, out));
            vec3 d = unit_vector(out.direction());
            // To float precision: scatter() draws from the renderer's float material contract.
            CHECK(d.x() == doctest::Approx(std::sin(a * deg)).epsilon(1e-6));
            CHECK(d.y() == doctest::Approx(std::cos(a * deg)).epsilon(1e-6));
            CHECK(att.x() == 1);
        }
    }
}

TEST_CASE("dielectric: below the critical angle the reflected fraction matches Schlick") {
    // For each case, R is Schlick's value written out by hand: r0 = ((1 - ri)/(1 + ri))^2 = 0.04
    // for ri = 1.5 or 1/1.5, R = r0 + (1 - r0)(1 - cos)^5. Reflections are recognised by the
    // direction going back to the normal's side (dir.y > 0); refractions must obey Snell.
    struct scenario {
        double angle_deg;
        bool front_face;
        double ri; // ratio used by the material: 1/1.5 entering, 1.5 leaving
    };
    const scenario cases[] = {{0, true, 1 / 1.5}, {30, false, 1.5}, {80, true, 1 / 1.5}, {40, false, 1.5}};
    const compiled_material glass = make_dielectric(1.5f);
    const vec3f n(0, 1, 0);
    pcg32 rng(31415);
    for (const scenario& sc : cases) {
        CAPTURE(sc.angle_deg);
        double c = std::cos(sc.angle_deg * deg);
        double R = 0.04 + 0.96 * std::pow(1 - c, 5);
        // e.g. 80 deg entering: cos = 0.173648, (0.826352)^5 = 0.385229, R = 0.409820
        //      30 deg leaving:  cos = 0.866025, (0.133975)^5 = 4.31e-5,  R = 0.040041
        vec3f wi(incident(sc.angle_deg * deg));
        double sin_t = sc.ri * std::sin(sc.angle_deg * deg);
        const long N = 200000;
        long reflected = 0;
        for (long i = 0; i < N; ++i) {
            vec3f dir, att;
            REQUIRE(test::sample_direction(glass, wi, n, sc.front_face, rng, dir, att));
            if (dir.y > 0) {
                ++reflected;
            } else if (i % 97 == 0) { // spot-check refracted directions
                CHECK(length(dir) == doctest::Approx(1).epsilon(1e-5));
                CHECK(dir.x == doctest::Approx(sin_t).epsilon(1e-4).scale(1e-5));
            }
        }
        check_binomial(reflected, N, R);
    }
}

// ------------------------------------------------------------------------------------------------
// Lambertian

TEST_CASE("lambertian sample(): unit directions on the normal's side, cosine distributed") {
    // Cosine-weighted hemisphere: mu = cos(theta) has density 2 mu on [0, 1], so
    //   E[mu] = 2/3, E[mu^2] = 1/2, Var[mu] = 1/2 - 4/9 = 1/18, Var[mu^2] = E[mu^4] - 1/4 = 1/3 - 1/4 = 1/12,
    //   P(mu > 1/2) = 1 - (1/2)^2 = 3/4.
    // A tangent component t = sin(theta) cos(phi) has mean 0 and variance E[sin^2] / 2 = (1 - 1/2)/2 = 1/4.
    const compiled_material m = make_lambertian({0.25f, 0.5f, 0.75f});
    const vec3f n = normalize(vec3f(1, 2, 3));
    const vec3f t = normalize(cross(n, vec3f(0, 0, 1))); // a unit tangent
    const vec3f wi = normalize(vec3f(0.3f, -1, -0.2f));
    pcg32 rng(1234);
    const long N = 200000;
    double sum_mu = 0, sum_mu2 = 0, sum_t = 0;
    long above_half = 0;
    for (long i = 0; i < N; ++i) {
        vec3f dir, att;
        REQUIRE(test::sample_direction(m, wi, n, true, rng, dir, att));
        if (i < 1000) {
            CHECK(att.x == 0.25f);
            CHECK(att.y == 0.5f);
            CHECK(att.z == 0.75f);
        }
        float len = length(dir);
        if (std::fabs(len - 1) > 1e-5f) FAIL_CHECK("direction not unit: " << len);
        double mu = dot(dir, n);
        if (mu < -1e-6) FAIL_CHECK("direction below the surface: cos = " << mu);
        sum_mu += mu;
        sum_mu2 += mu * mu;
        sum_t += dot(dir, t);
        if (mu > 0.5) ++above_half;
    }
    CHECK(std::fabs(sum_mu / N - 2.0 / 3.0) <= 5 * std::sqrt(1.0 / 18.0 / N));  // 5 sigma = 2.6e-3
    CHECK(std::fabs(sum_mu2 / N - 0.5) <= 5 * std::sqrt(1.0 / 12.0 / N));       // 5 sigma = 3.2e-3
    CHECK(std::fabs(sum_t / N) <= 5 * std::sqrt(0.25 / N));                      // 5 sigma = 5.6e-3
    check_binomial(above_half, N, 0.75);
}

TEST_CASE("lambertian::scatter (book path): normal + unit vector is cosine distributed") {
    // Same moments as above, for the normalised scattered direction.
    std::srand(77);
    lambertian mat(color(0.2, 0.4, 0.6));
    hit_record rec;
    rec.p = point3(1, 2, 3);
    rec.normal = unit_vector(vec3(-1, 1, 2));
    rec.front_face = true;
    const long N = 50000;
    double sum_mu = 0;
    for (long i = 0; i < N; ++i) {
        color att;
        ray out;
        REQUIRE(mat.scatter(ray(point3(0, 0, 0), vec3(1, 1, 1)), rec, att, out));
        if (i == 0) {
            CHECK(att.x() == double(0.2f)); // the albedo as the float contract holds it
            CHECK(out.origin().x() == 1);
            CHECK(out.origin().z() == 3);
        }
        double mu = dot(unit_vector(out.direction()), rec.normal);
        if (mu < -1e-12) FAIL_CHECK("direction below the surface");
        sum_mu += mu;
    }
    CHECK(std::fabs(sum_mu / N - 2.0 / 3.0) <= 5 * std::sqrt(1.0 / 18.0 / N));
}

// ------------------------------------------------------------------------------------------------
// Metal

TEST_CASE("metal with fuzz 0 reflects exactly into the mirror direction") {
    const compiled_material m = make_metal({0.9f, 0.8f, 0.7f}, 0);
    const vec3f n(0, 1, 0);
    pcg32 rng(5);
    for (double a : {0.0, 15.0, 45.0, 70.0, 89.0}) {
        CAPTURE(a);
        vec3f dir, att;
        REQUIRE(test::sample_direction(m, vec3f(incident(a * deg)), n, true, rng, dir, att));
        CHECK(dir.x == doctest::Approx(std::sin(a * deg)).epsilon(1e-6).scale(1e-6));
        CHECK(dir.y == doctest::Approx(std::cos(a * deg)).epsilon(1e-6).scale(1e-6));
        CHECK(dir.z == 0);
        CHECK(att.x == 0.9f);
        CHECK(att.y == 0.8f);
        CHECK(att.z == 0.7f);
    }
    // General position: mirror about a tilted normal. n = (0,1,1)/sqrt2, wi = (0,0,-1):
    // wi - 2 (wi.n) n = (0,0,-1) + sqrt2 (0,1,1)/sqrt2 = (0,1,0).
    vec3f dir, att;
    REQUIRE(test::sample_direction(m, vec3f(0, 0, -1), normalize(vec3f(0, 1, 1)), true, rng, dir, att));
    CHECK(std::fabs(dir.x) < 1e-6f);
    CHECK(dir.y == doctest::Approx(1).epsilon(1e-6));
    CHECK(std::fabs(dir.z) < 1e-6f);

    // The book's metal::scatter with fuzz 0: the mirror of the unit incident direction.
    std::srand(3);
    metal book(color(0.5, 0.6, 0.7), 0.0);
    hit_record rec;
    rec.normal = vec3(0, 1, 0);
    rec.front_face = true;
    color c;
    ray out;
    REQUIRE(book.scatter(ray(point3(0, 1, 0), 3 * incident(30 * deg)), rec, c, out));
    // To float precision: scatter() draws from the renderer's float material contract.
    CHECK(out.direction().x() == doctest::Approx(0.5).epsilon(1e-6));
    CHECK(out.direction().y() == doctest::Approx(std::cos(30 * deg)).epsilon(1e-6));
    CHECK(c.y() == double(0.6f));
}

TEST_CASE("metal fuzz: absorbed below the surface at grazing incidence, never at normal incidence") {
    // d = mirror + fuzz * s, s uniform inside the unit ball, is absorbed when d.n <= 0, i.e. when
    // s.n <= -a with a = mirror.n / fuzz. One coordinate of a uniform point in the unit ball has
    // density (3/4)(1 - x^2) on [-1, 1] (the area of the slice at x), so
    //   P(absorb) = integral_{-1}^{-a} (3/4)(1 - x^2) dx = 1/2 - 3a/4 + a^3/4   (for a <= 1).
    // Incidence 85 deg, fuzz 0.5: a = cos 85 / 0.5 = 0.1743115, P = 0.5 - 0.1307336 + 0.0013241
    // = 0.3705905.
    // Incidence 0 deg, fuzz 0.9: mirror.n = 1 > fuzz, so d.n >= 1 - 0.9 > 0: never absorbed.
    const vec3f n(0, 1, 0);
    pcg32 rng(8080);
    const long N = 100000;
    {
        const compiled_material m = make_metal({1, 1, 1}, 0.5f);
        vec3f wi(incident(85 * deg));
        long absorbed = 0;
        for (long i = 0; i < N; ++i) {
            vec3f dir, att;
            if (!test::sample_direction(m, wi, n, true, rng, dir, att)) {
                ++absorbed;
            } else {
                if (std::fabs(length(dir) - 1) > 1e-5f) FAIL_CHECK("not unit");
                if (!(dir.y > 0)) FAIL_CHECK("accepted a direction below the surface");
            }
        }
        const double a = std::cos(85 * deg) / 0.5;
        check_binomial(absorbed, N, 0.5 - 0.75 * a + 0.25 * a * a * a);
        CHECK(absorbed > 0);
    }
    for (float fuzz : {0.9f, 0.999f}) {
        const compiled_material m = make_metal({1, 1, 1}, fuzz);
        long absorbed = 0;
        for (long i = 0; i < N / 4; ++i) {
            vec3f dir, att;
            if (!test::sample_direction(m, vec3f(0, -1, 0), n, true, rng, dir, att)) ++absorbed;
        }
        CHECK(absorbed == 0);
    }

    // The book's metal::scatter: the same law (random_in_unit_sphere is uniform in the ball).
    // 60 deg, fuzz 1: a = 0.5, P = 0.5 - 0.375 + 0.03125 = 0.15625.
    std::srand(99);
    metal book(color(1, 1, 1), 1.0);
    hit_record rec;
    rec.normal = vec3(0, 1, 0);
    rec.front_face = true;
    long absorbed = 0;
    const long M = 40000;
    for (long i = 0; i < M; ++i) {
        color c;
        ray out;
        if (!book.scatter(ray(point3(0, 1, 0), incident(60 * deg)), rec, c, out)) ++absorbed;
    }
    check_binomial(absorbed, M, 0.15625);
}

TEST_CASE("metal constructor clamps fuzz to 1") {
    CHECK(metal(color(1, 1, 1), 5.0).fuzz() == 1);
    CHECK(metal(color(1, 1, 1), 0.3).fuzz() == 0.3);
    CHECK(metal(color(0.1, 0.2, 0.3), 0).albedo().z() == 0.3);
}

TEST_CASE("the base material absorbs everything") {
    material m;
    hit_record rec;
    color c;
    ray out;
    CHECK_FALSE(m.scatter(ray(point3(0, 0, 0), vec3(1, 0, 0)), rec, c, out));
}

} // namespace test_material
