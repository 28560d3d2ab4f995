#pragma once
// The scheduler: runs a per-sample function over every pixel of an image on worker threads and
// averages the samples into the image. It knows no integrator and no camera.
//
//   render_result r = render_samples(width, height, settings,
//       [&](int x, int y, int s, pcg32& rng, uint64_t& rays) -> vec3f { ... });
//
// The image is cut into 16x16 tiles that workers take from an atomic counter (with adaptive
// sampling: rounds over the whole image, planned by measure/adaptive.h). Sample s of pixel (x, y)
// draws from its own generator, sample_rng(seed, pixel, s), so the image is bit-identical for any
// thread count. A sample that comes out NaN or infinite is dropped (it counts as 0) and counted.
// Progress and a final statistics line go to stderr unless settings.quiet is set.

#include "../measure/adaptive.h"
#include "image.h"
#include "render_settings.h"
#include "rng.h"
#include "vec3f.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#if defined(__SSE2__) || defined(_M_X64)
#include <xmmintrin.h>
#define RTWEEKEND_HAS_MXCSR 1
#else
#define RTWEEKEND_HAS_MXCSR 0
#endif

#if __has_include(<unistd.h>)
#include <unistd.h>
#define RTWEEKEND_HAS_UNISTD 1
#endif

namespace rt {

struct render_stats {
    int width = 0, height = 0;
    int samples_per_pixel = 0;
    int threads = 0;
    uint64_t rays = 0;              // every ray traced: camera rays and scattered rays
    uint64_t samples = 0;           // camera samples taken
    uint64_t samples_saved = 0;     // by adaptive sampling: width * height * spp - samples
    uint64_t nonfinite_samples = 0; // samples that came out NaN or infinite (dropped)
    double seconds = 0;             // wall time of the render, compile included

    double mrays_per_second() const { return seconds > 0 ? double(rays) / seconds * 1e-6 : 0; }
};

struct render_result {
    image img;
    render_stats stats;
};

// Runs sample(x, y, s, rng, rays) -> vec3f for every sample of every pixel of a width x height
// image and returns the mean of each pixel's samples. `rays` is the sample's ray counter; `start`
// is when the render began (a caller that prepared a scene first passes its own start, so that
// the statistics include the preparation).
template <class SampleFn>
render_result render_samples(int width, int height, const render_settings& settings, SampleFn&& sample,
                             std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());

// One-line summary of a render's statistics, as printed at the end of a render.
std::string stats_line(const render_stats& s);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// Denormal floats (below 1.2e-38) cost a microcode assist of a hundred cycles or more per
// operation on x86. A path tracer has no use for them, so render threads flush them to zero
// (FTZ: denormal results become 0; DAZ: denormal inputs read as 0), as Embree asks of its users.
// The previous mode is restored on exit, since the calling thread is one of the workers.
class scoped_flush_denormals {
  public:
#if RTWEEKEND_HAS_MXCSR
    scoped_flush_denormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040u); }
    ~scoped_flush_denormals() { _mm_setcsr(saved_); }

  private:
    unsigned saved_;
#endif
  public:
    scoped_flush_denormals(const scoped_flush_denormals&) = delete;
    scoped_flush_denormals& operator=(const scoped_flush_denormals&) = delete;
#if !RTWEEKEND_HAS_MXCSR
    scoped_flush_denormals() = default;
#endif
};

inline bool stderr_is_terminal() {
#if RTWEEKEND_HAS_UNISTD
    return isatty(2) != 0;
#else
    return false;
#endif
}

// What the workers of a render counted.
struct sample_totals {
    uint64_t rays = 0, samples = 0, nonfinite = 0;
};

