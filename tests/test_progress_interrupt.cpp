// Progress lines and interrupted renders (render/scheduler.h): the progress text for hand-chosen
// inputs, and renders stopped through render_settings::stop from inside a synthetic sample
// function. The sample function returns (s, x, 1) for sample s of pixel (x, y): a pixel that took
// samples 0..n-1 averages exactly ((n-1)/2, x, 1), so each pixel's mean says how many samples it
// took. One thread makes the order of pixels, and so the point of the stop, deterministic: tiles
// in order, each pixel of a tile row by row, a whole pass over the image before the next.

#include <rtweekend/camera.h>
#include <rtweekend/render/scheduler.h>
#include <rtweekend/hittable_list.h>

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>

namespace test_progress_interrupt {

using namespace rt;

TEST_CASE("format_duration: m:ss below an hour, h:mm:ss from there, rounded down") {
    CHECK(format_duration(0) == "0:00");
    CHECK(format_duration(59.9) == "0:59");
    CHECK(format_duration(61) == "1:01");
    CHECK(format_duration(3599) == "59:59");
    CHECK(format_duration(3600) == "1:00:00");
    CHECK(format_duration(3725) == "1:02:05");
    CHECK(format_duration(-1) == "0:00");
}

TEST_CASE("format_progress: percentage, elapsed and the time left at the pace so far") {
    CHECK(format_progress(0, 100, 3) == "  0%  elapsed 0:03  left ?");         // nothing done: unknown
    CHECK(format_progress(42, 100, 12) == " 42%  elapsed 0:12  left 0:16");    // 12 * 58 / 42 = 16.6
    CHECK(format_progress(1, 4, 30) == " 25%  elapsed 0:30  left 1:30");
    CHECK(format_progress(999, 1000, 3600) == " 99%  elapsed 1:00:00  left 0:03"); // 3.6 s
    CHECK(format_progress(100, 100, 75) == "100%  elapsed 1:15  left 0:00");
}

namespace {

constexpr int W = 32, H = 16, pixels = W * H; // two 16x16 tiles side by side

render_settings one_thread(int spp) {
    render_settings s;
    s.samples_per_pixel = spp;
    s.threads = 1;
    s.quiet = true;
    return s;
}

// Renders with the stop flag raised at the `stop_at`-th sample (1-based; 0: never). The count is
// atomic: on several threads every worker adds to it.
render_result render_stopping_at(render_settings s, uint64_t stop_at) {
    std::atomic<bool> stop{false};
    s.stop = &stop;
    std::atomic<uint64_t> calls{0};
    return render_samples(W, H, s, [&](int x, int, int sample, pcg32&, uint64_t& rays) {
        ++rays;
        if (++calls == stop_at) stop = true;
        return vec3f(float(sample), float(x), 1.0f);
    });
}

// Exact equality of colours (vec3 has no operator==): the expected pixels are exact.
bool same(const color& a, const color& b) { return a.x() == b.x() && a.y() == b.y() && a.z() == b.z(); }

// Pixel k of the stopped renders below, in the order one thread takes them: tile 0 row by row.
int tile0_x(int k) { return k % 16; }
int tile0_y(int k) { return k / 16; }

} // namespace

TEST_CASE("render_samples: a stop during a pass leaves each pixel the mean of the samples it took"
          * doctest::test_suite("threads")) {
    // Passes of 1, 1, 2, 4 samples (spp 8): 512 + 512 samples, then samples 2 and 3 of each
    // pixel. The flag rises at the first sample of pixel 100 in the third pass (1024 + 2 * 100 + 1):
    // that pixel finishes its two samples, and the render stops before pixel 101.
    render_result r = render_stopping_at(one_thread(8), 1024 + 2 * 100 + 1);
    CHECK(r.stats.interrupted);
    CHECK(r.stats.samples == 1024 + 2 * 101);
    CHECK(r.stats.rays == 1024 + 2 * 101);
    CHECK(r.stats.min_pixel_samples == 2);
    CHECK(r.stats.max_pixel_samples == 4);
    CHECK(r.stats.pixels_without_samples == 0);
    CHECK(r.stats.samples_saved == 0);
    CHECK(r.stats.completed == doctest::Approx(1226.0 / 4096.0));
    CHECK(r.stats.mean_pixel_samples() == doctest::Approx(1226.0 / 512.0));
    int four = 0, two = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            color c = r.img.pixel(x, y);
            bool done = x < 16 && y * 16 + x <= 100; // pixels 0..100 of tile 0 took samples 0..3
            CHECK(c.x() == (done ? 1.5 : 0.5));      // mean of 0..3, or of 0..1
            CHECK(c.y() == x);
            CHECK(c.z() == 1.0);
            (done ? four : two) += 1;
        }
    CHECK(four == 101);
    CHECK(two == pixels - 101);
    CHECK(r.img.pixel(tile0_x(100), tile0_y(100)).x() == 1.5);
    CHECK(r.img.pixel(tile0_x(101), tile0_y(101)).x() == 0.5);
}

