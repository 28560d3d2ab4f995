// The samplers (rtweekend/render/sampler.h): the Sobol sequence against its definition, the
// stratification each sampler promises (one point per stratum, (0, m, 2)-nets, discrepancy
// bounds derived below), chi-square tests of every pair of consecutive dimensions of a path,
// determinism at any thread count, and an unbiased cover scene against the book's own reference
// (the analytic sphere-light floor is rendered with every sampler in test_lights.cpp).

#include "chi_square.h"
#include "test_helpers.h"

#include <rtweekend/render/sampler.h>
#include <rtweekend/image/image_read.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/rtweekend.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace test_sampler {

using namespace rt;

namespace {

const sampler_kind all_samplers[] = {sampler_kind::independent, sampler_kind::stratified, sampler_kind::sobol};

// The numbers a sampler gives sample s of pixel (x, y) in a 2-D or 1-D dimension.
uniform2 pair_of(const sampler_plan& plan, int x, int y, int s, uint32_t dimension) {
    pcg32 rng = sample_rng(7, uint64_t(y) * 1000 + uint64_t(x), uint64_t(s));
    pixel_sampler ps(plan, x, y, s, rng);
    return ps.get2d(dimension);
}
float one_of(const sampler_plan& plan, int x, int y, int s, uint32_t dimension) {
    pcg32 rng = sample_rng(7, uint64_t(y) * 1000 + uint64_t(x), uint64_t(s));
    pixel_sampler ps(plan, x, y, s, rng);
    return ps.get1d(dimension);
}

// The numbers of one camera sample in the order a path of `bounces` bounces asks for them: the
// pixel, lens and time, then per bounce the light choice and position, the lobe, the direction,
// the second lobe and direction, the mixture's strategy and Russian roulette.
std::vector<float> path_numbers(const sampler_plan& plan, int x, int y, int s, int bounces) {
    pcg32 rng = sample_rng(7, uint64_t(y) * 1000 + uint64_t(x), uint64_t(s));
    pixel_sampler ps(plan, x, y, s, rng);
    std::vector<float> v;
    auto two = [&](uint32_t d) {
        uniform2 u = ps.get2d(d);
        v.push_back(u.u1);
        v.push_back(u.u2);
    };
    two(sample_dimension::camera_pixel);
    two(sample_dimension::camera_lens);
    v.push_back(ps.get1d(sample_dimension::camera_time));
    for (int b = 0; b < bounces; ++b) {
        const uint32_t base = sample_dimension::bounce(b);
        v.push_back(ps.get1d(base + sample_dimension::light_choice));
        two(base + sample_dimension::light_position);
        v.push_back(ps.get1d(base + sample_dimension::lobe));
        two(base + sample_dimension::direction);
        v.push_back(ps.get1d(base + sample_dimension::lobe_extra));
        two(base + sample_dimension::direction_extra);
        v.push_back(ps.get1d(base + sample_dimension::strategy));
        v.push_back(ps.get1d(base + sample_dimension::roulette));
    }
    return v;
}

// Star discrepancy of points in [0,1)^2: the largest difference between the fraction of points
// in an anchored box [0,a) x [0,b) and its area, over boxes whose corners are at point
// coordinates or 1 (where the supremum is reached, as a limit from one side or the other).
double star_discrepancy(const std::vector<uniform2>& p) {
    const double n = double(p.size());
    std::vector<double> xs{1.0}, ys{1.0};
    for (const uniform2& q : p) {
        xs.push_back(q.u1);
        ys.push_back(q.u2);
    }
    double worst = 0;
    for (double a : xs)
        for (double b : ys) {
            int open = 0, closed = 0;
            for (const uniform2& q : p) {
                open += q.u1 < a && q.u2 < b;
                closed += q.u1 <= a && q.u2 <= b;
            }
            worst = std::max({worst, a * b - open / n, closed / n - a * b});
        }
    return worst;
}

double star_discrepancy_1d(std::vector<float> v) {
    std::sort(v.begin(), v.end());
    const double n = double(v.size());
    double worst = 0;
    for (size_t i = 0; i < v.size(); ++i)
        worst = std::max({worst, double(i + 1) / n - v[i], v[i] - double(i) / n});
    return worst;
}

} // namespace

