// The GGX microfacet materials (rtweekend/core/microfacet.h and core/materials/rough_*_bsdf.h,
// metal_rough_bsdf.h): the distribution against its closed forms and integrals, the visible
// normals' sampling against their density (chi-square), the energy-compensation table against
// random draws of its own, each material's sampling against its pdf over the whole sphere,
// reciprocity, the furnace (a white rough conductor reflects everything, in a direction's
// estimate and in a rendered image), the smooth limit against our mirror and glass, and the
// scene file's lines.

#include <rtweekend/core/microfacet.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/rtweekend.h>
#include <rtweekend/scene/material_compiler.h>

#include <doctest/doctest.h>

#include "chi_square.h"
#include "test_helpers.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace test_microfacet {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// A direction at cosine mu and azimuth phi in the frame of the shading normal used below.
const vec3f normal_m = normalize(vec3f(0.3f, 0.9f, -0.2f));

vec3f spherical(double mu, double phi) {
    const double s = std::sqrt(std::fmax(0.0, 1 - mu * mu));
    return vec3f{float(s * std::cos(phi)), float(s * std::sin(phi)), float(mu)};
}

// In world space about normal_m (through the materials' own frame: the tests of eval, pdf and
// sample below see the same frame as the materials, so bins are in the frame's coordinates).
vec3f world(double mu, double phi) { return normalize(microfacet_frame(normal_m).to_world(spherical(mu, phi))); }

double azimuth(const vec3f& local) {
    const double p = std::atan2(double(local.y), double(local.x));
    return p < 0 ? p + 2 * pi_d : p;
}

int bin(double x, double lo, double hi, int n) {
    const int i = int(std::floor((x - lo) / (hi - lo) * n));
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

// The integral over the hemisphere (mu in [0, 1]) of f(local direction), by the midpoint rule in
// a warped mu = 1 - s^2 (dense near the pole, where GGX peaks; d mu = 2 s ds) and phi.
template <class F>
double hemisphere_integral(F f, int ns = 800, int nphi = 256) {
    double sum = 0;
    for (int i = 0; i < ns; ++i) {
        const double s = (i + 0.5) / ns, mu = 1 - s * s;
        for (int j = 0; j < nphi; ++j) sum += f(spherical(mu, 2 * pi_d * (j + 0.5) / nphi)) * 2 * s;
    }
    return sum * (1.0 / ns) * (2 * pi_d / nphi);
}

// A material and its compiled record, which may point into the material (an anisotropic
// conductor's albedo table): kept together.
struct rough_case {
    std::string name;
    std::shared_ptr<material> owner;
    compiled_material m;
    template <class M>
    rough_case(std::string n, const M& made) : name(std::move(n)), owner(std::make_shared<M>(made)), m(compile_material(*owner)) {}
};

// The record of a material, which must outlive it (a rough_conductor's points into it).
compiled_material compiled(const material& m) { return compile_material(m); }

} // namespace

