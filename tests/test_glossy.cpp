// The glossy materials of the contract (rtweekend/core/bsdf.h): plastic (a Lambertian base under
// a smooth dielectric coat) and blinn_phong (a Lambertian lobe plus a normalised Blinn-Phong
// lobe), and the course scenes' mapping to blinn_phong. The generic contract checks (value ==
// eval / pdf, chi-square about the normal, reciprocity, furnace) run on them in
// test_material_contract.cpp; here, the values each model promises, derived by hand.

#include <rtweekend/core/bsdf.h>
#include <rtweekend/scene/material_compiler.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/course/whitted.h>
#include <rtweekend/material.h>
#include <rtweekend/sphere.h>
#include <rtweekend/whitted_material.h>

#include <doctest/doctest.h>

#include "chi_square.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace test_glossy {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// Fresnel reflectance of unpolarised light from air onto index n, in the trigonometric form of
// Fresnel's equations (Born and Wolf, Principles of Optics, 1.5.2): r_s = -sin(i - t) / sin(i + t),
// r_p = tan(i - t) / tan(i + t), with sin t = sin i / n; at normal incidence ((n - 1)/(n + 1))^2.
double fresnel_air_to(double cos_i, double n) {
    if (cos_i >= 1) return std::pow((n - 1) / (n + 1), 2);
    const double i = std::acos(cos_i), t = std::asin(std::sin(i) / n);
    const double rs = std::sin(i - t) / std::sin(i + t), rp = std::tan(i - t) / std::tan(i + t);
    return 0.5 * (rs * rs + rp * rp);
}

const vec3f normal_g = normalize(vec3f(-0.3f, 0.8f, 0.5f));

struct frame3 {
    vec3f t, b, n;
    explicit frame3(const vec3f& a) : n(a) {
        vec3f h = std::fabs(n.x) < 0.9f ? vec3f(1, 0, 0) : vec3f(0, 1, 0);
        t = normalize(cross(n, h));
        b = cross(n, t);
    }
    vec3f dir(double mu, double phi) const {
        double s = std::sqrt(std::fmax(0.0, 1 - mu * mu));
        return normalize(float(s * std::cos(phi)) * t + float(s * std::sin(phi)) * b + float(mu) * n);
    }
    double phi(const vec3f& v) const {
        double p = std::atan2(dot(v, b), dot(v, t));
        return p < 0 ? p + 2 * pi_d : p;
    }
};

vec3f outgoing(double deg) { return frame3(normal_g).dir(std::cos(deg * pi_d / 180), 1.3); }

// The mean of sample()'s value over n draws (absorbed draws count 0), and its standard error.
void mean_weight(const compiled_material& m, const vec3f& wo, long n, pcg32& rng, double mean[3], double se[3]) {
    const shading_point sp{normal_g, true};
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (long i = 0; i < n; ++i) {
        material_sample s;
        if (!m.sample(wo, sp, rng, s)) continue;
        for (int k = 0; k < 3; ++k) {
            sum[k] += s.value[k];
            sum2[k] += double(s.value[k]) * s.value[k];
        }
    }
    for (int k = 0; k < 3; ++k) {
        mean[k] = sum[k] / n;
        se[k] = std::sqrt(std::fmax(0.0, sum2[k] / n - mean[k] * mean[k]) / n);
    }
}

// The integral of eval over the hemisphere about the normal (midpoint rule in mu = cos and phi).
vec3f eval_integral(const compiled_material& m, const vec3f& wo, int nmu = 400, int nphi = 800) {
    const shading_point sp{normal_g, true};
    const frame3 f(normal_g);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < nmu; ++i)
        for (int j = 0; j < nphi; ++j) {
            const vec3f e = m.eval(wo, f.dir((i + 0.5) / nmu, 2 * pi_d * (j + 0.5) / nphi), sp);
            for (int k = 0; k < 3; ++k) sum[k] += e[k];
        }
    const double w = (1.0 / nmu) * (2 * pi_d / nphi);
    return vec3f(float(sum[0] * w), float(sum[1] * w), float(sum[2] * w));
}

} // namespace

