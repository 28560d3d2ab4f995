// Ray-sphere intersection: sphere::hit (the book's double API, rtweekend/sphere.h), sphere_roots,
// and the renderer's float closest-hit query compiled_scene::intersect (rtweekend/scene/scene_compiler.h).
//
// Reference values are analytic (worked out in the comments) or come from the textbook quadratic
// formula evaluated in long double.

#include <rtweekend/hittable_list.h>
#include <rtweekend/material.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/sphere.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <utility>
#include <vector>

namespace test_sphere {

using namespace rt;

namespace {

std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

const interval book_range(0.001, infinity); // the book's ray_color interval

// The world holding one sphere, compiled relative to `origin`.
compiled_scene compile_one(const point3& center, double radius, const point3& origin, hittable_list& keep) {
    keep.add(std::make_shared<sphere>(center, radius, grey()));
    return compile_scene(keep, origin);
}

// A float ray from `from` (world space) along the unit direction `dir`, relative to the scene origin.
ray3f make_ray(const compiled_scene& s, const point3& from, const vec3& dir, float tmin = 0,
               float tmax = std::numeric_limits<float>::infinity()) {
    ray3f r;
    r.origin = vec3f(from - s.origin);
    r.dir = vec3f(unit_vector(dir));
    r.tmin = tmin;
    r.tmax = tmax;
    return r;
}

// Textbook roots of |o + t d - c|^2 = r^2 in long double: a t^2 + b t + c = 0 with
// a = d.d, b = 2 d.(o - c), c = |o - c|^2 - r^2; t = (-b -+ sqrt(b^2 - 4ac)) / 2a.
bool textbook_roots(const vec3& o, const vec3& d, const vec3& center, double radius, long double& t0,
                    long double& t1) {
    long double ox = (long double)o.x() - center.x(), oy = (long double)o.y() - center.y(),
                oz = (long double)o.z() - center.z();
    long double dx = d.x(), dy = d.y(), dz = d.z();
    long double a = dx * dx + dy * dy + dz * dz;
    long double b = 2 * (dx * ox + dy * oy + dz * oz);
    long double c = ox * ox + oy * oy + oz * oz - (long double)radius * radius;
    long double disc = b * b - 4 * a * c;
    if (disc < 0) return false;
    long double s = std::sqrt(disc);
    t0 = (-b - s) / (2 * a);
    t1 = (-b + s) / (2 * a);
    return true;
}

} // namespace

// ------------------------------------------------------------------------------------------------
// sphere::hit (double)

TEST_CASE("sphere::hit from outside: t = distance - r, outward normal, front face") {
    // Centre (0,0,-5), r = 1, ray from the origin along -z: enters at z = -4, t = 5 - 1 = 4.
    sphere s(point3(0, 0, -5), 1, grey());
    hit_record rec;
    REQUIRE(s.hit(ray(point3(0, 0, 0), vec3(0, 0, -1)), book_range, rec));
    CHECK(rec.t == doctest::Approx(4).epsilon(1e-15));
    CHECK(rec.p.x() == 0);
    CHECK(rec.p.y() == 0);
    CHECK(rec.p.z() == doctest::Approx(-4).epsilon(1e-15));
    CHECK(rec.normal.z() == doctest::Approx(1).epsilon(1e-15));
    CHECK(rec.normal.x() == 0);
    CHECK(rec.normal.y() == 0);
    CHECK(rec.front_face);
    CHECK(rec.mat.get() == s.mat().get());

    // A direction that is not normalised gives t in units of that direction: |d| = 2 -> t = 2.
    REQUIRE(s.hit(ray(point3(0, 0, 0), vec3(0, 0, -2)), book_range, rec));
    CHECK(rec.t == doctest::Approx(2).epsilon(1e-15));
    CHECK(rec.p.z() == doctest::Approx(-4).epsilon(1e-15));

    // Oblique: centre (3,4,0) r = 2.5, ray from the origin along (3,4,0)/5: distance 5, t = 2.5.
    sphere s2(point3(3, 4, 0), 2.5, grey());
    REQUIRE(s2.hit(ray(point3(0, 0, 0), vec3(0.6, 0.8, 0)), book_range, rec));
    CHECK(rec.t == doctest::Approx(2.5).epsilon(1e-14));
    CHECK(rec.normal.x() == doctest::Approx(-0.6).epsilon(1e-14));
    CHECK(rec.normal.y() == doctest::Approx(-0.8).epsilon(1e-14));
    CHECK(rec.front_face);
}

TEST_CASE("sphere::hit from inside: far wall, back face, normal flipped towards the ray") {
    // Centre at the origin, r = 2, ray from the centre along +x: roots -2 and +2; -2 is outside
    // (0.001, inf), so the hit is the far wall at t = 2, p = (2,0,0), outward normal (1,0,0);
    // the ray leaves through the surface, so front_face is false and normal = -outward.
    sphere s(point3(0, 0, 0), 2, grey());
    hit_record rec;
    REQUIRE(s.hit(ray(point3(0, 0, 0), vec3(1, 0, 0)), book_range, rec));
    CHECK(rec.t == doctest::Approx(2).epsilon(1e-15));
    CHECK(rec.p.x() == doctest::Approx(2).epsilon(1e-15));
    CHECK_FALSE(rec.front_face);
    CHECK(rec.normal.x() == doctest::Approx(-1).epsilon(1e-15));
    CHECK(rec.normal.y() == 0);
    CHECK(rec.normal.z() == 0);

    // Off-centre inside point (0.5,0,0) along +x: far wall at x = 2, t = 1.5.
    REQUIRE(s.hit(ray(point3(0.5, 0, 0), vec3(1, 0, 0)), book_range, rec));
    CHECK(rec.t == doctest::Approx(1.5).epsilon(1e-15));
    CHECK_FALSE(rec.front_face);
}

TEST_CASE("sphere::hit tangent ray: grazes exactly at the tangent point") {
    // Centre (0,1,-5), r = 1; the ray from the origin along -z passes at distance exactly 1 from the
    // centre (every quantity here is exact in binary), touching the sphere at (0,0,-5), t = 5.
    // Decision (documented): an exact tangent counts as a hit. The normal there is perpendicular to
    // the ray, so which face is "front" is a 0-vs-0 convention; we only require the record to be
    // self-consistent (normal = +-outward (0,-1,0), perpendicular to the ray).
    sphere s(point3(0, 1, -5), 1, grey());
    hit_record rec;
    REQUIRE(s.hit(ray(point3(0, 0, 0), vec3(0, 0, -1)), book_range, rec));
    CHECK(rec.t == doctest::Approx(5).epsilon(1e-12));
    CHECK(std::fabs(rec.p.x()) < 1e-12);
    CHECK(std::fabs(rec.p.y()) < 1e-12);
    CHECK(rec.p.z() == doctest::Approx(-5).epsilon(1e-12));
    CHECK(std::fabs(rec.normal.y()) == doctest::Approx(1).epsilon(1e-12));
    CHECK(std::fabs(rec.normal.z()) < 1e-12);
    CHECK(rec.normal.y() == doctest::Approx(rec.front_face ? -1.0 : 1.0));

    // Just inside the tangent (distance 1 - 1e-6 from the centre): two close roots,
    // t = 5 -+ sqrt(1 - (1-1e-6)^2) = 5 -+ sqrt(2e-6 - 1e-12) ~ 5 -+ 1.41421e-3.
    REQUIRE(s.hit(ray(point3(0, 1e-6, 0), vec3(0, 0, -1)), book_range, rec));
    CHECK(rec.t == doctest::Approx(5 - std::sqrt(2e-6 - 1e-12)).epsilon(1e-9));
    CHECK(rec.front_face);
    // Just outside (distance 1 + 1e-6): a miss.
    CHECK_FALSE(s.hit(ray(point3(0, -1e-6, 0), vec3(0, 0, -1)), book_range, rec));
}

TEST_CASE("sphere::hit: spheres behind the ray are not hit, and ray_t limits are respected") {
    hit_record rec;
    // Sphere behind: centre (0,0,5), ray along -z from the origin: roots -6 and -4.
    sphere behind(point3(0, 0, 5), 1, grey());
    CHECK_FALSE(behind.hit(ray(point3(0, 0, 0), vec3(0, 0, -1)), book_range, rec));
    // With an unbounded interval the nearer root behind the origin, t = -6, is reported: the limits
    // alone decide what counts as "in front".
    REQUIRE(behind.hit(ray(point3(0, 0, 0), vec3(0, 0, -1)), interval::universe, rec));
    CHECK(rec.t == doctest::Approx(-6));
    // Miss to the side.
    sphere side(point3(3, 0, -5), 1, grey());
    CHECK_FALSE(side.hit(ray(point3(0, 0, 0), vec3(0, 0, -1)), book_range, rec));

    // Sphere (0,0,-5) r 1: roots t = 4 and t = 6.
    sphere s(point3(0, 0, -5), 1, grey());
    const ray r(point3(0, 0, 0), vec3(0, 0, -1));
    CHECK_FALSE(s.hit(r, interval(0.001, 3.9), rec)); // both beyond tmax
    CHECK_FALSE(s.hit(r, interval(0.001, 4.0), rec)); // open interval: t = 4 is excluded, 6 too
    REQUIRE(s.hit(r, interval(0.001, 4.0001), rec));
    CHECK(rec.t == doctest::Approx(4));
    REQUIRE(s.hit(r, interval(4.0, 10), rec)); // t = 4 excluded, so the far root 6
    CHECK(rec.t == doctest::Approx(6));
    CHECK_FALSE(rec.front_face);
    REQUIRE(s.hit(r, interval(4.5, 6.5), rec));
    CHECK(rec.t == doctest::Approx(6));
    CHECK_FALSE(s.hit(r, interval(6.0, 100), rec)); // both roots at or below tmin
    CHECK_FALSE(s.hit(r, interval::empty, rec));
}

TEST_CASE("sphere::hit: tiny sphere far away (r = 1e-3 at distance 1000)") {
    // Roots t = 1000 -+ 1e-3. The textbook formula computes b^2 - 4ac as the difference of two
    // numbers near 4e6 whose true difference is 4e-6; the stable form must still give t to ~1e-12.
    sphere tiny(point3(0, 0, -1000), 1e-3, grey());
    hit_record rec;
    REQUIRE(tiny.hit(ray(point3(0, 0, 0), vec3(0, 0, -1)), book_range, rec));
    CHECK(rec.t == doctest::Approx(1000 - 1e-3).epsilon(1e-12));
    CHECK(rec.normal.z() == doctest::Approx(1).epsilon(1e-6));
    CHECK(rec.front_face);
    // Offset by half a radius: the ray hits where the normal has lateral component 0.5 (the ray is
    // parallel to z, so sin of the normal's tilt = lateral offset / r).
    REQUIRE(tiny.hit(ray(point3(0.5e-3, 0, 0), vec3(0, 0, -1)), book_range, rec));
    CHECK(rec.normal.x() == doctest::Approx(0.5).epsilon(1e-6));
    CHECK(rec.normal.z() == doctest::Approx(std::sqrt(0.75)).epsilon(1e-6));
    // Offset by 1.5 radii: a miss.
    CHECK_FALSE(tiny.hit(ray(point3(1.5e-3, 0, 0), vec3(0, 0, -1)), book_range, rec));
}

TEST_CASE("sphere::hit: the cover's ground sphere seen from the cover camera") {
    // Ground: centre (0,-1000,0), r = 1000. From (13,2,3) towards the world origin, a point of the
    // sphere (its top). Points of the segment, (13s, 2s, 3s), satisfy
    // |p - c|^2 - r^2 = 169s^2 + (2s + 1000)^2 + 9s^2 - 1e6 = 182 s^2 + 4000 s > 0 for s > 0,
    // so the segment stays outside and the hit is exactly the origin: t = |(13,2,3)| = sqrt(182),
    // normal (0,1,0).
    sphere ground(point3(0, -1000, 0), 1000, grey());
    const point3 eye(13, 2, 3);
    hit_record rec;
    REQUIRE(ground.hit(ray(eye, unit_vector(point3(0, 0, 0) - eye)), book_range, rec));
    CHECK(rec.t == doctest::Approx(std::sqrt(182.0)).epsilon(1e-12));
    CHECK(std::fabs(rec.p.x()) < 1e-10);
    CHECK(std::fabs(rec.p.y()) < 1e-10);
    CHECK(std::fabs(rec.p.z()) < 1e-10);
    CHECK(rec.normal.y() == doctest::Approx(1).epsilon(1e-12));
    CHECK(rec.front_face);

    // Other downward directions: the hit point lies on the sphere, t agrees with the long double
    // textbook root.
    const point3 targets[] = {point3(5, 0, 1), point3(-20, 0, 7), point3(30, -3, -40), point3(13, 0, 3)};
    for (const point3& target : targets) {
        vec3 d = unit_vector(target - eye);
        REQUIRE(ground.hit(ray(eye, d), book_range, rec));
        long double t0 = 0, t1 = 0;
        REQUIRE(textbook_roots(eye, d, point3(0, -1000, 0), 1000, t0, t1));
        CHECK(rec.t == doctest::Approx(double(t0)).epsilon(1e-10));
        double dist = (rec.p - point3(0, -1000, 0)).length();
        CHECK(std::fabs(dist - 1000) <= 1e-10 * rec.t + 1e-12 * 1000);
    }
}

TEST_CASE("sphere_roots agrees with the textbook quadratic formula (random cases, double)") {
    std::mt19937_64 gen(20240607);
    std::uniform_real_distribution<double> pos(-50, 50), rad(0.01, 20), dirc(-1, 1);
    int hits = 0, misses = 0;
    for (int i = 0; i < 5000; ++i) {
        point3 o(pos(gen), pos(gen), pos(gen)), c(pos(gen), pos(gen), pos(gen));
        // An unnormalised direction (length 0.1 .. ~5), aimed near the sphere half the time.
        vec3 d(dirc(gen), dirc(gen), dirc(gen));
        if (i % 2 == 0) d = (c - o) / (c - o).length() + 0.1 * d;
        if (d.length() < 0.1) continue;
        d *= 0.5 + 4 * std::fabs(dirc(gen));
        double r = rad(gen);

        long double e0 = 0, e1 = 0;
        bool expect = textbook_roots(o, d, c, r, e0, e1);
        // Skip nearly-tangent cases where the answer is ill-conditioned: require the discriminant's
        // magnitude to exceed 1e-6 of h^2 (relative distance from tangency).
        long double a = d.length_squared(), h = dot(d, c - o), cc = (c - o).length_squared() - r * r;
        long double disc = h * h - a * cc;
        if (std::fabs((double)disc) < 1e-6 * (double)(h * h) + 1e-12) continue;

        double t0 = -1, t1 = -1;
        bool got = sphere_roots(o, d, c, r, t0, t1);
        REQUIRE(got == expect);
        if (!got) {
            ++misses;
            continue;
        }
        ++hits;
        double scale = std::fabs((double)e0) + std::fabs((double)e1) + 1e-3;
        CHECK(std::fabs(t0 - (double)e0) <= 1e-9 * scale);
        CHECK(std::fabs(t1 - (double)e1) <= 1e-9 * scale);
        CHECK(t0 <= t1);
    }
    // Both branches were exercised a good number of times.
    CHECK(hits > 1000);
    CHECK(misses > 1000);
}

// ------------------------------------------------------------------------------------------------
// compiled_scene::intersect (float, relative to the scene origin)

TEST_CASE("compiled_scene::intersect from outside") {
    hittable_list world;
    // Same geometry as above, but shifted by a camera position (13,2,3): the scene stores positions
    // relative to it. Centre = eye + (0,0,-5), r = 1: t = 4.
    const point3 eye(13, 2, 3);
    compiled_scene s = compile_one(eye + vec3(0, 0, -5), 1, eye, world);
    CHECK(s.set<sphere_set>().count == 1);
    surface_hit hit;
    REQUIRE(s.intersect(make_ray(s, eye, vec3(0, 0, -1)), hit));
    CHECK(hit.t == doctest::Approx(4).epsilon(1e-6));
    CHECK(hit.p.x == doctest::Approx(0).epsilon(1e-6));
    CHECK(hit.p.z == doctest::Approx(-4).epsilon(1e-6));
    CHECK(hit.normal.z == doctest::Approx(1).epsilon(1e-6));
    CHECK(hit.front_face);
    CHECK(hit.material == 0);
    CHECK(hit.user_shape == nullptr);
    CHECK(s.materials.at(hit.material).is<lambertian_bsdf>());
}

TEST_CASE("compiled_scene::intersect from inside") {
    hittable_list world;
    compiled_scene s = compile_one(point3(0, 0, 0), 2, point3(0, 0, 0), world);
    surface_hit hit;
    // Ray from the centre along +x: far wall at t = 2, back face, normal (-1,0,0).
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(1, 0, 0)), hit));
    CHECK(hit.t == doctest::Approx(2).epsilon(1e-6));
    CHECK(hit.p.x == doctest::Approx(2).epsilon(1e-6));
    CHECK_FALSE(hit.front_face);
    CHECK(hit.normal.x == doctest::Approx(-1).epsilon(1e-6));
    CHECK(std::fabs(hit.normal.y) < 1e-6f);
    CHECK(std::fabs(hit.normal.z) < 1e-6f);

    // From (0.5,0,0) along -x: far wall at x = -2, t = 2.5, normal (+1,0,0).
    REQUIRE(s.intersect(make_ray(s, point3(0.5, 0, 0), vec3(-1, 0, 0)), hit));
    CHECK(hit.t == doctest::Approx(2.5).epsilon(1e-6));
    CHECK_FALSE(hit.front_face);
    CHECK(hit.normal.x == doctest::Approx(1).epsilon(1e-6));
}