TEST_CASE("sampler names parse and print") {
    for (sampler_kind k : all_samplers) {
        sampler_kind parsed{};
        CHECK(parse_sampler(sampler_name(k), parsed));
        CHECK(parsed == k);
    }
    sampler_kind k{};
    CHECK_FALSE(parse_sampler("halton", k));
    CHECK(render_settings{}.sampler == sampler_kind::sobol); // the default, chosen in BENCHMARKS.md
}

TEST_CASE("bit reversal of 32 and 64 bits against a bit-by-bit loop") {
    auto reversed = [](uint64_t v, int bits) { // bit i moves to bits - 1 - i
        uint64_t r = 0;
        for (int i = 0; i < bits; ++i) r |= ((v >> i) & 1) << (bits - 1 - i);
        return r;
    };
    CHECK(detail::reverse_bits64(1) == uint64_t(1) << 63);
    CHECK(detail::reverse_bits32(0x80000000u) == 1u);
    pcg32 rng(7, 0);
    for (int i = 0; i < 1000; ++i) {
        const uint32_t a = rng.next_u32(), b = rng.next_u32();
        const uint64_t both = uint64_t(a) << 32 | b;
        CHECK(detail::reverse_bits32(a) == reversed(a, 32));
        CHECK(detail::reverse_bits32_by_shifts(a) == reversed(a, 32));
        CHECK(detail::reverse_bits64(both) == reversed(both, 64));
        // The two halves reversed in place of each other, as get2d uses it.
        CHECK(uint32_t(detail::reverse_bits64(both)) == detail::reverse_bits32(a));
    }
}

TEST_CASE("sample_lanes: every lane's numbers are its pixel_sampler's, bit for bit, for every sampler") {
    // Pixels near the origin (the Sobol index in 32 bits: the lanes' loops) and far out (the index
    // past 32 bits: high_index_hash, lane by lane), and batches of every size.
    for (sampler_kind kind : all_samplers)
        for (int spp : {1, 16, 1000})
            for (int far : {0, 1}) {
                const sampler_plan plan(kind, 11, spp);
                pcg32 pick(uint64_t(spp) * 3 + uint64_t(far), 5);
                for (int count = 1; count <= sample_lanes::capacity; ++count) {
                    int x[sample_lanes::capacity], y[sample_lanes::capacity], s[sample_lanes::capacity];
                    for (int k = 0; k < count; ++k) {
                        x[k] = int(pick.next_u32() % 500) + (far ? 60000 : 0);
                        y[k] = int(pick.next_u32() % 300) + (far ? 65000 : 0);
                        s[k] = int(pick.next_u32() % uint32_t(spp));
                    }
                    // Two sets of samplers from the same generators' seeds: one asked through the
                    // lanes, one alone.
                    std::vector<pcg32> streams, alone_streams;
                    for (int k = 0; k < count; ++k) {
                        streams.push_back(sample_rng(7, uint64_t(y[k]) * 1000 + uint64_t(x[k]), uint64_t(s[k])));
                        alone_streams.push_back(streams.back());
                    }
                    std::vector<pixel_sampler> lanes_of, alone;
                    lanes_of.reserve(size_t(count));
                    alone.reserve(size_t(count));
                    for (int k = 0; k < count; ++k) {
                        lanes_of.emplace_back(plan, x[k], y[k], s[k], streams[size_t(k)]);
                        alone.emplace_back(plan, x[k], y[k], s[k], alone_streams[size_t(k)]);
                    }
                    pixel_sampler* pointers[sample_lanes::capacity];
                    for (int k = 0; k < count; ++k) pointers[k] = &lanes_of[size_t(k)];
                    sample_lanes lanes(pointers, count);
                    float u1[sample_lanes::capacity], u2[sample_lanes::capacity], t[sample_lanes::capacity];
                    for (uint32_t d : {sample_dimension::camera_pixel, sample_dimension::camera_lens,
                                       sample_dimension::bounce(3) + sample_dimension::direction}) {
                        lanes.get2d(d, u1, u2);
                        for (int k = 0; k < count; ++k) {
                            const uniform2 p = alone[size_t(k)].get2d(d);
                            CHECK(u1[k] == p.u1);
                            CHECK(u2[k] == p.u2);
                        }
                    }
                    lanes.get1d(sample_dimension::camera_time, t);
                    for (int k = 0; k < count; ++k) CHECK(t[k] == alone[size_t(k)].get1d(sample_dimension::camera_time));
                }
            }
}

