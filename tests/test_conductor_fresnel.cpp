// The exact Fresnel equations (rtweekend/core/fresnel.h) and the two materials built on them:
// conductor(n, k, tint) and the absorbing, exact-Fresnel dielectric(ior, absorption).
//
// Reference values are worked out by hand in the comments (closed forms where the angles allow
// them) or come from an independent implementation here: Fresnel's amplitude coefficients in
// complex arithmetic (std::complex), which covers dielectrics, total internal reflection and
// conductors with one formula and shares no code or algebra with fresnel.h. Statistical tests
// use level 0.01 with fixed seeds, as in test_statistics.cpp.

#include "chi_square.h"

#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <vector>

namespace test_conductor_fresnel {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;
constexpr double alpha = 0.01;

// Unpolarised reflectance from the amplitude coefficients (Born and Wolf, Principles of Optics,
// section 1.5.2; Hecht, Optics, section 4.6.2) for light from index 1 onto relative index N
// (complex for a conductor, N = n + ik): with w = N cos_t = sqrt(N^2 - sin_i^2),
//   r_s = (cos_i - w) / (cos_i + w),   r_p = (N^2 cos_i - w) / (N^2 cos_i + w).
// Under total internal reflection w is imaginary and |r_s| = |r_p| = 1 by itself.
double reference_rs(double cos_i, std::complex<double> N) {
    const std::complex<double> w = std::sqrt(N * N - (1 - cos_i * cos_i));
    return std::norm((cos_i - w) / (cos_i + w));
}
double reference_rp(double cos_i, std::complex<double> N) {
    const std::complex<double> w = std::sqrt(N * N - (1 - cos_i * cos_i));
    return std::norm((N * N * cos_i - w) / (N * N * cos_i + w));
}
double reference_reflectance(double cos_i, std::complex<double> N) {
    return 0.5 * (reference_rs(cos_i, N) + reference_rp(cos_i, N));
}


// An orthonormal tangent of the unit vector n.
vec3 tangent_of(const vec3& n) {
    vec3 a = std::fabs(n.x()) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0);
    return unit_vector(cross(n, a));
}

// The unit direction arriving at `angle_deg` from the normal `n` (travelling towards the surface).
vec3 incident(const vec3& n, double angle_deg) {
    double th = angle_deg * pi_d / 180;
    return -std::cos(th) * n + std::sin(th) * tangent_of(n);
}

// Compiling a world with one sphere of `mat` must throw a scene_error mentioning `fragment`.
void check_rejected_material(std::shared_ptr<material> mat, const std::string& fragment) {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, 0), 1, std::move(mat)));
    CAPTURE(fragment);
    bool threw = false;
    try {
        compile_scene(world, point3(0, 0, 5));
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find(fragment) != std::string::npos);
    }
    CHECK(threw);
}

compiled_material compiled_desc(std::shared_ptr<material> mat) {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, 0), 1, std::move(mat)));
    compiled_scene s = compile_scene(world, point3(0, 0, 5));
    REQUIRE(s.materials.size() == 1);
    return s.materials[0];
}

} // namespace

// ================================================================================================
// fresnel.h against hand-computed values

TEST_CASE("fresnel: dielectric at normal incidence is ((eta - 1) / (eta + 1))^2, from either side") {
    // 1.5: (0.5 / 2.5)^2 = 0.04; 2.4: (1.4 / 3.4)^2 = 0.169550173010...; 1.33: (0.33 / 2.33)^2 =
    // 0.020059312199...; from inside (eta = 1 / n) the same: r_s = -r_p = (1 - eta) / (1 + eta).
    CHECK(fresnel_dielectric(1, 1.5) == doctest::Approx(0.04).epsilon(1e-14));
    CHECK(fresnel_dielectric(1, 1 / 1.5) == doctest::Approx(0.04).epsilon(1e-14));
    CHECK(fresnel_dielectric(1, 2.4) == doctest::Approx(0.1695501730103806).epsilon(1e-14));
    CHECK(fresnel_dielectric(1, 1 / 2.4) == doctest::Approx(0.1695501730103806).epsilon(1e-14));
    CHECK(fresnel_dielectric(1, 1.33) == doctest::Approx(0.020059312199524768).epsilon(1e-13));
    CHECK(fresnel_dielectric(1, 1.0) == 0);
    CHECK(fresnel_dielectric(0.3, 1.0) < 1e-30); // no interface, no reflection
}

TEST_CASE("fresnel: at Brewster's angle R_p = 0, so R = R_s / 2 = 25/338 for n = 1.5, both sides") {
    // tan(theta_B) = eta. From air onto 1.5: cos_i = 1/sqrt(3.25), and theta_i + theta_t = 90 deg
    // gives cos_t = sin_i = 1.5/sqrt(3.25), so r_s = (cos_i - 1.5 cos_t) / (cos_i + 1.5 cos_t) =
    // (1 - 2.25) / (1 + 2.25) = -5/13: R_s = 25/169 and R = 25/338 = 0.0739644970414...
    // From inside (eta = 1/1.5): cos_i = 1.5/sqrt(3.25), cos_t = 1/sqrt(3.25),
    // r_s = (1.5 - 1/1.5) / (1.5 + 1/1.5) = 5/13: the same R.
    const double R = 25.0 / 338.0;
    CHECK(fresnel_dielectric(1 / std::sqrt(3.25), 1.5) == doctest::Approx(R).epsilon(1e-13));
    CHECK(fresnel_dielectric(1.5 / std::sqrt(3.25), 1 / 1.5) == doctest::Approx(R).epsilon(1e-13));
    // And the reference agrees that R_p vanishes there (a check of the reference).
    CHECK(reference_rp(1 / std::sqrt(3.25), 1.5) < 1e-30);
}

TEST_CASE("fresnel: at 45 degrees R_p = R_s^2, with R_s = (9 - 2 sqrt 14) / (9 + 2 sqrt 14) for n = 1.5") {
    // cos_i = sin_i = 1/sqrt 2, sin_t = sin_i / 1.5, cos_t = sqrt(7)/3, so 1.5 cos_t = sqrt(7)/2:
    // r_s = (1/sqrt 2 - sqrt(7)/2) / (1/sqrt 2 + sqrt(7)/2) = (sqrt 2 - sqrt 7) / (sqrt 2 + sqrt 7), so
    // R_s = (9 - 2 sqrt 14) / (9 + 2 sqrt 14) = 0.0920133630...; and (times 6 sqrt 2 above and below)
    // r_p = (1.5/sqrt 2 - sqrt(7)/3) / (1.5/sqrt 2 + sqrt(7)/3) = (9 - 2 sqrt 14) / (9 + 2 sqrt 14)
    // = R_s, so R_p = R_s^2 (Abeles' 45-degree relation) and R = (R_s + R_s^2) / 2.
    const double Rs = (9 - 2 * std::sqrt(14.0)) / (9 + 2 * std::sqrt(14.0));
    CHECK(fresnel_dielectric(std::sqrt(0.5), 1.5) == doctest::Approx((Rs + Rs * Rs) / 2).epsilon(1e-13));
    CHECK((Rs + Rs * Rs) / 2 == doctest::Approx(0.05023991101223595).epsilon(1e-13));
}

TEST_CASE("fresnel: grazing incidence reflects everything, total internal reflection returns exactly 1") {
    for (double eta : {1.33, 1.5, 2.4, 1 / 1.5}) {
        CAPTURE(eta);
        CHECK(fresnel_dielectric(0, eta) == 1);
        CHECK(fresnel_dielectric(1e-9, eta) > 0.999999);
        CHECK(fresnel_dielectric(-0.5, eta) == 1); // clamped: grazing
        CHECK(fresnel_dielectric(std::nan(""), eta) == 1);
    }
    // From inside glass of 1.5 the critical angle has sin = 1/1.5: cos_c = sqrt(5)/3 = 0.745356.
    const double cos_c = std::sqrt(5.0) / 3;
    for (double c : {0.0, 0.2, 0.5, 0.7, cos_c - 1e-9}) CHECK(fresnel_dielectric(c, 1 / 1.5) == 1);
    CHECK(fresnel_dielectric(cos_c + 1e-3, 1 / 1.5) < 1);
    CHECK(fresnel_dielectric(cos_c + 1e-9, 1 / 1.5) > 0.999); // continuous at the critical angle
    // Monotonic in the angle from normal incidence to the critical angle (no Brewster dip in R
    // itself for a dielectric, since R_s rises faster than R_p falls -- checked, not assumed,
    // against the reference).
    double prev = 0;
    for (int i = 0; i <= 200; ++i) {
        double c = 1 - (1 - cos_c) * i / 200.0 * 0.999999;
        double R = fresnel_dielectric(c, 1 / 1.5);
        CHECK(R == doctest::Approx(reference_reflectance(c, 1 / 1.5)).epsilon(1e-9));
        CHECK(R >= prev);
        prev = R;
    }
}

TEST_CASE("fresnel: dielectric equals the complex-amplitude reference at every angle, both sides") {
    for (double n : {1.0001, 1.33, 1.5, 2.4, 4.0}) {
        for (double eta : {n, 1 / n}) {
            for (int i = 0; i <= 100; ++i) {
                double c = i / 100.0;
                CAPTURE(eta);
                CAPTURE(c);
                double R = fresnel_dielectric(c, eta);
                CHECK(R == doctest::Approx(reference_reflectance(c, eta)).epsilon(1e-9));
                CHECK(fresnel_dielectric_f(float(c), float(eta)) == doctest::Approx(R).epsilon(2e-5));
            }
        }
    }
}

TEST_CASE("fresnel: conductor at normal incidence is ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2)") {
    // n = 0.2, k = 3.5: (0.64 + 12.25) / (1.44 + 12.25) = 12.89 / 13.69 = 0.941563184806...
    CHECK(fresnel_conductor(1, 0.2, 3.5) == doctest::Approx(12.89 / 13.69).epsilon(1e-14));
    // Aluminium near 550 nm, n = 0.958, k = 6.69 (A. D. Rakic, Appl. Opt. 34, 1995):
    // (0.001764 + 44.7561) / (3.833764 + 44.7561) = 0.921135815..., the familiar 92 % of an
    // aluminium mirror.
    CHECK(fresnel_conductor(1, 0.958, 6.69) == doctest::Approx(0.9211358154861269).epsilon(1e-13));
    for (double n : {0.05, 0.5, 1.0, 2.0, 7.0})
        for (double k : {0.0, 0.1, 1.0, 4.0, 30.0}) {
            CAPTURE(n);
            CAPTURE(k);
            double expect = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
            CHECK(fresnel_conductor(1, n, k) == doctest::Approx(expect).epsilon(1e-13));
        }
}

TEST_CASE("fresnel: conductor equals the complex-amplitude reference, and Abeles' R_p = R_s^2 at 45 degrees") {
    for (double n : {0.05, 0.18, 0.42, 1.0, 1.37, 3.0})
        for (double k : {0.0, 0.5, 1.77, 3.42, 7.0, 40.0})
            for (int i = 0; i <= 50; ++i) {
                double c = i / 50.0;
                CAPTURE(n);
                CAPTURE(k);
                CAPTURE(c);
                if (n == 1 && k == 0 && c == 0) continue; // no interface, at grazing: 0/0
                const std::complex<double> N(n, k);
                double R = fresnel_conductor(c, n, k);
                CHECK(R == doctest::Approx(reference_reflectance(c, N)).epsilon(1e-10));
                CHECK(R >= 0);
                CHECK(R <= 1);
                CHECK(fresnel_conductor_f(float(c), float(n), float(k)) == doctest::Approx(R).epsilon(1e-5));
                if (i == 0) CHECK(R == 1);
            }
    // At 45 degrees r_p = r_s^2 for any complex index (F. Abeles, 1950): R = (R_s + R_s^2) / 2.
    for (double n : {0.18, 1.37})
        for (double k : {0.5, 3.42}) {
            double Rs = reference_rs(std::sqrt(0.5), std::complex<double>(n, k));
            CHECK(fresnel_conductor(std::sqrt(0.5), n, k) == doctest::Approx((Rs + Rs * Rs) / 2).epsilon(1e-12));
        }
}

TEST_CASE("fresnel: conductor with k = 0 is the dielectric, total internal reflection included") {
    for (double n : {0.5, 1 / 1.5, 1.33, 1.5, 2.4})
        for (int i = 0; i <= 100; ++i) {
            double c = i / 100.0;
            CAPTURE(n);
            CAPTURE(c);
            CHECK(fresnel_conductor(c, n, 0) == doctest::Approx(fresnel_dielectric(c, n)).epsilon(1e-12));
        }
}

TEST_CASE("fresnel: a perfect conductor (k -> infinity) reflects everything, at every angle") {
    // For k >> n, a = n k / b ~ n and a^2 + b^2 ~ k^2 in fresnel.h's notation, so
    // 1 - R_s ~ 2 t2 / t1 = 4 n cos / k^2 and 1 - R_p / R_s ~ 2 t4 / t3 = 4 n cos sin^2 /
    // (cos^2 k^2 + sin^4) <= 4 n / (cos k^2): the p-polarised loss is the larger, near grazing
    // (it peaks at 2 n / k where cos = 1 / k, the principal angle of a good conductor).
    for (double k : {1e6, 1e15, 1e30})
        for (double c : {0.0, 0.01, 0.3, 0.7071, 1.0}) {
            CAPTURE(k);
            CAPTURE(c);
            const double R = fresnel_conductor(c, 1.0, k);
            CHECK(R <= 1);
            if (c == 0) CHECK(R == 1);
            else CHECK(1 - R <= 4 / (c * k * k) + 4 / (k * k));
            if (c >= 0.3) CHECK(fresnel_conductor_f(float(c), 1.0f, float(k)) == 1.0f);
        }
    // Near the principal angle the loss is of order 1 / k, not 1 / k^2 (a check that the bound
    // above is not vacuous): for k = 1e6 at cos = 1e-6, 1 - R ~ (2 n / k) / 2 = 1e-6.
    CHECK(1 - fresnel_conductor(1e-6, 1.0, 1e6) > 5e-7);
}

// ================================================================================================
// The teaching surface (material.h) and compile-time validation

TEST_CASE("conductor: the book-interface scatter() mirrors and weights by tint * Fr per channel") {
    const color n(0.18, 0.42, 1.37), k(3.42, 2.35, 1.77), tint(1.0, 0.5, 0.25);
    conductor gold(n, k, tint);
    const vec3 N = unit_vector(vec3(0.2, 1, -0.3));
    for (double angle : {0.0, 30.0, 60.0, 85.0}) {
        CAPTURE(angle);
        vec3 d = incident(N, angle);
        hit_record rec;
        rec.p = point3(1, 2, 3);
        rec.t = 1;
        rec.set_face_normal(ray(rec.p - d, d), N);
        color att;
        ray out;
        REQUIRE(gold.scatter(ray(rec.p - 2 * d, 2 * d), rec, att, out));
        // scatter() draws from the renderer's material contract, in float: to float precision.
        vec3 mirror = d - 2 * dot(d, N) * N;
        CHECK((unit_vector(out.direction()) - mirror).length() < 2e-7);
        for (int c = 0; c < 3; ++c)
            CHECK(att[c] == doctest::Approx(tint[c] * reference_reflectance(std::cos(angle * pi_d / 180),
                                                                          std::complex<double>(n[c], k[c])))
                                .epsilon(2e-6));
    }
    // The scalar constructor is the grey case.
    conductor grey(0.5, 2.0, color(1, 1, 1));
    CHECK(grey.n().x() == 0.5);
    CHECK(grey.k().z() == 2.0);
}

TEST_CASE("fresnel: the book-interface absorbing dielectric applies Beer's law on the way out only") {
    // A ray of direction length 2 hitting the back face at t = 0.75 has travelled 1.5 inside:
    // attenuation exp(-sigma 1.5) per channel. Entering (front face) it is not attenuated.
    const color sigma(0.0, 0.4, 2.0);
    dielectric glass(1.5, sigma);
    CHECK(glass.exact_fresnel());
    CHECK(!dielectric(1.5).exact_fresnel());
    const vec3 N(0, 1, 0), d = unit_vector(vec3(0.1, -1, 0)) * 2;
    hit_record rec;
    rec.p = point3(0, 0, 0);
    rec.t = 0.75;
    rec.set_face_normal(ray(rec.p - d, d), -N); // leaving through a surface whose outward normal is -y
    REQUIRE(!rec.front_face);
    color att;
    ray out;
    REQUIRE(glass.scatter(ray(rec.p - 0.75 * d, d), rec, att, out));
    for (int c = 0; c < 3; ++c) CHECK(att[c] == doctest::Approx(std::exp(-sigma[c] * 1.5)).epsilon(1e-6)); // float
    rec.set_face_normal(ray(rec.p - d, d), N);
    REQUIRE(rec.front_face);
    REQUIRE(glass.scatter(ray(rec.p - 0.75 * d, d), rec, att, out));
    CHECK((att.x() == 1 && att.y() == 1 && att.z() == 1));
}

TEST_CASE("conductor: compile_scene maps the new materials and keeps the book's glass Schlick") {
    compiled_material book = compiled_desc(std::make_shared<dielectric>(1.5));
    CHECK(book.is<dielectric_bsdf>());
    compiled_material exact = compiled_desc(std::make_shared<dielectric>(1.5, color(0.1, 0.2, 0.3)));
    CHECK(exact.is<fresnel_glass_bsdf>());
    CHECK(exact.as<fresnel_glass_bsdf>().refraction_index == 1.5f);
    CHECK(exact.as<fresnel_glass_bsdf>().absorption.z == 0.3f);
    compiled_material metal_desc =
        compiled_desc(std::make_shared<conductor>(color(0.2, 0.3, 0.4), color(3, 2, 1), color(1, 0.5, 0.25)));
    CHECK(metal_desc.is<conductor_bsdf>());
    CHECK(metal_desc.as<conductor_bsdf>().eta.y == 0.3f);
    CHECK(metal_desc.as<conductor_bsdf>().k.x == 3.0f);
    CHECK(metal_desc.as<conductor_bsdf>().tint.z == 0.25f);
}