TEST_CASE("render_samples: a stop in the first pass leaves the pixels not reached black, and counted"
          * doctest::test_suite("threads")) {
    render_result r = render_stopping_at(one_thread(8), 100); // pixels 0..99 of tile 0 took sample 0
    CHECK(r.stats.interrupted);
    CHECK(r.stats.samples == 100);
    CHECK(r.stats.min_pixel_samples == 0);
    CHECK(r.stats.max_pixel_samples == 1);
    CHECK(r.stats.pixels_without_samples == uint64_t(pixels - 100));
    for (int k = 0; k < 100; ++k) CHECK(same(r.img.pixel(tile0_x(k), tile0_y(k)), color(0, tile0_x(k), 1)));
    CHECK(same(r.img.pixel(tile0_x(100), tile0_y(100)), color(0, 0, 0)));
    CHECK(same(r.img.pixel(31, 15), color(0, 0, 0)));
}

TEST_CASE("render_samples: a flag raised before the render takes no sample, one never raised changes nothing"
          * doctest::test_suite("threads")) {
    render_settings s = one_thread(8);
    std::atomic<bool> stop{true};
    s.stop = &stop;
    render_result none = render_samples(W, H, s, [](int, int, int, pcg32&, uint64_t&) { return vec3f(1, 1, 1); });
    CHECK(none.stats.interrupted);
    CHECK(none.stats.samples == 0);
    CHECK(none.stats.pixels_without_samples == uint64_t(pixels));
    CHECK(same(none.img.pixel(5, 5), color(0, 0, 0)));

    // Uninterrupted: the mean of samples 0..7 is 3.5 everywhere, at 1 and 2 threads, flag or not.
    render_result all = render_stopping_at(one_thread(8), 0);
    render_settings two = one_thread(8);
    two.threads = 2;
    render_result all2 = render_stopping_at(two, 0);
    CHECK_FALSE(all.stats.interrupted);
    CHECK(all.stats.samples == uint64_t(pixels) * 8);
    CHECK(all.stats.min_pixel_samples == 8);
    CHECK(all.stats.max_pixel_samples == 8);
    CHECK(all.stats.completed == 1.0);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) CHECK(same(all.img.pixel(x, y), color(3.5, x, 1)));
    CHECK(all.img.data() == all2.img.data());

    // A flag raised by the very last sample: the work is complete, so the render is not interrupted.
    render_result last = render_stopping_at(one_thread(8), uint64_t(pixels) * 8);
    CHECK_FALSE(last.stats.interrupted);
    CHECK(last.img.data() == all.img.data());
}

TEST_CASE("render_samples: the passes give each pixel the sum one pass would" * doctest::test_suite("threads")) {
    // Values whose floating-point sums depend on the order of additions: the image must be the
    // mean of the samples' fixed-point values (render/fixed_point.h), which no order changes:
    // each sample rounded to units of 2^-32 on its own, the integers added.
    render_settings s = one_thread(13);
    s.threads = 2;
    auto value = [](int x, int y, int sample) {
        return float(1.0 / (1 + sample * 7 + x)) + float(y) * 1e-7f + (sample % 3 == 0 ? 1e6f : 0.0f);
    };
    render_result r = render_samples(W, H, s, [&](int x, int y, int sample, pcg32&, uint64_t&) {
        float v = value(x, y, sample);
        return vec3f(v, v, v);
    });
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int64_t sum = 0;
            for (int sample = 0; sample < 13; ++sample) sum += std::llround(std::ldexp(double(value(x, y, sample)), 32));
            CHECK(r.img.data()[(size_t(y) * W + x) * 3] == static_cast<float>(std::ldexp(double(sum), -32) / 13));
        }
}

