// Light sampling (rtweekend/scene/light_sampling.h) and the alias table (core/alias_table.h).
//
// For every sampler and configuration: (a) chi-square of the sampled points against the pdf
// function integrated numerically over cells (of directions about the axis to a sphere's centre,
// or of the light's own parametrisation, the area element converted to solid angle here, in
// double); (b) the pdf a sample reports is the pdf function's at its point; (c) the pdf function
// integrates to 1 over the directions that meet the light (Monte Carlo over a cap of uniform
// directions, with the ray-shape intersections written here); (d) the rectangle's solid angle
// against closed forms, and its angles' arctangent against the double one; (e) the alias table's probabilities, exactly by enumerating every float
// uniform and by chi-square; (f) the power heuristic's edge cases. Everything is seeded.

#include <rtweekend/core/alias_table.h>
#include <rtweekend/scene/light_sampling.h>
#include <rtweekend/core/rng.h>

#include <doctest/doctest.h>

#include "chi_square.h"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_light_sampling {

using namespace rt;

namespace {

constexpr double pi_d = 3.14159265358979323846;

// Double vectors for the reference computations.
struct d3 {
    double x = 0, y = 0, z = 0;
};
d3 operator+(d3 a, d3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
d3 operator-(d3 a, d3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
d3 operator*(double t, d3 a) { return {t * a.x, t * a.y, t * a.z}; }
double dot(d3 a, d3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
d3 cross(d3 a, d3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double len(d3 a) { return std::sqrt(dot(a, a)); }
d3 unit(d3 a) { return (1 / len(a)) * a; }
d3 D(const vec3f& v) { return {v.x, v.y, v.z}; }
vec3f F(d3 v) { return {float(v.x), float(v.y), float(v.z)}; }

double rel(double a, double b) { return std::fabs(a - b) / std::fmax(1e-300, std::fmax(std::fabs(a), std::fabs(b))); }

int bin(double x, double lo, double hi, int n) {
    int i = int(std::floor((x - lo) / (hi - lo) * n));
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

// A right-handed frame about the unit vector n.
struct frame3 {
    d3 t, b, n;
    explicit frame3(d3 axis) : n(unit(axis)) {
        d3 h = std::fabs(n.x) < 0.9 ? d3{1, 0, 0} : d3{0, 1, 0};
        t = unit(cross(n, h));
        b = cross(n, t);
    }
    d3 dir(double cos_theta, double phi) const {
        double s = std::sqrt(std::fmax(0.0, 1 - cos_theta * cos_theta));
        return (s * std::cos(phi)) * t + (s * std::sin(phi)) * b + cos_theta * n;
    }
    double phi(d3 v) const {
        double p = std::atan2(dot(v, b), dot(v, t));
        return p < 0 ? p + 2 * pi_d : p;
    }
};

// Rotation of v about the unit axis k by angle a (Rodrigues).
d3 rotate(d3 v, d3 k, double a) {
    return (std::cos(a)) * v + std::sin(a) * cross(k, v) + (dot(k, v) * (1 - std::cos(a))) * k;
}

// --- ray-shape intersections, in double, independent of the header ---------------------------

// The first point where the half-line p + t w (t > 0, w unit) meets the sphere.
bool hit_sphere(d3 p, d3 w, d3 c, double r, d3& y, d3& n) {
    d3 oc = c - p;
    double h = dot(w, oc);
    d3 perp = oc - h * w;
    double disc = r * r - dot(perp, perp);
    if (disc < 0) return false;
    double s = std::sqrt(disc);
    double t = h - s > 0 ? h - s : h + s;
    if (!(t > 0)) return false;
    y = p + t * w;
    n = unit(y - c);
    return true;
}

// Where p + t w meets the plane Q + a u + b v, with (a, b).
bool hit_plane(d3 p, d3 w, d3 Q, d3 u, d3 v, d3& y, double& a, double& b) {
    d3 nn = cross(u, v);
    double denom = dot(nn, w);
    if (denom == 0) return false;
    double t = dot(nn, Q - p) / denom;
    if (!(t > 0)) return false;
    y = p + t * w;
    d3 rel_y = y - Q;
    a = dot(nn, cross(rel_y, v)) / dot(nn, nn);
    b = dot(nn, cross(u, rel_y)) / dot(nn, nn);
    return true;
}

// (a, b) of a point y of the plane Q + a u + b v.
void plane_coordinates(d3 y, d3 Q, d3 u, d3 v, double& a, double& b) {
    d3 nn = cross(u, v);
    d3 r = y - Q;
    a = dot(nn, cross(r, v)) / dot(nn, nn);
    b = dot(nn, cross(u, r)) / dot(nn, nn);
}

// --- lights under test ----------------------------------------------------------------------------

struct light_case {
    std::string name;
    vec3f p;
    std::function<bool(float, float, light_sample&)> sample;
    std::function<float(const vec3f& y, const vec3f& ny)> pdf;
    std::function<bool(d3 p, d3 w, d3& y, d3& n)> hit;     // this file's intersection
    std::function<double(d3 y)> off_surface;                 // distance of y from the shape
    std::function<d3(d3 y)> normal;                          // the expected unit normal at y
    d3 centre;                                               // a bounding sphere
    double radius = 0;
    enum { sphere, quad, triangle } kind = sphere;
    d3 origin, edge1, edge2;                                 // quad: Q, u, v; triangle: a, b - a, c - a
};

light_case sphere_case(const std::string& name, vec3f p, vec3f c, float r) {
    light_case L;
    L.name = name;
    L.p = p;
    L.sample = [=](float u1, float u2, light_sample& s) { return sample_sphere_light(p, c, r, u1, u2, s); };
    L.pdf = [=](const vec3f& y, const vec3f& ny) { return sphere_light_pdf(p, c, r, y, ny); };
    L.hit = [=](d3 pp, d3 w, d3& y, d3& n) { return hit_sphere(pp, w, D(c), r, y, n); };
    L.off_surface = [=](d3 y) { return std::fabs(len(y - D(c)) - r); };
    L.normal = [=](d3 y) { return unit(y - D(c)); };
    L.centre = D(c);
    L.radius = r;
    return L;
}

light_case quad_case(const std::string& name, vec3f p, vec3f Q, vec3f u, vec3f v, quad_sampling strategy) {
    light_case L;
    L.name = name;
    L.p = p;
    L.sample = [=](float u1, float u2, light_sample& s) { return sample_quad_light(p, Q, u, v, u1, u2, s, strategy); };
    L.pdf = [=](const vec3f& y, const vec3f& ny) { return quad_light_pdf(p, Q, u, v, y, ny, strategy); };
    L.hit = [=](d3 pp, d3 w, d3& y, d3& n) {
        double a, b;
        if (!hit_plane(pp, w, D(Q), D(u), D(v), y, a, b) || a < 0 || a > 1 || b < 0 || b > 1) return false;
        n = unit(cross(D(u), D(v)));
        return true;
    };
    L.off_surface = [=](d3 y) {
        double a, b;
        plane_coordinates(y, D(Q), D(u), D(v), a, b);
        d3 nn = unit(cross(D(u), D(v)));
        double out = std::fmax(std::fmax(-a, a - 1), std::fmax(-b, b - 1)); // outside the edges, in edge units
        return std::fabs(dot(y - D(Q), nn)) + std::fmax(0.0, out) * std::fmax(len(D(u)), len(D(v)));
    };
    L.normal = [=](d3) { return unit(cross(D(u), D(v))); };
    L.kind = light_case::quad;
    L.origin = D(Q), L.edge1 = D(u), L.edge2 = D(v);
    L.centre = D(Q) + 0.5 * D(u) + 0.5 * D(v);
    L.radius = 0.5 * std::fmax(len(D(u) + D(v)), len(D(u) - D(v)));
    return L;
}

light_case triangle_case(const std::string& name, vec3f p, vec3f a, vec3f b, vec3f c) {
    light_case L;
    L.name = name;
    L.p = p;
    L.sample = [=](float u1, float u2, light_sample& s) { return sample_triangle_light(p, a, b, c, u1, u2, s); };
    L.pdf = [=](const vec3f& y, const vec3f& ny) { return triangle_light_pdf(p, a, b, c, y, ny); };
    const d3 A = D(a), e1 = D(b) - D(a), e2 = D(c) - D(a);
    L.hit = [=](d3 pp, d3 w, d3& y, d3& n) {
        double s, t;
        if (!hit_plane(pp, w, A, e1, e2, y, s, t) || s < 0 || t < 0 || s + t > 1) return false;
        n = unit(cross(e1, e2));
        return true;
    };
    L.off_surface = [=](d3 y) {
        double s, t;
        plane_coordinates(y, A, e1, e2, s, t);
        double out = std::fmax(std::fmax(-s, -t), s + t - 1);
        return std::fabs(dot(y - A, unit(cross(e1, e2)))) + std::fmax(0.0, out) * std::fmax(len(e1), len(e2));
    };
    L.normal = [=](d3) { return unit(cross(e1, e2)); };
    L.kind = light_case::triangle;
    L.origin = A, L.edge1 = e1, L.edge2 = e2;
    L.centre = (1.0 / 3) * (D(a) + D(b) + D(c));
    L.radius = std::fmax(len(D(a) - L.centre), std::fmax(len(D(b) - L.centre), len(D(c) - L.centre)));
    return L;
}

// The configurations. Rectangles are built rotated in double and rounded, so their edges are
// perpendicular only to float precision (as a transformed scene's would be).
const d3 tilt_axis = unit(d3{0.3, -0.5, 0.8});

vec3f rot(d3 v) { return F(rotate(v, tilt_axis, 0.7)); }

struct quad_geometry {
    std::string name;
    vec3f p, Q, u, v;
};

std::vector<quad_geometry> quads() {
    std::vector<quad_geometry> q;
    {   // a 2 x 1 rectangle, p 0.6 above a point inside it: solid angle about 2.6 sr
        d3 Q{-1, -0.5, 0}, u{2, 0, 0}, v{0, 1, 0}, p{0.2, 0.1, 0.6};
        q.push_back({"rectangle, near, above it", rot(p), rot(Q), rot(u), rot(v)});
    }
    {   // seen obliquely (35 degrees above its plane) and from the side, at 3 units
        d3 Q{-1, -0.5, 0}, u{2, 0, 0}, v{0, 1, 0};
        d3 p = d3{0, 0, 0} + 3.0 * unit(d3{0.6, 0.55, 0.57});
        q.push_back({"rectangle, oblique", rot(p), rot(Q), rot(u), rot(v)});
    }
    {   // 0.05 x 0.02 at 3 units, 20 degrees off its axis: about 1e-4 sr
        d3 Q{-0.025, -0.01, 0}, u{0.05, 0, 0}, v{0, 0.02, 0};
        d3 p = 3.0 * unit(d3{std::sin(0.35), 0, std::cos(0.35)});
        q.push_back({"rectangle, far and small", rot(p), rot(Q), rot(u), rot(v)});
    }
    {   // a skewed parallelogram, p below it
        d3 Q{-0.5, -0.5, 0}, u{1.2, 0, 0}, v{0.7, 0.9, 0}, p{0.3, 0.2, -0.8};
        q.push_back({"parallelogram, skewed", rot(p), rot(Q), rot(u), rot(v)});
    }
    return q;
}

std::vector<light_case> all_lights() {
    std::vector<light_case> L;
    const vec3f c(0.3f, -0.2f, 0.5f);
    const d3 out = unit(d3{0.4, 0.7, -0.3});
    L.push_back(sphere_case("sphere, near (d = 1.5 r)", F(D(c) + 1.5 * out), c, 1.0f));
    L.push_back(sphere_case("sphere, grazing (d = 1.01 r)", F(D(c) + 1.01 * out), c, 1.0f));
    L.push_back(sphere_case("sphere, far and small (sin = 1e-3)", F(D(c) + 10.0 * out), c, 0.01f));
    // Centred near the origin so the sampled points are precise; a cone of 1e-5 rad, where
    // 1 - cos theta_max computed as a difference would be 0 in float.
    L.push_back(sphere_case("sphere, tiny and far (sin = 1e-5)", F(100.0 * out), vec3f(0, 0, 0), 1e-3f));
    L.push_back(sphere_case("sphere, p inside", F(D(c) + 0.6 * out), c, 1.0f));
    L.push_back(sphere_case("sphere, p at the centre", c, c, 0.5f));
    for (const quad_geometry& g : quads()) {
        L.push_back(quad_case("quad area: " + g.name, g.p, g.Q, g.u, g.v, quad_sampling::area));
        L.push_back(quad_case("quad automatic: " + g.name, g.p, g.Q, g.u, g.v, quad_sampling::automatic));
        if (g.name.find("rectangle") != std::string::npos)
            L.push_back(quad_case("quad solid angle: " + g.name, g.p, g.Q, g.u, g.v, quad_sampling::solid_angle));
    }
    L.push_back(triangle_case("triangle, near", vec3f(0.2f, 0.3f, 0.25f), vec3f(-1, -0.5f, 0), vec3f(1.5f, -0.2f, 0.1f),
                              vec3f(0.1f, 1.2f, -0.1f)));
    L.push_back(triangle_case("triangle, oblique", vec3f(3, 2.5f, 0.8f), vec3f(-1, -0.5f, 0), vec3f(1.5f, -0.2f, 0.1f),
                              vec3f(0.1f, 1.2f, -0.1f)));
    L.push_back(triangle_case("triangle, far", vec3f(-20, 15, 30), vec3f(-1, -0.5f, 0), vec3f(1.5f, -0.2f, 0.1f),
                              vec3f(0.1f, 1.2f, -0.1f)));
    return L;
}

} // namespace

TEST_CASE("light sampling: samples are on the light, unit, consistent, and report the pdf function's density") {
    pcg32 rng(11);
    for (const light_case& L : all_lights()) {
        CAPTURE(L.name);
        const d3 p = D(L.p);
        int failed = 0;
        for (int i = 0; i < 2000; ++i) {
            light_sample s;
            if (!L.sample(rng.next_float(), rng.next_float(), s)) {
                ++failed;
                continue;
            }
            REQUIRE(s.pdf > 0);
            REQUIRE(std::isfinite(s.pdf));
            const d3 y = D(s.y), to = y - p;
            CHECK(std::fabs(len(D(s.wi)) - 1) < 1e-6);
            CHECK(rel(s.distance, len(to)) < 1e-6);
            CHECK(len(D(s.wi) - unit(to)) < 1e-6);
            CHECK(L.off_surface(y) < 1e-5 * std::fmax(1.0, len(y)));
            CHECK(len(D(s.n) - L.normal(y)) < 1e-4);
            // (b) the reported density is the pdf function's at the sampled point.
            CHECK(rel(s.pdf, L.pdf(s.y, s.n)) < 1e-6);
        }
        CHECK(failed == 0);
    }
}

TEST_CASE("light sampling: the pdf functions integrate to 1 over the directions that meet the light") {
    // Directions uniform over the cap that the light's bounding sphere subtends (the whole sphere
    // of directions when p is inside it): the estimate cap * mean(pdf * hit) has its sample
    // standard deviation as the bound.
    pcg32 rng(22);
    for (const light_case& L : all_lights()) {
        CAPTURE(L.name);
        const d3 p = D(L.p);
        const d3 to = L.centre - p;
        const double d = len(to);
        const double cos_max = d > L.radius * 1.0001 ? std::sqrt(1 - (L.radius / d) * (L.radius / d)) : -1.0;
        const double one_minus = d > L.radius * 1.0001 ? (L.radius / d) * (L.radius / d) / (1 + cos_max) : 2.0;
        const double cap = 2 * pi_d * one_minus;
        const frame3 f(d > 0 ? to : d3{0, 0, 1});
        const int N = 60000;
        double sum = 0, sum2 = 0;
        for (int i = 0; i < N; ++i) {
            const double q = one_minus * rng.next_double(); // 1 - cos theta
            const double sin_theta = std::sqrt(q * (2 - q));
            const double phi = 2 * pi_d * rng.next_double();
            const d3 w = (sin_theta * std::cos(phi)) * f.t + (sin_theta * std::sin(phi)) * f.b + (1 - q) * f.n;
            d3 y, n;
            double value = 0;
            if (L.hit(p, w, y, n)) value = cap * L.pdf(F(y), F(n));
            sum += value;
            sum2 += value * value;
        }
        const double mean = sum / N;
        const double sigma = std::sqrt(std::fmax(0.0, sum2 / N - mean * mean) / N);
        INFO("integral " << mean << " +- " << sigma);
        CHECK(std::fabs(mean - 1) <= 5 * sigma + 2e-4);
    }
}

namespace {

// Chi-square of N samples binned by `cell` (-1: outside every cell, expected never) against the
// cells' expected probabilities.
void chi_square_check(const light_case& L, pcg32& rng, const std::vector<double>& probability,
                      const std::function<int(const light_sample&)>& cell, long N) {
    std::vector<double> observed(probability.size(), 0), expected(probability.size(), 0);
    double total = 0;
    for (size_t i = 0; i < probability.size(); ++i) {
        expected[i] = probability[i] * double(N);
        total += probability[i];
    }
    // The cells cover the light: their probabilities sum to 1, computed independently of the
    // sampler (and of the solid angle the quad sampler reports, for the rectangles).
    INFO("cells' probabilities sum to " << total);
    CHECK(std::fabs(total - 1) < 2e-3);
    long outside = 0;
    for (long k = 0; k < N; ++k) {
        light_sample s;
        REQUIRE(L.sample(rng.next_float(), rng.next_float(), s));
        int c = cell(s);
        if (c < 0) {
            ++outside;
            continue;
        }
        observed[size_t(c)] += 1;
    }
    CHECK(outside == 0);
    chi2::result r = chi2::test(observed, expected);
    INFO("chi2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
    CHECK(r.dof >= 40);
    CHECK(r.p_value > 1e-3);
}

} // namespace

TEST_CASE("light sampling: chi-square of sphere directions against the pdf over (1 - cos theta, phi) cells") {
    // Cells of directions about the axis from p to the centre: outside, q = 1 - cos theta in
    // [0, 1 - cos theta_max] (theta_max from the test's own double arithmetic), where d omega =
    // dq dphi; inside, cos theta over [-1, 1]. A cell expects pdf() integrated over it (midpoint
    // rule, 6 x 6 points), evaluated at the point where the test's own ray meets the sphere.
    pcg32 rng(33);
    for (const light_case& L : all_lights()) {
        if (L.kind != light_case::sphere) continue;
        CAPTURE(L.name);
        const d3 p = D(L.p), to = L.centre - p;
        const double d = len(to), r = L.radius;
        const bool outside = d > r;
        const double q_max = outside ? (r / d) * (r / d) / (1 + std::sqrt(1 - (r / d) * (r / d))) : 2.0;
        const frame3 f(d > 0 ? to : d3{0.2, 0.3, 0.9});
        const int nq = 10, nphi = 16, m = 6;
        std::vector<double> prob(nq * nphi, 0);
        for (int i = 0; i < nq; ++i)
            for (int j = 0; j < nphi; ++j) {
                double sum = 0;
                for (int a = 0; a < m; ++a)
                    for (int b = 0; b < m; ++b) {
                        const double q = q_max * (i + (a + 0.5) / m) / nq;
                        const double phi = 2 * pi_d * (j + (b + 0.5) / m) / nphi;
                        const double sin_theta = std::sqrt(q * (2 - q));
                        const d3 w =
                            (sin_theta * std::cos(phi)) * f.t + (sin_theta * std::sin(phi)) * f.b + (1 - q) * f.n;
                        d3 y, n;
                        if (L.hit(p, w, y, n)) sum += L.pdf(F(y), F(n));
                    }
                prob[size_t(i * nphi + j)] = sum * (q_max / nq / m) * (2 * pi_d / nphi / m);
            }
        chi_square_check(L, rng, prob, [&](const light_sample& s) {
            // The direction from the sampled point, in double: precise even where the cone is
            // 1e-5 rad wide. q = sin^2 / (1 + cos) without cancellation.
            const d3 w = unit(D(s.y) - p);
            const double c = dot(w, f.n), s2 = dot(cross(w, f.n), cross(w, f.n));
            const double q = c > 0 ? s2 / (1 + c) : 1 - c;
            if (q > q_max * (1 + 1e-4) + 1e-12) return -1;
            return bin(q, 0, q_max, nq) * nphi + bin(f.phi(w), 0, 2 * pi_d, nphi);
        }, 80000);
    }
}

TEST_CASE("light sampling: chi-square of quad and triangle points against the pdf over cells of the light") {
    // Cells of the light's own parameters: (a, b) of Q + a u + b v for quads; for triangles
    // (x1, x2) with the point a + x1 (b - a) + (1 - x1) x2 (c - a) (Duffy's square-to-triangle
    // map). A cell expects pdf() times the Jacobian d omega / d(params) = |cos_y| dA/d(params) / d^2,
    // computed here in double, integrated by the midpoint rule.
    pcg32 rng(44);
    for (const light_case& L : all_lights()) {
        if (L.kind == light_case::sphere) continue;
        const bool is_quad = L.kind == light_case::quad;
        CAPTURE(L.name);
        const d3 O = L.origin, e1 = L.edge1, e2 = L.edge2;
        const d3 p = D(L.p), nn = cross(e1, e2), normal = unit(nn);
        const double area_factor = len(nn); // |e1 x e2|: dA = area_factor da db (quads)
        const int n = 12, m = 8;
        std::vector<double> prob(n * n, 0);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                double sum = 0;
                for (int a = 0; a < m; ++a)
                    for (int b = 0; b < m; ++b) {
                        const double x1 = (i + (a + 0.5) / m) / n, x2 = (j + (b + 0.5) / m) / n;
                        const double s = x1, t = is_quad ? x2 : (1 - x1) * x2;
                        const double dA = is_quad ? area_factor : area_factor * (1 - x1);
                        const d3 y = O + s * e1 + t * e2;
                        const d3 to = y - p;
                        const double d2 = dot(to, to);
                        const double jacobian = dA * std::fabs(dot(normal, to)) / std::sqrt(d2) / d2;
                        sum += L.pdf(F(y), F(normal)) * jacobian;
                    }
                prob[size_t(i * n + j)] = sum / (double(n) * n * m * m);
            }
        chi_square_check(L, rng, prob, [&](const light_sample& smp) {
            double s, t;
            plane_coordinates(D(smp.y), O, e1, e2, s, t);
            const double tol = 1e-5;
            if (s < -tol || t < -tol || (is_quad ? (s > 1 + tol || t > 1 + tol) : s + t > 1 + tol)) return -1;
            const double x1 = s, x2 = is_quad ? t : (s < 1 ? t / (1 - s) : 0.0);
            return bin(x1, 0, 1, n) * n + bin(x2, 0, 1, n);
        }, 80000);
    }
}

TEST_CASE("light sampling: the quad's choice of strategy, and where nothing can be sampled") {
    pcg32 rng(55);
    for (const quad_geometry& g : quads()) {
        CAPTURE(g.name);
        const float S = quad_solid_angle(g.p, g.Q, g.u, g.v);
        const bool rectangle = g.name.find("rectangle") != std::string::npos;
        CHECK((S > 0) == rectangle);
        // automatic: by solid angle exactly for the near and oblique rectangles (S well inside
        // [3e-4, 6.22] and well conditioned); the small far one (about 1e-4 sr) and the
        // parallelogram by area.
        const bool by_solid_angle =
            g.name.find("near") != std::string::npos || g.name.find("oblique") != std::string::npos;
        for (int i = 0; i < 200; ++i) {
            light_sample s;
            REQUIRE(sample_quad_light(g.p, g.Q, g.u, g.v, rng.next_float(), rng.next_float(), s));
            const float area = quad_area_pdf(g.p, g.Q, g.u, g.v, s.y, s.n);
            // To rounding: sampler and pdf function compute alike, but a compiler may fuse
            // multiply-adds differently at the two call sites.
            if (by_solid_angle) {
                CHECK(rel(s.pdf, 1.0 / S) < 1e-6);
                CHECK(rel(s.pdf, quad_solid_angle_pdf(g.p, g.Q, g.u, g.v)) < 1e-6);
            } else {
                CHECK(rel(s.pdf, area) < 1e-6);
            }
        }
        light_sample s;
        CHECK(sample_quad_solid_angle(g.p, g.Q, g.u, g.v, 0.3f, 0.6f, s) == rectangle);
        if (!rectangle) CHECK(quad_solid_angle_pdf(g.p, g.Q, g.u, g.v) == 0);
    }
    SUBCASE("a rectangle seen at a grazing angle from the side is sampled by area (ill-conditioned warp)") {
        // 1 x 1, p 0.05 above its plane and 3 to the side: S is about 5e-3 sr, inside the
        // thresholds, but the condition number x^3 / (z0^2 w) is about 1e4.
        const vec3f Q(-0.5f, -0.5f, 0), u(1, 0, 0), v(0, 1, 0), p(3.0f, 0.2f, 0.05f);
        const float S = quad_solid_angle(p, Q, u, v);
        CHECK(S > quad_min_solid_angle);
        CHECK(S < quad_max_solid_angle);
        light_sample s;
        REQUIRE(sample_quad_light(p, Q, u, v, 0.4f, 0.7f, s));
        CHECK(rel(s.pdf, quad_area_pdf(p, Q, u, v, s.y, s.n)) < 1e-6);
        CHECK(rel(quad_light_pdf(p, Q, u, v, s.y, s.n), s.pdf) < 1e-6);
        REQUIRE(sample_quad_light(p, Q, u, v, 0.4f, 0.7f, s, quad_sampling::solid_angle));
        CHECK(rel(s.pdf, 1.0 / S) < 1e-6);
    }
    SUBCASE("a rectangle that looks small is sampled by area: A |cos| / d^2 at its centre below 0.1") {
        // A unit square seen straight on from its centre's normal at height h: the estimate is
        // 1 / h^2; its exact solid angle 4 asin(1 / (1 + 4 h^2)) (the centred rectangle's closed
        // form, 4 asin(a b / sqrt((a^2 + 4 h^2)(b^2 + 4 h^2)))) is inside [3e-4, 6.22] for both.
        const vec3f Q(-0.5f, -0.5f, 0), u(1, 0, 0), v(0, 1, 0);
        for (float h : {2.0f, 4.0f}) {
            CAPTURE(h);
            const vec3f p(0, 0, h);
            const double exact = 4 * std::asin(1.0 / (1.0 + 4.0 * double(h) * double(h)));
            CHECK(rel(quad_solid_angle(p, Q, u, v), exact) < 1e-5);
            const bool large = 1.0f / (h * h) >= quad_solid_angle_worth; // 0.25 and 0.0625 against 0.1
            CHECK(large == (h == 2.0f));
            light_sample s;
            REQUIRE(sample_quad_light(p, Q, u, v, 0.5f, 0.5f, s));
            // The centre of the square: by area its density is d^2 / (A cos) = h^2.
            CHECK(rel(s.pdf, large ? 1.0 / exact : double(h) * double(h)) < 1e-5);
            CHECK(rel(quad_light_pdf(p, Q, u, v, s.y, s.n), s.pdf) < 1e-6);
        }
    }
    SUBCASE("p on the light's plane, degenerate shapes") {
        const vec3f Q(0, 0, 0), u(1, 0, 0), v(0, 1, 0);
        light_sample s;
        for (vec3f p : {vec3f(0.5f, 0.5f, 0), vec3f(3, 0.5f, 0)}) {
            CHECK_FALSE(sample_quad_area(p, Q, u, v, 0.3f, 0.6f, s));
            CHECK_FALSE(sample_quad_solid_angle(p, Q, u, v, 0.3f, 0.6f, s));
            CHECK_FALSE(sample_quad_light(p, Q, u, v, 0.3f, 0.6f, s));
            CHECK(quad_solid_angle(p, Q, u, v) == 0);
            CHECK_FALSE(sample_triangle_light(p, Q, u, v, 0.3f, 0.6f, s));
        }
        const vec3f p(0.2f, 0.3f, 1);
        CHECK_FALSE(sample_quad_light(p, Q, u, 2.0f * u, 0.3f, 0.6f, s)); // u parallel to v
        CHECK(quad_light_pdf(p, Q, u, 2.0f * u, vec3f(0.5f, 0, 0), vec3f(0, 0, 1)) == 0);
        CHECK_FALSE(sample_triangle_light(p, Q, u, 2.0f * u, 0.3f, 0.6f, s));
        CHECK(triangle_light_pdf(p, Q, u, 2.0f * u, vec3f(0.5f, 0, 0), vec3f(0, 0, 1)) == 0);
        CHECK_FALSE(sample_sphere_light(p, Q, 0.0f, 0.3f, 0.6f, s));
        CHECK(sphere_light_pdf(p, Q, 0.0f, Q, v) == 0);
        // p on the unit sphere: uniform by area (and a point y = p is refused, not divided by).
        CHECK(sample_sphere_light(vec3f(1, 0, 0), vec3f(0, 0, 0), 1.0f, 0.3f, 0.6f, s));
        CHECK(rel(s.pdf, sphere_light_pdf(vec3f(1, 0, 0), vec3f(0, 0, 0), 1.0f, s.y, s.n)) < 1e-6);
    }
}

TEST_CASE("light sampling: the rectangle's solid angle against closed forms") {
    // A rectangle a x b seen from height h above one corner subtends
    //   omega(a, b, h) = atan(a b / (h sqrt(a^2 + b^2 + h^2))).
    // Derivation: the right rectangular pyramid with half apex angles alpha, beta subtends
    // 4 asin(sin alpha sin beta) (Wikipedia, "Solid angle", section "Pyramid"); for a 2a x 2b
    // rectangle at height h on its axis, sin alpha = a / sqrt(a^2 + h^2), and by symmetry a
    // quarter of it, a x b above its corner, subtends asin(a b / sqrt((a^2 + h^2)(b^2 + h^2))),
    // which is the atan form (sin(atan X) = X / sqrt(1 + X^2)). A square of side a on its axis is
    // then 4 asin(a^2 / (a^2 + 4 h^2)). A point above any other place is a signed sum of four such
    // corner rectangles (inclusion-exclusion).
    auto corner = [](double a, double b, double h) {
        if (a == 0 || b == 0) return 0.0;
        const double sign = (a > 0) == (b > 0) ? 1 : -1;
        a = std::fabs(a), b = std::fabs(b);
        return sign * std::atan(a * b / (h * std::sqrt(a * a + b * b + h * h)));
    };
    // The rectangle [x0, x0 + w] x [y0, y0 + l] of the plane z = 0, seen from (0, 0, h).
    auto closed = [&](double x0, double y0, double w, double l, double h) {
        const double x1 = x0 + w, y1 = y0 + l;
        return corner(x1, y1, h) - corner(x0, y1, h) - corner(x1, y0, h) + corner(x0, y0, h);
    };
    for (double h : {0.05, 0.5, 1.0, 3.0, 40.0}) {
        CAPTURE(h);
        const double a = 1.5;
        const double square = 4 * std::asin(a * a / (a * a + 4 * h * h));
        CHECK(closed(-a / 2, -a / 2, a, a, h) == doctest::Approx(square).epsilon(1e-12));
        // p on the axis, above and below (the sampler turns its frame towards p).
        const vec3f Q(-0.75f, -0.75f, 0), u(1.5f, 0, 0), v(0, 1.5f, 0);
        CHECK(quad_solid_angle(vec3f(0, 0, float(h)), Q, u, v) == doctest::Approx(square).epsilon(2e-6));
        CHECK(quad_solid_angle(vec3f(0, 0, -float(h)), Q, u, v) == doctest::Approx(square).epsilon(2e-6));
        CHECK(quad_solid_angle_pdf(vec3f(0, 0, float(h)), Q, u, v) == doctest::Approx(1 / square).epsilon(2e-6));
    }
    // Off the axis, inside and outside the rectangle's shadow, with a rotated frame.
    struct off_axis { double px, py, h; };
    for (off_axis o :
         {off_axis{0.3, -0.2, 0.7}, off_axis{2.5, 0.4, 1.2}, off_axis{-3.0, 4.0, 0.5}, off_axis{0.1, 0.9, 10.0}}) {
        CAPTURE(o.px);
        CAPTURE(o.py);
        CAPTURE(o.h);
        const double x0 = -1.0, y0 = -0.5, w = 2.0, l = 1.0;
        const double expected = closed(x0 - o.px, y0 - o.py, w, l, o.h);
        const vec3f Q = rot(d3{x0, y0, 0}), u = rot(d3{w, 0, 0}), v = rot(d3{0, l, 0}), p = rot(d3{o.px, o.py, o.h});
        // Float inputs: the tolerance is a few float ulps of the larger of the angles summed.
        CHECK(quad_solid_angle(p, Q, u, v) == doctest::Approx(expected).epsilon(2e-5));
    }
    // Far on the axis the solid angle stays precise to float's relative precision: the sampler
    // sums four small angles, never forming 2 pi - (four angles near pi / 2).
    for (double h : {100.0, 1e3, 1e4}) {
        CAPTURE(h);
        const vec3f Q(-0.5f, -0.25f, 0), u(1, 0, 0), v(0, 0.5f, 0);
        const double expected = closed(-0.5, -0.25, 1, 0.5, h);
        CHECK(quad_solid_angle(vec3f(0, 0, float(h)), Q, u, v) == doctest::Approx(expected).epsilon(1e-5));
    }
}

TEST_CASE("light sampling: the rectangle's angles, atan(y / x) without a call, within 3 ulps of the double value") {
    // Ratios from 1e-8 to 1e8 of either sign, uniform in their logarithm, and every ratio near
    // the range reduction's seams at tan(pi / 8) and tan(3 pi / 8); against std::atan2 in double.
    pcg32 g(77);
    double worst_ulps = 0;
    auto check = [&](float y, float x) {
        const double exact = std::atan2(double(y), double(x));
        const float got = detail::atan_of_ratio(y, x);
        const float magnitude = std::fabs(float(exact));
        const double ulp = double(std::nextafter(magnitude, 4.0f) - magnitude);
        worst_ulps = std::fmax(worst_ulps, std::fabs(double(got) - exact) / ulp);
        REQUIRE(std::signbit(got) == std::signbit(y));
    };
    for (int i = 0; i < 200000; ++i) {
        const float x = std::exp(g.next_float() * 20 - 10);
        const float ratio = std::exp(g.next_float() * 36.8f - 18.4f);
        check((i & 1 ? 1.0f : -1.0f) * ratio * x, x);
    }
    for (float seam : {0.41421356f, 2.4142135f})
        for (int k = -2000; k <= 2000; ++k) check(seam * (1 + float(k) * 1e-7f), 1.0f);
    check(0.0f, 1.0f);
    check(-0.0f, 1.0f);
    check(1.0f, 0.0f); // x -> 0+: pi / 2
    CAPTURE(worst_ulps);
    CHECK(worst_ulps <= 3.0);
    CHECK(detail::atan_of_ratio(1.0f, 1.0f) == doctest::Approx(0.7853981633974483).epsilon(2e-7));
    CHECK(detail::atan_of_ratio(-1e30f, 1.0f) == doctest::Approx(-1.5707963267948966).epsilon(2e-7));
}

TEST_CASE("light sampling: area_to_solid_angle by hand") {
    // d = 2, facing p: p_A d^2 = 4 p_A; at 60 degrees from the normal: divided by cos = 1/2.
    const vec3f p(0, 0, 0), y(0, 0, 2);
    CHECK(area_to_solid_angle(0.5f, p, y, vec3f(0, 0, -1)) == doctest::Approx(2.0));
    CHECK(area_to_solid_angle(0.5f, p, y, vec3f(0, 0, 1)) == doctest::Approx(2.0)); // either side
    const vec3f n60(std::sin(float(pi_d / 3)), 0, -std::cos(float(pi_d / 3)));
    CHECK(area_to_solid_angle(0.5f, p, y, n60) == doctest::Approx(4.0).epsilon(1e-5));
    CHECK(area_to_solid_angle(0.5f, p, y, vec3f(1, 0, 0)) == 0); // edge-on
    CHECK(area_to_solid_angle(0.5f, p, p, vec3f(0, 0, 1)) == 0); // y = p
}

TEST_CASE("power_heuristic: values and edge cases") {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(power_heuristic(1, 1) == doctest::Approx(0.5));
    CHECK(power_heuristic(2, 1) == doctest::Approx(0.8));
    CHECK(power_heuristic(1, 3) == doctest::Approx(0.1));
    CHECK(power_heuristic(0, 0) == 0);
    CHECK(power_heuristic(0, 5) == 0);
    CHECK(power_heuristic(3, 0) == 1);
    CHECK(power_heuristic(inf, 1) == 1);
    CHECK(power_heuristic(1, inf) == 0);
    CHECK(power_heuristic(inf, inf) == 0.5f);
    CHECK(power_heuristic(inf, 0) == 1);
    CHECK(power_heuristic(0, inf) == 0);
    CHECK(power_heuristic(nan, 1) == 0);
    CHECK(power_heuristic(-1, 1) == 0);
    CHECK(power_heuristic(1, nan) == 1);
    // Squares that would underflow or overflow alone.
    CHECK(power_heuristic(1e-30f, 1e-30f) == doctest::Approx(0.5));
    CHECK(power_heuristic(3e-30f, 1e-30f) == doctest::Approx(0.9));
    CHECK(power_heuristic(1e30f, 1e30f) == doctest::Approx(0.5));
    CHECK(power_heuristic(1e30f, 1) == 1);
    CHECK(power_heuristic(1, 1e30f) == 0);
    // The two weights of a pair sum to 1.
    pcg32 rng(66);
    for (int i = 0; i < 1000; ++i) {
        const float a = std::exp(40 * rng.next_float() - 20), b = std::exp(40 * rng.next_float() - 20);
        CHECK(power_heuristic(a, b) + power_heuristic(b, a) == doctest::Approx(1.0).epsilon(1e-6));
    }
}

TEST_CASE("alias_table: pmf, single entry, empty table, invalid weights") {
    const std::vector<double> w = {1, 0, 3, 0.5, 5.5};
    alias_table t(w);
    REQUIRE(t.size() == 5);
    CHECK_FALSE(t.empty());
    for (uint32_t i = 0; i < 5; ++i) CHECK(t.pmf(i) == float(w[i] / 10.0));
    CHECK(t.pmf(5) == 0);

    alias_table one(std::vector<double>{2.5});
    CHECK(one.size() == 1);
    CHECK(one.pmf(0) == 1.0f);
    for (float u : {0.0f, 0.3f, 0.5f, 0x1.fffffep-1f, 1.0f}) CHECK(one.sample(u) == 0);

    alias_table none;
    CHECK(none.empty());
    CHECK(none.size() == 0);
    CHECK(none.pmf(0) == 0);

    const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(alias_table(std::vector<double>{}), std::invalid_argument);
    CHECK_THROWS_AS(alias_table(std::vector<double>{0, 0, 0}), std::invalid_argument);
    CHECK_THROWS_AS(alias_table(std::vector<double>{1, -1}), std::invalid_argument);
    CHECK_THROWS_AS(alias_table(std::vector<double>{1, nan}), std::invalid_argument);
    CHECK_THROWS_AS(alias_table(std::vector<double>{1, inf}), std::invalid_argument);
    CHECK_THROWS_AS(alias_table(std::vector<double>{1e308, 1e308}), std::invalid_argument); // total overflows
}

TEST_CASE("alias_table: every float uniform enumerated gives the pmf to the uniform's resolution") {
    // u = k 2^-24 for every k: the exact probability sample() realises. Each index occupies at most
    // n pmf + 2 bins (its own and those it is the alias of), each split to a multiple of 2^-24
    // off, so the realised probability is within (n pmf + 3) 2^-24 of pmf.
    std::vector<double> w(37);
    for (size_t i = 0; i < w.size(); ++i) w[i] = i % 7 == 3 ? 0.0 : std::pow(1.4, double(i)) + (i == 20 ? 1e4 : 0.0);
    const alias_table t(w);
    std::vector<long> count(w.size(), 0);
    for (uint32_t k = 0; k < (1u << 24); ++k) ++count[t.sample(float(k) * 0x1p-24f)];
    const double n = double(w.size());
    for (uint32_t i = 0; i < w.size(); ++i) {
        CAPTURE(i);
        const double realised = double(count[i]) * 0x1p-24;
        if (w[i] == 0) CHECK(count[i] == 0);
        CHECK(std::fabs(realised - t.pmf(i)) <= (n * t.pmf(i) + 3) * 0x1p-24);
    }
}

TEST_CASE("alias_table: chi-square of sample() counts for skewed weights, zero weights never drawn") {
    // 2000 weights over 8 decades, a fifth of them zero: the O(n) build, and draws from pcg32.
    pcg32 rng(77);
    std::vector<double> w(2000);
    for (size_t i = 0; i < w.size(); ++i) w[i] = i % 5 == 1 ? 0.0 : std::pow(10.0, 8.0 * rng.next_double() - 4);
    w[17] = 5e4; // one dominant light
    const alias_table t(w);
    double total = 0;
    for (double x : w) total += x;
    const long N = 400000;
    std::vector<double> observed(w.size(), 0), expected(w.size(), 0);
    for (size_t i = 0; i < w.size(); ++i) expected[i] = double(N) * w[i] / total;
    long zero_drawn = 0;
    for (long k = 0; k < N; ++k) {
        const uint32_t i = t.sample(rng.next_float());
        REQUIRE(i < w.size());
        if (w[i] == 0) ++zero_drawn;
        observed[i] += 1;
    }
    CHECK(zero_drawn == 0);
    chi2::result r = chi2::test(observed, expected);
    INFO("chi2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
    CHECK(r.dof >= 100);
    CHECK(r.p_value > 1e-3);
    CHECK(r.observed_where_impossible == 0);
    // The first and the last uniform both land on an index that can be drawn.
    CHECK(w[t.sample(0.0f)] > 0);
    CHECK(w[t.sample(0x1.fffffep-1f)] > 0);
}

} // namespace test_light_sampling