TEST_CASE("conductor: invalid n, k, tint or absorption is a scene_error at compile time") {
    const double nan = std::nan(""), inf = INFINITY;
    const color one(1, 1, 1);
    check_rejected_material(std::make_shared<conductor>(0.0, 1.0, one), "conductor n must be positive");
    check_rejected_material(std::make_shared<conductor>(-1.0, 1.0, one), "conductor n");
    check_rejected_material(std::make_shared<conductor>(nan, 1.0, one), "conductor n");
    check_rejected_material(std::make_shared<conductor>(inf, 1.0, one), "conductor n");
    check_rejected_material(std::make_shared<conductor>(1.0, -0.5, one), "conductor k must be finite and non-negative");
    check_rejected_material(std::make_shared<conductor>(1.0, nan, one), "conductor k");
    check_rejected_material(std::make_shared<conductor>(1.0, inf, one), "conductor k");
    check_rejected_material(std::make_shared<conductor>(1.0, 1e39, one), "too large for single precision");
    check_rejected_material(std::make_shared<conductor>(1.0, 1.0, color(1, -0.1, 1)), "conductor tint");
    check_rejected_material(std::make_shared<conductor>(color(1, 1, 0), one, one), "conductor n must be positive");
    check_rejected_material(std::make_shared<dielectric>(1.5, color(0, -1, 0)), "dielectric absorption");
    check_rejected_material(std::make_shared<dielectric>(1.5, color(0, nan, 0)), "dielectric absorption");
    check_rejected_material(std::make_shared<dielectric>(1.5, color(inf, 0, 0)), "dielectric absorption");
    check_rejected_material(std::make_shared<dielectric>(0.0, color(0, 0, 0)), "refraction index must be positive");
    check_rejected_material(std::make_shared<dielectric>(nan, color(0, 0, 0)), "refraction index");
}

// ================================================================================================
// The material contract (core/bsdf.h)

TEST_CASE("conductor: the kernel mirrors exactly and weights by tint * Fr(cos) per channel") {
    const conductor_bsdf gold{{1.0f, 0.5f, 0.25f}, {0.18f, 0.42f, 1.37f}, {3.42f, 2.35f, 1.77f}};
    const compiled_material m = compiled_material::of(gold);
    pcg32 rng(7);
    const vec3 N = unit_vector(vec3(-0.3, 0.4, 0.9));
    for (double angle = 0; angle < 90; angle += 2.5) {
        CAPTURE(angle);
        vec3 d = incident(N, angle);
        for (bool front : {true, false}) {
            vec3f dir, att;
            REQUIRE(test::sample_direction(m, vec3f(d), vec3f(N), front, rng, dir, att));
            vec3 mirror = d - 2 * dot(d, N) * N;
            CHECK((dir.to_double() - mirror).length() < 1e-6);
            double c = std::cos(angle * pi_d / 180);
            for (int ch = 0; ch < 3; ++ch) {
                double Fr = reference_reflectance(c, std::complex<double>(gold.eta[ch], gold.k[ch]));
                CHECK(att[ch] == doctest::Approx(gold.tint[ch] * Fr).epsilon(1e-5));
            }
        }
    }
}

namespace {

struct exact_glass_case {
    double ior;
    bool front_face;
    double angle_deg;
};

// Counts reflections of N draws of the exact-Fresnel glass kernel and checks Snell's law and the
// weight (exactly 1) of every draw.
long count_exact_reflections(const exact_glass_case& g, float kernel_ior, long N, pcg32& rng) {
    const vec3 n = unit_vector(vec3(0.3, 0.9, -0.2));
    const vec3 wi = incident(n, g.angle_deg);
    const double ri = g.front_face ? 1 / g.ior : g.ior; // n_i / n_t
    // The absorption: the kernel ignores it (Beer's law is the tracer's).
    const compiled_material glass = compiled_material::of(fresnel_glass_bsdf{kernel_ior, {0.5f, 1.0f, 2.0f}});
    long reflected = 0;
    for (long i = 0; i < N; ++i) {
        vec3f dir, att;
        REQUIRE(test::sample_direction(glass, vec3f(wi), vec3f(n), g.front_face, rng, dir, att));
        if (!(att.x == 1 && att.y == 1 && att.z == 1)) FAIL_CHECK("weight is not 1");
        vec3 d = dir.to_double();
        if (std::fabs(d.length() - 1) > 1e-5) FAIL_CHECK("direction is not unit");
        if (dot(d, n) > 0) {
            ++reflected;
            if ((d - (wi - 2 * dot(wi, n) * n)).length() > 1e-5) FAIL_CHECK("not the mirror direction");
        } else if (kernel_ior == float(g.ior)) {
            // Snell: the tangential component of the refracted unit direction is ri sin(theta).
            if (std::fabs(cross(d, n).length() - ri * std::sin(g.angle_deg * pi_d / 180)) > 2e-5)
                FAIL_CHECK("not Snell's law");
        }
    }
    return reflected;
}

} // namespace

