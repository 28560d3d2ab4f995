// Fixed-point sample sums (rtweekend/render/fixed_point.h) and what they buy the scheduler: sums
// that do not depend on the order or grouping of a pixel's samples, so that renders of parts of
// the sample range, of the image's tiles, or of adaptive sampling's rounds split over processes
// add up to the lone render exactly; and clamping, counted, instead of overflow.

#include <rtweekend/render/fixed_point.h>
#include <rtweekend/render/scheduler.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <limits>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace test_fixed_point {

using namespace rt;

namespace {

constexpr int64_t int64_max = std::numeric_limits<int64_t>::max();

int64_t fixed(float v, int64_t limit = int64_max) {
    bool clamped = false;
    int64_t n = to_fixed(v, limit, clamped);
    CHECK_FALSE(clamped);
    return n;
}

// Sample values whose floating-point sums depend on the order of the additions: a large value
// every third sample, and small ones of many magnitudes.
float awkward(int x, int y, int s) {
    return float(1.0 / (1 + s * 7 + x)) + float(y) * 1e-7f + (s % 3 == 0 ? 1e6f : 0.0f) + (s % 5 == 1 ? 3e-12f : 0.0f);
}

render_settings quiet_settings(int spp, int threads) {
    render_settings s;
    s.samples_per_pixel = spp;
    s.threads = threads;
    s.quiet = true;
    return s;
}

template <class Value>
render_result render_values(int w, int h, const render_settings& s, Value value) {
    return render_samples(w, h, s, [&](int x, int y, int sample, pcg32&, uint64_t& rays) {
        ++rays;
        const float v = value(x, y, sample);
        return vec3f(v, 0.5f * v, float(sample));
    });
}

} // namespace

TEST_CASE("fixed point: a sample of at least 2^-9 converts exactly, smaller ones round to the nearest 2^-32") {
    // Exactly: n * 2^-32 gives the float back (float -> double and the power of two are exact).
    for (float v : {1.0f, 0.5f, 1.0f / 3.0f, 0x1p-9f, 0.7f, 15.0f, 255.0f, 1e6f, 123456.78f, -0.25f, -1e3f}) {
        CAPTURE(v);
        CHECK(double(fixed(v)) * 0x1p-32 == double(v));
    }
    CHECK(fixed(1.0f) == (int64_t(1) << 32));
    CHECK(fixed(0.0f) == 0);
    CHECK(fixed(-0.0f) == 0);
    // Below 2^-9 the float has bits finer than the unit: 2^-40 is 1/256 of a unit (0), three
    // quarters of a unit is 1, a half rounds up (towards +infinity), a negative half to 0.
    CHECK(fixed(0x1p-40f) == 0);
    CHECK(fixed(0x3p-34f) == 1);
    CHECK(fixed(0x1p-33f) == 1);
    CHECK(fixed(0x3p-33f) == 2); // 1.5 units
    CHECK(fixed(-0x1p-33f) == 0);
    CHECK(fixed(-0x3p-34f) == -1);
    // The error of a small sample is at most half a unit.
    for (float v : {1e-5f, 3.3e-6f, 7.77e-4f, 1.1e-9f}) {
        CAPTURE(v);
        CHECK(std::fabs(double(fixed(v)) - double(v) * 0x1p32) <= 0.5);
    }
}

TEST_CASE("fixed point: a sample beyond the per-sample limit is clamped and flagged, never overflows") {
    // At 4 samples per pixel a sample may be at most (2^63 - 1) / 4 units, just under 2^61:
    // 2^28 of radiance (2^60 units) fits, 2^30 (2^62 units) does not.
    const int64_t limit = sample_limit(4);
    CHECK(limit == int64_max / 4);
    CHECK(fixed(0x1p28f, limit) == (int64_t(1) << 60));
    auto clamped_value = [&](float v, int64_t expected) {
        bool clamped = false;
        CHECK(to_fixed(v, limit, clamped) == expected);
        CHECK(clamped);
    };
    clamped_value(0x1p30f, limit);
    clamped_value(-0x1p30f, -limit);
    clamped_value(3e38f, limit);
    clamped_value(std::numeric_limits<float>::infinity(), limit);
    clamped_value(-std::numeric_limits<float>::infinity(), -limit);
    clamped_value(std::numeric_limits<float>::quiet_NaN(), 0);
    // Four samples at the limit, in either sign, still fit in an int64.
    CHECK(limit * 4 <= int64_max);
    CHECK(-limit * 4 >= std::numeric_limits<int64_t>::min());
    // With one sample per pixel the whole int64 range is one sample's.
    CHECK(sample_limit(1) == int64_max);
    CHECK(fixed(0x1p30f, sample_limit(1)) == (int64_t(1) << 62));
}

TEST_CASE("fixed point: add_fixed3 adds exactly what to_fixed gives each channel, clamps included") {
    // add_fixed3 converts three channels side by side where it can (AVX-512DQ), one by one
    // elsewhere; either way the sums and the clamp flag must be to_fixed's. Values over every
    // size from 2^-40 to 2^40 of radiance (past 2^52 units, 2^20 of radiance, rounding stops; past
    // the limit, clamping starts), both signs, halves of a unit (2^-33), zeros, NaN and infinities,
    // at 1, 10 and 2^24 samples per pixel (limits of 2^63, 2^59.7 and 2^39 units).
    std::mt19937 gen(41);
    std::uniform_real_distribution<float> U(-1, 1), E(-40, 40);
    const float special[] = {0.0f, -0.0f, 0x1p-33f, -0x1p-33f, 3 * 0x1p-33f, 0x1p20f, -0x1p20f, std::nextafter(0x1p20f, 0.0f),
                             0x1p31f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity(), 0x1p7f, 0x1p8f};
    const int n_special = int(sizeof special / sizeof special[0]);
    for (int64_t spp : {int64_t(1), int64_t(10), int64_t(1) << 24}) {
        const int64_t limit = sample_limit(spp);
        for (int i = 0; i < 30000; ++i) {
            float c[3];
            for (float& v : c) v = U(gen) * std::exp2(E(gen));
            if (i < n_special * n_special) c[i % 3] = special[i % n_special], c[(i + 1) % 3] = special[i / n_special];
            // Earlier samples' sums to add to; at 1 spp the sample is the pixel's only one, and a sum
            // that starts elsewhere than 0 could leave the int64 range (the limit's contract).
            const int64_t start = spp == 1 ? 0 : int64_t(i);
            int64_t sum[3] = {start, -start, spp == 1 ? 0 : 7}, want[3] = {sum[0], sum[1], sum[2]};
            bool clamped = false, want_clamped = false;
            add_fixed3(c[0], c[1], c[2], limit, sum, clamped);
            for (int k = 0; k < 3; ++k) want[k] += to_fixed(c[k], limit, want_clamped);
            CAPTURE(spp);
            CAPTURE(i);
            CHECK(sum[0] == want[0]);
            CHECK(sum[1] == want[1]);
            CHECK(sum[2] == want[2]);
            CHECK(clamped == want_clamped);
        }
    }
}

TEST_CASE("fixed point: add_fixed refuses a sum outside the int64 range") {
    int64_t out = 0;
    CHECK(add_fixed(int64_max - 5, 5, out));
    CHECK(out == int64_max);
    CHECK_FALSE(add_fixed(int64_max - 5, 6, out));
    CHECK_FALSE(add_fixed(std::numeric_limits<int64_t>::min(), -1, out));
    CHECK(add_fixed(-7, 3, out));
    CHECK(out == -4);
}

TEST_CASE("fixed point: the mean is the sum in double over n, rounded once to float") {
    CHECK(fixed_mean(int64_t(3) << 32, 2) == 1.5f);
    CHECK(fixed_mean(int64_t(1) << 32, 3) == static_cast<float>(1.0 / 3.0));
    CHECK(fixed_mean(-(int64_t(5) << 30), 1) == -1.25f);
    CHECK(fixed_mean(12345, 0) == 0.0f);
    pixel_sums s(2, 1);
    s.rgb = {int64_t(6) << 32, int64_t(3) << 32, 0, int64_t(1) << 31, 0, -(int64_t(1) << 32)};
    s.counts = {3, 1};
    image img = mean_image(s);
    CHECK(img.data() == std::vector<float>{2.0f, 1.0f, 0.0f, 0.5f, 0.0f, -1.0f});
}