TEST_CASE("render_samples, adaptive: a stop in round 0 keeps the pixels done, black elsewhere"
          * doctest::test_suite("threads")) {
    render_settings s = one_thread(64);
    s.adaptive_error = 0.01;
    s.adaptive_min_samples = 4;
    // Round 0 takes samples 0..3 of each pixel in pixel order (y * W + x); the flag rises at the
    // first sample of pixel 10, which finishes its four.
    render_result r = render_stopping_at(s, 4 * 10 + 1);
    CHECK(r.stats.interrupted);
    CHECK(r.stats.samples == 44);
    CHECK(r.stats.min_pixel_samples == 0);
    CHECK(r.stats.max_pixel_samples == 4);
    CHECK(r.stats.pixels_without_samples == uint64_t(pixels - 11));
    CHECK(r.stats.samples_saved == 0);
    for (int x = 0; x <= 10; ++x) CHECK(same(r.img.pixel(x, 0), color(1.5, x, 1)));
    CHECK(same(r.img.pixel(11, 0), color(0, 0, 0)));
    CHECK(same(r.img.pixel(0, 1), color(0, 0, 0)));
}

TEST_CASE("render_samples: a stop raised by another thread during a two-thread render leaves a consistent image"
          * doctest::test_suite("threads")) {
    // As Ctrl-C does: the flag is raised from outside the workers, here by a thread that waits
    // until 3000 of the 32768 samples (spp 64) are taken. A worker that takes a sample past the
    // 3000th waits for the flag, so that a raiser the system keeps waiting (ctest runs tests side
    // by side) cannot let the render finish first. Where each worker is then is up to the
    // scheduler; what must hold: a pixel holds the mean of samples 0..n-1, so its red channel is
    // (n - 1) / 2, with n a pass boundary (0, 1, 2, 4, ... 64), and the counts add up.
    render_settings s = one_thread(64);
    s.threads = 2;
    std::atomic<bool> stop{false};
    s.stop = &stop;
    std::atomic<uint64_t> taken{0};
    std::thread raiser([&] {
        while (taken.load() < 3000) std::this_thread::sleep_for(std::chrono::microseconds(50));
        stop = true;
    });
    render_result r = render_samples(W, H, s, [&](int x, int, int sample, pcg32&, uint64_t& rays) {
        ++rays;
        if (++taken > 3000)
            while (!stop.load()) std::this_thread::yield();
        return vec3f(float(sample), float(x), 1.0f);
    });
    raiser.join();
    CHECK(r.stats.interrupted);
    CHECK(r.stats.threads == 2);
    CHECK(r.stats.samples == taken.load());
    CHECK(r.stats.rays == r.stats.samples);
    CHECK(r.stats.samples >= 3000);
    CHECK(r.stats.samples < uint64_t(pixels) * 64);
    uint64_t sum = 0, black = 0;
    int fewest = 64, most = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const color c = r.img.pixel(x, y);
            const int n = c.z() == 0 ? 0 : int(2 * c.x() + 1); // (n - 1) / 2 is exact in float
            CAPTURE(x);
            CAPTURE(y);
            CHECK((n == 0 || (n & (n - 1)) == 0)); // a pass boundary
            CHECK(c.x() == (n == 0 ? 0.0 : (n - 1) / 2.0));
            CHECK(c.y() == (n == 0 ? 0 : x));
            sum += uint64_t(n);
            black += n == 0;
            fewest = std::min(fewest, n);
            most = std::max(most, n);
        }
    CHECK(sum == r.stats.samples);
    CHECK(black == r.stats.pixels_without_samples);
    CHECK(fewest == r.stats.min_pixel_samples);
    CHECK(most == r.stats.max_pixel_samples);
    CHECK(most <= 2 * std::max(fewest, 1)); // the counts differ by the interrupted pass at most
}