// Runs job(i, totals) for i in [0, count) on `threads` threads (the caller's among them), the
// jobs handed out by an atomic counter; then rethrows the first exception a job threw.
template <class Job>
sample_totals run_jobs(int threads, int count, Job&& job) {
    std::atomic<int> next{0};
    std::atomic<uint64_t> rays{0}, samples{0}, nonfinite{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    std::atomic<bool> failed{false};
    auto worker = [&] {
        scoped_flush_denormals flush; // this thread's float mode, restored when the worker ends
        sample_totals mine;
        try {
            for (int i = next++; i < count && !failed; i = next++) job(i, mine);
        } catch (...) {
            std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            failed = true;
        }
        rays += mine.rays;
        samples += mine.samples;
        nonfinite += mine.nonfinite;
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < std::min(threads, count); ++i) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    if (failure) std::rethrow_exception(failure);
    return {rays.load(), samples.load(), nonfinite.load()};
}

// Sample s of pixel (x, y), from its own generator; a NaN or infinite sample is dropped and
// counts as a sample of 0.
template <class SampleFn>
vec3f take_sample(uint64_t seed, int width, SampleFn& sample, int x, int y, int s, sample_totals& t) {
    uint64_t pixel = uint64_t(y) * uint64_t(width) + uint64_t(x);
    pcg32 rng = sample_rng(seed, pixel, uint64_t(s));
    vec3f c = sample(x, y, s, rng, t.rays);
    ++t.samples;
    if (is_finite(c)) return c;
    ++t.nonfinite;
    return {0, 0, 0};
}

// Progress on stderr: a terminal gets a counter updated in place, a log every tenth percent.
class progress_meter {
  public:
    explicit progress_meter(bool quiet) : quiet_(quiet), interactive_(stderr_is_terminal()) {
        if (!quiet_ && !interactive_) std::fprintf(stderr, "rtweekend: rendering");
    }
    // Adaptive sampling's rounds: each is counted on its own, and a log gets their numbers only.
    void start_round(int round) {
        round_ = round;
        shown_ = -1;
        if (!quiet_ && !interactive_) std::fprintf(stderr, " [round %d]", round);
    }
    void show(int64_t done, int64_t total) {
        if (quiet_ || (round_ >= 0 && !interactive_)) return;
        int step = interactive_ ? 1 : 10;
        int pct = int(done * 100 / std::max<int64_t>(1, total)) / step * step;
        int shown = shown_.load();
        while (pct > shown && !shown_.compare_exchange_weak(shown, pct)) {}
        if (pct <= shown) return;
        if (round_ >= 0) std::fprintf(stderr, "\rrtweekend: rendering, round %d: %3d%%", round_, pct);
        else if (interactive_) std::fprintf(stderr, "\rrtweekend: rendering %3d%%", pct);
        else std::fprintf(stderr, " %d%%", pct);
    }
    void finish() {
        if (!quiet_) std::fprintf(stderr, "\n");
    }

  private:
    bool quiet_, interactive_;
    int round_ = -1;
    std::atomic<int> shown_{0};
};

inline int render_threads(const render_settings& settings, int jobs) {
    int threads = settings.threads > 0 ? settings.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    return std::max(1, std::min(threads, jobs));
}

inline render_stats make_stats(int width, int height, const render_settings& settings, int threads,
                               const sample_totals& t, std::chrono::steady_clock::time_point start) {
    render_stats st;
    st.width = width;
    st.height = height;
    st.samples_per_pixel = settings.samples_per_pixel;
    st.threads = threads;
    st.rays = t.rays;
    st.samples = t.samples;
    st.samples_saved = uint64_t(width) * uint64_t(height) * uint64_t(settings.samples_per_pixel) - t.samples;
    st.nonfinite_samples = t.nonfinite;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!settings.quiet) std::fprintf(stderr, "%s\n", stats_line(st).c_str());
    return st;
}

