#pragma once
// The scheduler: runs a per-sample function over every pixel of an image on worker threads and
// averages the samples into the image. It knows no integrator and no camera.
//
//   render_result r = render_samples(width, height, settings,
//       [&](int x, int y, int s, pcg32& rng, uint64_t& rays) -> vec3f { ... });
//   render_result r = render_samples(width, height, settings, [&](sample_batch& b) { ... });
//
// The second form takes samples in batches of up to sample_batch::capacity (a row of a tile's
// pixels, or one pixel's samples), so that the integrator can do the work its samples share at
// once (the path tracer's camera rays: camera_frame::sample_rays); the first is called sample by
// sample.
//
// The image is cut into 16x16 tiles that workers take from an atomic counter, in passes over the
// whole image (with adaptive sampling: rounds planned by measure/adaptive.h). Sample s of pixel
// (x, y) draws from its own generator, sample_rng(seed, pixel, s), so the image is bit-identical
// for any thread count. A sample that comes out NaN or infinite is dropped (it counts as 0) and
// counted. Progress (percentage, elapsed time, time left) and a final statistics line go to
// stderr unless settings.quiet is set.
//
// Interruption (settings.stop): the workers poll the flag before each pixel, so a render stops
// within one pixel's samples, and the image is the mean of the samples each pixel did take.
// Uniform sampling runs in passes, 1 sample per pixel, then 1 more, 2, 4, ... (the count doubling)
// so that a stopped render has spread its samples over the whole image: after the first pass
// every pixel has at least one, and the counts differ at most by the interrupted pass (a pixel
// has either n or 2n samples). Each pixel's sum is kept in 64-bit fixed point (fixed_point.h), which
// no order of additions changes, so an uninterrupted render gives exactly the image of a single
// pass, and renders of parts of the sample range (settings.first_sample, end_sample) or of the
// image (settings.share) add up to exactly the sums of the whole (settings.keep_sums hands them
// out: render_result::sums).

#include "../measure/adaptive.h"
#include "fixed_point.h"
#include "../image/image.h"
#include "processors.h"
#include "render_settings.h"
#include "../core/function_ref.h"
#include "../core/rng.h"
#include "../core/vec3f.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
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
    int threads = 0;                // over all processes of a shared render
    int ranks = 1;                  // processes that shared the render (render/mpi_render.h)
    uint64_t rays = 0;              // every ray traced: camera rays and scattered rays
    uint64_t samples = 0;           // camera samples taken
    uint64_t samples_saved = 0;     // by adaptive sampling: width * height * spp - samples
    uint64_t nonfinite_samples = 0; // samples that came out NaN or infinite (dropped)
    uint64_t saturated_samples = 0; // samples beyond the fixed-point range, clamped (fixed_point.h)
    int first_sample = 0, end_sample = 0; // the sample range of every pixel rendered
    double seconds = 0;             // wall time of the render, compile included
    // Stopped early by render_settings::stop: each pixel holds the mean of the samples it took.
    bool interrupted = false;
    int min_pixel_samples = 0;       // the fewest samples a pixel took (0: some pixels are black)
    int max_pixel_samples = 0;       // the most
    uint64_t pixels_without_samples = 0; // black pixels, only after an early stop
    // The share of the planned samples taken (uniform sampling; 1 when not interrupted). Adaptive
    // sampling does not know its total in advance: there it is samples / (pixels * spp), a floor.
    double completed = 1;

    double mrays_per_second() const { return seconds > 0 ? double(rays) / seconds * 1e-6 : 0; }
    double mean_pixel_samples() const {
        return width > 0 && height > 0 ? double(samples) / (double(width) * double(height)) : 0;
    }
};

struct render_result {
    image img;
    render_stats stats;
    pixel_sums sums; // the exact sums behind img, with settings.keep_sums (uniform sampling); else empty
};

// Samples handed to a batched sample function: sample k < count is sample s[k] of pixel
// (x[k], y[k]), with its own generator rng[k] (sample_rng); the function sets color[k] and adds
// the rays it traced for it to rays[k] (which start at 0). `workspace` is the function's own:
// empty at first, and kept from one batch to the next of the same worker and job (a tile's pass),
// for buffers it would otherwise build for every batch.
struct sample_batch {
    static constexpr int capacity = 32;
    int count = 0;
    int x[capacity], y[capacity], s[capacity];
    pcg32 rng[capacity];
    vec3f color[capacity];
    uint64_t rays[capacity];
    std::shared_ptr<void> workspace;
};

