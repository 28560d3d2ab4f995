// mpi_bench: what combining a render over MPI ranks costs (rtweekend/render/mpi_render.h), apart
// from rendering. Never run as a test; for measuring on a quiet machine or a cluster.
//
//   mpirun -n 2 mpi_bench --reduce                    a 3840x2160 image of int64 RGB sums (199 MB)
//                                                     reduced to rank 0 with MPI_SUM, as render_mpi does
//   mpirun -n 2 mpi_bench --reduce --width 1920 --height 1080 --runs 9
//   mpirun -n 2 mpi_bench --adaptive-round            one adaptive round's state over the whole
//                                                     image (8 words per pixel, MPI_Allreduce with MPI_BOR)
//
// Rank 0 prints one line per run and a summary: the median time and the rate in bytes of sums per
// second. The buffers are filled (so that no page is first touched while timed) and the ranks
// meet at a barrier before each run.

#include <rtweekend/measure/adaptive.h>

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

// The chunk size of render/mpi_render.h (MPI counts are ints).
constexpr size_t chunk = size_t(1) << 22;

[[noreturn]] void usage(int rank, const std::string& message) {
    if (rank == 0) {
        if (!message.empty()) std::fprintf(stderr, "mpi_bench: error: %s\n", message.c_str());
        std::fprintf(message.empty() ? stdout : stderr,
                     "usage: mpirun -n N mpi_bench --reduce|--adaptive-round [--width W] [--height H] [--runs R]\n"
                     "  --reduce          MPI_Reduce (MPI_SUM, to rank 0) of W x H x 3 int64 sums\n"
                     "  --adaptive-round  MPI_Allreduce (MPI_BOR) of W x H x 8 words, an adaptive round's state\n"
                     "  --width, --height the image (default 3840 x 2160), --runs the repetitions (default 5)\n");
    }
    MPI_Finalize();
    std::exit(message.empty() ? 0 : 2);
}

} // namespace

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    std::string mode;
    long long width = 3840, height = 2160, runs = 5;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto number = [&](long long max) {
            if (i + 1 >= argc) usage(rank, arg + " needs a value");
            char* end = nullptr;
            const long long v = std::strtoll(argv[++i], &end, 10);
            if (*end != '\0' || v < 1 || v > max) usage(rank, arg + " needs a number from 1 to " + std::to_string(max));
            return v;
        };
        if (arg == "--reduce" || arg == "--adaptive-round") mode = arg;
        else if (arg == "--width") width = number(1 << 16);
        else if (arg == "--height") height = number(1 << 16);
        else if (arg == "--runs") runs = number(1000);
        else if (arg == "--help" || arg == "-h") usage(rank, "");
        else usage(rank, "unknown option '" + arg + "'");
    }
    if (mode.empty()) usage(rank, "give --reduce or --adaptive-round");

    const size_t pixels = size_t(width) * size_t(height);
    const size_t words = pixels * (mode == "--reduce" ? 3 : rt::detail::adaptive_sampler::words_per_pixel);
    std::vector<uint64_t> buffer(words);
    for (size_t i = 0; i < words; ++i) buffer[i] = (uint64_t(rank) << 40) + i; // every page touched
    std::vector<double> seconds;
    for (long long run = 0; run < runs; ++run) {
        MPI_Barrier(MPI_COMM_WORLD);
        const auto start = std::chrono::steady_clock::now();
        for (size_t at = 0; at < words; at += chunk) {
            const int n = int(std::min(chunk, words - at));
            if (mode == "--reduce")
                MPI_Reduce(rank == 0 ? MPI_IN_PLACE : static_cast<const void*>(buffer.data() + at), buffer.data() + at, n,
                           MPI_INT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
            else
                MPI_Allreduce(MPI_IN_PLACE, buffer.data() + at, n, MPI_UINT64_T, MPI_BOR, MPI_COMM_WORLD);
        }
        double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        MPI_Allreduce(MPI_IN_PLACE, &t, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD); // the slowest rank's
        seconds.push_back(t);
        if (rank == 0) std::printf("run %lld: %.4f s\n", run + 1, t);
    }
    if (rank == 0) {
        std::sort(seconds.begin(), seconds.end());
        const double median = seconds[seconds.size() / 2];
        const double bytes = double(words) * 8;
        std::printf("%s %lldx%lld on %d ranks: %.1f MB per rank, median %.4f s (%.0f MB/s per rank), runs %lld\n",
                    mode.c_str() + 2, width, height, ranks, bytes * 1e-6, median, bytes * 1e-6 / median, runs);
    }
    MPI_Finalize();
    return 0;
}
