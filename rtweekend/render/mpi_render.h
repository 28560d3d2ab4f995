#pragma once
// One render split over the ranks of an MPI communicator, with the same image, byte for byte, as
// one process makes. Only MPI programs include this header (it includes <mpi.h>); nothing else in
// rtweekend/ includes it, so every other header stays usable without MPI.
//
//   MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
//   rt::render_result r = rt::mpi::path_trace(MPI_COMM_WORLD, world, cam.frame(), cam.sky(),
//                                             cam.settings());          // on every rank
//   if (rank == 0) rt::write_image("out.png", r.img);                   // the image is rank 0's
//
// Call these from the thread that initialised MPI (at least MPI_THREAD_FUNNELED: the worker
// threads of each rank never call MPI), on every rank of the communicator, in the same order.
//
// How the work is split. Every rank loads and compiles the whole scene and uses all its threads
// on its part:
//   - uniform sampling: the sample range [F, E) of every pixel (F, E from the settings, the whole
//     range by default) in contiguous parts, rank r taking [F + (E - F) r / N, F + (E - F)(r + 1) / N),
//     when that splits well: E - F a multiple of the N ranks, or at least 4 samples per rank (a
//     rank then does at most 5/4 of the average). Otherwise, and always for the Whitted integrator
//     (one sample per pixel), the 16x16 tiles in turn: rank r takes tiles r, r + N, r + 2N, ...
//     The parts are exact fixed-point sums (fixed_point.h), added by MPI_Reduce with MPI_SUM on
//     rank 0: integer addition is associative and commutative and no partial sum can overflow
//     (each pixel's samples over all ranks are at most spp clamped ones), so whatever order the
//     reduction tree adds them in, rank 0 holds the integers one process would have.
//   - adaptive sampling: every rank keeps the whole state and plans the same rounds; each round's
//     pixels are split into equal shares of samples, and after the round MPI_Allreduce with
//     MPI_BOR gives every rank every pixel's new state (each word non-zero only on the rank that
//     sampled that pixel: OR with zeros is exact, for integers and for the bits of doubles alike).
//     The next round's plan is then the same on every rank, and the same as one process's.
//
// Failure. A rank that fails (bad input, no memory) must not leave the others waiting in a
// collective for it: every rank passes the same agreement points (agree(): an allreduce of a
// status, then the lowest failing rank's message broadcast): once its scene is compiled (render
// _share::ready(), called by the scheduler) and after its part of the render. A failure anywhere
// is then thrown on every rank as the same rank_error, naming the lowest failing rank and its
// message. A rank killed outright (SIGKILL, the OOM killer) cannot take part: MPI's runtime ends
// the job (mpirun reports the rank and the signal), and since rank 0 writes its output only at
// the end, and atomically, no half-written file is left either way. Interrupting (render_settings
// ::stop) is not supported here: the ranks would stop at different points; mpirun ends a job on
// Ctrl-C.
//
// Progress goes to stderr from rank 0 only (its own part: the parts are balanced), and the
// statistics line once, for the whole render, from rank 0 (unless settings.quiet).

#include "../core/scene_error.h"
#include "camera_frame.h"
#include "environment.h"
#include "fixed_point.h"
#include "path_tracer.h"
#include "render_settings.h"
#include "scheduler.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace rt::mpi {

// A failure on one rank, known to every rank: the functions here throw it on all ranks alike.
// what() is "rank R: <the rank's message>".
class rank_error : public scene_error {
  public:
    rank_error(int rank, const std::string& problem)
        : scene_error("rank " + std::to_string(rank) + ": " + problem), rank_(rank), problem_(problem) {}
    int rank() const { return rank_; }
    const std::string& problem() const { return problem_; }

  private:
    int rank_;
    std::string problem_;
};

int rank_of(MPI_Comm comm);
int size_of(MPI_Comm comm);

// Every rank calls this at the same point with its own outcome: "" for success, else its error
// message. Returns if every rank succeeded; otherwise throws rank_error, the same on every rank,
// with the lowest failing rank and its message.
void agree(MPI_Comm comm, const std::string& error);

// Runs step() on every rank and agrees on how it went (a scene_error's or other exception's
// message, "out of memory" for bad_alloc): step()'s result, or rank_error on every rank.
template <class Step>
auto together(MPI_Comm comm, Step&& step) -> decltype(step());

// Throws rank_error on every rank unless every rank holds the same `value` as rank 0: the lowest
// rank that differs is named, with "its <what> differs from rank 0's ('<its>' against '<rank 0's>')".
void require_same(MPI_Comm comm, const std::string& value, const std::string& what);

// The path tracer over all ranks of `comm` (see the top). Every rank returns the whole render's
// statistics; rank 0 the image (and with settings.keep_sums the sums), the others an empty image.
// settings.stop must be null.
render_result path_trace(MPI_Comm comm, const hittable& world, const camera_frame& frame, const environment& env,
                         const render_settings& settings, const std::vector<point_light>& point_lights = {},
                         const std::vector<directional_light>& directional_lights = {});