// Runs sample(x, y, s, rng, rays) -> vec3f for every sample of every pixel of a width x height
// image and returns the mean of each pixel's samples. `rays` is the sample's ray counter; `start`
// is when the render began (a caller that prepared a scene first passes its own start, so that
// the statistics include the preparation).
template <class SampleFn>
render_result render_samples(int width, int height, const render_settings& settings, SampleFn&& sample,
                             std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());

// The same, plus work that adds to any pixel rather than to its own: paths traced from the lights
// (caustic_paths.h). For every sample index s of the range, `splats` runs
// splats.jobs_per_sample() jobs, splats.run(s, job, add, totals), which call add(x, y, value);
// each pixel's values are added to its sum as one of its samples would be, so a pixel's mean is
// its own samples' plus the splats of the same sample indices, over its sample count. Uniform
// sampling only (adaptive sampling decides counts per pixel, which splats cannot follow).
template <class SampleFn, class Splats>
render_result render_samples_with_splats(int width, int height, const render_settings& settings, SampleFn&& sample,
                                         const Splats& splats,
                                         std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());

// One-line summary of a render's statistics, as printed at the end of a render.
std::string stats_line(const render_stats& s);

// A duration as m:ss, or h:mm:ss from an hour on (rounded down to the second).
std::string format_duration(double seconds);

// The progress line's body: "42%  elapsed 0:12  left 0:16". The time left assumes the remaining
// work goes at the pace of the work done: elapsed * (total - done) / done; before any work is
// done it is unknown ("left ?").
std::string format_progress(int64_t done, int64_t total, double elapsed_seconds);

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
    uint64_t rays = 0, samples = 0, nonfinite = 0, saturated = 0;

    void add(const sample_totals& t) {
        rays += t.rays;
        samples += t.samples;
        nonfinite += t.nonfinite;
        saturated += t.saturated;
    }
};

// Runs job(i, totals) for i in [0, count) on `threads` threads (the caller's among them), the
// jobs handed out by an atomic counter; then rethrows the first exception a job threw.
template <class Job>
sample_totals run_jobs(int threads, int count, Job&& job) {
    std::atomic<int> next{0};
    std::atomic<uint64_t> rays{0}, samples{0}, nonfinite{0}, saturated{0};
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
        saturated += mine.saturated;
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < std::min(threads, count); ++i) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    if (failure) std::rethrow_exception(failure);
    return {rays.load(), samples.load(), nonfinite.load(), saturated.load()};
}

// A sample function as the scheduler takes it, compiled once for every integrator: a batch's
// samples at a time, and whether it wants one pixel's samples per batch (a per-sample function,
// which render_samples turns into one: a stop then comes exactly between pixels).
struct batch_function {
    function_ref<void(sample_batch&)> take;
    bool pixel_by_pixel = false;
};

// The samples of batch b, each from its own generator; a NaN or infinite sample is dropped and
// counts as a sample of 0. Afterwards b.color and b.rays hold each sample's result and rays.
inline void take_samples(uint64_t seed, int width, const batch_function& sample, sample_batch& b, sample_totals& t) {
    for (int k = 0; k < b.count; ++k) {
        const uint64_t pixel = uint64_t(b.y[k]) * uint64_t(width) + uint64_t(b.x[k]);
        b.rng[k] = sample_rng(seed, pixel, uint64_t(b.s[k]));
        b.rays[k] = 0;
    }
    sample.take(b);
    for (int k = 0; k < b.count; ++k) {
        t.rays += b.rays[k];
        ++t.samples;
        if (!is_finite(b.color[k])) {
            ++t.nonfinite;
            b.color[k] = {0, 0, 0};
        }
    }
}

// Gathers samples into batches and takes them. Pixels are added whole (all the samples the pass
// or round gives them), so a stop, asked before each pixel, leaves every pixel with all of them
// or none. A per-sample function gets one pixel's samples per batch, so that it stops exactly
// there; a batched one gets samples of consecutive pixels together. done(batch, k) sees each
// sample taken, in order; the caller flushes the last batch.
class batcher {
  public:
    using done_function = function_ref<void(const sample_batch&, int)>;
    batcher(uint64_t seed, int width, const batch_function& sample, sample_totals& totals, done_function done)
        : seed_(seed), width_(width), sample_(sample), totals_(totals), done_(done) {}