TEST_CASE("sample_lanes::prepare2d: each sampler then gives the pair it would have computed, and only for that dimension") {
    // The path tracer draws a batch's bounce directions ahead this way; the images stay the same
    // only if a held pair is exactly the computed one and other dimensions are untouched.
    const uint32_t held = sample_dimension::bounce(2) + sample_dimension::direction;
    const uint32_t others[] = {sample_dimension::bounce(1) + sample_dimension::direction,
                               sample_dimension::bounce(3) + sample_dimension::direction, sample_dimension::camera_lens};
    for (int spp : {1, 64}) {
        const sampler_plan plan(sampler_kind::sobol, 3, spp);
        const int count = sample_lanes::capacity;
        std::vector<pcg32> streams, alone_streams;
        for (int k = 0; k < count; ++k) {
            streams.push_back(sample_rng(5, uint64_t(k), uint64_t(k % spp)));
            alone_streams.push_back(streams.back());
        }
        std::vector<pixel_sampler> ahead, alone;
        ahead.reserve(size_t(count));
        alone.reserve(size_t(count));
        for (int k = 0; k < count; ++k) {
            ahead.emplace_back(plan, 3 * k, 2 * k + 1, k % spp, streams[size_t(k)]);
            alone.emplace_back(plan, 3 * k, 2 * k + 1, k % spp, alone_streams[size_t(k)]);
        }
        pixel_sampler* pointers[sample_lanes::capacity];
        for (int k = 0; k < count; ++k) pointers[k] = &ahead[size_t(k)];
        sample_lanes lanes(pointers, count);
        REQUIRE(lanes.vectorised()); // Sobol numbers of small pixels: the lanes' own loop
        lanes.prepare2d(held);
        for (int k = 0; k < count; ++k) {
            const uniform2 expected = alone[size_t(k)].get2d(held);
            for (int again = 0; again < 2; ++again) { // asked twice: the same pair both times
                const uniform2 got = ahead[size_t(k)].get2d(held);
                CHECK(got.u1 == expected.u1);
                CHECK(got.u2 == expected.u2);
            }
            for (uint32_t d : others) {
                const uniform2 a = ahead[size_t(k)].get2d(d), b = alone[size_t(k)].get2d(d);
                CHECK(a.u1 == b.u1);
                CHECK(a.u2 == b.u2);
            }
            // The sample's PCG stream is not touched by the numbers drawn ahead.
            CHECK(streams[size_t(k)].next_u32() == alone_streams[size_t(k)].next_u32());
        }
    }
    // Independent and stratified numbers are not drawn in lanes: the path tracer asks each
    // sampler in turn, in the order its path draws them.
    for (sampler_kind kind : {sampler_kind::independent, sampler_kind::stratified}) {
        const sampler_plan plan(kind, 3, 16);
        pcg32 rng = sample_rng(5, 0, 0);
        pixel_sampler one(plan, 0, 0, 0, rng);
        pixel_sampler* pointer = &one;
        CHECK_FALSE(sample_lanes(&pointer, 1).vectorised());
    }
}