TEST_CASE("fresnel_average: the share of diffuse light a smooth dielectric reflects") {
    CHECK(fresnel_average(1.0) == doctest::Approx(0).epsilon(1e-12));
    // Light crossing an interface both ways: by reciprocity (Stokes relations, with the n^2 of
    // radiance), what diffuse light transmits from inside, 1 - F_avg(1/n), is (1 - F_avg(n)) / n^2.
    for (double n : {1.33, 1.5, 2.4}) {
        CAPTURE(n);
        CHECK(1 - fresnel_average(1 / n) == doctest::Approx((1 - fresnel_average(n)) / (n * n)).epsilon(1e-4));
    }
    // Egan and Hilgeman's fit of the internal diffuse reflectance (1979; used by Jensen et al.,
    // SIGGRAPH 2001): -1.440/n^2 + 0.710/n + 0.668 + 0.0636 n = 0.5967 for n = 1.5, so from outside
    // 1 - 2.25 (1 - 0.5967) = 0.0926, within the fit's accuracy of the exact 0.0918.
    CHECK(std::fabs(fresnel_average(1.5) - 0.0926) < 0.002);
}

TEST_CASE("plastic: reflects F(cos) + albedo (1 - F(cos)), a white plastic reflects everything") {
    pcg32 rng(17);
    for (double n : {1.5, 2.0}) {
        for (color albedo : {color(1, 1, 1), color(0.8, 0.3, 0.05)}) {
            const compiled_material m = compile_material(plastic(albedo, n));
            REQUIRE(m.is<plastic_bsdf>());
            for (double deg : {0.0, 35.0, 70.0, 88.0}) {
                CAPTURE(n);
                CAPTURE(deg);
                const vec3f wo = outgoing(deg);
                const double F = fresnel_air_to(std::cos(deg * pi_d / 180), n);
                double mean[3], se[3];
                mean_weight(m, wo, 200000, rng, mean, se);
                // The base alone, integrated over the hemisphere: albedo (1 - F).
                const vec3f base = eval_integral(m, wo);
                for (int k = 0; k < 3; ++k) {
                    const double want = F + albedo[k] * (1 - F);
                    CAPTURE(k);
                    CHECK(std::fabs(mean[k] - want) <= 5 * se[k] + 1e-6);
                    CHECK(base[k] == doctest::Approx(albedo[k] * (1 - F)).epsilon(2e-3));
                }
            }
        }
    }
}

TEST_CASE("plastic: the coat's mirror is a delta lobe of weight F, chosen with the probability sample() reports") {
    pcg32 rng(18);
    const compiled_material m = compile_material(plastic(color(0.5, 0.6, 0.7), 1.5));
    const shading_point sp{normal_g, true};
    for (double deg : {0.0, 60.0, 85.0}) {
        CAPTURE(deg);
        const vec3f wo = outgoing(deg);
        const double F = fresnel_air_to(std::cos(deg * pi_d / 180), 1.5);
        // Chosen in proportion to what each returns: F against 0.7 (1 - F).
        const double q = F / (F + 0.7 * (1 - F));
        long coat = 0;
        const long N = 100000;
        for (long i = 0; i < N; ++i) {
            material_sample s;
            REQUIRE(m.sample(wo, sp, rng, s));
            if (!s.is_delta()) continue;
            ++coat;
            CHECK(s.sampled == delta_reflection);
            CHECK(s.pdf == doctest::Approx(q).epsilon(1e-4));
            CHECK(s.value.x == doctest::Approx(F / q).epsilon(1e-4));
            CHECK(dot(s.wi, normal_g) == doctest::Approx(std::cos(deg * pi_d / 180)).epsilon(1e-4));
        }
        CHECK(std::fabs(double(coat) / N - q) <= 5 * std::sqrt(q * (1 - q) / N));
        // The Whitted integrator's request for the mirror alone: weight F, probability 1.
        material_sample s;
        REQUIRE(m.sample(wo, sp, rng, s, delta_reflection));
        CHECK(s.value.y == doctest::Approx(F).epsilon(1e-4));
    }
    // A plastic of index 1 has no coat: a Lambertian surface.
    const compiled_material bare = compile_material(plastic(color(0.5, 0.5, 0.5), 1.0));
    const vec3f wo = outgoing(40), wi = frame3(normal_g).dir(0.6, 2.0);
    CHECK(bare.eval(wo, wi, sp).x == doctest::Approx(0.5 * 0.6 / pi_d).epsilon(1e-5));
}