    // The samples [first, last) of pixel (x, y).
    void add_pixel(int x, int y, int first, int last) {
        for (int s = first; s < last; ++s) {
            const int k = batch_.count++;
            batch_.x[k] = x;
            batch_.y[k] = y;
            batch_.s[k] = s;
            if (batch_.count == sample_batch::capacity) flush();
        }
        if (sample_.pixel_by_pixel) flush();
    }
    void flush() {
        if (batch_.count == 0) return;
        take_samples(seed_, width_, sample_, batch_, totals_);
        for (int k = 0; k < batch_.count; ++k) done_(batch_, k);
        batch_.count = 0;
    }

  private:
    uint64_t seed_;
    int width_;
    const batch_function& sample_;
    sample_totals& totals_;
    done_function done_;
    sample_batch batch_;
};

// Progress on stderr. On a terminal one line updated in place ("\r"), at most four times a second
// (more is flicker, and each update is a write). In a log (stderr not a terminal) a full line
// whenever another 10 % is done or 30 s have passed, but never two lines within 5 s: a short
// render logs a few lines, a long one a line every 30 s, both readable with tail. Workers call
// show() once per tile or job; the one that finds the meter busy or the update not due returns at
// once (try_lock), so the workers never wait on each other here.
class progress_meter {
  public:
    using clock = std::chrono::steady_clock;
    explicit progress_meter(bool quiet, clock::time_point start = clock::now())
        : quiet_(quiet), interactive_(stderr_is_terminal()), start_(start), round_start_(start), last_line_(start) {}
    // Adaptive sampling's rounds: each is counted on its own (their total is not known ahead).
    void start_round(int round) {
        std::lock_guard<std::mutex> lock(mutex_);
        round_ = round;
        round_start_ = clock::now();
        last_pct_ = -1;
        done_ = 0;
    }
    void show(int64_t done, int64_t total) {
        if (quiet_) return;
        // The most done so far, even from a call that skips printing: finish() shows it.
        int64_t seen = done_.load();
        while (done > seen && !done_.compare_exchange_weak(seen, done)) {}
        total_ = total;
        std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
        if (!lock.owns_lock()) return;
        const clock::time_point now = clock::now();
        const double since = std::chrono::duration<double>(now - last_line_).count();
        const int pct = int(done * 100 / std::max<int64_t>(1, total));
        bool due = interactive_ ? since >= 0.25 : since >= 5 && (pct >= last_pct_ + 10 || since >= 30);
        if (!due) return;
        print(now, false);
        last_line_ = now;
        last_pct_ = pct;
    }
    // The last state (100 % unless interrupted), ending the terminal's line.
    void finish() {
        if (quiet_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        if (total_.load() > 0) print(clock::now(), true);
    }

  private:
    void print(clock::time_point now, bool last) const {
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        const int64_t done = done_.load(), total = total_.load();
        std::string body;
        if (round_ >= 0) {
            // The time left is the round's: its pace, from its own start.
            body = "round " + std::to_string(round_) + ":" +
                   format_progress(done, total, std::chrono::duration<double>(now - round_start_).count()) +
                   " (total " + format_duration(elapsed) + ")";
        } else {
            body = format_progress(done, total, elapsed);
        }
        // On a terminal the padding wipes what a longer earlier line left behind; the line stays
        // within 80 columns (66 with the padding), as one that wraps could not be rewritten by "\r".
        if (interactive_) std::fprintf(stderr, "\rrtweekend: rendering %-45s%s", body.c_str(), last ? "\n" : "");
        else std::fprintf(stderr, "rtweekend: rendering %s\n", body.c_str());
    }

    bool quiet_, interactive_;
    clock::time_point start_, round_start_, last_line_;
    int round_ = -1, last_pct_ = -1;
    std::atomic<int64_t> done_{0}, total_{0};
    std::mutex mutex_;
};

inline bool stop_requested(const render_settings& settings) {
    return settings.stop != nullptr && settings.stop->load(std::memory_order_relaxed);
}

inline int render_threads(const render_settings& settings, int jobs) {
    int threads = settings.threads > 0 ? settings.threads : processors_available();
    return std::max(1, std::min(threads, jobs));
}

// The statistics; `counts(i)` is the number of samples pixel i took, `planned` the number the
// render set out to take. The statistics line goes to stderr unless settings.quiet, or the render
// is shared (the share's owner reports the whole render, not this process's part).
template <class Counts>
render_stats make_stats(int width, int height, const render_settings& settings, int threads, const sample_totals& t,
                        uint64_t planned, std::chrono::steady_clock::time_point start, Counts&& counts) {
    render_stats st;
    st.width = width;
    st.height = height;
    st.samples_per_pixel = settings.samples_per_pixel;
    st.first_sample = settings.first_sample;
    st.end_sample = settings.sample_end();
    st.threads = threads;
    st.rays = t.rays;
    st.samples = t.samples;
    st.nonfinite_samples = t.nonfinite;
    st.saturated_samples = t.saturated;
    const size_t pixels = size_t(width) * size_t(height);
    st.min_pixel_samples = pixels > 0 ? settings.samples_per_pixel : 0;
    for (size_t i = 0; i < pixels; ++i) {
        const int n = counts(i);
        st.min_pixel_samples = std::min(st.min_pixel_samples, n);
        st.max_pixel_samples = std::max(st.max_pixel_samples, n);
        if (n == 0) ++st.pixels_without_samples;
    }
    st.interrupted = stop_requested(settings) && (settings.adaptive_error > 0 || t.samples < planned);
    // Samples not taken are saved by adaptive sampling; an interrupted render did not save them.
    st.samples_saved = st.interrupted || t.samples > planned ? 0 : planned - t.samples;
    st.completed = st.interrupted && planned > 0 ? double(t.samples) / double(planned) : 1.0;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!settings.quiet && settings.share == nullptr) std::fprintf(stderr, "%s\n", stats_line(st).c_str());
    return st;
}