TEST_CASE("compiled_scene::intersect tangent ray") {
    // As for sphere::hit: centre (0,1,-5), r = 1, ray along -z from the origin touches at
    // (0,0,-5), t = 5 (every float here is exact, the discriminant is exactly 0). Decision: a hit,
    // with a normal perpendicular to the ray.
    hittable_list world;
    compiled_scene s = compile_one(point3(0, 1, -5), 1, point3(0, 0, 0), world);
    surface_hit hit;
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1)), hit));
    CHECK(hit.t == doctest::Approx(5).epsilon(1e-6));
    CHECK(std::fabs(hit.p.y) < 1e-5f);
    CHECK(hit.p.z == doctest::Approx(-5).epsilon(1e-6));
    CHECK(std::fabs(hit.normal.y) == doctest::Approx(1).epsilon(1e-6));
    CHECK(std::fabs(dot(hit.normal, vec3f(0, 0, -1))) < 1e-5f);

    // Inside the tangent by 1e-3: roots 5 -+ sqrt(1 - 0.999^2) = 5 -+ 0.0447102; outside: miss.
    REQUIRE(s.intersect(make_ray(s, point3(0, 1e-3, 0), vec3(0, 0, -1)), hit));
    CHECK(hit.t == doctest::Approx(5 - std::sqrt(1 - 0.999 * 0.999)).epsilon(1e-5));
    CHECK(hit.front_face);
    CHECK_FALSE(s.intersect(make_ray(s, point3(0, -1e-3, 0), vec3(0, 0, -1)), hit));
}

