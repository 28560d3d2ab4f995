#pragma once
// The course scenes' Whitted integrator (course/whitted.h) over the ranks of an MPI communicator:
// every camera of the scene, each split by tiles (render/mpi_render.h says how a render is shared
// and how failures are agreed on). Only MPI programs include this header.
//
//   std::vector<rt::whitted_render> images = rt::mpi::render_whitted(MPI_COMM_WORLD, scene, settings);

#include "../render/mpi_render.h"
#include "whitted.h"
#include "whitted_scene.h"

#include <memory>
#include <vector>

namespace rt::mpi {

// Every camera of a course scene with the Whitted integrator, each split by tiles. Rank 0 gets the
// images, the others empty ones; statistics on every rank.
std::vector<whitted_render> render_whitted(MPI_Comm comm, const whitted_scene& scene, const render_settings& settings);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline std::vector<whitted_render> render_whitted(MPI_Comm comm, const whitted_scene& scene,
                                                  const render_settings& settings) {
    const detail::communicator_share share(comm, /*by_tiles=*/true);
    render_settings mine = settings;
    mine.share = &share;
    mine.keep_sums = true;
    mine.quiet = settings.quiet || share.rank != 0;
    // Compiling the scene may fail on one rank: agreed on before any camera is rendered.
    std::unique_ptr<whitted_renderer> renderer = together(comm, [&] { return std::make_unique<whitted_renderer>(scene); });
    render_settings whole; // the Whitted integrator's: one sample through each pixel's centre
    whole.samples_per_pixel = 1;
    whole.threads = settings.threads;
    whole.quiet = settings.quiet;
    std::vector<whitted_render> out;
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        render_result r = detail::run_shared(comm, share, whole, [&](const render_settings&) {
            whitted_render w = renderer->render(i, mine);
            return render_result{std::move(w.img), w.stats, std::move(w.sums)};
        });
        out.push_back({std::move(r.img), r.stats, pixel_sums()});
    }
    return out;
}

} // namespace rt::mpi