TEST_CASE("scheduler: a pixel's value is the fixed-point mean of its samples, the same for any thread count") {
    const int w = 20, h = 9, spp = 13;
    render_result one = render_values(w, h, quiet_settings(spp, 1), awkward);
    render_result three = render_values(w, h, quiet_settings(spp, 3), awkward);
    CHECK(test::same_bits(one.img, three.img));
    CHECK(one.stats.saturated_samples == 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Each sample rounded on its own (llround: the values here are positive, where its
            // halves-away-from-zero agree with halves up), the integers added in any order.
            int64_t sum = 0;
            for (int s = spp - 1; s >= 0; --s) sum += std::llround(std::ldexp(double(awkward(x, y, s)), 32));
            const float expected = static_cast<float>(std::ldexp(double(sum), -32) / spp);
            CHECK(one.img.data()[(size_t(y) * w + x) * 3] == expected);
        }
}

TEST_CASE("scheduler: renders of disjoint sample ranges add up to the whole render's sums and image") {
    const int w = 37, h = 18, spp = 13; // tiles that do not fill the image, a prime spp
    render_settings whole = quiet_settings(spp, 2);
    whole.keep_sums = true;
    render_result all = render_values(w, h, whole, awkward);
    REQUIRE(all.sums.rgb.size() == size_t(w) * h * 3);
    CHECK(test::same_bits(all.img, mean_image(all.sums)));

    // [0, 5), [5, 6), [6, 13), added in reverse order.
    pixel_sums added(w, h);
    std::vector<std::pair<int, int>> ranges = {{6, 13}, {5, 6}, {0, 5}};
    uint64_t samples = 0;
    for (auto [first, end] : ranges) {
        render_settings part = whole;
        part.first_sample = first;
        part.end_sample = end;
        part.threads = 1 + first % 3;
        render_result r = render_values(w, h, part, awkward);
        CHECK(r.stats.samples == uint64_t(w) * h * uint64_t(end - first));
        CHECK(r.stats.first_sample == first);
        CHECK(r.stats.end_sample == end);
        CHECK_FALSE(r.stats.interrupted);
        samples += r.stats.samples;
        for (size_t i = 0; i < added.rgb.size(); ++i) added.rgb[i] += r.sums.rgb[i];
        for (size_t i = 0; i < added.counts.size(); ++i) {
            CHECK(r.sums.counts[i] == end - first);
            added.counts[i] += r.sums.counts[i];
        }
    }
    CHECK(samples == all.stats.samples);
    CHECK(added.rgb == all.sums.rgb);
    CHECK(added.counts == all.sums.counts);
    CHECK(test::same_bits(mean_image(added), all.img));
    // A render of part of the range is the mean of its own samples, not the whole's.
    render_settings tail = whole;
    tail.first_sample = 1;
    render_result part = render_values(w, h, tail, awkward);
    CHECK_FALSE(test::same_bits(part.img, all.img));
}

TEST_CASE("scheduler: a batched sample function takes every sample once and makes the per-sample function's image") {
    const int w = 37, h = 18, spp = 13;
    for (int adaptive : {0, 1})
        for (int threads : {1, 3}) {
            render_settings st = quiet_settings(spp, threads);
            if (adaptive) {
                st.adaptive_error = 0.05;
                st.adaptive_min_samples = 4;
            }
            // Samples whose values a pixel's mean shows, with some noise for adaptive sampling.
            auto value = [](int x, int y, int sample) { return awkward(x, y, sample) * 1e-6f + float((sample * 7 + x) % 5); };
            const render_result single = render_values(w, h, st, value);
            std::vector<std::atomic<int>> taken(size_t(w) * h * spp);
            std::atomic<int> batches{0}, largest{0};
            const render_result batched = render_samples(w, h, st, [&](sample_batch& b) {
                ++batches;
                largest = std::max(largest.load(), b.count);
                for (int k = 0; k < b.count; ++k) {
                    CHECK(b.rays[k] == 0);
                    ++taken[(size_t(b.y[k]) * w + size_t(b.x[k])) * spp + size_t(b.s[k])];
                    b.rays[k] = 1;
                    const float v = value(b.x[k], b.y[k], b.s[k]);
                    b.color[k] = vec3f(v, 0.5f * v, float(b.s[k]));
                }
            });
            CHECK(test::same_bits(single.img, batched.img));
            CHECK(single.stats.samples == batched.stats.samples);
            CHECK(batched.stats.rays == batched.stats.samples);
            uint64_t once = 0, more = 0;
            for (const auto& t : taken) (t == 1 ? once : more) += t > 0;
            CHECK(once == batched.stats.samples);
            CHECK(more == 0);
            // Batches of several pixels' samples: far fewer calls than samples.
            CHECK(largest == sample_batch::capacity);
            CHECK(uint64_t(batches) * 4 < batched.stats.samples);
        }
}

TEST_CASE("scheduler: the sample range is checked") {
    render_settings s = quiet_settings(8, 1);
    auto fails = [&](int first, int end) {
        render_settings bad = s;
        bad.first_sample = first;
        bad.end_sample = end;
        CHECK_THROWS_AS(render_values(4, 4, bad, awkward), scene_error);
    };
    fails(-1, 4);
    fails(4, 4);
    fails(5, 3);
    fails(0, 9);
    fails(8, 0); // end 0 means spp: [8, 8) is empty
    render_settings adaptive = s;
    adaptive.adaptive_error = 0.1;
    adaptive.adaptive_min_samples = 4;
    adaptive.first_sample = 2;
    CHECK_THROWS_AS(render_values(4, 4, adaptive, awkward), scene_error);
}

TEST_CASE("scheduler: samples beyond the fixed-point range are clamped, counted and reported") {
    const int w = 3, h = 2, spp = 4;
    render_result r = render_samples(w, h, quiet_settings(spp, 1), [](int x, int y, int s, pcg32&, uint64_t&) {
        // Pixel (1, 0): every sample far beyond the limit in red, one sample so in green (negative).
        if (x == 1 && y == 0) return vec3f(1e30f, s == 2 ? -1e30f : 1.0f, 2.0f);
        return vec3f(1.0f, 1.0f, 1.0f);
    });
    CHECK(r.stats.saturated_samples == 4); // a sample is counted once, however many channels
    CHECK(r.stats.nonfinite_samples == 0);
    const int64_t limit = sample_limit(spp);
    const color c = r.img.pixel(1, 0);
    CHECK(c.x() == double(fixed_mean(4 * limit, 4)));
    CHECK(c.x() == doctest::Approx(std::ldexp(1.0, 31) / spp));
    CHECK(c.y() == double(fixed_mean(3 * (int64_t(1) << 32) - limit, 4)));
    CHECK(c.z() == 2.0);
    CHECK(r.img.pixel(0, 0).x() == 1.0);
    const std::string line = stats_line(r.stats);
    CHECK(line.find(", 4 samples beyond the fixed-point range (clamped)") != std::string::npos);
    // None: not mentioned.
    render_result calm = render_values(w, h, quiet_settings(spp, 1), awkward);
    CHECK(stats_line(calm.stats).find("fixed-point") == std::string::npos);
}

namespace {

// An in-process stand-in for the processes of a shared render: `ranks` threads each render their
// part through render_samples; combine_owned() meets all of them (a barrier), ORs their words and
// hands every one the result, as MPI_Allreduce with MPI_BOR would.
class thread_group {
  public:
    explicit thread_group(int ranks) : ranks_(ranks) {}

    void combine(uint64_t* words, size_t count) {
        std::unique_lock<std::mutex> lock(mutex_);
        const uint64_t generation = generation_;
        if (arrived_ == 0) combined_.assign(count, 0);
        CHECK(combined_.size() == count);
        for (size_t i = 0; i < count; ++i) combined_[i] |= words[i];
        if (++arrived_ == ranks_) {
            result_ = combined_;
            arrived_ = 0;
            ++generation_;
            changed_.notify_all();
        } else {
            changed_.wait(lock, [&] { return generation_ != generation; });
        }
        std::copy(result_.begin(), result_.end(), words);
    }

  private:
    int ranks_, arrived_ = 0;
    uint64_t generation_ = 0;
    std::vector<uint64_t> combined_, result_;
    std::mutex mutex_;
    std::condition_variable changed_;
};

class thread_share : public render_share {
  public:
    thread_share(thread_group& group, int rank, int ranks, bool by_tiles)
        : render_share(rank, ranks, by_tiles), group_(group) {}
    void ready() const override {}
    void round_done(std::exception_ptr failure) const override {
        if (failure) std::rethrow_exception(failure);
    }
    void combine_owned(uint64_t* words, size_t count) const override { group_.combine(words, count); }

  private:
    thread_group& group_;
};

// A noisy synthetic render for adaptive sampling: the noise grows to the right, so pixels take
// different counts and the rounds differ.
vec3f noisy(int x, int y, int, pcg32& rng, uint64_t& rays) {
    rays += 1 + uint64_t(x % 3);
    const float u = rng.next_float();
    const float v = 0.2f + 0.05f * float(y) + float(x) * 0.08f * (u - 0.5f);
    return vec3f(v, v * u, 0.3f);
}

} // namespace

TEST_CASE("scheduler: a render shared by tiles adds up to the lone render, each pixel from one process") {
    const int w = 50, h = 35, spp = 3;
    render_settings lone = quiet_settings(spp, 2);
    lone.keep_sums = true;
    render_result all = render_values(w, h, lone, awkward);
    for (int ranks : {2, 3, 7}) {
        CAPTURE(ranks);
        thread_group group(ranks);
        pixel_sums added(w, h);
        uint64_t samples = 0;
        for (int rank = 0; rank < ranks; ++rank) {
            thread_share share(group, rank, ranks, true);
            render_settings s = lone;
            s.share = &share;
            render_result r = render_values(w, h, s, awkward);
            samples += r.stats.samples;
            for (size_t i = 0; i < added.rgb.size(); ++i) added.rgb[i] += r.sums.rgb[i];
            for (size_t i = 0; i < added.counts.size(); ++i) added.counts[i] += r.sums.counts[i];
        }
        CHECK(samples == all.stats.samples);
        // Every pixel was rendered by exactly one process: all of its samples, once.
        CHECK(std::all_of(added.counts.begin(), added.counts.end(), [&](int32_t n) { return n == spp; }));
        CHECK(added.rgb == all.sums.rgb);
        CHECK(test::same_bits(mean_image(added), all.img));
    }
}

TEST_CASE("scheduler: adaptive sampling shared by processes ends every round with the lone render's state") {
    const int w = 24, h = 12, spp = 64;
    render_settings lone = quiet_settings(spp, 2);
    lone.adaptive_error = 0.05;
    lone.adaptive_min_samples = 4;
    render_result alone = render_samples(w, h, lone, noisy);
    REQUIRE(alone.stats.samples_saved > 0); // the plan did vary the counts
    REQUIRE(alone.stats.max_pixel_samples > alone.stats.min_pixel_samples);
    for (int ranks : {2, 3}) {
        CAPTURE(ranks);
        thread_group group(ranks);
        std::vector<render_result> results(static_cast<size_t>(ranks));
        std::vector<std::thread> processes;
        for (int rank = 0; rank < ranks; ++rank)
            processes.emplace_back([&, rank] {
                thread_share share(group, rank, ranks, false);
                render_settings s = lone;
                s.threads = 1;
                s.share = &share;
                results[size_t(rank)] = render_samples(w, h, s, noisy);
            });
        for (std::thread& t : processes) t.join();
        uint64_t samples = 0, rays = 0;
        for (const render_result& r : results) {
            CHECK(test::same_bits(r.img, alone.img)); // every process holds the whole image
            samples += r.stats.samples;
            rays += r.stats.rays;
        }
        CHECK(samples == alone.stats.samples);
        CHECK(rays == alone.stats.rays);
        // The work was shared: no process took all of it.
        for (const render_result& r : results) CHECK(r.stats.samples < alone.stats.samples);
    }
}

} // namespace test_fixed_point