TEST_CASE("compiled_scene::intersect: behind the ray, and the (tmin, tmax) limits") {
    hittable_list w1;
    compiled_scene behind = compile_one(point3(0, 0, 5), 1, point3(0, 0, 0), w1);
    surface_hit hit;
    CHECK_FALSE(behind.intersect(make_ray(behind, point3(0, 0, 0), vec3(0, 0, -1)), hit));

    hittable_list w2;
    compiled_scene s = compile_one(point3(0, 0, -5), 1, point3(0, 0, 0), w2);
    // Roots 4 and 6.
    CHECK_FALSE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1), 0, 3.9f), hit));
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1), 0, 4.1f), hit));
    CHECK(hit.t == doctest::Approx(4).epsilon(1e-6));
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1), 4.5f), hit)); // far root only
    CHECK(hit.t == doctest::Approx(6).epsilon(1e-6));
    CHECK_FALSE(hit.front_face);
    CHECK(hit.normal.z == doctest::Approx(1).epsilon(1e-6)); // outward is -z there, flipped
    CHECK_FALSE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1), 6.5f), hit));
    CHECK_FALSE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1), 4.5f, 5.5f), hit));
}

TEST_CASE("compiled_scene::intersect picks the closest of many spheres") {
    // 40 unit spheres along -z at z = -3k (k = 1..40), added in shuffled order: more than one SIMD
    // block. The ray along -z hits the nearest, at z = -3 + 1: t = 2.
    hittable_list world;
    std::vector<int> order;
    for (int k = 1; k <= 40; ++k) order.push_back(k);
    std::mt19937 gen(5);
    std::shuffle(order.begin(), order.end(), gen);
    for (int k : order) world.add(std::make_shared<sphere>(point3(0, 0, -3.0 * k), 1, grey()));
    compiled_scene s = compile_scene(world, point3(0, 0, 0));
    CHECK(s.set<sphere_set>().count == 40);
    surface_hit hit;
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1)), hit));
    CHECK(hit.t == doctest::Approx(2).epsilon(1e-6));
    // Sphere k spans t in [3k-1, 3k+1]; tmin = 22.5 lies between k = 7 (20..22) and k = 8 (23..25),
    // so the closest hit past tmin is sphere 8's near side, t = 23.
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1), 22.5f), hit));
    CHECK(hit.t == doctest::Approx(23).epsilon(1e-6));
}

