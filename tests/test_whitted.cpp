// The Whitted renderer (rtweekend/course/whitted.h) on small CENG795 XML scenes (tests/data/ceng795/)
// whose pixels are worked out by hand here, from the format's rules
// (shared/formats/ceng795-xml.md), not from the renderer's own helpers:
//
//   pixel (i, j), j = 0 the top row:  s = e - d w + (l + (i+0.5)(r-l)/nx) u + (t - (j+0.5)(t-b)/ny) v
//   L = ka Ia + sum over visible lights of E (kd max(0, n.l) + ks max(0, n.h)^p),  E = I / d^2,
//       h = normalize(l + v)
//   mirror: + km L(reflected); conductor: + km Fr L(reflected); dielectric: Fr L(reflected) +
//   (1 - Fr) L(refracted), exp(-c x) over a path x inside; MaxRecursionDepth counts bounces;
//   a primary miss is the background, a secondary miss is black; bytes = trunc(clamp(L, 0, 255)).
//
// Every asserted byte must be within +-1 of the truncated hand value (the course's tolerance),
// except where a test is about the exact 8-bit encoding itself.

#include <rtweekend/sphere.h>
#include <rtweekend/io/xml_scene.h>
#include <rtweekend/course/whitted.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace test_whitted {

namespace {

const double pi = 3.14159265358979323846;

const std::string ceng795_dir = std::string(RTWEEKEND_TEST_DATA) + "/ceng795/";

rt::whitted_scene load(const std::string& name) { return rt::load_xml_scene(ceng795_dir + name); }

struct rendered {
    int width = 0, height = 0;
    std::vector<unsigned char> bytes; // RGB, row-major, top row first
    std::vector<float> raw;           // the unclamped radiance, same layout
};

rendered render(const rt::whitted_scene& scene, size_t camera, int threads = 0, bool cull = false) {
    rt::render_settings opt = rt::whitted_renderer::defaults();
    opt.threads = threads;
    opt.whitted.cull_back_faces = cull;
    rt::whitted_render r = rt::render_whitted(scene, camera, opt);
    rendered out;
    out.width = r.img.width();
    out.height = r.img.height();
    out.bytes = rt::encode_whitted_8bit(r.img);
    out.raw = r.img.data();
    return out;
}

size_t index_of(const rendered& r, int i, int j, int c) { return 3 * (size_t(j) * size_t(r.width) + size_t(i)) + size_t(c); }

// The course's 8-bit value of a radiance: clamp to [0, 255], then truncate.
int course_byte(double radiance) {
    double v = std::min(std::max(radiance, 0.0), 255.0);
    return static_cast<int>(v);
}

struct rgb {
    double r, g, b;
    double operator[](int c) const { return c == 0 ? r : (c == 1 ? g : b); }
};

// Pixel (i, j) must be within `tol` of the truncated hand radiance `want`, in every channel.
void check_pixel(const rendered& img, int i, int j, const rgb& want, int tol = 1) {
    REQUIRE(i < img.width);
    REQUIRE(j < img.height);
    for (int c = 0; c < 3; ++c) {
        int got = img.bytes[index_of(img, i, j, c)];
        int expected = course_byte(want[c]);
        INFO("pixel (" << i << ", " << j << ") channel " << c << ": hand radiance " << want[c] << " -> byte "
                       << expected << "; renderer radiance " << img.raw[index_of(img, i, j, c)] << " -> byte "
                       << got);
        CHECK(std::abs(got - expected) <= tol);
    }
}

// A tiny vector of doubles for the hand computations (deliberately not rt::vec3).
struct v3 {
    double x, y, z;
};
v3 operator+(v3 a, v3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
v3 operator-(v3 a, v3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
v3 operator*(double s, v3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(v3 a) { return std::sqrt(dot(a, a)); }
v3 normalized(v3 a) { return (1.0 / length(a)) * a; }

// Blinn-Phong radiance of one channel from one unshadowed point light:
// E (kd max(0, n.l) + ks max(0, n.h)^p), E = I / d^2, h = normalize(l + v).
double course_blinn_phong(v3 x, v3 n, v3 v, v3 light, double intensity, double kd, double ks, double p) {
    v3 to_light = light - x;
    double d2 = dot(to_light, to_light);
    v3 l = normalized(to_light);
    v3 h = normalized(l + v);
    double E = intensity / d2;
    return E * (kd * std::max(0.0, dot(n, l)) + ks * std::pow(std::max(0.0, dot(n, h)), p));
}

} // namespace

TEST_CASE("whitted: the test scenes load with the values their files give") {
    rt::whitted_scene s = load("sphere.xml");
    REQUIRE(s.cameras.size() == 3);
    CHECK(s.cameras[0].width == 5);
    CHECK(s.cameras[0].height == 5);
    CHECK(s.cameras[1].width == 9);
    CHECK(s.cameras[1].height == 7);
    CHECK(s.max_recursion_depth == 2);
    CHECK(s.background.x() == doctest::Approx(12));
    CHECK(s.background.y() == doctest::Approx(34));
    CHECK(s.background.z() == doctest::Approx(56));
    REQUIRE(s.lights.size() == 1);
    CHECK(s.lights[0].intensity.x() == doctest::Approx(72000));
    CHECK(s.ambient_light.x() == doctest::Approx(20));

    rendered r = render(s, 0);
    CHECK(r.width == 5);
    CHECK(r.height == 5);
    CHECK(r.bytes.size() == size_t(5 * 5 * 3));
    rendered r2 = render(s, 1);
    CHECK(r2.width == 9);
    CHECK(r2.height == 7);
}

TEST_CASE("whitted: one sphere, one point light, ambient: centre pixel and background") {
    // sphere.xml, camera 1: e = 0, gaze -z, up +y => w = (0,0,1), u = (1,0,0), v = (0,1,0);
    // near plane [-1,1]^2 at d = 1, 5x5. Centre pixel (2,2): s = (0,0,-1), so the ray is (0,0,-1).
    // Sphere: centre = vertex 2 = (0,0,-10) (1-based ids), radius 2 => hit x = (0,0,-8),
    // normal n = (0,0,1), towards the viewer v = (0,0,1).
    // Light at (0,6,-2), I = 72000: x->light = (0,6,6), d^2 = 72, E = 1000;
    //   l = (0,1,1)/sqrt2, n.l = 1/sqrt2 = 0.70711;
    //   h = normalize(l + v) = normalize(0, 0.70711, 1.70711), n.h = cos(22.5 deg) = 0.92388,
    //   (n.h)^10 = 0.45306.
    // ka = (0.5,1,1), Ia = 20 => ambient (10, 20, 20); kd = (0.1, 0.05, 0.02); ks = 0.1.
    //   R = 10 + 1000 (0.1  * 0.70711 + 0.1 * 0.45306) = 10 + 70.711 + 45.306 = 126.02 -> 126
    //   G = 20 + 1000 (0.05 * 0.70711 + 0.1 * 0.45306) = 20 + 35.355 + 45.306 = 100.66 -> 100
    //   B = 20 + 1000 (0.02 * 0.70711 + 0.1 * 0.45306) = 20 + 14.142 + 45.306 =  79.45 ->  79
    // The shadow ray leaves the sphere's front (n.l > 0) and nothing else is in the scene: lit.
    rt::whitted_scene s = load("sphere.xml");
    rendered img = render(s, 0);
    REQUIRE(img.width == 5);
    REQUIRE(img.height == 5);

    const v3 x{0, 0, -8}, n{0, 0, 1}, view{0, 0, 1}, light{0, 6, -2};
    const double I = 72000, Ia = 20;
    const double nl = 1 / std::sqrt(2.0);
    const double nh = std::cos(pi / 8); // the angle between n and h is half of 45 degrees
    CHECK(dot(n, normalized(normalized(light - x) + view)) == doctest::Approx(nh));
    const double E = I / 72;
    rgb want{0.5 * Ia + E * (0.1 * nl + 0.1 * std::pow(nh, 10)),
             1.0 * Ia + E * (0.05 * nl + 0.1 * std::pow(nh, 10)),
             1.0 * Ia + E * (0.02 * nl + 0.1 * std::pow(nh, 10))};
    CHECK(want.r == doctest::Approx(course_blinn_phong(x, n, view, light, I, 0.1, 0.1, 10) + 10));
    check_pixel(img, 2, 2, want);

    // Every other pixel misses: its ray makes at least atan(0.4) = 21.8 degrees with the axis
    // (pixel centres at x, y in {-0.8, -0.4, 0, 0.4, 0.8}), and the sphere subtends
    // asin(2/10) = 11.5 degrees. A primary miss is exactly BackgroundColor (12, 34, 56).
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            if (i == 2 && j == 2) continue;
            check_pixel(img, i, j, {12, 34, 56}, 0);
        }
}

TEST_CASE("whitted: a lookAt camera: centre pixel by hand, and the same bytes as its plain twin") {
    // sphere.xml camera 2: lookAt from e = (3,2,5) at the sphere's centre C = (0,0,-10), FovY 40,
    // NearDistance 2, 9x7: the image plane is symmetric, so the centre pixel (4,3) looks exactly
    // along Gaze = C - e. It hits the sphere where the normal points back at the camera:
    //   n = normalize(e - C) = (3,2,15)/sqrt(238), x = C + 2 n, v = n.
    // Light (0,6,-2), I = 72000: E = I/|L-x|^2, l = normalize(L-x), h = normalize(l+v); n.l > 0.
    // L = ka Ia + E (kd n.l + ks (n.h)^10), ka = (0.5,1,1), Ia = 20, kd = (0.1,0.05,0.02), ks = 0.1.
    rt::whitted_scene s = load("sphere.xml");
    rendered look = render(s, 1);
    REQUIRE(look.width == 9);
    REQUIRE(look.height == 7);

    const v3 e{3, 2, 5}, C{0, 0, -10}, light{0, 6, -2};
    const v3 n = normalized(e - C);
    const v3 x = C + 2.0 * n;
    REQUIRE(dot(n, normalized(light - x)) > 0);
    rgb want{0.5 * 20 + course_blinn_phong(x, n, n, light, 72000, 0.1, 0.1, 10),
             1.0 * 20 + course_blinn_phong(x, n, n, light, 72000, 0.05, 0.1, 10),
             1.0 * 20 + course_blinn_phong(x, n, n, light, 72000, 0.02, 0.1, 10)};
    check_pixel(look, 4, 3, want);
    // The corners miss (the sphere subtends asin(2/15.4) = 7.5 degrees; the corners' rays are
    // more than 20 degrees off the gaze): background.
    check_pixel(look, 0, 0, {12, 34, 56}, 0);
    check_pixel(look, 8, 6, {12, 34, 56}, 0);

    // Camera 3 is camera 2 written as a plain camera: Gaze = GazePoint - Position = (-3,-2,-15),
    // NearDistance 1, t = tan(FovY/2) = tan(20 deg) = 0.36397, r = t * 9/7 = 0.46796, l = -r,
    // b = -t. (The lookAt camera's NearDistance 2 scales its plane, not its rays.)
    rendered plain = render(s, 2);
    REQUIRE(plain.width == 9);
    REQUIRE(plain.height == 7);
    REQUIRE(plain.bytes.size() == look.bytes.size());
    int differing = 0;
    for (size_t k = 0; k < look.bytes.size(); ++k) {
        INFO("byte " << k << ": lookAt " << int(look.bytes[k]) << ", plain " << int(plain.bytes[k]));
        CHECK(std::abs(int(look.bytes[k]) - int(plain.bytes[k])) <= 1);
        differing += look.bytes[k] != plain.bytes[k];
    }
    CHECK(differing <= 3);
    // Not a trivial comparison: more than the centre pixel shows the sphere.
    int sphere_pixels = 0;
    for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 9; ++i) sphere_pixels += look.bytes[index_of(look, i, j, 2)] != 56;
    CHECK(sphere_pixels >= 4);
}

TEST_CASE("whitted: shadows: occluded, unoccluded, and an occluder beyond the light") {
    // shadow.xml: plane z = -10, normal n = (0,0,1); camera at the origin, 5x5, near plane [-1,1]^2
    // at d = 1: pixel (i,j) hits the plane at (10(-1 + 0.4(i+0.5)), 10(1 - 0.4(j+0.5)), -10).
    // Light P = (0,0,-6), I = 3200; Ia = 30; ka = (0.5,0.4,0.3) => ambient (15, 12, 9);
    // kd = (0.5,0.3,0.1), ks = 0.2, p = 4.
    rt::whitted_scene s = load("shadow.xml");
    rendered img = render(s, 0);
    REQUIRE(img.width == 5);
    REQUIRE(img.height == 5);
    const v3 n{0, 0, 1}, light{0, 0, -6};
    const rgb ambient{0.5 * 30, 0.4 * 30, 0.3 * 30};

    // Pixel (2,2) -> D = (0,0,-10): light straight above at distance 4: E = 3200/16 = 200,
    // l = n, v = (0,0,1) = n => h = n, n.l = n.h = 1:
    //   L = (15 + 200 (0.5 + 0.2), 12 + 200 (0.3 + 0.2), 9 + 200 (0.1 + 0.2)) = (155, 112, 69).
    check_pixel(img, 2, 2, {15 + 200 * (0.5 + 0.2), 12 + 200 * (0.3 + 0.2), 9 + 200 * (0.1 + 0.2)});

    // Pixel (1,2) -> A = (-4,0,-10): the segment to the light passes through (-2,0,-8), the centre
    // of sphere 1 (radius 0.5): shadowed, ambient only: (15, 12, 9).
    check_pixel(img, 1, 2, ambient);

    // Pixel (3,2) -> B = (4,0,-10): nothing in the way. x->light = (-4,0,4), d^2 = 32, E = 100,
    // l = (-1,0,1)/sqrt2, n.l = 0.70711; v = normalize(0 - B) = (-4,0,10)/sqrt(116);
    // h = normalize(l + v), n.h = 0.83484, (n.h)^4 = 0.48575:
    //   L = (15 + 100 (0.5*0.70711 + 0.2*0.48575), 12 + 100 (0.3*0.70711 + 0.2*0.48575),
    //        9 + 100 (0.1*0.70711 + 0.2*0.48575)) = (60.07, 42.93, 25.79).
    const v3 B{4, 0, -10};
    const v3 vB = normalized(v3{0, 0, 0} - B);
    const double nhB = dot(n, normalized(normalized(light - B) + vB));
    CHECK(nhB == doctest::Approx(0.83484).epsilon(1e-4));
    const double nl = 1 / std::sqrt(2.0);
    rgb lit{15 + 100 * (0.5 * nl + 0.2 * std::pow(nhB, 4)), 12 + 100 * (0.3 * nl + 0.2 * std::pow(nhB, 4)),
            9 + 100 * (0.1 * nl + 0.2 * std::pow(nhB, 4))};
    CHECK(lit.r == doctest::Approx(15 + course_blinn_phong(B, n, vB, light, 3200, 0.5, 0.2, 4)));
    check_pixel(img, 3, 2, lit);

    // Pixel (2,1) -> C = (0,4,-10): sphere 2 (centre (0,-6,0), radius 0.5) lies on the line from C
    // through the light, at distance |(0,-10,10)| = 14.1 from C, beyond the light (5.66 from C):
    // no shadow. C is B turned 90 degrees about the viewing axis, so its radiance is B's.
    const v3 Cp{0, 4, -10};
    CHECK(dot(n, normalized(normalized(light - Cp) + normalized(v3{0, 0, 0} - Cp))) == doctest::Approx(nhB));
    check_pixel(img, 2, 1, lit);
}

TEST_CASE("whitted: a chain of mirrors, and MaxRecursionDepth counting bounces") {
    // mirror.xml: ambient light only, Ia = 100, so each surface's own radiance is ka Ia:
    //   M1 (mirror, km1 = 0.5):          own (10, 0, 0)
    //   M2 (mirror, km2 = (0.5,0.8,0.6)): own (0, 20, 0)
    //   W  (plain):                      own (40, 60, 100)
    // Camera 1 centre ray (0,0,-1) hits M1 at (0,0,-10), normal (1,0,1)/sqrt2:
    //   r = d - 2 (d.n) n = (0,0,-1) + (1,0,1) = (1,0,0) -> M2 at (10,0,-10), normal (-1,0,1)/sqrt2:
    //   r = (1,0,0) + (-1,0,1) = (0,0,1) -> W at (10,0,5).
    //   depth 0: own(M1)                                           = (10, 0, 0)
    //   depth 1: own(M1) + km1 own(M2)                             = (10, 10, 0)
    //   depth 2: ... + km1 km2 own(W) = + 0.5 (20, 48, 60)         = (20, 34, 30)
    //   depth 3: W is plain: no more                                = (20, 34, 30)
    // Camera 2 (at (10,0,0)) centre ray hits M2 at (10,0,-10): r = (0,0,-1) + (-1,0,1) = (-1,0,0)
    //   -> M1 at (0,0,-10): r = (-1,0,0) + (1,0,1) = (0,0,1) -> nothing (W is at x >= 7):
    //   a secondary miss is black, not the background (50, 60, 70):
    //   depth 0: (0, 20, 0); depth >= 1: (0, 20, 0) + km2 (10, 0, 0) = (5, 20, 0).
    rt::whitted_scene s = load("mirror.xml");
    CHECK(s.max_recursion_depth == 2);
    const rgb ownM1{0.1 * 100, 0, 0}, ownM2{0, 0.2 * 100, 0}, ownW{0.4 * 100, 0.6 * 100, 1.0 * 100};
    const rgb km1{0.5, 0.5, 0.5}, km2{0.5, 0.8, 0.6};
    for (int depth = 0; depth <= 3; ++depth) {
        CAPTURE(depth);
        s.max_recursion_depth = depth;
        double chain[3], escape[3];
        for (int c = 0; c < 3; ++c) {
            double from_m2 = ownM2[c] + (depth >= 2 ? km2[c] * ownW[c] : 0.0);
            chain[c] = ownM1[c] + (depth >= 1 ? km1[c] * from_m2 : 0.0);
            const double missed = 0.0; // M1's reflection, towards +z, hits nothing: black
            double from_m1 = ownM1[c] + (depth >= 2 ? km1[c] * missed : 0.0);
            escape[c] = ownM2[c] + (depth >= 1 ? km2[c] * from_m1 : 0.0);
        }
        rendered one = render(s, 0);
        REQUIRE(one.width == 3);
        check_pixel(one, 1, 1, {chain[0], chain[1], chain[2]});
        rendered two = render(s, 1);
        check_pixel(two, 1, 1, {escape[0], escape[1], escape[2]});
    }
    // The numbers of the table above, spelled out.
    s.max_recursion_depth = 0;
    check_pixel(render(s, 0), 1, 1, {10, 0, 0});
    s.max_recursion_depth = 1;
    check_pixel(render(s, 0), 1, 1, {10, 10, 0});
    s.max_recursion_depth = 2;
    check_pixel(render(s, 0), 1, 1, {20, 34, 30});
    check_pixel(render(s, 1), 1, 1, {5, 20, 0});
}

TEST_CASE("whitted: a conductor at normal incidence") {
    // conductor.xml: camera at the origin, centre ray (0,0,-1); conductor quad in z = -10,
    // normal (0,0,1); n = 1.5, k = 2, MirrorReflectance km = (1, 0.8, 0.6).
    // Fresnel at normal incidence (Rs = Rp there):
    //   Fr = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) = (0.25 + 4) / (6.25 + 4) = 4.25 / 10.25 = 0.41463.
    // Own shading at x = (0,0,-10): light (0,0,-5), I = 2500: d = 5, E = 100, l = v = n => h = n:
    //   ka Ia + E (kd + ks) = 0.1*20 + 100 ((0.1,0.2,0.3) + 0.1) = (22, 32, 42).
    // The reflected ray (0,0,1) hits the plain wall W in z = 5 at (0,0,5), normal (0,0,-1), which
    // the light (in front of it, at distance 10; the conductor lies beyond the light) sees:
    //   E = 25, l = (0,0,-1) = n, v = -(0,0,1) = n, ks = 0:
    //   L_W = (1,2,3)*20 + 25 (4,2,1) = (120, 90, 85).
    // Pixel = own + km Fr L_W = (22 + 0.41463*120, 32 + 0.8*0.41463*90, 42 + 0.6*0.41463*85)
    //       = (71.76, 61.85, 63.15).
    rt::whitted_scene s = load("conductor.xml");
    const double n = 1.5, k = 2;
    const double Fr = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    CHECK(Fr == doctest::Approx(4.25 / 10.25));
    const rgb own{0.1 * 20 + 100 * (0.1 + 0.1), 0.1 * 20 + 100 * (0.2 + 0.1), 0.1 * 20 + 100 * (0.3 + 0.1)};
    const rgb wall{1 * 20 + 25 * 4.0, 2 * 20 + 25 * 2.0, 3 * 20 + 25 * 1.0};
    const rgb km{1, 0.8, 0.6};
    rendered img = render(s, 0);
    REQUIRE(img.width == 3);
    check_pixel(img, 1, 1, {own.r + km.r * Fr * wall.r, own.g + km.g * Fr * wall.g, own.b + km.b * Fr * wall.b});

    // Without recursion only its own shading is left.
    s.max_recursion_depth = 0;
    check_pixel(render(s, 0), 1, 1, own);
}

TEST_CASE("whitted: a dielectric slab at normal incidence with Beer's law") {
    // glass_slab.xml: closed box z in [-6,-4] (thickness 2), index n = 2.4, c = (0.05,0.1,0.2),
    // no own shading. Behind it the plain wall B (z = -10), ambient only: L_B = ka Ia =
    // (2.5,2,1.5)*100 = (250, 200, 150) wherever it is hit. Camera 1's centre ray is (0,0,-1).
    // At normal incidence, on either side: R = ((n-1)/(n+1))^2 = (1.4/3.4)^2 = 0.16955, T = 1 - R.
    // One crossing attenuates by a = exp(-2c) = (0.90484, 0.81873, 0.67032).
    // The paths (each dielectric hit spawns a reflected and a refracted ray, one bounce each):
    //   depth 0 F(front, z=-4): reflected -> +z -> misses everything: black (secondary miss);
    //           refracted (x T) -> inside, crosses 2 (x a) -> depth 1 at K (back, z=-6):
    //   depth 1 K: refracted out (x T) -> depth 2: hits B: L_B                 [needs max >= 2]
    //              reflected (x R) -> inside back to F (x a) -> depth 2 at F:
    //   depth 2 F: refracted out -> +z -> black; reflected (x R) -> to K (x a) -> depth 3 at K:
    //   depth 3 K: refracted out (x T) -> depth 4: L_B                           [needs max >= 4]
    // So with MaxRecursionDepth D:
    //   D = 0, 1: 0 (the glass has no own shading; the ray inside cannot leave)
    //   D = 2, 3: T a T L_B        = 0.68965 (226.21, 163.75, 100.55) = (156.01, 112.93, 69.34)
    //   D = 4, 5: + T R a R a T a L_B = + 0.019825 a^3 L_B = + (3.67, 2.18, 0.90)
    //                                                         = (159.68, 115.11, 70.25)
    // (D = 6 would add T R^4 a^5 T L_B < 0.09: not asserted.)
    rt::whitted_scene s = load("glass_slab.xml");
    CHECK(s.max_recursion_depth == 4);
    const double n = 2.4;
    const double R = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
    const double T = 1 - R;
    const double c[3] = {0.05, 0.1, 0.2};
    const double LB[3] = {250, 200, 150};
    for (int depth = 0; depth <= 5; ++depth) {
        CAPTURE(depth);
        s.max_recursion_depth = depth;
        double want[3];
        for (int ch = 0; ch < 3; ++ch) {
            double a = std::exp(-c[ch] * 2);
            want[ch] = 0;
            if (depth >= 2) want[ch] += T * a * T * LB[ch];
            if (depth >= 4) want[ch] += T * a * R * a * R * a * T * LB[ch];
        }
        rendered img = render(s, 0);
        REQUIRE(img.width == 3);
        check_pixel(img, 1, 1, {want[0], want[1], want[2]});
    }
    // The same numbers, spelled out.
    s.max_recursion_depth = 2;
    check_pixel(render(s, 0), 1, 1, {156.01, 112.93, 69.34});
    s.max_recursion_depth = 4;
    check_pixel(render(s, 0), 1, 1, {159.68, 115.11, 70.25});
}

TEST_CASE("whitted: a dielectric slab at 45 degrees: exact Fresnel and the slanted path") {
    // glass_slab.xml camera 2: from (-4,0,0) along (1,0,-1): hits the front face at (0,0,-4) at
    // theta_i = 45 degrees. Snell: sin(theta_t) = sin(45)/2.4 = 0.29463, cos(theta_t) = 0.95561.
    // Exact Fresnel (unpolarised) entering, n1 = 1, n2 = 2.4, ci = cos(theta_i), ct = cos(theta_t):
    //   r_par  = (n2 ci - n1 ct) / (n2 ci + n1 ct) =  0.27951
    //   r_perp = (n1 ci - n2 ct) / (n1 ci + n2 ct) = -0.52868
    //   F = (r_par^2 + r_perp^2) / 2 = 0.17882
    // Leaving through the back face, from inside at theta_t, gives the same F (swap n1, n2 and the
    // angles: each ratio only changes sign). The path inside is 2 / cos(theta_t) = 2.0929 long:
    // a' = exp(-c 2.0929). The ray leaves parallel to (1,0,-1) and hits the wall B (L_B as above);
    // the front face's reflection and every ray leaving towards +z miss: black.
    //   D = 2, 3: (1-F) a' (1-F) L_B                        = (151.84, 109.41, 66.57)
    //   D = 4:    + (1-F) F^2 (1-F) a'^3 L_B                 = (155.78, 111.71, 67.49)
    // (The internal zig-zag advances 0.62 along x per crossing; three crossings stay inside the
    // box's x <= 3.)  Schlick's approximation would give 154.6 in red at D = 2: told apart.
    rt::whitted_scene s = load("glass_slab.xml");
    const double n1 = 1, n2 = 2.4;
    const double ci = std::cos(pi / 4);
    const double st = std::sin(pi / 4) * n1 / n2;
    const double ct = std::sqrt(1 - st * st);
    const double r_par = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
    const double r_perp = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct);
    const double F = (r_par * r_par + r_perp * r_perp) / 2;
    CHECK(F == doctest::Approx(0.17882).epsilon(1e-4));
    // From inside: n1' = 2.4, n2' = 1, incidence theta_t, transmitted theta_i.
    const double r_par_out = (n1 * ct - n2 * ci) / (n1 * ct + n2 * ci);
    const double r_perp_out = (n2 * ct - n1 * ci) / (n2 * ct + n1 * ci);
    const double F_out = (r_par_out * r_par_out + r_perp_out * r_perp_out) / 2;
    CHECK(F_out == doctest::Approx(F));
    const double path = 2 / ct;
    const double c[3] = {0.05, 0.1, 0.2};
    const double LB[3] = {250, 200, 150};
    for (int depth = 2; depth <= 4; ++depth) {
        CAPTURE(depth);
        s.max_recursion_depth = depth;
        double want[3];
        for (int ch = 0; ch < 3; ++ch) {
            double a = std::exp(-c[ch] * path);
            want[ch] = (1 - F) * a * (1 - F_out) * LB[ch];
            if (depth >= 4) want[ch] += (1 - F) * a * F_out * a * F_out * a * (1 - F_out) * LB[ch];
        }
        rendered img = render(s, 1);
        REQUIRE(img.width == 3);
        check_pixel(img, 1, 1, {want[0], want[1], want[2]});
    }
}