TEST_CASE("blinn_phong: the glossy lobe reflects at most ks, exactly its closed form at normal incidence") {
    // At normal incidence h makes theta_h = theta_i / 2 with the normal and wi.h = cos theta_h,
    // and d omega_i = 4 cos theta_h d omega_h, so the lobe's reflectance is
    //   (n + 1) int_{1/sqrt 2}^1 c^n (2 c^2 - 1) dc
    //     = (n + 1) [2 (1 - s^(n+3)) / (n + 3) - (1 - s^(n+1)) / (n + 1)],  s = 1 / sqrt 2
    // (half vectors beyond 45 degrees reflect below the surface). Elsewhere it is at most 1.
    pcg32 rng(19);
    for (double n : {0.0, 1.0, 10.0, 100.0}) {
        const compiled_material m = compile_material(blinn_phong(color(0, 0, 0), color(1, 1, 1), n));
        REQUIRE(m.is<blinn_phong_bsdf>());
        const double s = std::sqrt(0.5);
        const double normal = (n + 1) * (2 * (1 - std::pow(s, n + 3)) / (n + 3) - (1 - std::pow(s, n + 1)) / (n + 1));
        for (double deg : {0.0, 30.0, 60.0, 80.0}) {
            CAPTURE(n);
            CAPTURE(deg);
            const vec3f wo = outgoing(deg);
            double mean[3], se[3];
            mean_weight(m, wo, 100000, rng, mean, se);
            const vec3f integral = eval_integral(m, wo);
            CHECK(mean[0] <= 1 + 5 * se[0]);
            CHECK(integral.x <= 1.0f + 1e-3f);
            CHECK(std::fabs(mean[0] - integral.x) <= 5 * se[0] + 2e-3); // the sampler against eval
            if (deg == 0) {
                CHECK(integral.x == doctest::Approx(normal).epsilon(3e-3));
                CHECK(std::fabs(mean[0] - normal) <= 5 * se[0] + 1e-6);
            }
        }
    }
}

TEST_CASE("blinn_phong: diffuse + specular above 1 is scaled down per channel, the surface stays within 1") {
    const compiled_material m = compile_material(blinn_phong(color(0.8, 0.2, 0.5), color(1.0, 0.5, 0.3), 30));
    CHECK(m.as<blinn_phong_bsdf>().albedo.x == doctest::Approx(0.8 / 1.8));
    CHECK(m.as<blinn_phong_bsdf>().specular.x == doctest::Approx(1.0 / 1.8));
    CHECK(m.as<blinn_phong_bsdf>().albedo.y == doctest::Approx(0.2)); // 0.7: kept
    CHECK(m.as<blinn_phong_bsdf>().specular.y == doctest::Approx(0.5));
    CHECK(m.as<blinn_phong_bsdf>().albedo.z == doctest::Approx(0.5)); // 0.8: kept
    pcg32 rng(20);
    for (double deg : {0.0, 50.0, 85.0}) {
        double mean[3], se[3];
        mean_weight(m, outgoing(deg), 100000, rng, mean, se);
        for (int k = 0; k < 3; ++k) CHECK(mean[k] <= 1 + 5 * se[k]);
    }
    CHECK_THROWS_AS(compile_material(blinn_phong(color(0.5, 0.5, 0.5), color(0.5, 0.5, 0.5), -1)), scene_error);
    CHECK_THROWS_AS(compile_material(plastic(color(0.5, 0.5, 0.5), 0.0)), scene_error);
}

