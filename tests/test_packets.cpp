// Rays traced together (compiled_scene::intersect_batch over bvh.h's traverse_packet): every ray of
// a packet finds bit for bit what it finds alone, in scenes of one shape kind and of all of them,
// for coherent camera-like rays and for rays in every direction; the hits agree with a brute-force
// loop in double; and hits at exactly one distance go to the same shape whatever the order of
// the walk (leaf_query.h, beats).

#include "test_helpers.h"

#include <rtweekend/camera.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/material.h>
#include <rtweekend/mesh.h>
#include <rtweekend/quad.h>
#include <rtweekend/sphere.h>
#include <rtweekend/transform.h>
#include <rtweekend/triangle.h>

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace test_packets {

using namespace rt;

namespace {

std::shared_ptr<material> grey() { return std::make_shared<lambertian>(color(0.5, 0.5, 0.5)); }

bool same(const vec3f& a, const vec3f& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Batches of 1 to 16 rays through intersect_batch, each against intersect alone: the same
// answer, the same t, point, normals, material and shape. Returns how many rays hit.
int check_batches(const compiled_scene& s, const std::vector<ray3f>& rays) {
    int hits = 0;
    size_t at = 0;
    for (int n = 1; at < rays.size(); n = n % 16 + 1) {
        const int count = int(std::min<size_t>(size_t(n), rays.size() - at));
        surface_hit together[16];
        bool found[16];
        s.intersect_batch(count, rays.data() + at, together, found);
        for (int k = 0; k < count; ++k) {
            surface_hit alone;
            const bool got = s.intersect(rays[at + size_t(k)], alone);
            CAPTURE(at + size_t(k));
            REQUIRE(found[k] == got);
            if (!got) continue;
            ++hits;
            CHECK(together[k].t == alone.t);
            CHECK(same(together[k].p, alone.p));
            CHECK(same(together[k].normal, alone.normal));
            CHECK(same(together[k].shading_normal, alone.shading_normal));
            CHECK(together[k].front_face == alone.front_face);
            CHECK(together[k].material == alone.material);
            CHECK(together[k].kind == alone.kind);
            CHECK(together[k].index == alone.index);
        }
        at += size_t(count);
    }
    return hits;
}

ray3f ray_from(const compiled_scene& s, const point3& from, const vec3& dir, float tmax = std::numeric_limits<float>::infinity()) {
    ray3f r;
    r.origin = vec3f(from - s.origin);
    r.dir = vec3f(unit_vector(dir));
    r.tmax = tmax;
    return r;
}

// Camera-like rays: from points near `eye`, through a small window around `at`, 16 neighbours at
// a time (what a batch of a tile row holds).
std::vector<ray3f> coherent_rays(const compiled_scene& s, const point3& eye, const point3& at, int count, pcg32& rng) {
    std::vector<ray3f> rays;
    const vec3 w = unit_vector(at - eye), u = unit_vector(cross(w, vec3(0, 1, 0))), v = cross(u, w);
    for (int i = 0; i < count; ++i) {
        const double px = (i % 16) / 16.0 - 0.5 + 0.02 * rng.next_float(), py = (i / 16 % 32) / 32.0 - 0.5;
        const point3 o = eye + 0.05 * (rng.next_float() - 0.5) * u + 0.05 * (rng.next_float() - 0.5) * v;
        rays.push_back(ray_from(s, o, (at + 6.0 * px * u + 3.0 * py * v) - o));
    }
    return rays;
}

// Rays from anywhere in any direction, some with a finite range, some degenerate.
std::vector<ray3f> incoherent_rays(const compiled_scene& s, double spread, int count, pcg32& rng) {
    std::vector<ray3f> rays;
    auto u = [&] { return double(rng.next_float()); };
    for (int i = 0; i < count; ++i) {
        const point3 o(spread * (u() - 0.5), spread * (u() - 0.5), spread * (u() - 0.5));
        vec3 d(u() - 0.5, u() - 0.5, u() - 0.5);
        if (i % 17 == 3) d = vec3(0, 0, u() < 0.5 ? 1 : -1); // axis-aligned: zero components
        if (i % 17 == 11) d = vec3(-0.0, u() < 0.5 ? -0.0 : 0.0, u() < 0.5 ? 1 : -1); // negative zeros: run down
        rays.push_back(ray_from(s, o, d, i % 5 == 1 ? float(spread * u()) : std::numeric_limits<float>::infinity()));
        if (i % 29 == 7) rays.back().dir = {std::numeric_limits<float>::quiet_NaN(), 0, 1}; // hits nothing
    }
    return rays;
}

} // namespace

TEST_CASE("packets: a packet's rays go into lanes float for float, zeros past the count") {
    // detail::rays_to_lanes against its definition, written out here: lane a of ray k is its
    // origin (a < 3), direction (3-5) or tmin (6), t_best its tmax; bit k of dir_signs[a] the sign
    // bit of its direction (so -0 counts as negative); lanes from count on hold +0.
    constexpr int W = int(floatv::width);
    pcg32 rng(7, 3);
    auto any = [&](int k) {
        if (k % 5 == 0) return (k % 2 ? -0.0f : 0.0f);
        return float(rng.next_double() * 200.0 - 100.0);
    };
    for (int count = 1; count <= W; ++count) {
        std::vector<ray3f> rays(size_t(count) + 1); // one more ray after them, never read
        for (int k = 0; k <= count; ++k) {
            ray3f& r = rays[size_t(k)];
            r.origin = {any(k + 1), any(k + 2), any(k + 3)};
            r.dir = {any(k), any(k + 4), any(k + 6)};
            r.tmin = float(rng.next_double());
            r.tmax = k % 3 ? float(rng.next_double() * 1e3) : std::numeric_limits<float>::infinity();
            r.time = 0.5f;
        }
        alignas(64) float lane[7][W];
        alignas(64) float t_best[W];
        unsigned signs[3];
        detail::rays_to_lanes(rays.data(), count, lane, t_best, signs);
        CAPTURE(count);
        for (int k = 0; k < W; ++k) {
            const ray3f r = k < count ? rays[size_t(k)] : ray3f{{0, 0, 0}, {0, 0, 0}, 0.0f, 0.0f, 0.0f};
            const float expect[8] = {r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.tmin, r.tmax};
            for (int a = 0; a < 8; ++a) {
                const float got = a < 7 ? lane[a][k] : t_best[k];
                CAPTURE(k);
                CAPTURE(a);
                CHECK(std::memcmp(&got, &expect[a], sizeof got) == 0); // bit for bit: -0 stays -0
            }
        }
        for (int a = 0; a < 3; ++a) {
            unsigned expect = 0;
            for (int k = 0; k < count; ++k) expect |= unsigned(std::signbit(rays[size_t(k)].dir[a])) << k;
            CHECK(signs[a] == expect);
        }
    }
}

TEST_CASE("packets: the cover scene's camera rays and bounce rays find what each finds alone") {
    scene_description d = load_scene(std::string(RTWEEKEND_TEST_DATA) + "/rtiow_cover.txt");
    const compiled_scene s = compile_scene(d.world, d.cam.lookfrom);
    REQUIRE(s.single_kind);
    CHECK(*s.single_kind == shape_id<sphere_set>);
    pcg32 rng(1, 2);
    const int camera_hits = check_batches(s, coherent_rays(s, d.cam.lookfrom, d.cam.lookat, 4096, rng));
    CHECK(camera_hits > 3000); // the view is mostly ground and spheres
    const int bounce_hits = check_batches(s, incoherent_rays(s, 30, 4096, rng));
    CHECK(bounce_hits > 200);
}

TEST_CASE("packets: every shape kind at once, against each ray alone and against brute force in double") {
    pcg32 rng(5, 6);
    auto u = [&] { return double(rng.next_float()); };
    hittable_list world;
    auto m = grey();
    for (int i = 0; i < 600; ++i) {
        const point3 c(20 * u() - 10, 20 * u() - 10, 20 * u() - 10);
        const vec3 e1(u() - 0.5, u() - 0.5, u() - 0.5), e2(u() - 0.5, u() - 0.5, u() - 0.5);
        world.add(std::make_shared<triangle>(c, c + 2.0 * e1, c + 2.0 * e2, m));
    }
    for (int i = 0; i < 150; ++i)
        world.add(std::make_shared<sphere>(point3(20 * u() - 10, 20 * u() - 10, 20 * u() - 10), 0.05 + 0.5 * u(), m));
    for (int i = 0; i < 100; ++i)
        world.add(std::make_shared<quad>(point3(20 * u() - 10, 20 * u() - 10, 20 * u() - 10),
                                         vec3(u() - 0.5, u() - 0.5, u()), vec3(u(), u() - 0.5, u() - 0.5), m));
    for (int i = 0; i < 40; ++i) {
        const point3 c(20 * u() - 10, 20 * u() - 10, 20 * u() - 10);
        world.add(std::make_shared<sphere>(c, c + vec3(0, 0.3, 0), 0.3, m)); // moving: time 0
    }
    // A cluster of 40 triangles placed twice: an instance (scene_compiler::must_instance).
    auto cluster = std::make_shared<hittable_list>();
    for (int i = 0; i < 40; ++i) {
        const point3 c(2 * u(), 2 * u(), 2 * u());
        cluster->add(std::make_shared<triangle>(c, c + vec3(u() - 0.5, u() - 0.5, u()), c + vec3(u(), u() - 0.5, u() - 0.5), m));
    }
    world.add(std::make_shared<translate>(std::make_shared<rotate_y>(cluster, 30), vec3(2, -1, 0)));
    world.add(std::make_shared<translate>(cluster, vec3(-4, 3, 2)));
    const point3 origin(1, 2, 3);
    const compiled_scene s = compile_scene(world, origin);
    CHECK_FALSE(s.single_kind);
    CHECK(s.set<instance_set>().count() == 2);
    CHECK(s.set<moving_sphere_set>().count == 40);

    std::vector<ray3f> rays = coherent_rays(s, point3(0, 0, 25), point3(0, 0, 0), 2048, rng);
    const std::vector<ray3f> more = incoherent_rays(s, 30, 4096, rng);
    rays.insert(rays.end(), more.begin(), more.end());
    CHECK(check_batches(s, rays) > 1000);

    // The batch against the teaching surface in double (as test_triangle.cpp's brute force):
    // hit or miss and t agree but for a few grazing rays.
    int disagree = 0;
    for (size_t at = 0; at + 16 <= rays.size(); at += 16) {
        surface_hit hits[16];
        bool found[16];
        s.intersect_batch(16, rays.data() + at, hits, found);
        for (int k = 0; k < 16; ++k) {
            const ray3f& r = rays[at + size_t(k)];
            if (!is_finite(r.dir)) continue;
            hit_record rec;
            const bool ref = world.hit(ray(origin + r.origin.to_double(), r.dir.to_double(), 0.0),
                                       interval(0, double(r.tmax)), rec);
            if (ref != found[k] || (ref && std::fabs(hits[k].t - rec.t) > 1e-4 * (1 + rec.t))) ++disagree;
        }
    }
    CHECK(disagree <= 4);
}

TEST_CASE("packets: hits at one distance go to the lowest shape, alone and in a packet") {
    // A square of two coplanar triangles meeting on the diagonal x = y, and a copy of the first
    // triangle lying on it (a duplicate): rays along -z through the diagonal meet two triangles at
    // exactly one distance, and rays through the first triangle meet it twice. Either way the
    // shape with the lower index in the compiled scene wins, whichever the walk meets first.
    auto m = grey();
    hittable_list world;
    world.add(std::make_shared<triangle>(point3(0, 0, 0), point3(1, 0, 0), point3(1, 1, 0), m));
    world.add(std::make_shared<triangle>(point3(0, 0, 0), point3(1, 1, 0), point3(0, 1, 0), m));
    world.add(std::make_shared<triangle>(point3(0, 0, 0), point3(1, 0, 0), point3(1, 1, 0), m));
    // Enough other shapes around it for a tree with nodes.
    pcg32 rng(3, 4);
    for (int i = 0; i < 200; ++i) {
        const point3 c(10 + 10 * rng.next_float(), 10 * rng.next_float(), -10 * rng.next_float());
        world.add(std::make_shared<sphere>(c, 0.2, m));
    }
    const compiled_scene s = compile_scene(world, point3(0.5, 0.5, 4));
    REQUIRE(s.set<triangle_set>().count == 3);
    // The compiled index of each input triangle: by its second and third corners.
    auto index_of = [&](float bx, float by, float cx, float cy) {
        for (uint32_t i = 0; i < 3; ++i)
            if (s.set<triangle_set>().vertex[3][i] + s.origin.x() == bx && s.set<triangle_set>().vertex[4][i] + s.origin.y() == by &&
                s.set<triangle_set>().vertex[6][i] + s.origin.x() == cx && s.set<triangle_set>().vertex[7][i] + s.origin.y() == cy)
                return i;
        return hit_ref::none;
    };
    const uint32_t second = index_of(1, 1, 0, 1); // the triangle above the diagonal
    REQUIRE(second != hit_ref::none);
    const uint32_t lower_copy = second == 0 ? 1 : 0; // the lower index of the first and its copy
    std::vector<ray3f> diagonal, inside;
    for (int i = 0; i < 16; ++i) {
        const double a = (i + 0.5) / 16.0; // (a, a) is on the diagonal, exactly in float
        diagonal.push_back(ray_from(s, point3(a, a, 4), vec3(0, 0, -1)));
        inside.push_back(ray_from(s, point3(0.75, 0.25 * a, 4), vec3(0, 0, -1)));
    }
    for (const auto* rays : {&diagonal, &inside}) {
        surface_hit together[16];
        bool found[16];
        s.intersect_batch(16, rays->data(), together, found);
        for (int k = 0; k < 16; ++k) {
            surface_hit alone;
            REQUIRE(s.intersect((*rays)[size_t(k)], alone));
            REQUIRE(found[k]);
            CHECK(alone.t == 4.0f);
            CHECK(together[k].index == alone.index);
            CHECK(alone.kind == shape_id<triangle_set>);
            CHECK(alone.index == (rays == &diagonal ? 0u : lower_copy));
        }
    }
}

TEST_CASE("ties: at one distance the lower (kind, index) beats, in whatever order the shapes come") {
    // beats() by itself: nearer wins; at exactly one distance the lower kind, then the lower index;
    // with no best yet the range is open (t_best is the ray's tmax).
    const hit_ref tri5{shape_id<triangle_set>, 5};
    CHECK(beats(1.5f, shape_id<triangle_set>, 9, 2.0f, tri5));
    CHECK_FALSE(beats(2.5f, shape_id<triangle_set>, 1, 2.0f, tri5));
    CHECK(beats(2.0f, shape_id<triangle_set>, 3, 2.0f, tri5));
    CHECK_FALSE(beats(2.0f, shape_id<triangle_set>, 7, 2.0f, tri5));
    CHECK_FALSE(beats(2.0f, shape_id<triangle_set>, 5, 2.0f, tri5));
    CHECK(beats(2.0f, shape_id<sphere_set>, 900, 2.0f, tri5));
    CHECK_FALSE(beats(2.0f, shape_id<quad_set>, 0, 2.0f, tri5));
    CHECK_FALSE(beats(2.0f, shape_id<sphere_set>, 0, 2.0f, hit_ref{}));
    CHECK(beats(1.0f, shape_id<quad_set>, 4, 2.0f, hit_ref{}));
    // Three shapes at one distance taken in every order end at the same one.
    const hit_ref shapes[3] = {{shape_id<quad_set>, 2}, {shape_id<triangle_set>, 8}, {shape_id<triangle_set>, 4}};
    const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& order : orders) {
        float t_best = std::numeric_limits<float>::infinity();
        hit_ref best;
        for (int i : order)
            if (beats(3.0f, shapes[i].kind, shapes[i].index, t_best, best)) {
                t_best = 3.0f;
                best = shapes[i];
            }
        CHECK(best.kind == shape_id<triangle_set>);
        CHECK(best.index == 4u);
    }
    // take_closest over lanes: the nearest lane, the first of equal ones, against the best so far.
    float t[floatv::width];
    for (size_t k = 0; k < floatv::width; ++k) t[k] = 10.0f + float(k);
    t[floatv::width - 1] = 2.0f;
    float t_best = 2.0f;
    hit_ref best{shape_id<triangle_set>, 100};
    CHECK(take_closest(first_lanes(unsigned(floatv::width)), floatv::load(t), shape_id<triangle_set>, 40, t_best, best));
    CHECK(best.index == 40 + floatv::width - 1); // index 40 + width - 1 < 100: the tie goes to it
    CHECK_FALSE(take_closest(first_lanes(unsigned(floatv::width)), floatv::load(t), shape_id<triangle_set>, 400, t_best, best));
    CHECK_FALSE(take_closest(first_lanes(0), floatv::load(t), shape_id<sphere_set>, 0, t_best, best));
}

namespace {

// A user-written hittable that is never hit and has no box: the scene then "calls user code", and
// the path tracer takes its paths one after another, each ray walking alone (path_tracer.h),
// instead of a batch's paths side by side with their rays in packets. It draws no random numbers
// and changes no hit, so the two must give the same image bit for bit.
class nothing_here : public hittable {
  public:
    bool hit(const ray&, interval, hit_record&) const override { return false; }
};

} // namespace

TEST_CASE("packets: a batch's paths side by side make the image of its paths one by one, bit for bit" * doctest::test_suite("heavy")) {
    // With Sobol numbers the camera's time is a dimension of its own, which the scene with user
    // code draws and the other does not; nothing depends on it here. Light tracing of caustics
    // is off (it needs a scene without user code).
    for (const char* file : {"rtiow_cover.txt", "cornell_final.txt", "bunny.txt", "sphere_room.txt"}) {
        CAPTURE(file);
        scene_description d = load_scene(std::string(RTWEEKEND_TEST_DATA) + "/" + file);
        camera cam = d.cam;
        cam.image_width = 64;
        cam.image_height = 40;
        cam.samples_per_pixel = 8;
        cam.settings.threads = 2;
        cam.settings.quiet = true;
        cam.settings.caustic_paths = 0;
        for (path_estimator e : {path_estimator::nee, path_estimator::bsdf, path_estimator::mixture}) {
            cam.settings.estimator = e;
            const render_result batched = render(cam, d.world);
            hittable_list with_user_code = d.world;
            with_user_code.add(std::make_shared<nothing_here>());
            const render_result one_by_one = render(cam, with_user_code);
            CHECK(test::same_bits(batched.img, one_by_one.img));
            CHECK(batched.stats.rays == one_by_one.stats.rays);
        }
    }
}

} // namespace test_packets