// Adaptive sampling (the plan and why: measure/adaptive.h): rounds over the whole image, each
// round's samples taken in parallel, each pixel by one thread in sample order. A stop ends the
// render between pixels: the pixels of the round not reached keep the samples of earlier rounds
// (none, if it was round 0).
inline render_result run_adaptive(int w, int h, const render_settings& settings, const batch_function& sample,
                                  std::chrono::steady_clock::time_point start) {
    const int threads = render_threads(settings, int(std::min<int64_t>(int64_t(w) * h, 1 << 20)));
    adaptive_settings plan_settings;
    plan_settings.width = w;
    plan_settings.height = h;
    plan_settings.error = settings.adaptive_error;
    plan_settings.min_samples = settings.adaptive_min_samples;
    plan_settings.max_samples = settings.samples_per_pixel;
    plan_settings.threads = threads;
    if (settings.share) {
        plan_settings.rank = settings.share->rank;
        plan_settings.ranks = settings.share->ranks;
    }
    adaptive_sampler plan(plan_settings);

    progress_meter progress(settings.quiet, start);
    sample_totals totals;
    if (settings.share) settings.share->ready();
    for (int round = 0; !stop_requested(settings) && plan.plan_round(); ++round) {
        progress.start_round(round);
        std::atomic<int> jobs_done{0};
        const int jobs = int(plan.job_count());
        auto take_round = [&] {
            return run_jobs(threads, jobs, [&](int j, sample_totals& mine) {
                auto add = [&](const sample_batch& b, int k) {
                    plan.add(uint64_t(b.y[k]) * uint64_t(w) + uint64_t(b.x[k]), b.color[k], b.rays[k]);
                };
                batcher samples(settings.seed, w, sample, mine, add);
                for (const adaptive_sampler::work_item& item : plan.job(size_t(j))) {
                    if (stop_requested(settings)) break;
                    samples.add_pixel(int(item.pixel % uint64_t(w)), int(item.pixel / uint64_t(w)), item.first,
                                      item.first + item.count);
                }
                samples.flush();
                progress.show(++jobs_done, jobs);
            });
        };
        sample_totals t;
        std::exception_ptr failure; // shared renders: agreed on below, on every process
        if (!settings.share) {
            t = take_round();
        } else {
            try {
                t = take_round();
            } catch (...) {
                failure = std::current_exception();
            }
        }
        totals.add(t);
        if (settings.share) {
            // Every pixel's new state from the process that sampled it (see render_share); the
            // words are made before the agreement, so that nothing can fail between it and the
            // combination.
            std::vector<uint64_t> words;
            if (!failure) {
                try {
                    words = plan.pack_round();
                } catch (...) {
                    failure = std::current_exception();
                }
            }
            settings.share->round_done(failure);
            settings.share->combine_owned(words.data(), words.size());
            plan.unpack_round(words);
        }
    }
    progress.finish();

    render_result result;
    result.img = image(w, h);
    plan.write(result.img.data());
    const uint64_t planned = uint64_t(w) * uint64_t(h) * uint64_t(settings.samples_per_pixel);
    result.stats =
        make_stats(w, h, settings, threads, totals, planned, start, [&](size_t i) { return plan.samples(i); });
    return result;
}