TEST_CASE("render_samples, batched: a stop leaves every pixel the whole of the passes it took part in"
          * doctest::test_suite("threads")) {
    // Batches hold several pixels' samples (a pass of 2 samples: capacity / 2 pixels a batch, 16
    // for a batch of 32); the flag rises during the batch that holds pixel 100 of tile 0 in the
    // third pass (samples 2 and 3). That batch finishes whole (pixels 96..111 for 16 a batch), and
    // the render stops before the next pixel: on one thread pixels 0..last of tile 0 took four
    // samples, every other pixel two.
    const int pixels_per_batch = sample_batch::capacity / 2;
    const int last = (100 / pixels_per_batch + 1) * pixels_per_batch - 1;
    for (int threads : {1, 2}) {
        render_settings s = one_thread(8);
        s.threads = threads;
        std::atomic<bool> stop{false};
        s.stop = &stop;
        std::atomic<uint64_t> batches{0};
        render_result r = render_samples(W, H, s, [&](sample_batch& b) {
            for (int k = 0; k < b.count; ++k) {
                b.rays[k] = 1;
                b.color[k] = vec3f(float(b.s[k]), float(b.x[k]), 1.0f);
                if (b.s[k] == 2 && b.x[k] == tile0_x(100) && b.y[k] == tile0_y(100) && b.x[k] < 16) stop = true;
            }
            ++batches;
        });
        CHECK(r.stats.interrupted);
        uint64_t sum = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const color c = r.img.pixel(x, y);
                const int n = int(2 * c.x() + 1); // the mean of samples 0..n-1 is (n - 1) / 2
                CAPTURE(x);
                CAPTURE(y);
                CHECK((n == 2 || n == 4));
                CHECK(c.y() == x);
                sum += uint64_t(n);
                if (threads == 1) CHECK(n == (x < 16 && y * 16 + x <= last ? 4 : 2));
            }
        CHECK(sum == r.stats.samples);
        CHECK(r.stats.min_pixel_samples == 2);
        CHECK(r.stats.max_pixel_samples == 4);
    }
}

// The milestone apps 02-06 render with their own ray_color through rt::render(cam, world,
// ray_color), which returns the statistics with the image: the sample counts of an interrupted
// render are known, as the path tracer's are.
TEST_CASE("render(cam, world, ray_color): the statistics of a shader render, and of one stopped by cam.settings.stop") {
    camera cam;
    cam.image_width = 32;
    cam.aspect_ratio = 2.0; // 32x16: two 16x16 tiles
    cam.samples_per_pixel = 4;
    cam.settings.threads = 1;
    cam.settings.quiet = true;
    hittable_list world;
    std::atomic<bool> stop{false};
    uint64_t calls = 0, stop_at = 0;
    auto shade = [&](const ray&, const hittable&) {
        if (++calls == stop_at) stop = true;
        return color(0.25, 0.5, 1.0);
    };
    // Uninterrupted: every pixel 4 samples, a ray each, the colour exactly.
    render_result all = render(cam, world, shade);
    CHECK_FALSE(all.stats.interrupted);
    CHECK(all.stats.samples == uint64_t(pixels) * 4);
    CHECK(all.stats.rays == uint64_t(pixels) * 4);
    CHECK(all.stats.min_pixel_samples == 4);
    CHECK(same(all.img.pixel(31, 15), color(0.25, 0.5, 1.0)));
    CHECK(all.img.data() == cam.render_image(world, shade).data()); // the image render_image gives

    // Stopped at the 600th call: passes of 1, 1 and 2 samples per pixel (512, 512, 1024 calls);
    // call 600 is the 88th of the second pass, pixel 87 of tile 0, which finishes: pixels 0..87
    // of tile 0 took 2 samples, the rest 1.
    cam.settings.stop = &stop;
    calls = 0;
    stop_at = 600;
    render_result part = render(cam, world, shade);
    CHECK(part.stats.interrupted);
    CHECK(part.stats.samples == 600);
    CHECK(part.stats.min_pixel_samples == 1);
    CHECK(part.stats.max_pixel_samples == 2);
    CHECK(part.stats.pixels_without_samples == 0);
    CHECK(part.stats.completed == doctest::Approx(600.0 / 2048.0));
    CHECK(part.stats.mean_pixel_samples() == doctest::Approx(600.0 / 512.0));
    CHECK(same(part.img.pixel(0, 0), color(0.25, 0.5, 1.0)));
}

} // namespace test_progress_interrupt