TEST_CASE("whitted: a triangle's edge pixels") {
    // triangle_edges.xml: camera at the origin, gaze -z, near plane [-1,1]x[-0.8,0.8] at d = 1,
    // 10x8: pixel (i,j) looks through (x, y) = (-0.9 + 0.2 i, 0.7 - 0.2 j) on the plane z = -1.
    // The triangle (vertices 1 2 3 = (-1.2,-1.2,-2), (1.4,-1.2,-2), (-1.2,1.4,-2)), projected onto
    // z = -1: (-0.6,-0.6), (0.7,-0.6), (-0.6,0.7), bounded by x = -0.6, y = -0.6 and x + y = 0.1.
    // A pixel centre is inside when
    //   x > -0.6  <=> -0.9 + 0.2 i > -0.6  <=> i >= 2   (i = 1: x = -0.7, i = 2: x = -0.5)
    //   y > -0.6  <=>  0.7 - 0.2 j > -0.6  <=> j <= 6   (j = 6: y = -0.5, j = 7: y = -0.7)
    //   x + y < 0.1 <=> -0.2 + 0.2 (i - j) < 0.1 <=> i <= j + 1   (x + y is 0 or 0.2 either side)
    // Every centre is at least 0.1 (in x, y or x + y) from an edge. Inside: ka Ia =
    // (1, 0.5, 0.25) * 100 = (100, 50, 25); outside: the background (10, 20, 30).
    //   j=0  . . . . . . . . . .
    //   j=1  . . # . . . . . . .
    //   j=2  . . # # . . . . . .
    //   ...
    //   j=6  . . # # # # # # . .
    //   j=7  . . . . . . . . . .
    rt::whitted_scene s = load("triangle_edges.xml");
    rendered img = render(s, 0);
    REQUIRE(img.width == 10);
    REQUIRE(img.height == 8);
    int inside_count = 0;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 10; ++i) {
            bool inside = i >= 2 && j <= 6 && i <= j + 1;
            inside_count += inside;
            if (inside)
                check_pixel(img, i, j, {100, 50, 25});
            else
                check_pixel(img, i, j, {10, 20, 30}, 0);
        }
    CHECK(inside_count == 21);
}

TEST_CASE("whitted: 8-bit encoding clamps to [0, 255] and truncates") {
    // Directly: a 2x2 image, row-major, top row first.
    rt::image im(2, 2);
    const float values[12] = {100.7f, 255.5f, 1e6f,   // (0,0)
                              -3.0f,  0.999f, 254.999f, // (1,0)
                              0.0f,   1.0f,   55.5f,  // (0,1)
                              200.99f, 256.0f, 128.49f}; // (1,1)
    for (int k = 0; k < 12; ++k) im.data()[size_t(k)] = values[k];
    std::vector<unsigned char> bytes = rt::encode_whitted_8bit(im);
    const int want[12] = {100, 255, 255, 0, 0, 254, 0, 1, 55, 200, 255, 128};
    REQUIRE(bytes.size() == 12);
    for (int k = 0; k < 12; ++k) {
        CAPTURE(k);
        CHECK(int(bytes[size_t(k)]) == want[k]);
    }

    // Through a render (clamp.xml): the centre pixel's radiance is ka Ia = Ia = (1000, 200.99, 55.5)
    // -> (255, 200, 55), and the image keeps the unclamped 1000; the other pixels miss: background
    // (300, 100.7, 0.99) -> (255, 100, 0). Exact bytes: rounding would give 201, 56 and 101, 1.
    rt::whitted_scene s = load("clamp.xml");
    rendered img = render(s, 0);
    REQUIRE(img.width == 3);
    REQUIRE(img.height == 3);
    CHECK(img.raw[index_of(img, 1, 1, 0)] == doctest::Approx(1000).epsilon(1e-4));
    CHECK(img.raw[index_of(img, 0, 0, 0)] == doctest::Approx(300).epsilon(1e-4));
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            CAPTURE(i);
            CAPTURE(j);
            const int centre[3] = {255, 200, 55}, background[3] = {255, 100, 0};
            const int* w = (i == 1 && j == 1) ? centre : background;
            for (int c = 0; c < 3; ++c) CHECK(int(img.bytes[index_of(img, i, j, c)]) == w[c]);
        }
}

TEST_CASE("whitted: one and two threads give identical bytes" * doctest::test_suite("threads")) {
    for (const char* name : {"closed.xml", "glass_slab.xml", "sphere.xml", "shadow.xml"}) {
        CAPTURE(name);
        rt::whitted_scene s = load(name);
        for (size_t cam = 0; cam < s.cameras.size(); ++cam) {
            CAPTURE(cam);
            rendered one = render(s, cam, 1);
            rendered two = render(s, cam, 2);
            REQUIRE(one.bytes.size() == two.bytes.size());
            CHECK(one.bytes == two.bytes);
            CHECK(one.raw == two.raw);
        }
    }
}

TEST_CASE("whitted: back-face culling does not change a closed opaque scene seen from outside") {
    // closed.xml: an opaque box, a mirror sphere and a conductor sphere on a floor that every ray
    // meets from above; culling can only skip triangles facing away from a ray, which are never
    // the nearest hit here.
    rt::whitted_scene s = load("closed.xml");
    rendered plain = render(s, 0, 0, false);
    rendered culled = render(s, 0, 0, true);
    REQUIRE(plain.width == 48);
    REQUIRE(plain.height == 36);
    CHECK(plain.bytes == culled.bytes);
    // Not trivial: the picture holds many different colours (floor, box, spheres, shadows).
    std::vector<unsigned char> sorted = plain.bytes;
    std::sort(sorted.begin(), sorted.end());
    CHECK(std::unique(sorted.begin(), sorted.end()) - sorted.begin() > 50);
}

// The scenes below are built in code and seen by a 3x3 camera at the origin looking down -z,
// its image plane [-half, half]^2 at distance 1; these render it and check the centre pixel.
namespace {

std::vector<unsigned char> render_3x3(rt::whitted_scene& s, double half = 1) {
    rt::view_camera c;
    c.width = c.height = 3;
    c.left = c.bottom = -half;
    c.right = c.top = half;
    c.image_name = "x.png";
    s.cameras.push_back(c);
    return rt::encode_whitted_8bit(rt::render_whitted(s, 0).img);
}

void check_centre(const std::vector<unsigned char>& b, int r, int g, int bl) {
    const size_t centre = 3 * (1 * 3 + 1);
    CHECK(std::abs(int(b[centre]) - r) <= 1);
    CHECK(std::abs(int(b[centre + 1]) - g) <= 1);
    CHECK(std::abs(int(b[centre + 2]) - bl) <= 1);
}

} // namespace

// The built-in path-tracer materials have Whitted equivalents, so a book-style world renders in
// Whitted mode too: a Lambertian sphere is diffuse with kd = albedo.
TEST_CASE("whitted: a book-style lambertian sphere shades with kd = albedo") {
    rt::whitted_scene s;
    s.world.add(std::make_shared<rt::sphere>(rt::point3(0, 0, -5), 1.0,
                                             std::make_shared<rt::lambertian>(rt::color(0.5, 0.25, 0.125))));
    s.lights.push_back({rt::point3(0, 0, 0), rt::color(1600, 1600, 1600)});
    // Centre pixel: the ray along -z meets (0, 0, -4) head on; the light at the eye is 4 away,
    // E = 1600 / 16 = 100, n.l = 1: L = 100 * albedo = (50, 25, 12.5).
    std::vector<unsigned char> b = render_3x3(s);
    check_centre(b, 50, 25, 12);
}

// CENG477's files give materials no type: a non-zero MirrorReflectance makes a mirror there.
TEST_CASE("whitted: an untyped material with a MirrorReflectance reflects") {
    auto quad = [](double z, bool facing_plus_z, std::shared_ptr<rt::whitted_material> m) {
        auto mesh = std::make_shared<rt::triangle_mesh>();
        mesh->positions = {rt::point3(-3, -3, z), rt::point3(3, -3, z), rt::point3(3, 3, z), rt::point3(-3, 3, z)};
        mesh->faces = facing_plus_z ? std::vector<std::array<uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}}
                                    : std::vector<std::array<uint32_t, 3>>{{0, 2, 1}, {0, 3, 2}};
        mesh->mat = std::move(m);
        return mesh;
    };
    auto mirror = std::make_shared<rt::whitted_material>(); // no type given, as in CENG477
    mirror->mirror = rt::color(0.5, 0.5, 0.5);
    auto wall = std::make_shared<rt::whitted_material>();
    wall->ambient = rt::color(1, 0.5, 0.25);
    rt::whitted_scene s;
    s.ambient_light = rt::color(100, 100, 100);
    s.max_recursion_depth = 1;
    s.world.add(quad(-5, true, mirror)); // in front of the camera, facing it
    s.world.add(quad(5, false, wall));   // behind the camera, facing it
    // Centre pixel: the ray along -z meets the mirror (own shading 0) and comes straight back
    // along +z to the wall, which shows ambient only: 0.5 * 100 * (1, 0.5, 0.25) = (50, 25, 12.5).
    check_centre(render_3x3(s, 0.1), 50, 25, 12);
}

// A user-written hittable renders in Whitted mode too, with the material it reports.
namespace {
class wrapped_sphere : public rt::hittable {
  public:
    explicit wrapped_sphere(std::shared_ptr<rt::material> m) : inner_(rt::point3(0, 0, -5), 1.0, std::move(m)) {}
    bool hit(const rt::ray& r, rt::interval t, rt::hit_record& rec) const override { return inner_.hit(r, t, rec); }

  private:
    rt::sphere inner_;
};
} // namespace

TEST_CASE("whitted: a user-written hittable is shaded with the material it reports") {
    auto m = std::make_shared<rt::whitted_material>();
    m->diffuse = rt::color(0.5, 0.25, 0.125);
    rt::whitted_scene s;
    s.world.add(std::make_shared<wrapped_sphere>(m));
    s.lights.push_back({rt::point3(0, 0, 0), rt::color(1600, 1600, 1600)});
    // As for the built-in sphere: E = 1600 / 4^2 = 100 at (0, 0, -4), n.l = 1: (50, 25, 12.5).
    std::vector<unsigned char> b = render_3x3(s);
    check_centre(b, 50, 25, 12);
    CHECK(int(b[0]) == 0); // a corner misses: the default black background
}

// The course's rule for glass seen from inside: a hit on a dielectric reached from inside it has
// no ambient, diffuse or specular term (whitted_settings::shade_inside_dielectrics, docs/course.md).
TEST_CASE("whitted: a hit on glass from inside gets no local shading (the course's rule), or all of it (option)") {
    // glass_slab_shaded.xml: glass_slab.xml's slab (n = 2.4, c = (0.05,0.1,0.2), thickness 2) and
    // wall B (L_B = (250,200,150)), the glass now shaded: ka = (0.3,0.2,0.1), kd = (0.1,0.2,0.3),
    // ks = 0.5, p = 10, Ia = 100, a light I = 3920 at (0,0,10); MaxRecursionDepth 2. Camera 1's
    // centre ray goes down -z; R = (1.4/3.4)^2 at normal incidence, T = 1 - R, a = exp(-2c).
    //   depth 0, F (front face, from outside, at (0,0,-4)): local shading
    //     S_F = ka Ia + E (kd + ks),  E = 3920 / 14^2 = 20, n.l = n.h = 1 (light, eye, normal on
    //     the axis: l = v = h = +z): S_F = (30,20,10) + 20 (0.6,0.7,0.8) = (42,34,26);
    //     its reflection leaves towards +z: black; its refraction (x T) crosses the slab (x a) to
    //   depth 1, K (back face, from inside): local shading S_in; refraction out (x T) to B: L_B;
    //     reflection (x R) back across (x a) to
    //   depth 2, F from inside: local shading S_in only (no bounces left).
    //   L = S_F + T a (S_in + T L_B + R a S_in)
    // The course's rule: S_in = 0. Shading inside too: S_in = ka Ia, no more (the shadow ray of a
    // hit from inside starts inside the glass and the glass blocks it).
    rt::whitted_scene s = load("glass_slab_shaded.xml");
    REQUIRE(s.max_recursion_depth == 2);
    const double n = 2.4;
    const double R = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
    const double T = 1 - R;
    const double c[3] = {0.05, 0.1, 0.2}, LB[3] = {250, 200, 150};
    const double ka[3] = {0.3, 0.2, 0.1}, kd[3] = {0.1, 0.2, 0.3}, ks = 0.5, Ia = 100, E = 3920.0 / (14 * 14);
    double course[3], shaded[3];
    for (int ch = 0; ch < 3; ++ch) {
        const double a = std::exp(-2 * c[ch]);
        const double S_F = ka[ch] * Ia + E * (kd[ch] + ks);
        course[ch] = S_F + T * a * (0 + T * LB[ch] + R * a * 0);
        const double S_in = ka[ch] * Ia;
        shaded[ch] = S_F + T * a * (S_in + T * LB[ch] + R * a * S_in);
    }
    // The numbers: (198.01, 146.93, 95.34) and (224.01, 162.42, 101.54).
    CHECK(course[0] == doctest::Approx(198.01).epsilon(1e-4));
    CHECK(shaded[0] == doctest::Approx(224.01).epsilon(1e-4));

    rendered by_default = render(s, 0);
    REQUIRE(by_default.width == 3);
    check_pixel(by_default, 1, 1, {course[0], course[1], course[2]});

    rt::render_settings opt = rt::whitted_renderer::defaults();
    opt.whitted.shade_inside_dielectrics = true;
    rt::whitted_render r = rt::render_whitted(s, 0, opt);
    rendered inside_shaded{r.img.width(), r.img.height(), rt::encode_whitted_8bit(r.img), r.img.data()};
    check_pixel(inside_shaded, 1, 1, {shaded[0], shaded[1], shaded[2]});

    // The rule changes nothing where no ray travels inside glass: glass_slab.xml's glass has no
    // own shading (ka = kd = ks = 0), and sphere.xml has no glass.
    for (const char* name : {"glass_slab.xml", "sphere.xml"}) {
        CAPTURE(name);
        rt::whitted_scene other = load(name);
        rt::whitted_render a = rt::render_whitted(other, 0, opt);
        CHECK(a.img.data() == render(other, 0).raw);
    }
}

// Interrupting a Whitted render (render_settings::stop): a user-written sphere that counts the
// rays it is asked about raises the flag, as Ctrl-C would, from inside the render.
namespace {
class counting_sphere : public rt::hittable {
  public:
    counting_sphere(std::shared_ptr<rt::material> m, std::atomic<bool>& stop, uint64_t stop_at)
        : inner_(rt::point3(0, 0, -5), 1.0, std::move(m)), stop_(stop), stop_at_(stop_at) {}
    bool hit(const rt::ray& r, rt::interval t, rt::hit_record& rec) const override {
        if (++calls_ == stop_at_) stop_ = true;
        return inner_.hit(r, t, rec);
    }
    uint64_t calls() const { return calls_.load(); }

  private:
    rt::sphere inner_;
    std::atomic<bool>& stop_;
    uint64_t stop_at_;
    mutable std::atomic<uint64_t> calls_{0};
};

struct stopped_whitted {
    rt::whitted_render r;
    uint64_t calls = 0;
};

// A 32x16 image (two 16x16 tiles) in which every camera ray hits the sphere, whose material shows
// only the ambient light: (10, 20, 30). No light, no bounces: one question to the sphere per pixel.
stopped_whitted render_stopping(int threads, uint64_t stop_at, bool raised_before = false) {
    auto m = std::make_shared<rt::whitted_material>();
    m->ambient = rt::color(1, 1, 1);
    std::atomic<bool> stop{raised_before};
    auto sphere = std::make_shared<counting_sphere>(m, stop, stop_at);
    rt::whitted_scene s;
    s.background = rt::color(1, 2, 3);
    s.ambient_light = rt::color(10, 20, 30);
    s.world.add(sphere);
    rt::view_camera c;
    c.left = -0.1;
    c.right = 0.1;
    c.bottom = -0.05;
    c.top = 0.05;
    c.width = 32;
    c.height = 16;
    s.cameras.push_back(c);
    rt::render_settings opt = rt::whitted_renderer::defaults();
    opt.threads = threads;
    opt.stop = &stop;
    stopped_whitted out{rt::render_whitted(s, 0, opt), 0};
    out.calls = sphere->calls();
    return out;
}

bool is_rgb(const rt::image& img, int x, int y, float r, float g, float b) {
    const size_t i = 3 * (size_t(y) * size_t(img.width()) + size_t(x));
    return img.data()[i] == r && img.data()[i + 1] == g && img.data()[i + 2] == b;
}
} // namespace

TEST_CASE("whitted: a stop between pixels leaves the pixels traced, the others black, and says how many") {
    // One thread takes tile 0 (x, y < 16) row by row: the flag rises while pixel 39 = (7, 2) is
    // traced; it is finished, and the render stops before pixel 40.
    stopped_whitted one = render_stopping(1, 40);
    CHECK(one.calls == 40);
    CHECK(one.r.stats.interrupted);
    CHECK(one.r.stats.samples == 40);
    CHECK(one.r.stats.pixels_without_samples == 32 * 16 - 40);
    CHECK(one.r.stats.min_pixel_samples == 0);
    CHECK(one.r.stats.max_pixel_samples == 1);
    CHECK(one.r.stats.completed == doctest::Approx(40.0 / 512.0));
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x) {
            CAPTURE(x);
            CAPTURE(y);
            const bool traced = x < 16 && y * 16 + x < 40;
            CHECK(is_rgb(one.r.img, x, y, traced ? 10.0f : 0.0f, traced ? 20.0f : 0.0f, traced ? 30.0f : 0.0f));
        }

    // Raised before the render: nothing traced, all black.
    stopped_whitted none = render_stopping(1, 0, true);
    CHECK(none.calls == 0);
    CHECK(none.r.stats.interrupted);
    CHECK(none.r.stats.samples == 0);
    CHECK(none.r.stats.pixels_without_samples == 512);
    CHECK(is_rgb(none.r.img, 0, 0, 0, 0, 0));

    // Never raised: the whole image, not interrupted.
    stopped_whitted all = render_stopping(1, 0);
    CHECK_FALSE(all.r.stats.interrupted);
    CHECK(all.r.stats.samples == 512);
    CHECK(all.r.stats.pixels_without_samples == 0);
    CHECK(is_rgb(all.r.img, 31, 15, 10, 20, 30));
}

TEST_CASE("whitted: a stop on two threads: every pixel is traced or black, as the statistics say"
          * doctest::test_suite("threads")) {
    // Where the two workers are when the flag rises is up to the scheduler; what must hold is
    // that each pixel was either traced whole or left black, and that the counts agree.
    stopped_whitted two = render_stopping(2, 100);
    CHECK(two.r.stats.interrupted);
    CHECK(two.r.stats.threads == 2);
    CHECK(two.r.stats.samples >= 100);
    CHECK(two.r.stats.samples < 512);
    CHECK(two.r.stats.samples == two.calls);
    uint64_t traced = 0, black = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x) {
            if (is_rgb(two.r.img, x, y, 10, 20, 30)) ++traced;
            else if (is_rgb(two.r.img, x, y, 0, 0, 0)) ++black;
        }
    CHECK(traced == two.r.stats.samples);
    CHECK(black == two.r.stats.pixels_without_samples);
    CHECK(traced + black == 512);
}

} // namespace test_whitted
