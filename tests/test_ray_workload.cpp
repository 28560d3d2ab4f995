// The standard mesh workload (apps/ray_workload.h), driven by an analytic sphere tracer at small
// resolutions: camera placement, ray counts against a pixel-grid prediction, the secondary
// origins' offset, shadow rays towards the light, and determinism.

#include "ray_workload.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

namespace test_ray_workload {

using rt::vec3;
using rt::vec3f;

namespace {

const double deg20 = 20.0 * rt::pi / 180.0;

// The sphere of radius 2 about (1, -2, 3) and its bounding box; R = 2 sqrt(3).
const vec3 centre(1, -2, 3);
const double radius = 2;
const vec3f box_lo{-1, -4, 1}, box_hi{3, 0, 5};
const double big_r = 2 * std::sqrt(3.0);

vec3 to_double(const vec3f& v) { return vec3(v.x, v.y, v.z); }

// Closest hit on the sphere, in double; the normal is p - centre (outward, not unit).
struct sphere_tracer {
    bool inward = false;
    bool operator()(const rt::ray3f& r, float& t, vec3f& n) const {
        vec3 o = to_double(r.origin), d = to_double(r.dir);
        vec3 oc = o - centre;
        double b = rt::dot(oc, d), c = rt::dot(oc, oc) - radius * radius;
        double disc = b * b - c;
        if (disc < 0) return false;
        double s = std::sqrt(disc);
        for (double root : {-b - s, -b + s}) {
            if (root >= r.tmin && root <= r.tmax) {
                t = float(root);
                vec3 p = o + root * d - centre;
                if (inward) p = -p;
                n = vec3f(float(p.x()), float(p.y()), float(p.z()));
                return true;
            }
        }
        return false;
    }
};

const vec3 view_dir = rt::unit_vector(vec3(0.45, 0.35, 1)); // from the centre towards the eye
const vec3 light = centre + 3 * big_r * rt::unit_vector(vec3(-0.5, 1, 0.6));

void check_close(const vec3& a, const vec3& b, double tol) {
    CAPTURE(a);
    CAPTURE(b);
    CHECK((a - b).length() <= tol);
}

} // namespace

TEST_CASE("workload: the camera looks at the box centre from d = R / sin 20deg along (0.45, 0.35, 1)") {
    app::workload w = app::make_standard_workload(box_lo, box_hi, sphere_tracer{}, 5);
    REQUIRE(w.primary.rays.size() == 25);
    CHECK(w.primary.kind == rt::ray_query::closest);

    const vec3 eye = centre + (big_r / std::sin(deg20)) * view_dir; // d = 10.129...
    for (const rt::ray3f& r : w.primary.rays) {
        check_close(to_double(r.origin), eye, 1e-5);
        CHECK(r.tmin == 0.0f);
        CHECK(r.tmax == std::numeric_limits<float>::infinity());
    }
    // 5 x 5: pixel (2, 2), index 12, is the exact centre of the image.
    check_close(to_double(w.primary.rays[12].dir), -view_dir, 1e-6);

    // The top-left pixel centre sits at (-0.8, +0.8) tan 20deg on the image plane at distance 1:
    // its angle to the axis has cosine 1 / sqrt(1 + 2 (0.8 tan 20deg)^2), it points left (against
    // right = (1, 0, -0.45) / |.|) and up.
    const vec3 corner = to_double(w.primary.rays[0].dir);
    const double k = 0.8 * std::tan(deg20);
    CHECK(rt::dot(corner, -view_dir) == doctest::Approx(1 / std::sqrt(1 + 2 * k * k)).epsilon(1e-6));
    const vec3 right = rt::unit_vector(vec3(1, 0, -0.45));
    CHECK(rt::dot(corner, right) == doctest::Approx(-k / std::sqrt(1 + 2 * k * k)).epsilon(1e-5));
    CHECK(corner.y() > w.primary.rays[12].dir.y);
    // Row-major from the top-left: index 1 is one pixel right, index 5 one pixel down.
    CHECK(rt::dot(to_double(w.primary.rays[1].dir) - corner, right) > 0);
    CHECK(w.primary.rays[5].dir.y < w.primary.rays[0].dir.y);
}

TEST_CASE("workload: hit counts follow the sphere's silhouette on the pixel grid") {
    // The sphere (radius r) subtends half-angle a with sin a = r / d = sin 20deg / sqrt(3). A
    // pixel centre at image-plane coordinates (x, y) tan 20deg hits iff x^2 + y^2 < (tan a / tan 20deg)^2.
    const double sin_a = std::sin(deg20) / std::sqrt(3.0);
    const double ratio = sin_a / std::sqrt(1 - sin_a * sin_a) / std::tan(deg20); // 0.55343
    auto predicted_hits = [&](int n) {
        size_t hits = 0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                double x = 2 * (i + 0.5) / n - 1, y = 1 - 2 * (j + 0.5) / n;
                hits += x * x + y * y < ratio * ratio ? 1 : 0;
            }
        return hits;
    };
    // 5 x 5 by hand: only (0, 0) and (+-0.4, 0), (0, +-0.4) are inside radius 0.553.
    CHECK(predicted_hits(5) == 5);