// Uniform sampling: the samples [first_sample, end_sample) of every pixel (all samples_per_pixel
// of them by default), in passes over the image (1, 1, 2, 4, ... samples: see the top), each pass
// cut into 16x16 tiles handed to the workers. A shared render by tiles takes only its own tiles.
// The passes wait for each other (a pass must not start on a pixel whose previous pass is still
// running, as both would write its sums); a pass costs as much as all before it, so the waits at
// their ends add up to about twice the last pass's.
// Work that adds to any pixel (render_samples_with_splats), as the scheduler takes it: jobs per
// sample index, and run(s, job, add, totals), which calls add(x, y, value).
struct splat_function {
    using add_function = function_ref<void(int, int, const vec3f&)>;
    int jobs_per_sample = 0;
    function_ref<void(int, int, add_function, sample_totals&)> run;
};

// Splats of a pass, in fixed point (fixed_point.h), added from any thread: integer additions in
// any order give the same sums, so the image stays the same at any thread count. Each splat is
// clamped to splat_limit(spp), 1/64 of a sample's share: the sums of 64 spp maximal splats fit.
struct splat_sums {
    std::vector<std::atomic<int64_t>> rgb;
    explicit splat_sums(size_t pixels) : rgb(pixels * 3) {}
    static int64_t splat_limit(int spp) { return sample_limit(int64_t(spp) * 64); }
};