TEST_CASE("GGX: Lambda and G1 at chosen angles, D and the visible normals integrate to 1") {
    // Lambda for alpha 0.5 at 60 degrees, by hand: tan^2 = 3, (sqrt(1 + 0.25 * 3) - 1) / 2
    // = (1.3228757 - 1) / 2 = 0.16143783; G1 = 1 / 1.16143783 = 0.86100.
    const ggx iso{0.5f, 0.5f};
    const vec3f w60 = spherical(0.5, 0.0);
    CHECK(iso.lambda(w60) == doctest::Approx(0.16143783).epsilon(1e-5));
    CHECK(iso.g1(w60) == doctest::Approx(0.8610).epsilon(1e-4));
    // At normal incidence nothing is masked; D at the pole is 1 / (pi au av).
    CHECK(iso.g1(vec3f{0, 0, 1}) == 1.0f);
    const ggx aniso{0.2f, 0.6f};
    CHECK(aniso.d(vec3f{0, 0, 1}) == doctest::Approx(1.0 / (pi_d * 0.2 * 0.6)).epsilon(1e-5));
    // Anisotropic Lambda along each axis is the isotropic one of that axis's alpha: at 60 degrees
    // along the tangent, (sqrt(1 + 0.04 * 3) - 1) / 2 = 0.0291503.
    CHECK(aniso.lambda(spherical(0.5, 0.0)) == doctest::Approx(0.0291503).epsilon(1e-4));
    CHECK(aniso.lambda(spherical(0.5, pi_d / 2)) == doctest::Approx((std::sqrt(1 + 0.36 * 3) - 1) / 2).epsilon(1e-4));

    for (const ggx& g : {ggx{0.5f, 0.5f}, ggx{0.2f, 0.6f}, ggx{1.0f, 1.0f}, ggx{0.1f, 0.1f}}) {
        CAPTURE(g.alpha_u);
        CAPTURE(g.alpha_v);
        // The projected microfacet area is the macro surface's: int D(m) m.z dm = 1.
        CHECK(hemisphere_integral([&](const vec3f& m) { return g.d(m) * m.z; }) == doctest::Approx(1).epsilon(2e-3));
        // The visible normals' density is a density: int D_wo(m) dm = 1 (Heitz 2014, eq. 38).
        for (double mu : {1.0, 0.7, 0.2}) {
            const vec3f wo = spherical(mu, 0.4);
            CAPTURE(mu);
            CHECK(hemisphere_integral([&](const vec3f& m) { return g.visible_pdf(wo, m); }) ==
                  doctest::Approx(1).epsilon(3e-3));
        }
    }
}