    for (int n : {5, 32}) {
        CAPTURE(n);
        app::workload w = app::make_standard_workload(box_lo, box_hi, sphere_tracer{}, n);
        CHECK(w.primary.rays.size() == size_t(n) * n);
        CHECK(w.diffuse.rays.size() == predicted_hits(n));
        CHECK(w.diffuse.kind == rt::ray_query::closest);
        CHECK(w.shadow.kind == rt::ray_query::any);
        CHECK(w.shadow.rays.size() > 0);
        CHECK(w.shadow.rays.size() < w.diffuse.rays.size());
    }
}

TEST_CASE("workload: secondary rays start 1e-4 R off the surface, and shadow rays stop just short of the light") {
    app::workload w = app::make_standard_workload(box_lo, box_hi, sphere_tracer{}, 5);
    REQUIRE(w.diffuse.rays.size() == 5); // pixels 7, 11, 12, 13, 17

    // Pixel 12 is the third hit: the centre ray meets the sphere at centre + r * view_dir, where
    // the normal is view_dir.
    const rt::ray3f& d = w.diffuse.rays[2];
    const vec3 q = to_double(d.origin);
    check_close(q, centre + (radius + 1e-4 * big_r) * view_dir, 1e-5);
    CHECK((q - centre).length() - radius == doctest::Approx(1e-4 * big_r).epsilon(0.02));
    CHECK(d.tmin == 0.0f);
    CHECK(d.tmax == std::numeric_limits<float>::infinity());

    // Its direction is the cosine sample about the normal from sample_rng(0, pixel 12, 0).
    rt::pcg32 rng = rt::sample_rng(0, 12, 0);
    float u1 = rng.next_float(), u2 = rng.next_float();
    vec3f expected = rt::sample_cosine_direction(vec3f(float(view_dir.x()), float(view_dir.y()), float(view_dir.z())), u1, u2);
    check_close(to_double(d.dir), to_double(expected), 1e-6);
    CHECK(rt::dot(to_double(d.dir), view_dir) > 0);

    // The light is above the surface there (n . (L - p) = 3R * 0.4963 - r > 0): a shadow ray
    // from the same origin, aimed at the light, ending 1e-4 of the way short of it.
    const rt::ray3f* s = nullptr;
    for (const rt::ray3f& r : w.shadow.rays)
        if (r.origin.x == d.origin.x && r.origin.y == d.origin.y && r.origin.z == d.origin.z) s = &r;
    REQUIRE(s != nullptr);
    const double distance = (light - q).length();
    check_close(to_double(s->dir), (light - q) / distance, 1e-6);
    CHECK(s->tmax == doctest::Approx(distance * (1 - 1e-4)).epsilon(1e-6));
    CHECK(double(s->tmax) < distance);
    CHECK(s->tmin == 0.0f);
}

TEST_CASE("workload: a shadow ray exactly where the light is above the surface") {
    // On the sphere, n . (L - p) > 0  <=>  n . unit(L - c) > r / |L - c| = 1 / (3 sqrt 3).
    app::workload w = app::make_standard_workload(box_lo, box_hi, sphere_tracer{}, 24);
    const vec3 to_light = rt::unit_vector(light - centre);
    size_t expected = 0;
    for (const rt::ray3f& d : w.diffuse.rays) {
        vec3 n = rt::unit_vector(to_double(d.origin) - centre);
        double margin = rt::dot(n, to_light) - 1 / (3 * std::sqrt(3.0));
        REQUIRE(std::fabs(margin) > 1e-4); // no pixel sits on the terminator
        bool lit = margin > 0;
        expected += lit ? 1 : 0;
        bool found = false;
        for (const rt::ray3f& s : w.shadow.rays)
            found = found || (s.origin.x == d.origin.x && s.origin.y == d.origin.y && s.origin.z == d.origin.z);
        CHECK(found == lit);
    }
    CHECK(w.shadow.rays.size() == expected);
    for (const rt::ray3f& s : w.shadow.rays) {
        vec3 end = to_double(s.origin) + (double(s.tmax) / (1 - 1e-4)) * to_double(s.dir);
        check_close(end, light, 1e-4);
    }
}

TEST_CASE("workload: deterministic, and indifferent to the orientation of the tracer's normal") {
    app::workload a = app::make_standard_workload(box_lo, box_hi, sphere_tracer{}, 16);
    app::workload b = app::make_standard_workload(box_lo, box_hi, sphere_tracer{}, 16);
    app::workload flipped = app::make_standard_workload(box_lo, box_hi, sphere_tracer{true}, 16);
    for (auto* w : {&b, &flipped}) {
        CHECK(rt::encode_rays(w->primary) == rt::encode_rays(a.primary));
        CHECK(rt::encode_rays(w->diffuse) == rt::encode_rays(a.diffuse));
        CHECK(rt::encode_rays(w->shadow) == rt::encode_rays(a.shadow));
    }
}

TEST_CASE("workload: misses give no secondary rays, impossible tracer answers and boxes are refused") {
    auto miss = [](const rt::ray3f&, float&, vec3f&) { return false; };
    app::workload w = app::make_standard_workload(box_lo, box_hi, miss, 4);
    CHECK(w.primary.rays.size() == 16);
    CHECK(w.diffuse.rays.empty());
    CHECK(w.shadow.rays.empty());

    auto zero_normal = [](const rt::ray3f&, float& t, vec3f& n) {
        t = 1;
        n = {0, 0, 0};
        return true;
    };
    CHECK_THROWS_WITH_AS(app::make_standard_workload(box_lo, box_hi, zero_normal, 4), doctest::Contains("normal"),
                         rt::scene_error);
    auto nan_t = [](const rt::ray3f&, float& t, vec3f& n) {
        t = std::numeric_limits<float>::quiet_NaN();
        n = {0, 1, 0};
        return true;
    };
    CHECK_THROWS_WITH_AS(app::make_standard_workload(box_lo, box_hi, nan_t, 4), doctest::Contains("t = "), rt::scene_error);

    CHECK_THROWS_AS(app::make_standard_workload(box_hi, box_lo, miss, 4), rt::scene_error);          // inverted box
    CHECK_THROWS_AS(app::make_standard_workload(box_lo, box_lo, miss, 4), rt::scene_error);          // a point
    CHECK_THROWS_AS(app::make_standard_workload(box_lo, box_hi, miss, 0), rt::scene_error);          // no pixels
}

} // namespace test_ray_workload