inline render_result run_tiles(int w, int h, const render_settings& settings, const batch_function& sample,
                               std::chrono::steady_clock::time_point start, const splat_function* splats = nullptr) {
    constexpr int tile = 16;
    const int spp = settings.samples_per_pixel;
    const int first_sample = settings.first_sample, end_sample = settings.sample_end();
    const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile, tile_count = tiles_x * tiles_y;
    // This render's tiles: all, or every ranks-th from its rank on (round robin spreads the costly
    // parts of an image over the processes better than bands would).
    const bool by_tiles = settings.share != nullptr && settings.share->by_tiles && settings.share->ranks > 1;
    const int tile_step = by_tiles ? settings.share->ranks : 1, tile_first = by_tiles ? settings.share->rank : 0;
    const int my_tiles = tile_first < tile_count ? (tile_count - tile_first + tile_step - 1) / tile_step : 0;
    const int threads = render_threads(settings, std::max(1, my_tiles));
    // Every sample is clamped so that spp of them cannot overflow a sum (fixed_point.h).
    const int64_t limit = sample_limit(spp);

    pixel_sums sums(w, h);
    progress_meter progress(settings.quiet, start);
    uint64_t my_pixels = 0;
    for (int j = tile_first; j < tile_count; j += tile_step) {
        const int x0 = (j % tiles_x) * tile, y0 = (j / tiles_x) * tile;
        my_pixels += uint64_t(std::min(x0 + tile, w) - x0) * uint64_t(std::min(y0 + tile, h) - y0);
    }
    const int64_t total = int64_t(my_pixels) * (end_sample - first_sample);
    std::atomic<int64_t> done{0};
    sample_totals totals;
    // Splats: this pass's, and those of the passes that completed ([first_sample, splat_end)).
    const int splat_jobs = splats ? splats->jobs_per_sample : 0;
    std::vector<int64_t> kept_splats(splat_jobs > 0 ? size_t(w) * size_t(h) * 3 : 0, 0);
    splat_sums pass_splats(splat_jobs > 0 ? size_t(w) * size_t(h) : 0);
    int splat_end = first_sample;
    const int64_t splat_limit = splat_sums::splat_limit(spp);
    auto owns_pixel = [&](int x, int y) {
        return !by_tiles || ((y / tile) * tiles_x + x / tile) % tile_step == tile_first;
    };
    if (settings.share) settings.share->ready();
    for (int first = first_sample; first < end_sample && !stop_requested(settings);) {
        // This pass: samples [first, last), 1 sample, then 1, 2, 4 ... counted from the range's start.
        const int last = std::min(end_sample, first_sample + std::max(1, 2 * (first - first_sample)));
        sample_totals t = run_jobs(threads, my_tiles, [&](int job, sample_totals& mine) {
            const int j = tile_first + job * tile_step;
            int x0 = (j % tiles_x) * tile, y0 = (j / tiles_x) * tile;
            int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
            // Each pixel's sum, added to in place: a pixel's samples are all in one batch or in
            // batches taken one after the other, and no other worker touches the tile.
            auto add = [&](const sample_batch& b, int k) {
                const size_t i = (size_t(b.y[k]) * size_t(w) + size_t(b.x[k])) * 3;
                const vec3f& c = b.color[k];
                bool clamped = false;
                // No overflow: at most spp samples of at most `limit` each (fixed_point.h).
                add_fixed3(c.x, c.y, c.z, limit, &sums.rgb[i], clamped);
                if (clamped) ++mine.saturated;
            };
            batcher samples(settings.seed, w, sample, mine, add);
            bool stopped = false;
            for (int y = y0; y < y1 && !stopped; ++y) {
                for (int x = x0; x < x1; ++x) {
                    if (stop_requested(settings)) {
                        stopped = true;
                        break;
                    }
                    samples.add_pixel(x, y, first, last);
                    sums.counts[size_t(y) * size_t(w) + size_t(x)] = last - first_sample;
                }
            }
            samples.flush();
            if (stopped) return;
            progress.show(done += int64_t(x1 - x0) * (y1 - y0) * (last - first), total);
        });
        totals.add(t);
        if (splat_jobs > 0 && !stop_requested(settings)) {
            sample_totals st = run_jobs(threads, (last - first) * splat_jobs, [&](int job, sample_totals& mine) {
                if (stop_requested(settings)) return;
                auto add = [&](int x, int y, const vec3f& value) {
                    if (x < 0 || x >= w || y < 0 || y >= h || !owns_pixel(x, y) || !is_finite(value)) return;
                    const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 3;
                    bool clamped = false;
                    pass_splats.rgb[i].fetch_add(to_fixed(value.x, splat_limit, clamped), std::memory_order_relaxed);
                    pass_splats.rgb[i + 1].fetch_add(to_fixed(value.y, splat_limit, clamped), std::memory_order_relaxed);
                    pass_splats.rgb[i + 2].fetch_add(to_fixed(value.z, splat_limit, clamped), std::memory_order_relaxed);
                    if (clamped) ++mine.saturated;
                };
                splats->run(first + job / splat_jobs, job % splat_jobs, add, mine);
            });
            totals.rays += st.rays;
            totals.saturated += st.saturated;
            // A pass's splats count only when all of them were traced.
            if (!stop_requested(settings)) {
                for (size_t i = 0; i < kept_splats.size(); ++i)
                    kept_splats[i] += pass_splats.rgb[i].exchange(0, std::memory_order_relaxed);
                splat_end = last;
            }
        }
        first = last;
    }
    progress.finish();

    // The splats join the sums: exactly, for every pixel that took the samples [first_sample,
    // splat_end); in proportion to its count for one that took more or fewer (a render stopped early).
    if (splat_end > first_sample) {
        const int64_t splat_samples = splat_end - first_sample;
        for (size_t i = 0; i < sums.pixel_count(); ++i) {
            const int64_t n = sums.counts[i];
            if (n == 0) continue;
            for (size_t k = 0; k < 3; ++k) {
                int64_t add = kept_splats[i * 3 + k];
                if (n != splat_samples) add = int64_t(std::llround(double(add) * double(n) / double(splat_samples)));
                if (!add_fixed(sums.rgb[i * 3 + k], add, sums.rgb[i * 3 + k])) ++totals.saturated;
            }
        }
    }

    render_result result;
    result.img = mean_image(sums);
    const uint64_t planned = my_pixels * uint64_t(end_sample - first_sample);
    result.stats = make_stats(w, h, settings, threads, totals, planned, start, [&](size_t i) { return sums.counts[i]; });
    if (settings.keep_sums) result.sums = std::move(sums);
    return result;
}

} // namespace detail

namespace detail {
// The scheduler itself, for a sample function of either form (batches, or one sample at a time).
inline render_result run_samples(int width, int height, const render_settings& settings, const batch_function& sample,
                                 std::chrono::steady_clock::time_point start, const splat_function* splats) {
    settings.check();
    if (settings.adaptive_error > 0) {
        if (splats) throw scene_error("splats need uniform sampling (adaptive sampling is on)");
        return run_adaptive(width, height, settings, sample, start);
    }
    return run_tiles(width, height, settings, sample, start, splats);
}

// A sample function as a batch_function: a batched one as it is; a per-sample one called for
// each sample of a batch, which then holds one pixel's samples.
template <class SampleFn>
render_result run_any(int width, int height, const render_settings& settings, SampleFn& sample,
                      std::chrono::steady_clock::time_point start, const splat_function* splats) {
    if constexpr (std::is_invocable_v<SampleFn&, sample_batch&>) {
        return run_samples(width, height, settings, batch_function{sample, false}, start, splats);
    } else {
        auto one_by_one = [&](sample_batch& b) {
            for (int k = 0; k < b.count; ++k) b.color[k] = sample(b.x[k], b.y[k], b.s[k], b.rng[k], b.rays[k]);
        };
        return run_samples(width, height, settings, batch_function{one_by_one, true}, start, splats);
    }
}
} // namespace detail

template <class SampleFn>
render_result render_samples(int width, int height, const render_settings& settings, SampleFn&& sample,
                             std::chrono::steady_clock::time_point start) {
    return detail::run_any(width, height, settings, sample, start, nullptr);
}

template <class SampleFn, class Splats>
render_result render_samples_with_splats(int width, int height, const render_settings& settings, SampleFn&& sample,
                                         const Splats& splats, std::chrono::steady_clock::time_point start) {
    auto run = [&](int s, int job, detail::splat_function::add_function add, detail::sample_totals& totals) {
        splats.run(s, job, add, totals);
    };
    const detail::splat_function work{splats.jobs_per_sample(), run};
    return detail::run_any(width, height, settings, sample, start, &work);
}

inline std::string stats_line(const render_stats& s) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "rtweekend: %dx%d, %d spp: %llu rays in %.3f s = %.2f Mrays/s (%d thread%s%s), %llu NaN/Inf samples",
                  s.width, s.height, s.samples_per_pixel, static_cast<unsigned long long>(s.rays), s.seconds,
                  s.mrays_per_second(), s.threads, s.threads == 1 ? "" : "s",
                  s.ranks > 1 ? (" on " + std::to_string(s.ranks) + " ranks").c_str() : "",
                  static_cast<unsigned long long>(s.nonfinite_samples));
    std::string text = line;
    // Only when there are any: a clamp is a sign of a broken scene (fixed_point.h gives the limit).
    if (s.saturated_samples > 0) {
        std::snprintf(line, sizeof line, ", %llu samples beyond the fixed-point range (clamped)",
                      static_cast<unsigned long long>(s.saturated_samples));
        text += line;
    }
    // A part of the sample range (a slice, an MPI rank's share): which part.
    if (s.end_sample > 0 && (s.first_sample != 0 || s.end_sample != s.samples_per_pixel)) {
        std::snprintf(line, sizeof line, ", samples %d to %d", s.first_sample, s.end_sample - 1);
        text += line;
    }
    if (s.interrupted) {
        std::snprintf(line, sizeof line, ", interrupted: %.1f samples per pixel on average (%d to %d)",
                      s.mean_pixel_samples(), s.min_pixel_samples, s.max_pixel_samples);
        text += line;
    }
    if (s.samples_saved > 0) {
        std::snprintf(line, sizeof line, ", adaptive: %.1f spp on average, %.1f %% of samples saved",
                      double(s.samples) / (double(s.width) * s.height),
                      100.0 * double(s.samples_saved) / double(s.samples + s.samples_saved));
        text += line;
    }
    return text;
}

inline std::string format_duration(double seconds) {
    const long long t = seconds > 0 && std::isfinite(seconds) ? static_cast<long long>(seconds) : 0;
    char text[64];
    if (t >= 3600) std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", t / 3600, t / 60 % 60, t % 60);
    else std::snprintf(text, sizeof text, "%lld:%02lld", t / 60, t % 60);
    return text;
}

inline std::string format_progress(int64_t done, int64_t total, double elapsed_seconds) {
    done = std::max<int64_t>(0, std::min(done, total));
    const int pct = total > 0 ? int(done * 100 / total) : 0;
    char text[128];
    std::snprintf(text, sizeof text, "%3d%%  elapsed %s  left %s", pct, format_duration(elapsed_seconds).c_str(),
                  done > 0 ? format_duration(elapsed_seconds * double(total - done) / double(done)).c_str() : "?");
    return text;
}

} // namespace rt