TEST_CASE("fresnel: the exact glass kernel reflects with probability Fr at many angles, both sides") {
    // Per case the reflection count of N draws is binomial(N, Fr), Fr from the complex reference;
    // z^2 = (k - N Fr)^2 / (N Fr (1 - Fr)) is approximately chi-square with 1 dof. Each case must
    // pass at alpha / m (Bonferroni over the m cases), and the sum of the z^2 (chi-square with
    // m dof) at alpha. Beyond the critical angle every draw must reflect. Grazing and Brewster
    // (56.31 deg for 1.5 outside, 33.69 inside) are among the angles, where Schlick is worst.
    std::vector<exact_glass_case> cases;
    for (double ior : {1.5, 2.4})
        for (bool front : {true, false})
            for (double a : {0.0, 20.0, 33.69, 40.0, 56.31, 70.0, 80.0, 87.0}) cases.push_back({ior, front, a});
    pcg32 rng(91);
    const long N = 20000;
    int m = 0;
    auto expected = [](const exact_glass_case& g) {
        double eta = g.front_face ? g.ior : 1 / g.ior;
        return reference_reflectance(std::cos(g.angle_deg * pi_d / 180), eta);
    };
    for (const auto& g : cases) m += expected(g) < 1 - 1e-12;
    double sum_z2 = 0;
    int total_internal = 0;
    for (const auto& g : cases) {
        CAPTURE(g.ior);
        CAPTURE(g.front_face);
        CAPTURE(g.angle_deg);
        const double R = expected(g);
        const long k = count_exact_reflections(g, float(g.ior), N, rng);
        if (R >= 1 - 1e-12) {
            ++total_internal;
            CHECK(k == N);
            continue;
        }
        const double z2 = (k - N * R) * (k - N * R) / (N * R * (1 - R));
        INFO("reflected " << k << " of " << N << ", expected " << N * R << ", z^2 = " << z2);
        CHECK(chi2::upper_tail(z2, 1) > alpha / m);
        sum_z2 += z2;
    }
    INFO("sum of z^2 = " << sum_z2 << " over " << m << " cases");
    CHECK(total_internal >= 6); // inside, past the critical angle (41.8 and 24.6 deg)
    CHECK(m >= 20);
    CHECK(chi2::upper_tail(sum_z2, m) > alpha);
}

TEST_CASE("fresnel power: the binomial test tells exact Fresnel from Schlick, and 1.5 from 1.6") {
    // At 80 deg onto 1.5, exact Fr = 0.3877 and Schlick 0.04 + 0.96 (1 - cos 80)^5 = 0.4099: a
    // shift of 444 reflections in N = 20000, 6.4 standard deviations (sqrt(N 0.41 0.59) = 70).
    pcg32 rng(92);
    const long N = 20000;
    const exact_glass_case g{1.5, true, 80};
    const double c = std::cos(80 * pi_d / 180);
    const double schlick = 0.04 + 0.96 * std::pow(1 - c, 5);
    long k = count_exact_reflections(g, 1.5f, N, rng);
    double z2 = (k - N * schlick) * (k - N * schlick) / (N * schlick * (1 - schlick));
    CHECK(chi2::upper_tail(z2, 1) < 1e-4);
    // Normal incidence, kernel 1.6 (Fr = 0.0533) against 1.5 (0.04): 13 standard deviations.
    k = count_exact_reflections({1.5, true, 0}, 1.6f, 2 * N, rng);
    z2 = (k - 2 * N * 0.04) * (k - 2 * N * 0.04) / (2 * N * 0.04 * 0.96);
    CHECK(chi2::upper_tail(z2, 1) < 1e-6);
}

// ================================================================================================
// Renders

