#pragma once
// The render loop: tiles on std::thread workers, and the path tracer.
//
//   render_result render(const camera& cam, const hittable& world);   // image + statistics
//
// The world is first compiled into a flat scene (scene.h). The image is cut into 16x16 tiles
// that workers take from an atomic counter; each pixel's samples are drawn from generators
// seeded by (seed, pixel, sample), so the image is bit-identical for any thread count. A sample
// that comes out NaN or infinite is dropped and counted; the count is reported. Progress and the
// final statistics (rays, seconds, Mrays/s) go to stderr unless cam.quiet is set.

#include "camera.h"
#include "image.h"
#include "ray_offset.h"
#include "rng.h"
#include "scene.h"

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

// Adaptive sampling's stopping rule for one pixel (see camera::adaptive_error): a running mean
// and variance of the samples' luminance, and a confidence interval checked every 8 samples.
class adaptive_stop {
  public:
    explicit adaptive_stop(const camera& cam)
        : error_(cam.adaptive_error), min_samples_(std::max(2, cam.adaptive_min_samples)) {}

    // Records the sample; true when the pixel has enough.
    bool enough(const vec3f& c, int taken) {
        if (error_ <= 0) return false;
        // Rec. 709 luminance: the noise a viewer sees is mostly in brightness.
        double y = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
        sum_ += y;
        sum_squares_ += y * y;
        if (taken < min_samples_ || (taken - min_samples_) % check_every != 0) return false;
        double n = taken, mean = sum_ / n;
        double variance = std::max(0.0, (sum_squares_ - n * mean * mean) / (n - 1));
        double half_width = 1.96 * std::sqrt(variance / n); // 95 % interval of the mean
        // "Relative to the pixel's value" means the value of the first min_samples samples, fixed
        // from then on: a target that followed the running mean would let a pixel stop sooner
        // whenever its mean happened to be high, and bias the image upwards.
        if (taken == min_samples_) scale_ = std::sqrt(mean * mean + 0.01);
        // The target loosens as sqrt(n / min_samples): a pixel stops once sigma / n, the error
        // one more sample would remove, is small, which spends samples in proportion to a
        // pixel's noise (the allocation that minimises the image's total squared error). A fixed
        // target would spend them in proportion to the noise squared, and pour the budget into
        // the few noisiest pixels.
        return half_width <= error_ * scale_ * std::sqrt(n / min_samples_);
    }

  private:
    static constexpr int check_every = 8;
    double error_;
    int min_samples_;
    double sum_ = 0, sum_squares_ = 0;
    double scale_ = 1;
};

// Runs `sample(x, y, s, rng, rays)` -> vec3f for every sample of every pixel, in tiles on
// worker threads, and averages the samples into an image.
template <class SampleFn>
render_result run_tiles(const camera& cam, const camera_frame& frame, SampleFn&& sample,
                        std::chrono::steady_clock::time_point start) {
    constexpr int tile = 16;
    const int w = frame.width, h = frame.height, spp = cam.samples_per_pixel;
    const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile, tile_count = tiles_x * tiles_y;
    int threads = cam.threads > 0 ? cam.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, tile_count);

    render_result result;
    result.img = image(w, h);
    std::vector<float>& pixels = result.img.data();
    std::atomic<int> next_tile{0}, tiles_done{0}, percent_shown{0};
    std::atomic<uint64_t> total_rays{0}, total_nonfinite{0}, total_samples{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    std::atomic<bool> failed{false};

    const bool interactive = stderr_is_terminal();
    if (!cam.quiet && !interactive) std::fprintf(stderr, "rtweekend: rendering");

    auto worker = [&] {
        scoped_flush_denormals flush; // this thread's float mode, restored when the worker ends
        uint64_t rays = 0, nonfinite = 0, samples = 0;
        try {
            for (int t = next_tile++; t < tile_count && !failed; t = next_tile++) {
                int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
                int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
                for (int y = y0; y < y1; ++y) {
                    for (int x = x0; x < x1; ++x) {
                        uint64_t pixel = uint64_t(y) * uint64_t(w) + uint64_t(x);
                        double sum[3] = {0, 0, 0};
                        adaptive_stop stop(cam);
                        int taken = 0;
                        while (taken < spp) {
                            pcg32 rng = sample_rng(cam.seed, pixel, uint64_t(taken));
                            vec3f c = sample(x, y, taken, rng, rays);
                            ++taken;
                            if (!is_finite(c)) { // dropped: it counts as a sample of 0
                                ++nonfinite;
                                c = {0, 0, 0};
                            }
                            sum[0] += c.x;
                            sum[1] += c.y;
                            sum[2] += c.z;
                            if (stop.enough(c, taken)) break;
                        }
                        samples += uint64_t(taken);
                        float* out = &pixels[pixel * 3];
                        for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(sum[k] / taken);
                    }
                }
                int done = ++tiles_done;
                if (!cam.quiet) {
                    // A terminal gets a counter updated in place; a log gets every tenth percent.
                    int step = interactive ? 1 : 10;
                    int pct = int(int64_t(done) * 100 / tile_count) / step * step;
                    int shown = percent_shown.load();
                    while (pct > shown && !percent_shown.compare_exchange_weak(shown, pct)) {}
                    if (pct > shown) {
                        if (interactive) std::fprintf(stderr, "\rrtweekend: rendering %3d%%", pct);
                        else std::fprintf(stderr, " %d%%", pct);
                    }
                }
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            failed = true;
        }
        total_rays += rays;
        total_nonfinite += nonfinite;
        total_samples += samples;
    };

    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    if (!cam.quiet) std::fprintf(stderr, "\n");
    if (failure) std::rethrow_exception(failure);

    render_stats& st = result.stats;
    st.width = w;
    st.height = h;
    st.samples_per_pixel = spp;
    st.threads = threads;
    st.rays = total_rays;
    st.samples = total_samples;
    st.samples_saved = uint64_t(w) * uint64_t(h) * uint64_t(spp) - total_samples;
    st.nonfinite_samples = total_nonfinite;
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!cam.quiet) std::fprintf(stderr, "%s\n", describe(st).c_str());
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