TEST_CASE("compiled_scene::intersect: tiny sphere far away (r = 1e-3 at distance 100)") {
    hittable_list world;
    compiled_scene s = compile_one(point3(0, 0, -100), 1e-3, point3(0, 0, 0), world);
    surface_hit hit;
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), vec3(0, 0, -1)), hit));
    // t = 100 - 1e-3 = 99.999; float resolves about 1e-5 at 100.
    CHECK(hit.t == doctest::Approx(99.999).epsilon(2e-7));
    CHECK(hit.normal.z == doctest::Approx(1).epsilon(1e-3));
    CHECK(hit.front_face);
    // Half a radius off-axis: hits with normal.x = 0.5 (see the double test); 1.5 radii: miss.
    REQUIRE(s.intersect(make_ray(s, point3(0.5e-3, 0, 0), vec3(0, 0, -1)), hit));
    CHECK(hit.normal.x == doctest::Approx(0.5).epsilon(2e-2));
    CHECK_FALSE(s.intersect(make_ray(s, point3(1.5e-3, 0, 0), vec3(0, 0, -1)), hit));
    // Aimed from the side at an angle: direction towards a point half a radius below the centre.
    REQUIRE(s.intersect(make_ray(s, point3(0, 0, 0), point3(0, -0.5e-3, -100) - point3(0, 0, 0)), hit));
    CHECK(hit.normal.y == doctest::Approx(-0.5).epsilon(2e-2));
}