// The same for a scene every rank has compiled already (each camera of a course scene, say).
render_result path_trace(MPI_Comm comm, const compiled_scene& scene, const camera_frame& frame, const environment& env,
                         const render_settings& settings);

// The course scenes' Whitted integrator over ranks is in course/whitted_mpi.h.

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

// MPI counts are ints: large buffers go in pieces of this many elements (32 MiB of int64s, which
// also bounds the temporary memory MPI may take for a reduction).
inline constexpr size_t chunk_elements = size_t(1) << 22;

// The longest message agree() passes on: an error line, not a file.
inline constexpr size_t max_message = 4096;

inline std::string describe(std::exception_ptr e) {
    try {
        std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
        return "out of memory";
    } catch (const std::exception& x) {
        std::string text = x.what();
        return text.empty() ? "unknown error" : text;
    } catch (...) {
        return "unknown error";
    }
}

// The rank's part of a render shared over a communicator (render_share in render_settings.h).
class communicator_share : public render_share {
  public:
    communicator_share(MPI_Comm comm, bool by_tiles) : render_share(rank_of(comm), size_of(comm), by_tiles), comm_(comm) {}

    // The first agreement point: every rank has compiled its scene. Throws rank_error if one failed.
    void ready() const override {
        ready_called_ = true;
        try {
            agree(comm_, "");
        } catch (const rank_error&) {
            failed_ = true;
            throw;
        }
    }

    // After each adaptive round: a failure on any rank, thrown on every rank.
    void round_done(std::exception_ptr failure) const override {
        try {
            agree(comm_, failure ? describe(failure) : "");
        } catch (const rank_error&) {
            failed_ = true;
            throw;
        }
    }

    void combine_owned(uint64_t* words, size_t count) const override {
        for (size_t at = 0; at < count; at += chunk_elements) {
            const int n = int(std::min(chunk_elements, count - at));
            MPI_Allreduce(MPI_IN_PLACE, words + at, n, MPI_UINT64_T, MPI_BOR, comm_);
        }
    }

    void reset() const { ready_called_ = failed_ = false; }
    bool ready_called() const { return ready_called_; }
    // Whether an agreement inside the render failed: every rank knows, and threw it already.
    bool failed() const { return failed_; }

  private:
    MPI_Comm comm_;
    mutable bool ready_called_ = false, failed_ = false;
};

// How a uniform render of `samples` samples per pixel splits over `ranks`: by samples when that
// is balanced (see the top), otherwise by tiles.
inline bool split_by_samples(int64_t samples, int ranks) {
    return samples % ranks == 0 || samples >= 4 * int64_t(ranks);
}

// This rank's part of a render: runs part(s) with this rank's settings, agrees on the outcome,
// and combines the parts on rank 0. `settings` is the whole render's.
template <class Part>
render_result run_shared(MPI_Comm comm, const communicator_share& share, const render_settings& settings, Part&& part) {
    const auto start = std::chrono::steady_clock::now();
    const int rank = share.rank, ranks = share.ranks;
    share.reset();
    render_settings mine = settings;
    mine.share = &share;
    mine.stop = nullptr;
    mine.quiet = settings.quiet || rank != 0; // progress from rank 0 only
    const bool adaptive = settings.adaptive_error > 0;
    const int64_t first = settings.first_sample, end = settings.sample_end();
    if (!adaptive) {
        mine.keep_sums = true;
        if (!share.by_tiles) {
            mine.first_sample = int(first + (end - first) * rank / ranks);
            mine.end_sample = int(first + (end - first) * (rank + 1) / ranks);
        }
    }

    render_result r;
    std::string error;
    try {
        if (settings.stop != nullptr) throw scene_error("an MPI render cannot be interrupted (settings.stop must be null)");
        r = part(mine);
    } catch (const rank_error&) {
        if (share.failed()) throw; // an agreement inside the render: every rank knows already
        error = describe(std::current_exception());
    } catch (...) {
        error = describe(std::current_exception());
    }
    // A rank that failed before its scene was ready still owes the others that agreement.
    if (!share.ready_called()) agree(comm, error.empty() ? "the render never started" : error);
    agree(comm, error); // failures during the render

    // The statistics of the whole render, on every rank.
    uint64_t totals[4] = {r.stats.rays, r.stats.samples, r.stats.nonfinite_samples, r.stats.saturated_samples};
    MPI_Allreduce(MPI_IN_PLACE, totals, 4, MPI_UINT64_T, MPI_SUM, comm);
    int threads = r.stats.threads;
    MPI_Allreduce(MPI_IN_PLACE, &threads, 1, MPI_INT, MPI_SUM, comm);
    render_stats st = r.stats;
    st.rays = totals[0];
    st.samples = totals[1];
    st.nonfinite_samples = totals[2];
    st.saturated_samples = totals[3];
    st.threads = threads;
    st.ranks = ranks;
    st.first_sample = int(first);
    st.end_sample = int(end);
    const uint64_t pixels = uint64_t(st.width) * uint64_t(st.height);

    if (adaptive) {
        // Every rank ended with the whole state, so the image and the per-pixel counts in its
        // statistics are already the whole render's; only the sample totals were this rank's.
        const uint64_t planned = pixels * uint64_t(settings.samples_per_pixel);
        st.samples_saved = planned > st.samples ? planned - st.samples : 0;
        if (rank != 0) r.img = image();
    } else {
        if (st.samples != pixels * uint64_t(end - first))
            throw scene_error("the ranks took " + std::to_string(st.samples) + " samples, not the " +
                              std::to_string(pixels * uint64_t(end - first)) + " of the render");
        pixel_sums& sums = r.sums;
        for (size_t at = 0; at < sums.rgb.size(); at += chunk_elements) {
            const int n = int(std::min(chunk_elements, sums.rgb.size() - at));
            // The order of the additions does not matter: see the top.
            MPI_Reduce(rank == 0 ? MPI_IN_PLACE : static_cast<const void*>(sums.rgb.data() + at), sums.rgb.data() + at, n,
                       MPI_INT64_T, MPI_SUM, 0, comm);
        }
        st.min_pixel_samples = st.max_pixel_samples = int(end - first);
        st.pixels_without_samples = 0;
        st.samples_saved = 0;
        if (rank == 0) {
            std::fill(sums.counts.begin(), sums.counts.end(), int32_t(end - first));
            r.img = mean_image(sums);
            if (!settings.keep_sums) r.sums = pixel_sums();
        } else {
            r.img = image();
            r.sums = pixel_sums();
        }
    }
    st.interrupted = false;
    st.completed = 1;
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, comm);
    st.seconds = seconds;
    r.stats = st;
    if (rank == 0 && !settings.quiet) std::fprintf(stderr, "%s\n", stats_line(st).c_str());
    return r;
}

} // namespace detail