TEST_CASE("Sobol: the first points of dimensions 0 and 1 from their definitions") {
    // Dimension 0: 1/2, 1/4, 3/4, 1/8, ... (van der Corput). Dimension 1, columns 1/2, 3/4, 5/8,
    // 15/16 (v_i = v_{i-1} xor v_{i-1}/2), index i the xor of the columns of its set bits:
    // 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
    const double d0[8] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
    const double d1[8] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
    for (uint32_t i = 0; i < 8; ++i) {
        CHECK(double(detail::sobol_dimension0(i)) * 0x1p-32 == d0[i]);
        CHECK(double(detail::sobol_dimension1(i)) * 0x1p-32 == d1[i]);
    }
    CHECK(detail::sobol_dimension1(8) == 0xf0000000u); // the fourth column, 15/16
    // The reversed form the sampler computes (a superset sum over bit positions) agrees with the
    // definition's column by column construction.
    pcg32 g(3);
    for (int i = 0; i < 2000; ++i) {
        const uint32_t index = g.next_u32();
        CHECK(detail::sobol_dimension1_reversed(index) == detail::reverse_bits32(detail::sobol_dimension1(index)));
    }
    for (uint32_t bit = 0; bit < 32; ++bit) // each column alone
        CHECK(detail::sobol_dimension1_reversed(1u << bit) == detail::reverse_bits32(detail::sobol_dimension1(1u << bit)));
    // Owen scrambling permutes: 256 distinct 8-bit prefixes stay 256 distinct ones.
    std::vector<int> seen(256, 0);
    for (uint32_t i = 0; i < 256; ++i) ++seen[detail::owen_scramble(i << 24, 0x1234567u) >> 24];
    CHECK(std::count(seen.begin(), seen.end(), 1) == 256);
}

TEST_CASE("sobol: every power-of-two prefix of a pixel's samples is a (0, m, 2)-net in each 2-D dimension") {
    // A (0, m, 2)-net in base 2: each of the 2^m boxes [i/2^a, (i+1)/2^a) x [j/2^(m-a), ...)
    // holds exactly one of the 2^m points, for every a = 0..m.
    const sampler_plan plan(sampler_kind::sobol, 11, 128);
    for (uint32_t dim : {sample_dimension::camera_pixel, sample_dimension::camera_lens,
                         sample_dimension::bounce(0) + sample_dimension::direction,
                         sample_dimension::bounce(5) + sample_dimension::light_position})
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) {
                std::vector<uniform2> p;
                for (int s = 0; s < 128; ++s) p.push_back(pair_of(plan, x + 37, y + 5, s, dim));
                for (int m = 0; m <= 7; ++m) {
                    const int n = 1 << m;
                    bool net = true;
                    for (int a = 0; a <= m; ++a) {
                        std::vector<int> box(size_t(n), 0);
                        for (int i = 0; i < n; ++i) {
                            const int bx = int(p[size_t(i)].u1 * float(1 << a)), by = int(p[size_t(i)].u2 * float(1 << (m - a)));
                            ++box[size_t(bx + (1 << a) * by)];
                        }
                        net = net && std::count(box.begin(), box.end(), 1) == n;
                    }
                    INFO("dimension " << dim << ", pixel " << x << "," << y << ", m " << m);
                    CHECK(net);
                }
            }
}

TEST_CASE("stratified: one sample per stratum in 1-D and per cell of the k x k grid in 2-D") {
    for (int n : {16, 10, 7}) {
        const sampler_plan plan(sampler_kind::stratified, 5, n);
        const int k = int(std::floor(std::sqrt(double(n))));
        for (int x = 0; x < 6; ++x) {
            std::vector<int> strata(size_t(n), 0), cells(size_t(k * k), 0);
            for (int s = 0; s < n; ++s) {
                ++strata[size_t(one_of(plan, x, 2, s, sample_dimension::bounce(1) + sample_dimension::lobe) * float(n))];
                const uniform2 u = pair_of(plan, x, 2, s, sample_dimension::camera_pixel);
                ++cells[size_t(int(u.u1 * float(k)) + k * int(u.u2 * float(k)))];
            }
            INFO("n " << n << ", pixel " << x);
            CHECK(std::count(strata.begin(), strata.end(), 1) == n);
            // Every cell of the grid holds one of the first k^2 strata; the n - k^2 samples past
            // them fall anywhere.
            CHECK(std::count(cells.begin(), cells.end(), 0) == 0);
            if (n == k * k) CHECK(std::count(cells.begin(), cells.end(), 1) == n);
        }
    }
}