TEST_CASE("conductor: a perfect conductor sphere (k huge, tint 1) renders exactly the background") {
    // For k = 1e8, 1 - Fr <= 4 / (cos k^2) + 4 / k^2 < 1e-11 (see the perfect-conductor test above)
    // wherever cos > 1e-4, which is all but a fraction 1e-8 of the sphere's disk: there Fr rounds
    // to 1 in float. Every camera ray that hits the convex sphere reflects once and escapes
    // carrying B; the others see B directly.
    const color B(0.25, 0.5, 1.0);
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<conductor>(1.0, 1e8, color(1, 1, 1))));
    camera cam = test::test_camera(16, 16, 4, 8);
    cam.background = B;
    cam.vfov = 60;
    cam.lookfrom = point3(0, 1, 3);
    cam.lookat = point3(0, 0, 0);
    render_result r = render(cam, world);
    CHECK(r.stats.nonfinite_samples == 0);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            color p = r.img.pixel(x, y);
            CHECK((p.x() == B.x() && p.y() == B.y() && p.z() == B.z()));
        }
}

TEST_CASE("conductor: every pixel of a gold sphere is tint * Fr(cos) * B at the pixel centre's ray") {
    // One sample per pixel is the pixel centre's ray (no jitter). A unit sphere seen from 1.5 away
    // with vfov 50 fills the view (its angular radius asin(1/1.5) = 41.8 deg exceeds the 33.4 deg
    // half-diagonal), and a ray that reflects off the convex sphere escapes: every pixel is
    // tint * Fr(cos) * B for the cosine at its centre ray, computed here by an independent
    // ray-sphere intersection and the complex-amplitude reference, per channel. Every sample is
    // exactly two rays.
    const color n(0.18, 0.42, 1.37), k(3.42, 2.35, 1.77), tint(1.0, 0.9, 0.8), B(1.0, 0.75, 0.5);
    const int W = 24, H = 24;
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<conductor>(n, k, tint)));
    camera cam = test::test_camera(W, H, 1, 4);
    cam.background = B;
    cam.vfov = 50;
    cam.lookfrom = point3(0, 0, 1.5);
    cam.lookat = point3(0, 0, 0);
    render_result r = render(cam, world);
    CHECK(r.stats.rays == 2 * uint64_t(W) * H);
    const double half = std::tan(25 * pi_d / 180);
    const vec3 O(0, 0, 1.5);
    int bad = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            vec3 d = unit_vector(vec3((2 * (x + 0.5) / W - 1) * half, (1 - 2 * (y + 0.5) / H) * half, -1));
            double h = -dot(O, d), disc = h * h - (dot(O, O) - 1);
            REQUIRE(disc > 0);
            vec3 normal = O + (h - std::sqrt(disc)) * d;
            double c = -dot(d, normal);
            color p = r.img.pixel(x, y);
            for (int ch = 0; ch < 3; ++ch) {
                double expect = tint[ch] * B[ch] * reference_reflectance(c, std::complex<double>(n[ch], k[ch]));
                if (std::fabs(p[ch] - expect) > 2e-5 && bad++ < 3)
                    FAIL_CHECK("pixel (" << x << "," << y << ") channel " << ch << " = " << p[ch] << ", expected "
                                         << expect);
            }
        }
    CHECK(bad == 0);
}

TEST_CASE("fresnel: a clear exact-Fresnel glass sphere renders exactly a constant background") {
    // Absorption 0 and weight 1 at every event: an escaping path carries exactly B, so every pixel
    // is B unless a path is still inside at max_depth 64. Inside a sphere every wall is met at the
    // refraction angle of entry, where the reflectance equals the entry's R (Stokes' relations),
    // so a path entering at R is trapped with probability <= (1 - R) R^62 <= 0.006. R > 0.75 needs
    // an entry cosine below 0.05, a fraction 0.05^2 of the sphere's disk; elsewhere the trap
    // probability is below 0.75^62 = 2e-8: over 2048 samples the expected loss is below 1e-4.
    const color B(0.25, 0.5, 0.75);
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, 0), 1, std::make_shared<dielectric>(1.5, color(0, 0, 0))));
    camera cam = test::test_camera(16, 16, 8, 64);
    cam.background = B;
    cam.vfov = 30;
    cam.lookfrom = point3(0.5, 1, 3);
    cam.lookat = point3(0, 0, 0);
    render_result r = render(cam, world);
    CHECK(r.stats.nonfinite_samples == 0);
    int bad = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            color p = r.img.pixel(x, y);
            if (!(p.x() == B.x() && p.y() == B.y() && p.z() == B.z()) && bad++ < 3)
                FAIL_CHECK("pixel (" << x << "," << y << ") = " << p);
        }
    CHECK(bad == 0);
}