TEST_CASE("blinn_phong: chi-square of sample() against pdf() about the mirror direction, for a sharp lobe") {
    // Binned by mu about the mirror direction of wo over [0.9, 1] (where the lobe of exponent 400
    // is: h within ~6 degrees, wi within ~12), azimuth about it; one more cell for the rest.
    pcg32 rng(21);
    const compiled_material m = compile_material(blinn_phong(color(0.1, 0.1, 0.1), color(0.8, 0.8, 0.8), 400));
    for (double deg : {0.0, 40.0, 70.0}) {
        CAPTURE(deg);
        const shading_point sp{normal_g, true};
        const vec3f wo = outgoing(deg);
        const vec3f axis = normalize(reflect_f(-wo, normal_g));
        const frame3 f(axis);
        const double mu0 = 0.98;
        const int nmu = 10, nphi = 12, q = 12;
        const long N = 200000;
        std::vector<double> obs(nmu * nphi + 1, 0), expect(nmu * nphi + 1, 0);
        double total = 0;
        for (int i = 0; i < nmu; ++i)
            for (int j = 0; j < nphi; ++j) {
                double p = 0;
                for (int a = 0; a < q; ++a)
                    for (int b = 0; b < q; ++b) {
                        const double mu = mu0 + (1 - mu0) * (i + (a + 0.5) / q) / nmu;
                        p += m.pdf(wo, f.dir(mu, 2 * pi_d * (j + (b + 0.5) / q) / nphi), sp);
                    }
                p *= (1 - mu0) / nmu / q * (2 * pi_d / nphi) / q;
                expect[size_t(i * nphi + j)] = N * p;
                total += p;
            }
        expect[nmu * nphi] = N * (1 - total);
        for (long k = 0; k < N; ++k) {
            material_sample s;
            const double mu = m.sample(wo, sp, rng, s) ? double(dot(s.wi, axis)) : -2.0;
            if (mu < mu0) {
                obs[nmu * nphi] += 1;
                continue;
            }
            const int i = std::min(nmu - 1, int((mu - mu0) / (1 - mu0) * nmu));
            const int j = std::min(nphi - 1, int(f.phi(s.wi) / (2 * pi_d) * nphi));
            obs[size_t(i * nphi + j)] += 1;
        }
        chi2::result r = chi2::test(obs, expect);
        INFO("chi2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
        CHECK(r.dof >= 20);
        CHECK(r.p_value > 0.01);
    }
}

TEST_CASE("course scenes: a plain material with a specular term is blinn_phong to the path tracer, Lambertian to Whitted") {
    auto shiny = std::make_shared<whitted_material>();
    shiny->diffuse = color(0.5, 0.4, 0.3);
    shiny->specular = color(0.3, 0.3, 0.3);
    shiny->phong_exponent = 40;
    const compiled_material m = compile_material(*shiny);
    CHECK(m.is<blinn_phong_bsdf>());
    CHECK(m.as<blinn_phong_bsdf>().albedo.x == doctest::Approx(0.5));
    CHECK(m.as<blinn_phong_bsdf>().specular.y == doctest::Approx(0.3));
    CHECK(m.as<blinn_phong_bsdf>().exponent == 40);
    // Without a specular term: Lambertian, as before; a mirror keeps its mirror (specular unused).
    auto matte = std::make_shared<whitted_material>();
    matte->diffuse = color(0.5, 0.5, 0.5);
    CHECK(compile_material(*matte).is<lambertian_bsdf>());
    auto mirror = std::make_shared<whitted_material>(*shiny);
    mirror->mirror = color(0.5, 0.5, 0.5);
    CHECK(compile_material(*mirror).is<metal_bsdf>());
    // The Whitted integrator shades the course's specular by its own formula (whitted_terms), so
    // its table holds the Lambertian base.
    whitted_scene scene;
    scene.world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, shiny));
    view_camera cam;
    cam.width = cam.height = 4;
    scene.cameras.push_back(cam);
    whitted_renderer renderer(scene);
    REQUIRE(renderer.compiled().materials.size() == 1);
    CHECK(renderer.compiled().materials[0].is<lambertian_bsdf>());
    CHECK(renderer.compiled().materials[0].as<lambertian_bsdf>().albedo.x == doctest::Approx(0.5));
}

} // namespace test_glossy