TEST_CASE("discrepancy: 1-D dimensions below 1/N, Sobol's 2-D dimensions below (m + 1)/N") {
    // 1-D: with one point in each [i/N, (i+1)/N), the count in [0, a) is within 1 of N a.
    // 2-D, a (0, m, 2)-net of N = 2^m points: split [0, a) by the binary digits of a into at most
    // m dyadic columns of width 2^-i plus a last one narrower than 2^-m. Column i is cut in
    // y into elementary boxes 2^-i x 2^-(m-i) of one point each, counted exactly, and at most one
    // partial box (error at most 1 point); the last column lies inside one box 2^-m x 1 of one
    // point. So N D* <= m + 1. Independent points, for contrast, have N D* near sqrt(N).
    constexpr int n = 256, m = 8;
    for (sampler_kind k : {sampler_kind::stratified, sampler_kind::sobol}) {
        const sampler_plan plan(k, 3, n);
        for (uint32_t dim : {sample_dimension::camera_time, sample_dimension::bounce(0) + sample_dimension::light_choice,
                             sample_dimension::bounce(2) + sample_dimension::roulette}) {
            std::vector<float> v;
            for (int s = 0; s < n; ++s) v.push_back(one_of(plan, 9, 4, s, dim));
            INFO(std::string(sampler_name(k)) << ", dimension " << dim);
            CHECK(star_discrepancy_1d(v) <= 1.0 / n + 1e-6);
        }
    }
    const sampler_plan sobol(sampler_kind::sobol, 3, n);
    for (uint32_t dim : {sample_dimension::camera_pixel, sample_dimension::bounce(1) + sample_dimension::direction}) {
        std::vector<uniform2> p;
        for (int s = 0; s < n; ++s) p.push_back(pair_of(sobol, 9, 4, s, dim));
        const double d = star_discrepancy(p);
        INFO("dimension " << dim << ": N D* = " << d * n);
        CHECK(d <= double(m + 1) / n + 1e-6);
    }
    // The independent sampler does not meet the 2-D bound (a check that the bound has teeth).
    const sampler_plan independent(sampler_kind::independent, 3, n);
    std::vector<uniform2> p;
    for (int s = 0; s < n; ++s) p.push_back(pair_of(independent, 9, 4, s, sample_dimension::camera_pixel));
    CHECK(star_discrepancy(p) > double(m + 1) / n);
}

TEST_CASE("chi-square: every pair of consecutive numbers of a path is uniform over the square, for every sampler") {
    // 48 x 48 pixels x 16 samples = 36,864 points per pair, counted in an 8 x 8 grid (576
    // expected per cell). A pair of dimensions that correlate (the same scramble, a shared
    // stratum) piles points up along a curve and fails by far.
    constexpr int side = 48, spp = 16, grid = 8, bounces = 2;
    for (sampler_kind k : all_samplers) {
        const sampler_plan plan(k, 21, spp);
        std::vector<std::vector<double>> counts;
        long outside = 0; // numbers outside [0, 1)
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x)
                for (int s = 0; s < spp; ++s) {
                    const std::vector<float> v = path_numbers(plan, x, y, s, bounces);
                    if (counts.empty()) counts.assign(v.size() - 1, std::vector<double>(grid * grid, 0.0));
                    for (float u : v) outside += !(u >= 0.0f && u < 1.0f);
                    if (outside) continue;
                    for (size_t i = 0; i + 1 < v.size(); ++i)
                        ++counts[i][size_t(int(v[i] * grid) + grid * int(v[i + 1] * grid))];
                }
        CHECK(outside == 0);
        const double expected = double(side * side * spp) / (grid * grid);
        for (size_t i = 0; i < counts.size(); ++i) {
            const chi2::result r = chi2::test(counts[i], std::vector<double>(grid * grid, expected));
            INFO(std::string(sampler_name(k)) << ", numbers " << i << " and " << i + 1 << ": p = " << r.p_value);
            CHECK(r.p_value > 1e-4);
        }
    }
}