TEST_CASE("fresnel: Beer's law through an absorbing slab, multiple internal reflections included") {
    // A slab of glass (ior 2.4, thickness d = 0.5, absorption sigma per channel) between the
    // planes y = 0 and y = -d, made of two 200 x 200 squares (outward normals +y and -y; the
    // open sides are far out of reach). The camera looks straight down from y = 5 with a 1-degree
    // field of view, under the book's sky: a ray going down sees white D = (1, 1, 1), a ray going
    // up sees U = (0.5, 0.7, 1) (within 2e-5 for directions within 0.7 deg of vertical).
    //
    // At normal incidence R = ((2.4 - 1) / (2.4 + 1))^2 at both faces, and one crossing keeps
    // tau = exp(-sigma d). A sample's path is one of:
    //   reflected at the top:                                 probability R,                  value U
    //   down through after j round trips inside (j >= 0):     (1 - R)^2 R^(2j),               tau^(2j+1) D
    //   back up after j round trips and one more reflection:  (1 - R)^2 R^(2j+1),             tau^(2j+2) U
    // (every bounce is a ray; paths lost to max_depth 40 have probability < R^36 < 1e-27).
    // Summing the geometric series:
    //   E[X]   = R U + (1 - R)^2 tau / (1 - R^2 tau^2) D + (1 - R)^2 R tau^2 / (1 - R^2 tau^2) U
    //   E[X^2] = R U^2 + (1 - R)^2 tau^2 / (1 - R^2 tau^4) D^2 + (1 - R)^2 R tau^4 / (1 - R^2 tau^4) U^2
    // -- the classic slab transmittance (1 - R)^2 tau / (1 - R^2 tau^2) and reflectance
    // R + (1 - R)^2 R tau^2 / (1 - R^2 tau^2), weighted by what each side sees. The image's mean
    // over its N equal-weight samples is then normal with that mean and variance Var / N per
    // channel; each channel must be within 2.935 standard errors (two-sided alpha / 3).
    const double ior = 2.4, d = 0.5, L = 100;
    const color sigma(0.0, 0.6, 2.0);
    auto glass = std::make_shared<dielectric>(ior, sigma);
    hittable_list world;
    auto quad = [&](double y, bool up) { // two triangles, outward normal +y (up) or -y
        point3 a(-L, y, -L), b(-L, y, L), c(L, y, -L), e(L, y, L);
        if (up) {
            world.add(std::make_shared<triangle>(a, b, c, glass)); // (b - a) x (c - a) = +y
            world.add(std::make_shared<triangle>(e, c, b, glass));
        } else {
            world.add(std::make_shared<triangle>(a, c, b, glass));
            world.add(std::make_shared<triangle>(e, b, c, glass));
        }
    };
    quad(0, true);
    quad(-d, false);
    camera cam = test::test_camera(16, 16, 256, 40);
    cam.vfov = 1;
    cam.lookfrom = point3(0, 5, 0);
    cam.lookat = point3(0, 0, 0);
    cam.vup = vec3(0, 0, -1);
    cam.settings.seed = 11;
    render_result r = render(cam, world);
    CHECK(r.stats.nonfinite_samples == 0);

    const double R = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    const color U(0.5, 0.7, 1.0), D(1, 1, 1);
    const double N = 16.0 * 16.0 * 256.0;
    for (int ch = 0; ch < 3; ++ch) {
        CAPTURE(ch);
        const double tau = std::exp(-sigma[ch] * d), t2 = tau * tau, q = (1 - R) * (1 - R);
        const double mean = R * U[ch] + q * tau / (1 - R * R * t2) * D[ch] + q * R * t2 / (1 - R * R * t2) * U[ch];
        const double second = R * U[ch] * U[ch] + q * t2 / (1 - R * R * t2 * t2) * D[ch] * D[ch] +
                              q * R * t2 * t2 / (1 - R * R * t2 * t2) * U[ch] * U[ch];
        const double se = std::sqrt((second - mean * mean) / N);
        double sum = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) sum += r.img.pixel(x, y)[ch];
        const double observed = sum / 256;
        INFO("observed " << observed << ", expected " << mean << ", standard error " << se);
        CHECK(std::fabs(observed - mean) <= 2.935 * se);
        // Power: without Beer's law (tau = 1) the expectation differs by many standard errors.
        if (sigma[ch] > 0) {
            const double clear = R * U[ch] + (1 - R) / (1 + R) * D[ch] + (1 - R) * R / (1 + R) * U[ch];
            CHECK(std::fabs(observed - clear) > 20 * se);
        }
    }
}

} // namespace test_conductor_fresnel