inline int rank_of(MPI_Comm comm) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    return rank;
}

inline int size_of(MPI_Comm comm) {
    int size = 1;
    MPI_Comm_size(comm, &size);
    return size;
}

inline void agree(MPI_Comm comm, const std::string& error) {
    const int rank = rank_of(comm), size = size_of(comm);
    int mine = error.empty() ? size : rank, lowest = size;
    MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, comm);
    if (lowest == size) return;
    // The lowest failing rank tells the others what went wrong.
    unsigned long long length = rank == lowest ? std::min(error.size(), detail::max_message) : 0;
    MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, lowest, comm);
    std::string message = rank == lowest ? error.substr(0, size_t(length)) : std::string(size_t(length), ' ');
    if (length > 0) MPI_Bcast(&message[0], int(length), MPI_CHAR, lowest, comm);
    throw rank_error(lowest, message);
}

template <class Step>
auto together(MPI_Comm comm, Step&& step) -> decltype(step()) {
    using result = decltype(step());
    std::string error;
    if constexpr (std::is_void_v<result>) {
        try {
            step();
        } catch (...) {
            error = detail::describe(std::current_exception());
        }
        agree(comm, error);
    } else {
        std::unique_ptr<result> value;
        try {
            value = std::make_unique<result>(step());
        } catch (...) {
            error = detail::describe(std::current_exception());
        }
        agree(comm, error);
        return std::move(*value);
    }
}

inline void require_same(MPI_Comm comm, const std::string& value, const std::string& what) {
    unsigned long long length = value.size();
    MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
    std::string first = rank_of(comm) == 0 ? value : std::string(size_t(length), ' ');
    for (size_t at = 0; at < first.size(); at += detail::chunk_elements)
        MPI_Bcast(&first[at], int(std::min(detail::chunk_elements, first.size() - at)), MPI_CHAR, 0, comm);
    agree(comm, value == first ? "" : "its " + what + " differs from rank 0's ('" + value + "' against '" + first + "')");
}

inline render_result path_trace(MPI_Comm comm, const hittable& world, const camera_frame& frame, const environment& env,
                                const render_settings& settings, const std::vector<point_light>& point_lights,
                                const std::vector<directional_light>& directional_lights) {
    const int ranks = size_of(comm);
    const bool by_tiles = settings.adaptive_error == 0 &&
                          !detail::split_by_samples(settings.sample_end() - settings.first_sample, ranks);
    const detail::communicator_share share(comm, by_tiles);
    return detail::run_shared(comm, share, settings, [&](const render_settings& mine) {
        return rt::path_trace(world, frame, env, mine, point_lights, directional_lights);
    });
}

inline render_result path_trace(MPI_Comm comm, const compiled_scene& scene, const camera_frame& frame,
                                const environment& env, const render_settings& settings) {
    const int ranks = size_of(comm);
    const bool by_tiles = settings.adaptive_error == 0 &&
                          !detail::split_by_samples(settings.sample_end() - settings.first_sample, ranks);
    const detail::communicator_share share(comm, by_tiles);
    return detail::run_shared(comm, share, settings, [&](const render_settings& mine) {
        return rt::path_trace(scene, frame, env, mine);
    });
}

} // namespace rt::mpi