TEST_CASE("every sampler: identical images at 1, 2 and 3 threads, adaptive sampling included"
          * doctest::test_suite("threads")) {
    hittable_list world;
    world.add(std::make_shared<sphere>(point3(0, 0, -3), 1, std::make_shared<metal>(color(0.8, 0.6, 0.4), 0.3)));
    world.add(std::make_shared<sphere>(point3(1.5, 0, -3), 0.5, std::make_shared<dielectric>(1.5)));
    world.add(std::make_shared<sphere>(point3(0, -101, -3), 100, std::make_shared<lambertian>(color(0.5, 0.5, 0.5))));
    for (sampler_kind k : all_samplers)
        for (double adaptive : {0.0, 0.05}) {
            camera cam = test::test_camera(40, 24, 32, 8);
            cam.defocus_angle = 2;
            cam.focus_dist = 3;
            cam.settings.sampler = k;
            cam.settings.adaptive_error = adaptive;
            cam.settings.threads = 1;
            const render_result one = render(cam, world);
            for (int threads : {2, 3}) {
                cam.settings.threads = threads;
                const render_result other = render(cam, world);
                INFO(std::string(sampler_name(k)) << ", adaptive " << adaptive << ", threads " << threads);
                CHECK(test::same_bits(one.img, other.img));
                CHECK(one.stats.samples == other.stats.samples);
            }
        }
}

TEST_CASE("every sampler is unbiased on the cover scene, and Sobol and stratified beat independent at equal spp" * doctest::test_suite("heavy")) {
    // The book's cover at 400x225, 4 samples per pixel, against the book's own 6144-spp render.
    // The image mean is an integral over the film: a sample is at most ~1.1 (the sky), so its
    // standard deviation is below 0.6 and the mean of 360,000 samples is within 4.5 standard
    // errors = 0.0045 of the truth. Per pixel, stratified numbers lower the error.
    scene_description scene = load_scene(std::string(RTWEEKEND_TEST_DATA) + "/rtiow_cover.txt");
    const loaded_image ref = read_image(std::string(RTWEEKEND_TEST_DATA) + "/rtiow_cover_400x225_ref.pfm");
    REQUIRE(ref.pixels.width() == 400);
    camera cam = scene.cam;
    cam.image_width = 400;
    cam.samples_per_pixel = 4;
    cam.max_depth = 50;
    cam.settings.quiet = true;
    auto mean_of = [](const image& img) {
        double s = 0;
        for (float v : img.data()) s += v;
        return s / double(img.data().size());
    };
    const double ref_mean = mean_of(ref.pixels);
    double mse[3] = {0, 0, 0};
    for (sampler_kind k : all_samplers) {
        cam.settings.sampler = k;
        const image img = test::render_checked(cam, scene.world).img;
        REQUIRE(img.height() == ref.pixels.height());
        INFO(std::string(sampler_name(k)) << ": mean " << mean_of(img) << ", reference " << ref_mean);
        CHECK(std::fabs(mean_of(img) - ref_mean) < 0.0045);
        double e = 0;
        for (size_t i = 0; i < img.data().size(); ++i) {
            const double d = double(img.data()[i]) - double(ref.pixels.data()[i]);
            e += d * d;
        }
        mse[int(k)] = e / double(img.data().size());
    }
    INFO("MSE independent " << mse[0] << ", stratified " << mse[1] << ", sobol " << mse[2]);
    CHECK(mse[1] < 0.9 * mse[0]);
    CHECK(mse[2] < 0.8 * mse[0]);
}

} // namespace test_sampler