TEST_CASE("compiled_scene::intersect: ground sphere from the cover camera, hit point on the sphere") {
    const point3 eye(13, 2, 3), centre(0, -1000, 0);
    hittable_list world;
    compiled_scene s = compile_one(centre, 1000, eye, world);
    surface_hit hit;

    // Towards the world origin: exactly the sphere's top (see the double test): t = sqrt(182).
    REQUIRE(s.intersect(make_ray(s, eye, point3(0, 0, 0) - eye), hit));
    CHECK(hit.t == doctest::Approx(std::sqrt(182.0)).epsilon(1e-5));
    point3 p = eye + hit.p.to_double();
    CHECK(p.length() <= 1e-4 * std::sqrt(182.0));
    CHECK(hit.normal.y == doctest::Approx(1).epsilon(1e-5));
    CHECK(hit.front_face);

    // Other downward directions: |p - c| = r to 1e-4 of the distance travelled, and t agrees with
    // the long double textbook root to 1e-4 relative.
    const point3 targets[] = {point3(5, 0, 1), point3(-20, 0, 7), point3(30, -3, -40), point3(13, 0, 3),
                              point3(-200, -30, 100)};
    for (const point3& target : targets) {
        vec3 d = unit_vector(target - eye);
        REQUIRE(s.intersect(make_ray(s, eye, d), hit));
        long double t0 = 0, t1 = 0;
        REQUIRE(textbook_roots(eye, vec3f(d).to_double(), centre, 1000, t0, t1));
        CHECK(hit.t == doctest::Approx(double(t0)).epsilon(1e-4));
        point3 q = eye + hit.p.to_double();
        CHECK(std::fabs((q - centre).length() - 1000) <= 1e-4 * double(t0));
        CHECK(hit.front_face);
        // The normal is the outward radial direction there.
        vec3 radial = unit_vector(q - centre);
        CHECK(dot(hit.normal.to_double(), radial) == doctest::Approx(1).epsilon(1e-5));
    }
}

TEST_CASE("compiled_scene::intersect agrees with sphere::hit on random rays") {
    // 30 random spheres; for random rays the closest float hit must match the double closest hit
    // (hittable_list::hit) to float accuracy, except for rays that nearly graze a sphere, where the
    // two precisions may legitimately disagree about hit-or-miss.
    std::mt19937_64 gen(99);
    std::uniform_real_distribution<double> U(-1, 1);
    hittable_list world;
    std::vector<std::pair<point3, double>> spheres;
    for (int i = 0; i < 30; ++i) {
        point3 c(10 * U(gen), 10 * U(gen), -20 + 10 * U(gen));
        double r = 0.5 + 2 * std::fabs(U(gen));
        spheres.push_back({c, r});
        world.add(std::make_shared<sphere>(c, r, grey()));
    }
    const point3 eye(0.25, -0.5, 3);
    compiled_scene s = compile_scene(world, eye);
    int compared = 0;
    for (int i = 0; i < 2000; ++i) {
        vec3 d = unit_vector(vec3(0.6 * U(gen), 0.6 * U(gen), -1));
        vec3 dd = vec3f(d).to_double(); // the float ray's exact direction
        // Skip rays that pass within 1e-3 of any sphere's silhouette.
        bool near_graze = false;
        for (auto& [c, r] : spheres) {
            vec3 oc = c - eye;
            double h = dot(dd, oc);
            double dist = (oc - h * dd).length();
            if (std::fabs(dist - r) < 1e-3) near_graze = true;
        }
        if (near_graze) continue;
        hit_record rec;
        bool expect = world.hit(ray(eye, dd), interval(0, infinity), rec);
        surface_hit hit;
        bool got = s.intersect(make_ray(s, eye, dd), hit);
        REQUIRE(got == expect);
        if (got) {
            ++compared;
            CHECK(hit.t == doctest::Approx(rec.t).epsilon(1e-5));
            CHECK(dot(hit.normal.to_double(), rec.normal) == doctest::Approx(1).epsilon(1e-4));
            CHECK(hit.front_face == rec.front_face);
        }
    }
    CHECK(compared > 200);
}

TEST_CASE("surface_hit::set_face_normal: the book's rule, the normal negated by its sign bits") {
    // front_face = d . outward < 0; the normal (and the shading normal) faces the ray: outward on
    // the front face, -outward (every sign bit flipped, zeros too) otherwise, a grazing ray (d .
    // outward = 0) included, as the book's set_face_normal has it.
    auto same_bits = [](const vec3f& a, const vec3f& b) {
        return float_bits(a.x) == float_bits(b.x) && float_bits(a.y) == float_bits(b.y) && float_bits(a.z) == float_bits(b.z);
    };
    const vec3f outward{0.0f, 0.6f, -0.8f};
    surface_hit h;
    h.set_face_normal({0.0f, -1.0f, 0.0f}, outward); // against it: d . n = -0.6
    CHECK(h.front_face);
    CHECK(same_bits(h.normal, outward));
    CHECK(same_bits(h.shading_normal, outward));
    h.set_face_normal({0.0f, 0.0f, -1.0f}, outward); // along it: d . n = 0.8
    CHECK_FALSE(h.front_face);
    CHECK(same_bits(h.normal, {-0.0f, -0.6f, 0.8f}));
    CHECK(same_bits(h.shading_normal, h.normal));
    h.set_face_normal({1.0f, 0.0f, 0.0f}, outward); // grazing: d . n = 0
    CHECK_FALSE(h.front_face);
    CHECK(same_bits(h.normal, {-0.0f, -0.6f, 0.8f}));
}

} // namespace test_sphere