TEST_CASE("GGX: chi-square of sample_visible() against visible_pdf()") {
    pcg32 rng(41);
    for (const ggx& g : {ggx{0.3f, 0.3f}, ggx{0.15f, 0.5f}, ggx{1.0f, 1.0f}}) {
        for (double mu_o : {1.0, 0.6, 0.15}) {
            CAPTURE(g.alpha_u);
            CAPTURE(g.alpha_v);
            CAPTURE(mu_o);
            const vec3f wo = spherical(mu_o, 1.1);
            // Bins in s = sqrt(1 - mu) (uniform in s: dense near the pole) and phi; the expected
            // count of a cell is N times the density integrated over it (6 x 6 midpoints).
            const int ns = 12, nphi = 16, q = 6;
            const long N = test::sanitized_share(300000); // an eighth under the sanitizers
            std::vector<double> obs(ns * nphi, 0), expect(ns * nphi, 0);
            for (int i = 0; i < ns; ++i)
                for (int j = 0; j < nphi; ++j) {
                    double p = 0;
                    for (int a = 0; a < q; ++a)
                        for (int b = 0; b < q; ++b) {
                            const double s = (i + (a + 0.5) / q) / ns, mu = 1 - s * s;
                            p += g.visible_pdf(wo, spherical(mu, 2 * pi_d * (j + (b + 0.5) / q) / nphi)) * 2 * s;
                        }
                    expect[size_t(i * nphi + j)] = N * p / (ns * q) * (2 * pi_d / (nphi * q));
                }
            for (long k = 0; k < N; ++k) {
                const vec3f m = g.sample_visible(wo, rng.next_float(), rng.next_float());
                REQUIRE(dot(m, wo) >= -1e-5f);
                const double s = std::sqrt(std::fmax(0.0, 1.0 - m.z));
                obs[size_t(bin(s, 0, 1, ns) * nphi + bin(azimuth(m), 0, 2 * pi_d, nphi))] += 1;
            }
            const chi2::result r = chi2::test(obs, expect);
            INFO("chi2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
            CHECK(r.dof >= 30);
            CHECK(r.p_value > 0.001);
        }
    }
}

TEST_CASE("GGX albedo table: against random draws, its limits, and its Schlick split") {
    // E(mu) by 400 000 random visible normals (pcg32), between the table's nodes; the table's own
    // quadrature is deterministic and different.
    pcg32 rng(77);
    for (double r : {0.11, 0.37, 0.62, 0.95}) {
        for (double mu : {0.98, 0.55, 0.13}) {
            const float alpha = float(r * r);
            const ggx g{alpha, alpha};
            const vec3f wo = spherical(mu, 0);
            const long N = test::sanitized_share(400000); // an eighth under the sanitizers
            double sum = 0, sum5 = 0, sum2 = 0;
            for (long k = 0; k < N; ++k) {
                const vec3f m = g.sample_visible(wo, rng.next_float(), rng.next_float());
                const vec3f wi = 2.0f * dot(wo, m) * m - wo;
                if (!(wi.z > 0)) continue;
                const double w = g.g2(wo, wi) / g.g1(wo), x = 1 - dot(wo, m);
                sum += w;
                sum2 += w * w;
                sum5 += w * x * x * x * x * x;
            }
            const double e = sum / N, se = std::sqrt(std::fmax(0.0, sum2 / N - e * e) / N);
            CAPTURE(r);
            CAPTURE(mu);
            // 4 standard errors plus the table's interpolation between nodes (bilinear in mu and
            // roughness, nodes 1/31 apart): 2e-3.
            CHECK(std::fabs(ggx_albedo().albedo(float(mu), alpha) - e) <= 4 * se + 2e-3);
            // Schlick's Fresnel from f0: f0 E + (1 - f0) E5.
            const double f0 = 0.04;
            CHECK(std::fabs(ggx_albedo().albedo(float(mu), alpha, float(f0)) - (f0 * e + (1 - f0) * sum5 / N)) <= 4 * se + 2e-3);
        }
    }
    // A smooth mirror loses nothing; a rough one loses more the rougher it is.
    CHECK(ggx_albedo().albedo(0.5f, 0.0f) == doctest::Approx(1).epsilon(1e-4));
    CHECK(ggx_albedo().average(0.0f) == doctest::Approx(1).epsilon(1e-3));
    float previous = 2;
    for (int j = 0; j <= 10; ++j) {
        const float a = alpha_of_roughness(j / 10.0f), avg = ggx_albedo().average(a);
        CHECK(avg < previous + 1e-6f);
        previous = avg;
    }
    CHECK(previous < 0.5f); // roughness 1 loses more than half (E_avg 0.409 here)
}

TEST_CASE("rough materials: sample() is eval / pdf, and chi-square against pdf() over the whole sphere") {
    std::vector<rough_case> cases;
    for (double r : {0.5, 0.75, 1.0}) {
        const std::string rs = " r " + std::to_string(r).substr(0, 4);
        cases.emplace_back("rough_conductor gold" + rs, rough_conductor(color(0.18, 0.42, 1.37), color(3.42, 2.35, 1.77), r));
        cases.emplace_back("rough_conductor anisotropic" + rs, rough_conductor(color(0.9, 0.7, 0.5), r, r * 0.7));
        cases.emplace_back("rough_dielectric 1.5" + rs, rough_dielectric(1.5, r));
        cases.emplace_back("metal_roughness 0.5" + rs, metal_roughness(color(0.8, 0.5, 0.2), 0.5, r));
        cases.emplace_back("metal_roughness 0" + rs, metal_roughness(color(0.3, 0.6, 0.9), 0.0, r));
    }
    // Cells: on each side of the surface, the angle theta to the normal in [0, pi/2] (even in
    // theta: finer than even cosines near the normal, where lobes of wo near the normal peak) by
    // the azimuth about the normal. Refraction has an edge: a microfacet standing on end passes
    // light at |cos theta_i| = cos theta_o / eta (the tangential part of wo along the normal kept,
    // over eta), none beyond, and the density peaks at it; a cell boundary lies there, so that no
    // cell straddles it. The expected count is N times the pdf integrated over the cell (16 x 16
    // midpoints, d omega = sin theta dtheta dphi); one more cell for the draws that fail
    // (absorbed), expecting the rest.
    const int ns = 18, nphi = 16, q = 16;
    pcg32 rng(1234);
    for (const rough_case& c : cases) {
        for (bool front : {true, false}) {
            if (!front && !c.m.transmits()) continue;
            for (double deg : {0.0, 50.0, 82.0}) {
                CAPTURE(c.name);
                CAPTURE(front);
                CAPTURE(deg);
                const shading_point sp{normal_m, front};
                const vec3f wo = world(std::cos(deg * pi_d / 180), 0.8);
                // The cells' theta edges on each side: even, or split at the refraction's edge.
                std::vector<double> edges[2];
                const double eta = front ? 1.5 : 1 / 1.5, edge_cos = std::cos(deg * pi_d / 180) / eta;
                for (int side = 0; side < 2; ++side) {
                    if (side == 1 && c.m.transmits() && edge_cos < 0.999) {
                        const double te = std::acos(edge_cos), n_in = ns - 4;
                        for (int i = 0; i <= n_in; ++i) edges[side].push_back(te * i / n_in);
                        for (int i = 1; i <= 4; ++i) edges[side].push_back(te + (pi_d / 2 - te) * i / 4);
                    } else {
                        for (int i = 0; i <= ns; ++i) edges[side].push_back(pi_d / 2 * i / ns);
                    }
                }
                auto theta_cell = [&](int side, double theta) {
                    const std::vector<double>& e = edges[side];
                    int i = int(std::upper_bound(e.begin(), e.end(), theta) - e.begin()) - 1;
                    return i < 0 ? 0 : std::min(i, ns - 1);
                };
                const long N = test::sanitized_share(200000); // an eighth under the sanitizers
                const size_t cells = 2 * ns * nphi;
                std::vector<double> obs(cells + 1, 0), expect(cells + 1, 0);
                double total = 0;
                for (int side = 0; side < 2; ++side)
                    for (int i = 0; i < ns; ++i)
                        for (int j = 0; j < nphi; ++j) {
                            const double t0 = edges[side][size_t(i)], t1 = edges[side][size_t(i + 1)];
                            double p = 0;
                            for (int a = 0; a < q; ++a)
                                for (int b = 0; b < q; ++b) {
                                    const double t = t0 + (t1 - t0) * (a + 0.5) / q;
                                    p += c.m.pdf(wo, world((side ? -1 : 1) * std::cos(t), 2 * pi_d * (j + (b + 0.5) / q) / nphi), sp) *
                                         std::sin(t);
                                }
                            p *= ((t1 - t0) / q) * (2 * pi_d / (nphi * q));
                            expect[size_t((side * ns + i) * nphi + j)] = N * p;
                            total += p;
                        }
                expect[cells] = N * std::fmax(0.0, 1 - total);
                const microfacet_frame f(normal_m);
                long compared = 0;
                for (long k = 0; k < N; ++k) {
                    material_sample s;
                    if (!c.m.sample(wo, sp, rng, s)) {
                        obs[cells] += 1;
                        continue;
                    }
                    REQUIRE(!s.is_delta());
                    const vec3f l = f.to_local(s.wi);
                    const int side = l.z < 0;
                    const double theta = std::acos(std::fmin(1.0, std::fabs(double(l.z))));
                    obs[size_t((side * ns + theta_cell(side, theta)) * nphi + bin(azimuth(l), 0, 2 * pi_d, nphi))] += 1;
                    if (k % 97 == 0) {
                        // The value is eval / pdf, and pdf() gives the density sample() reported.
                        const vec3f e = c.m.eval(wo, s.wi, sp);
                        const float p = c.m.pdf(wo, s.wi, sp);
                        CHECK(p == doctest::Approx(s.pdf).epsilon(2e-3));
                        for (int ch = 0; ch < 3; ++ch) CHECK(e[ch] / p == doctest::Approx(s.value[ch]).epsilon(2e-3));
                        ++compared;
                    }
                }
                CHECK(compared > N / 200);
                const chi2::result r = chi2::test(obs, expect);
                INFO("chi2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
                CHECK(r.dof >= 20);
                CHECK(r.p_value > 0.0005); // over some 60 tests
            }
        }
    }
}

TEST_CASE("rough materials: reciprocity") {
    // Reflection: f(a, b) = f(b, a), with eval = f |cos wi|. Rough glass's refraction, which does
    // not scale radiance by the index ratio (as the books' glass), carries the ratio in f: from
    // the BTDF (rough_dielectric_bsdf.h) with eta = n_i / n_o, h fixed and (i.h + o.h / eta)^2 =
    // (n_i i.h + n_o o.h)^2 / n_i^2, f(o, i) n_o^2 = f(i, o) n_i^2, where the second evaluation
    // sees the surface from i's side.
    pcg32 rng(99);
    const std::vector<rough_case> cases = {
        {"rough_conductor", rough_conductor(color(0.9, 0.6, 0.3), 0.3, 0.6)},
        {"metal_roughness", metal_roughness(color(0.7, 0.5, 0.3), 0.4, 0.5)},
        {"rough_dielectric", rough_dielectric(1.5, 0.5)},
    };
    for (const rough_case& c : cases) {
        CAPTURE(c.name);
        long reflections = 0, refractions = 0;
        for (int k = 0; k < 6000; ++k) {
            const vec3f a = world(0.05 + 0.95 * rng.next_double(), 2 * pi_d * rng.next_double());
            const bool through = c.m.transmits() && k % 2;
            const vec3f b = world((through ? -1 : 1) * (0.05 + 0.95 * rng.next_double()), 2 * pi_d * rng.next_double());
            const shading_point sp_a{normal_m, true};
            const vec3f ab = c.m.eval(a, b, sp_a);
            if (!(ab.x > 1e-6f)) continue;
            const double cos_a = std::fabs(dot(a, normal_m)), cos_b = std::fabs(dot(b, normal_m));
            if (!through) {
                const vec3f ba = c.m.eval(b, a, sp_a);
                for (int ch = 0; ch < 3; ++ch) CHECK(ab[ch] / cos_b == doctest::Approx(ba[ch] / cos_a).epsilon(1e-3));
                ++reflections;
            } else {
                const shading_point sp_b{-normal_m, false}; // b is inside: the normal on its side
                const vec3f ba = c.m.eval(b, a, sp_b);
                const double n_o = 1.0, n_i = 1.5;
                CHECK(ab.x / cos_b * n_o * n_o == doctest::Approx(ba.x / cos_a * n_i * n_i).epsilon(2e-3));
                ++refractions;
            }
        }
        CHECK(reflections > 500);
        if (c.m.transmits()) CHECK(refractions > 500);
    }
}

TEST_CASE("rough materials: the furnace: a white rough conductor reflects everything at every roughness") {
    // The mean of sample()'s value at incidence wo is what the surface reflects. With the
    // multiple-scattering lobe a white conductor (Fresnel 1: albedo 1 under Schlick) and a white
    // metal_roughness, metallic 1 or 0 (the base takes what the coat leaves), return exactly 1;
    // single scattering alone loses 1 - E (the table: 0.69 at roughness 1, normal incidence).
    pcg32 rng(2024);
    for (double r : {0.05, 0.2, 0.5, 0.8, 1.0}) {
        const std::vector<rough_case> white = {
            {"rough_conductor", rough_conductor(color(1, 1, 1), r)},
            {"rough_conductor anisotropic", rough_conductor(color(1, 1, 1), r, r * 0.3)},
            {"metal_roughness metallic", metal_roughness(color(1, 1, 1), 1.0, r)},
            {"metal_roughness plastic", metal_roughness(color(1, 1, 1), 0.0, r)},
        };
        for (const rough_case& c : white)
            for (double deg : {0.0, 45.0, 75.0, 88.0}) {
                CAPTURE(c.name);
                CAPTURE(r);
                CAPTURE(deg);
                const shading_point sp{normal_m, true};
                const vec3f wo = world(std::cos(deg * pi_d / 180), 2.0);
                const long N = test::sanitized_share(100000); // an eighth under the sanitizers
                double sum = 0, sum2 = 0;
                for (long k = 0; k < N; ++k) {
                    material_sample s;
                    if (!c.m.sample(wo, sp, rng, s)) continue;
                    sum += s.value.y;
                    sum2 += double(s.value.y) * s.value.y;
                }
                const double mean = sum / N, se = std::sqrt(std::fmax(0.0, sum2 / N - mean * mean) / N);
                // 5 standard errors, plus the table's interpolation (2e-3; more at grazing, where
                // E changes fastest between nodes).
                CHECK(std::fabs(mean - 1) <= 5 * se + (deg > 85 ? 6e-3 : 2e-3));
            }
    }
    // Rough glass is single scattering only: it loses light, more the rougher, never gains.
    for (double r : {0.2, 0.6, 1.0}) {
        const compiled_material m = compiled(rough_dielectric(1.5, r));
        pcg32 g(5);
        const shading_point sp{normal_m, true};
        const long N = test::sanitized_share(100000); // an eighth under the sanitizers
        double sum = 0;
        for (long k = 0; k < N; ++k) {
            material_sample s;
            if (m.sample(world(1.0, 0), sp, g, s)) sum += s.value.x;
        }
        CAPTURE(r);
        CHECK(sum / N <= 1.0 + 3e-3);
        if (r == 1.0) CHECK(sum / N < 0.95); // about 0.89 at normal incidence
    }
}

TEST_CASE("rough materials: a white rough conductor sphere in a white sky renders white") {
    // The furnace of test_render.cpp: every camera ray hits a unit sphere under a white sky of
    // radiance 1; a convex surface's reflection leaves for the sky at once, so each pixel's mean
    // is the mean sample weight: 1 within noise, at roughness 0.05 to 1.
    for (double r : {0.05, 0.3, 0.6, 1.0}) {
        for (int kind = 0; kind < 2; ++kind) {
            CAPTURE(r);
            CAPTURE(kind);
            camera cam = test::test_camera(20, 12, 64, 8);
            cam.vfov = 20;
            cam.lookfrom = point3(0, 0, 0);
            cam.lookat = point3(0, 0, -1);
            cam.background = color(1, 1, 1);
            hittable_list world;
            std::shared_ptr<material> m = kind == 0 ? std::shared_ptr<material>(std::make_shared<rough_conductor>(color(1, 1, 1), r))
                                                    : std::make_shared<metal_roughness>(color(1, 1, 1), 1.0, r);
            world.add(std::make_shared<sphere>(point3(0, 0, -2), 1, m));
            const render_result res = test::render_checked(cam, world);
            double sum = 0, sum2 = 0;
            long n = 0;
            for (int y = 0; y < res.img.height(); ++y)
                for (int x = 0; x < res.img.width(); ++x) {
                    const double v = res.img.pixel(x, y).y();
                    sum += v;
                    sum2 += v * v;
                    ++n;
                }
            const double mean = sum / n, se = std::sqrt(std::fmax(0.0, sum2 / n - mean * mean) / n);
            INFO("mean " << mean << " +- " << se);
            CHECK(std::fabs(mean - 1) <= 5 * se + 2e-3);
        }
    }
}

TEST_CASE("rough materials: roughness 0 is our mirror and glass, slightly rough is close to them") {
    // Roughness 0 (alpha below 1e-3) is a delta lobe, drawn exactly as conductor and the exact-
    // Fresnel dielectric draw: the same directions and weights from the same random numbers.
    const rough_conductor gold_material(color(0.18, 0.42, 1.37), color(3.42, 2.35, 1.77), 0.0);
    const compiled_material gold = compiled(gold_material);
    const compiled_material mirror = compiled(conductor(color(0.18, 0.42, 1.37), color(3.42, 2.35, 1.77), color(1, 1, 1)));
    const compiled_material frosted0 = compiled(rough_dielectric(1.5, 0.0));
    const compiled_material clear = compiled(dielectric(1.5, color(0, 0, 0)));
    CHECK(gold.has_delta_lobe());
    CHECK(!gold.has_non_delta_lobe());
    CHECK(frosted0.has_delta_lobe());
    CHECK(frosted0.refracts());
    for (bool front : {true, false})
        for (double deg : {0.0, 40.0, 70.0, 89.0}) {
            const shading_point sp{normal_m, front};
            const vec3f wo = world(std::cos(deg * pi_d / 180), 0.3);
            pcg32 r1(8), r2(8), r3(8), r4(8);
            for (int k = 0; k < 50; ++k) {
                material_sample a, b;
                REQUIRE(gold.sample(wo, sp, r1, a));
                REQUIRE(mirror.sample(wo, sp, r2, b));
                CHECK(length(a.wi - b.wi) < 1e-6f);
                for (int ch = 0; ch < 3; ++ch) CHECK(a.value[ch] == doctest::Approx(b.value[ch]).epsilon(1e-5));
                material_sample c, d;
                REQUIRE(frosted0.sample(wo, sp, r3, c));
                REQUIRE(clear.sample(wo, sp, r4, d));
                CHECK(c.sampled == d.sampled);
                CHECK(length(c.wi - d.wi) < 1e-6f);
                CHECK(c.value.x == doctest::Approx(d.value.x).epsilon(1e-6));
            }
        }
    // Roughness 0.05 (alpha 0.0025): directions within a few degrees of the mirror and the
    // refraction, and the conductor's reflectance within 1 % of Fresnel's.
    const rough_conductor gold_rough_material(color(0.18, 0.42, 1.37), color(3.42, 2.35, 1.77), 0.05);
    const compiled_material gold_rough = compiled(gold_rough_material);
    const compiled_material frosted = compiled(rough_dielectric(1.5, 0.05));
    pcg32 rng(17);
    for (double deg : {0.0, 40.0, 70.0}) {
        CAPTURE(deg);
        const shading_point sp{normal_m, true};
        const vec3f wo = world(std::cos(deg * pi_d / 180), 0.3);
        const vec3f mirror_dir = normalize(reflect_f(-wo, normal_m));
        double sum[3] = {0, 0, 0};
        long near = 0, refracted = 0, near_refraction = 0;
        const long N = 20000;
        material_sample smooth;
        pcg32 r0(3);
        // The smooth glass's refraction, drawn until it refracts.
        do REQUIRE(clear.sample(wo, sp, r0, smooth));
        while (smooth.sampled != delta_transmission);
        for (long k = 0; k < N; ++k) {
            material_sample s;
            if (gold_rough.sample(wo, sp, rng, s)) {
                for (int ch = 0; ch < 3; ++ch) sum[ch] += s.value[ch];
                if (dot(s.wi, mirror_dir) > std::cos(3 * pi_d / 180)) ++near;
            }
            material_sample t;
            if (frosted.sample(wo, sp, rng, t) && dot(t.wi, normal_m) < 0) {
                ++refracted;
                if (dot(t.wi, smooth.wi) > std::cos(3 * pi_d / 180)) ++near_refraction;
            }
        }
        const double c = std::cos(deg * pi_d / 180);
        const double n[3] = {0.18, 0.42, 1.37}, kk[3] = {3.42, 2.35, 1.77};
        for (int ch = 0; ch < 3; ++ch) CHECK(sum[ch] / N == doctest::Approx(fresnel_conductor(c, n[ch], kk[ch])).epsilon(0.01));
        CHECK(double(near) / N > 0.95);
        CHECK(double(near_refraction) / double(refracted) > 0.95);
    }
}

TEST_CASE("scene files: rough_conductor, rough_dielectric and metal_roughness lines") {
    auto parse = [](const std::string& text) {
        std::istringstream in(text);
        return parse_scene(in, "rough.txt");
    };
    scene_description s = parse("sphere 0 0 -1 0.5 rough_conductor 0.9 0.6 0.3 0.25 0\n"
                                "sphere 1 0 -1 0.5 rough_dielectric 0 0 0 0.5 1.33\n"
                                "sphere 2 0 -1 0.5 metal_roughness 0.2 0.4 0.6 0.75 0.1\n");
    REQUIRE(s.world.objects.size() == 3);
    auto material_of = [&](size_t i) {
        hit_record rec;
        const auto& sp = s.world.objects[i];
        const point3 c(double(i), 0, -1);
        REQUIRE(sp->hit(ray(c + vec3(0, 0, 2), vec3(0, 0, -1)), interval(0.001, 100), rec));
        return rec.mat;
    };
    const auto* rc = dynamic_cast<const rough_conductor*>(material_of(0).get());
    REQUIRE(rc);
    CHECK(rc->albedo().x() == 0.9);
    CHECK(rc->roughness_u() == 0.25);
    CHECK(!rc->complex_index());
    const auto* rd = dynamic_cast<const rough_dielectric*>(material_of(1).get());
    REQUIRE(rd);
    CHECK(rd->refraction_index() == 1.33);
    CHECK(rd->roughness_v() == 0.5);
    const auto* mr = dynamic_cast<const metal_roughness*>(material_of(2).get());
    REQUIRE(mr);
    CHECK(mr->base_colour().z() == 0.6);
    CHECK(mr->metallic() == 0.75);
    CHECK(mr->roughness() == 0.1);

    auto fails = [&](const std::string& text, const std::string& fragment) {
        CAPTURE(text);
        try {
            parse(text);
            FAIL("no error");
        } catch (const scene_error& e) {
            const std::string msg = e.what();
            CHECK(msg.find("rough.txt:1: ") == 0);
            CHECK(msg.find(fragment) != std::string::npos);
            CHECK(msg.find('\n') == std::string::npos);
        }
    };
    fails("sphere 0 0 -1 0.5 rough_conductor 0.9 0.6 0.3 1.5 0\n", "rough_conductor roughness must be in [0, 1], got 1.5");
    fails("sphere 0 0 -1 0.5 rough_dielectric 0 0 0 -0.1 1.5\n", "rough_dielectric roughness must be in [0, 1], got -0.1");
    fails("sphere 0 0 -1 0.5 rough_dielectric 0 0 0 0.3 0\n", "rough_dielectric ior must be positive, got 0");
    fails("sphere 0 0 -1 0.5 metal_roughness 1 1 1 2 0.5\n", "metal_roughness metallic must be in [0, 1], got 2");
    fails("sphere 0 0 -1 0.5 metal_roughness 1 1 1 0.5 nan\n", "roughness");

    // From a main: a parameter out of range is one scene_error when the scene is compiled.
    CHECK_THROWS_WITH_AS(compile_material(rough_conductor(color(1, 1, 1), std::nan(""))),
                         "rough_conductor roughness must be in [0, 1], got nan", scene_error);
    CHECK_THROWS_WITH_AS(compile_material(rough_conductor(color(1, 1, 1), color(-1, 1, 1), 0.5)),
                         doctest::Contains("rough_conductor"), scene_error);
    CHECK_THROWS_WITH_AS(compile_material(metal_roughness(color(1, 1, 1), 0.5, 3)),
                         "metal_roughness roughness must be in [0, 1], got 3", scene_error);
}

} // namespace test_microfacet
