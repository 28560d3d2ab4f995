#pragma once
// render_settings: how a render samples the image, apart from what it looks at (the camera) and
// what it traces (the compiled scene). The scheduler (scheduler.h) and the integrators (the path
// tracer, path_tracer.h; the Whitted integrator, course/whitted.h) read these, each the fields it
// uses; the book's camera carries one (camera::settings), beside the book's own fields. A new
// setting is a field here (and a flag in the apps that offer it).

#include "../core/scene_error.h"
#include "sampler.h"

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

namespace rt {

// One process's part of a render that several processes share (MPI ranks: render/mpi_render.h
// implements this over a communicator). The scheduler (scheduler.h) knows no MPI: it asks this
// interface, and only where a shared render differs from a lone one:
//   - ready(): called once by every process when its scene is compiled, before the first sample.
//     A process that failed before (a bad scene, no memory) never gets there; the MPI share
//     agrees on it here and throws on every process, so none waits for a partner that is gone.
//   - by_tiles: uniform sampling takes only the 16x16 tiles t with t % ranks == rank (the
//     Whitted integrator's one sample per pixel cannot be split by samples); otherwise the share
//     takes every tile and the caller splits the sample range (render_settings::first_sample).
//   - adaptive sampling: each round's work is split by pixel (measure/adaptive.h). After the
//     round, round_done() is called on every process with the round's failure on this one (or
//     null): the processes agree on it before anything else, and a failure anywhere is thrown on
//     all. Then combine_owned() gives every process every pixel's new state: each word is non-zero
//     on at most the one process that computed it, so the combination is exact (MPI: bitwise OR),
//     and every process plans the next round from the same state as a lone process would.
class render_share {
  public:
    render_share(int rank_, int ranks_, bool by_tiles_) : rank(rank_), ranks(ranks_), by_tiles(by_tiles_) {}
    virtual ~render_share() = default;
    virtual void ready() const = 0;
    virtual void round_done(std::exception_ptr failure) const = 0;
    virtual void combine_owned(uint64_t* words, size_t count) const = 0;

    int rank = 0, ranks = 1; // this process, of all that share the render
    bool by_tiles = false;
};

// How the path tracer estimates the light arriving at a surface (path_tracer.h):
//   nee       next-event estimation: at every diffuse or glossy surface a light is sampled and a
//             shadow ray tested, besides the material's own sample; the two are weighed by
//             multiple importance sampling (power heuristic). Russian roulette ends long paths.
//   bsdf      the books' path tracer: the material's sample alone; a light is found only when a
//             ray happens to hit it (point lights never are)
//   mixture   book 3's estimator: one direction, drawn half the time towards the lights and half
//             from the material, weighed by the mixture of the two densities
enum class path_estimator : uint8_t { nee, bsdf, mixture };

inline const char* estimator_name(path_estimator e) {
    switch (e) {
    case path_estimator::nee: return "nee";
    case path_estimator::bsdf: return "bsdf";
    case path_estimator::mixture: return "mixture";
    }
    return "?";
}

// The estimator named `name` ("nee", "bsdf" or "mixture"); false for another name.
inline bool parse_estimator(const std::string& name, path_estimator& e) {
    for (path_estimator candidate : {path_estimator::nee, path_estimator::bsdf, path_estimator::mixture})
        if (name == estimator_name(candidate)) {
            e = candidate;
            return true;
        }
    return false;
}

// The classic (Whitted) integrator's own settings: course/whitted.h says what each does.
struct whitted_settings {
    bool cull_back_faces = false;        // skip back faces of opaque objects for primary and reflected rays
    float min_branch_weight = 1.0f / (1 << 24); // a branch lighter than this in every channel is not followed
    uint32_t max_branch_rays = 1u << 14; // the most rays that follow one camera ray
    bool shade_inside_dielectrics = false; // local shading at hits on glass from inside (the course: none)
};

struct render_settings {
    int samples_per_pixel = 10; // most samples a pixel takes (all of them without adaptive sampling)
    int max_depth = 10;         // most rays in one path (the path tracer)
    uint64_t seed = 0;          // the same seed gives the same image at any thread count
    int threads = 0;            // worker threads; 0 = one per processor this process may use
    bool quiet = false;         // no progress or statistics on stderr
    // Adaptive sampling (measure/adaptive.h), off while adaptive_error is 0: every pixel takes
    // adaptive_min_samples samples, then more until its error estimate is small enough.
    double adaptive_error = 0;
    int adaptive_min_samples = 16;
    path_estimator estimator = path_estimator::nee; // the path tracer's
    // Caustics traced from the lights (render/caustic_paths.h), with nee and uniform sampling: light
    // paths per pixel per sample; 0 leaves caustics to the camera paths alone.
    double caustic_paths = 0.25;
    sampler_kind sampler = sampler_kind::sobol;      // where a sample's numbers come from (sampler.h)
    // The samples this render takes of every pixel: [first_sample, end_sample), end_sample 0 meaning
    // samples_per_pixel. Sample s is the same sample in any range (its numbers depend on (seed,
    // pixel, s) and on samples_per_pixel, the whole render's), so renders of disjoint ranges add up
    // to the whole render exactly (render/fixed_point.h): `render --samples A:B` slices
    // (io/slice_file.h), MPI ranks. Uniform sampling only: adaptive sampling decides its counts.
    int first_sample = 0;
    int end_sample = 0;
    // Keep the exact fixed-point sums in render_result::sums (uniform sampling), for whoever adds
    // renders of parts together. Off by default: they take twice the memory of the image.
    bool keep_sums = false;
    // A render shared with other processes (see render_share above); null for a lone render.
    const render_share* share = nullptr;
    // The Whitted integrator's (course/whitted.h); the path tracer ignores them.
    whitted_settings whitted;
    // Set to true (from any thread, e.g. an app's SIGINT handling) to stop the render early: the
    // scheduler polls it between pixels and returns the average of the samples taken so far
    // (render_stats::interrupted). The caller owns the flag; the library installs no signal handler.
    const std::atomic<bool>* stop = nullptr;

