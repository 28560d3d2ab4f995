#pragma once
// The render loop: tiles on std::thread workers, and the path tracer.
//
//   render_result render(const camera& cam, const hittable& world);   // image + statistics
//
// The world is first compiled into a flat scene (scene.h). The image is cut into 16x16 tiles
// that workers take from an atomic counter (with adaptive sampling: rounds over the whole image,
// planned by adaptive.h); each pixel's samples are drawn from generators seeded by (seed, pixel,
// sample), so the image is bit-identical for any thread count. A sample
// that comes out NaN or infinite is dropped and counted; the count is reported. Progress and the
// final statistics (rays, seconds, Mrays/s) go to stderr unless cam.quiet is set.

#include "../measure/adaptive.h"
#include "../camera.h"
#include "../io/image_write.h"
#include "ray_offset.h"
#include "rng.h"
#include "compiled_scene.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
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

// Renders `world` as seen by `cam` with the path tracer. Throws scene_error on bad input.
render_result render(const camera& cam, const hittable& world);

// One-line summary of a render's statistics, as printed at the end of a render.
std::string describe(const render_stats& s);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// What a ray that escapes the scene sees.
struct environment {
    bool constant = false;
    vec3f color{0, 0, 0};

    vec3f eval(const vec3f& unit_dir) const {
        if (constant) return color;
        // The book's sky: white at the horizon blending to light blue overhead.
        float a = 0.5f * (unit_dir.y + 1.0f);
        return (1.0f - a) * vec3f{1, 1, 1} + a * vec3f{0.5f, 0.7f, 1.0f};
    }
};

inline environment make_environment(const camera& cam) {
    environment env;
    if (cam.background) {
        env.constant = true;
        env.color = vec3f(*cam.background);
    }
    return env;
}

// A non-owning shared_ptr, for handing the renderer's material pointers to user code.
inline std::shared_ptr<material> borrow(const material* m) {
    return std::shared_ptr<material>(std::shared_ptr<material>(), const_cast<material*>(m));
}

// Scattering by a user's material subclass, through the book's virtual interface.
inline bool scatter_custom(const compiled_scene& scene, const material* m, const ray3f& r, const surface_hit& hit,
                           vec3f& dir, vec3f& attenuation) {
    hit_record rec;
    if (hit.custom_object) {
        rec = hit.custom_record;
    } else {
        rec.p = scene.origin + hit.p.to_double();
        rec.normal = hit.normal.to_double();
        rec.t = hit.t;
        rec.front_face = hit.front_face;
        rec.mat = borrow(m);
    }
    ray r_in(scene.origin + r.origin.to_double(), r.dir.to_double());
    color att;
    ray scattered;
    if (!m->scatter(r_in, rec, att, scattered)) return false;
    dir = normalize(vec3f(scattered.direction()));
    attenuation = vec3f(att);
    return true;
}

// One path from the camera: the book's ray_color, as a loop. Returns the radiance it carries.
inline vec3f trace_path(const compiled_scene& scene, const environment& env, ray3f r, int max_depth, pcg32& rng,
                        uint64_t& rays) {
    vec3f throughput{1, 1, 1};
    surface_hit hit;
    for (int depth = 0; depth < max_depth; ++depth) {
        ++rays;
        if (!scene.intersect(r, hit)) return throughput * env.eval(r.dir);

        // A user-written hittable reports its own material; a built-in sphere indexes the table.
        material_desc custom_desc;
        const material_desc* m;
        if (hit.custom_object) {
            custom_desc = scene.describe_material(hit.custom_record.mat.get());
            m = &custom_desc;
        } else {
            m = &scene.materials[hit.material];
        }
        // Beer's law: a ray that reaches the back face of absorbing glass has travelled hit.t
        // inside it (directions are unit).
        if (m->kind == material_kind::exact_dielectric && !hit.front_face)
            throughput *= beer_transmittance(m->absorption, hit.t);

        vec3f dir, attenuation;
        bool scattered = m->kind == material_kind::custom
                             ? scatter_custom(scene, m->custom, r, hit, dir, attenuation)
                             : scatter_builtin(*m, r.dir, hit.normal, hit.front_face, rng, dir, attenuation);
        if (!scattered) return {0, 0, 0};
        throughput *= attenuation;

        // Leave the surface on the side the new direction points to.
        vec3f side = dot(dir, hit.normal) >= 0 ? hit.normal : -hit.normal;
        r.origin = offset_ray_origin(hit.p, side) + hit.offset * side;
        r.dir = dir;
        r.tmin = 0;
        r.tmax = std::numeric_limits<float>::infinity();
    }
    return {0, 0, 0}; // the book: no more light is gathered past the bounce limit
}

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

inline int render_threads(const camera& cam, int jobs) {
    int threads = cam.threads > 0 ? cam.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    return std::max(1, std::min(threads, jobs));
}

inline render_stats make_stats(const camera& cam, const camera_frame& frame, int threads, const sample_totals& t,
                               std::chrono::steady_clock::time_point start) {
    render_stats st;
    st.width = frame.width;
    st.height = frame.height;
    st.samples_per_pixel = cam.samples_per_pixel;
    st.threads = threads;
    st.rays = t.rays;
    st.samples = t.samples;
    st.samples_saved = uint64_t(frame.width) * uint64_t(frame.height) * uint64_t(cam.samples_per_pixel) - t.samples;
    st.nonfinite_samples = t.nonfinite;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!cam.quiet) std::fprintf(stderr, "%s\n", describe(st).c_str());
    return st;
}

// Adaptive sampling (camera::adaptive_error; the plan and why: adaptive.h): rounds over the
// whole image, each round's samples taken in parallel, each pixel by one thread in sample order.
template <class SampleFn>
render_result run_adaptive(const camera& cam, const camera_frame& frame, SampleFn& sample,
                           std::chrono::steady_clock::time_point start) {
    const int w = frame.width, h = frame.height;
    const int threads = render_threads(cam, int(std::min<int64_t>(int64_t(w) * h, 1 << 20)));
    adaptive_settings settings;
    settings.width = w;
    settings.height = h;
    settings.error = cam.adaptive_error;
    settings.min_samples = cam.adaptive_min_samples;
    settings.max_samples = cam.samples_per_pixel;
    settings.threads = threads;
    adaptive_sampler plan(settings);

    progress_meter progress(cam.quiet);
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
                    vec3f c = take_sample(cam.seed, w, sample, x, y, s, mine);
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
    result.stats = make_stats(cam, frame, threads, totals, start);
    return result;
}

// Runs `sample(x, y, s, rng, rays)` -> vec3f for every sample of every pixel, in tiles on
// worker threads, and averages the samples into an image (with adaptive sampling, when
// cam.adaptive_error is set, a pixel takes as many samples as it needs, at most
// samples_per_pixel).
template <class SampleFn>
render_result run_tiles(const camera& cam, const camera_frame& frame, SampleFn&& sample,
                        std::chrono::steady_clock::time_point start) {
    if (cam.adaptive_error > 0) return run_adaptive(cam, frame, sample, start);
    constexpr int tile = 16;
    const int w = frame.width, h = frame.height, spp = cam.samples_per_pixel;
    const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile, tile_count = tiles_x * tiles_y;
    const int threads = render_threads(cam, tile_count);

    render_result result;
    result.img = image(w, h);
    std::vector<float>& pixels = result.img.data();
    progress_meter progress(cam.quiet);
    std::atomic<int> tiles_done{0};
    sample_totals totals = run_jobs(threads, tile_count, [&](int t, sample_totals& mine) {
        int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
        int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
                double sum[3] = {0, 0, 0};
                for (int s = 0; s < spp; ++s) {
                    vec3f c = take_sample(cam.seed, w, sample, x, y, s, mine);
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
    result.stats = make_stats(cam, frame, threads, totals, start);
    return result;
}

// The camera sample for pixel (x, y): jittered uniformly over the pixel (the pixel centre when
// there is only one sample, as in the book's chapters before antialiasing), from the lens disk
// when the camera has a thin lens.
inline ray3f camera_sample(const camera_frame& frame, int spp, int x, int y, pcg32& rng) {
    float jx = 0.5f, jy = 0.5f;
    if (spp > 1) {
        jx = rng.next_float();
        jy = rng.next_float();
    }
    float lu = 0, lv = 0;
    if (frame.thin_lens) {
        float u1 = rng.next_float(), u2 = rng.next_float();
        vec3f d = sample_unit_disk(u1, u2);
        lu = d.x;
        lv = d.y;
    }
    return frame.generate(float(x) + jx, float(y) + jy, lu, lv);
}

} // namespace detail

inline std::string describe(const render_stats& s) {
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

inline render_result render(const camera& cam, const hittable& world) {
    auto start = std::chrono::steady_clock::now();
    const camera_frame frame = cam.frame();
    const compiled_scene scene = compile_scene(world, cam.lookfrom);
    const detail::environment env = detail::make_environment(cam);
    const int spp = cam.samples_per_pixel, max_depth = cam.max_depth;
    bool user_code = !scene.custom_objects.empty() || scene.has_custom_materials;
    return detail::run_tiles(
        cam, frame,
        [&](int x, int y, int, pcg32& rng, uint64_t& rays) {
            ray3f r = detail::camera_sample(frame, spp, x, y, rng);
            if (user_code) {
                // User-written shapes and materials may call random_double(): give them this
                // sample's generator so the image stays deterministic.
                detail::scoped_sample_rng guard(rng);
                return detail::trace_path(scene, env, r, max_depth, rng, rays);
            }
            return detail::trace_path(scene, env, r, max_depth, rng, rays);
        },
        start);
}

inline image camera::render_image(const hittable& world) const { return rt::render(*this, world).img; }

template <class RayColor>
image camera::render_image(const hittable& world, RayColor ray_color) const {
    auto start = std::chrono::steady_clock::now();
    const camera_frame frame = this->frame();
    const int spp = samples_per_pixel;
    const point3 origin = lookfrom;
    return detail::run_tiles(
               *this, frame,
               [&](int x, int y, int, pcg32& rng, uint64_t& rays) {
                   ray3f r = detail::camera_sample(frame, spp, x, y, rng);
                   ++rays;
                   detail::scoped_sample_rng guard(rng);
                   color c = ray_color(ray(origin + r.origin.to_double(), r.dir.to_double()), world);
                   return vec3f(c);
               },
               start)
        .img;
}

inline void camera::render(const hittable& world) const {
    try {
        write_ppm(std::cout, render_image(world));
        std::cout.flush();
    } catch (const scene_error& e) {
        std::cerr << "rtweekend: error: " << e.what() << '\n';
        std::exit(1);
    }
}

} // namespace rt