// Adaptive sampling (the plan and why: measure/adaptive.h): rounds over the whole image, each
// round's samples taken in parallel, each pixel by one thread in sample order.
template <class SampleFn>
render_result run_adaptive(int w, int h, const render_settings& settings, SampleFn& sample,
                           std::chrono::steady_clock::time_point start) {
    const int threads = render_threads(settings, int(std::min<int64_t>(int64_t(w) * h, 1 << 20)));
    adaptive_settings plan_settings;
    plan_settings.width = w;
    plan_settings.height = h;
    plan_settings.error = settings.adaptive_error;
    plan_settings.min_samples = settings.adaptive_min_samples;
    plan_settings.max_samples = settings.samples_per_pixel;
    plan_settings.threads = threads;
    adaptive_sampler plan(plan_settings);

    progress_meter progress(settings.quiet);
    sample_totals totals;
    for (int round = 0; plan.plan_round(); ++round) {
        progress.start_round(round);
        std::atomic<int> jobs_done{0};
        const int jobs = int(plan.job_count());
        sample_totals t = run_jobs(threads, jobs, [&](int j, sample_totals& mine) {
            for (const adaptive_sampler::work_item& item : plan.job(size_t(j))) {
                int x = int(item.pixel % uint64_t(w)), y = int(item.pixel / uint64_t(w));
                for (int s = item.first; s < item.first + item.count; ++s) {
                    uint64_t rays_before = mine.rays;
                    vec3f c = take_sample(settings.seed, w, sample, x, y, s, mine);
                    plan.add(item.pixel, c, mine.rays - rays_before);
                }
            }
            progress.show(++jobs_done, jobs);
        });
        totals.rays += t.rays;
        totals.samples += t.samples;
        totals.nonfinite += t.nonfinite;
    }
    progress.finish();

    render_result result;
    result.img = image(w, h);
    plan.write(result.img.data());
    result.stats = make_stats(w, h, settings, threads, totals, start);
    return result;
}

// Uniform sampling: samples_per_pixel samples in every pixel, 16x16 tiles handed to the workers.
template <class SampleFn>
render_result run_tiles(int w, int h, const render_settings& settings, SampleFn& sample,
                        std::chrono::steady_clock::time_point start) {
    constexpr int tile = 16;
    const int spp = settings.samples_per_pixel;
    const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile, tile_count = tiles_x * tiles_y;
    const int threads = render_threads(settings, tile_count);

    render_result result;
    result.img = image(w, h);
    std::vector<float>& pixels = result.img.data();
    progress_meter progress(settings.quiet);
    std::atomic<int> tiles_done{0};
    sample_totals totals = run_jobs(threads, tile_count, [&](int t, sample_totals& mine) {
        int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
        int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                double sum[3] = {0, 0, 0};
                for (int s = 0; s < spp; ++s) {
                    vec3f c = take_sample(settings.seed, w, sample, x, y, s, mine);
                    sum[0] += c.x;
                    sum[1] += c.y;
                    sum[2] += c.z;
                }
                float* out = &pixels[(size_t(y) * size_t(w) + size_t(x)) * 3];
                for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(sum[k] / spp);
            }
        }
        progress.show(++tiles_done, tile_count);
    });
    progress.finish();
    result.stats = make_stats(w, h, settings, threads, totals, start);
    return result;
}

} // namespace detail

template <class SampleFn>
render_result render_samples(int width, int height, const render_settings& settings, SampleFn&& sample,
                             std::chrono::steady_clock::time_point start) {
    if (settings.adaptive_error > 0) return detail::run_adaptive(width, height, settings, sample, start);
    return detail::run_tiles(width, height, settings, sample, start);
}

inline std::string stats_line(const render_stats& s) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "rtweekend: %dx%d, %d spp: %llu rays in %.3f s = %.2f Mrays/s (%d thread%s), %llu NaN/Inf samples",
                  s.width, s.height, s.samples_per_pixel, static_cast<unsigned long long>(s.rays), s.seconds,
                  s.mrays_per_second(), s.threads, s.threads == 1 ? "" : "s",
                  static_cast<unsigned long long>(s.nonfinite_samples));
    std::string text = line;
    if (s.samples_saved > 0) {
        std::snprintf(line, sizeof line, ", adaptive: %.1f spp on average, %.1f %% of samples saved",
                      double(s.samples) / (double(s.width) * s.height),
                      100.0 * double(s.samples_saved) / double(s.samples + s.samples_saved));
        text += line;
    }
    return text;
}

} // namespace rt