    // Throws scene_error "<owner>: <problem>" for a setting that cannot be rendered.
    void check(const std::string& owner = "render settings") const;

    // The end of the sample range: end_sample, or samples_per_pixel when it is 0.
    int sample_end() const { return end_sample != 0 ? end_sample : samples_per_pixel; }
    bool whole_sample_range() const { return first_sample == 0 && sample_end() == samples_per_pixel; }
};

// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES
RTWEEKEND_ENGINE_FUNCTION void render_settings::check(const std::string& owner) const {
    auto require = [&](bool ok, const std::string& problem) {
        if (!ok) throw scene_error(owner + ": " + problem);
    };
    require(samples_per_pixel >= 1, "samples_per_pixel must be at least 1, got " + std::to_string(samples_per_pixel));
    require(max_depth >= 1, "max_depth must be at least 1, got " + std::to_string(max_depth));
    require(threads >= 0, "threads must be 0 (all cores) or more, got " + std::to_string(threads));
    require(std::isfinite(adaptive_error) && adaptive_error >= 0,
            "adaptive_error must be 0 (off) or positive, got " + number_text(adaptive_error));
    require(std::isfinite(caustic_paths) && caustic_paths >= 0 && caustic_paths <= 1024,
            "caustic_paths must lie in [0, 1024] (light paths per pixel per sample), got " +
                number_text(caustic_paths));
    require(adaptive_min_samples >= 2, "adaptive_min_samples must be at least 2 (a variance needs two samples), got " +
                                           std::to_string(adaptive_min_samples));
    const int end = sample_end();
    require(first_sample >= 0 && first_sample < end && end <= samples_per_pixel,
            "the sample range [" + std::to_string(first_sample) + ", " + std::to_string(end) +
                ") must be a non-empty part of [0, " + std::to_string(samples_per_pixel) + ")");
    require(adaptive_error == 0 || (first_sample == 0 && end == samples_per_pixel),
            "a sample range applies to uniform sampling only (adaptive sampling decides how many samples a "
            "pixel takes)");
    require(share == nullptr || (share->ranks >= 1 && share->rank >= 0 && share->rank < share->ranks),
            "a shared render's rank must lie in [0, ranks)");
    require(whitted.min_branch_weight >= 0 && whitted.min_branch_weight < 1,
            "whitted.min_branch_weight must be in [0, 1)");
}
#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt
