// ab_compare: two builds of this library side by side in one process, to measure a change.
//
//   ab_compare --mesh FILE.obj --rays FILE.rays [--rays MORE.rays ...] [--rounds N]
//   ab_compare --scene FILE [--width N] [--spp N] [--rounds N]
//
// Build A is compiled from the tree named by the CMake cache variable RTWEEKEND_AB_BASE (a checkout
// of another commit, e.g. `git worktree add /tmp/base HEAD~1`), build B from this tree; by default
// both are this tree, which measures the noise itself. Each round times A and B once each, one
// after the other, the order reversed every other round, on one thread: every ray file traced once
// (one ray at a time, as bench does), or the scene rendered once. It prints, per workload, each
// build's median, the median of the per-round ratios B/A with its quartiles, and whether the two
// found the same hits or made the same image, bit for bit; when they did not, it exits with 1
// (after the timings), as embree_bench stops when the hit counts differ.
//
// Why: on a shared machine the speed of one process drifts by 10-20 % from minute to minute, so
// builds timed in separate processes differ by more than most changes do. Interleaved in one
// process, round by round, both see the same drift: the per-round ratios' quartiles span about
// 2 % where separate processes' spanned 20 % (BENCHMARKS.md section 23).

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#define AB_DECLARE(v)                                                                               \
    void* ab_##v##_load_mesh(const char* obj, char* error, size_t error_size);                     \
    bool ab_##v##_add_rays(void* workload, const char* path, char* error, size_t error_size);       \
    double ab_##v##_trace(void* workload, int which, uint64_t* hits, double* sum_t);                \
    size_t ab_##v##_ray_count(void* workload, int which);                                           \
    void* ab_##v##_load_scene(const char* path, int width, int spp, char* error, size_t error_size); \
    double ab_##v##_render(void* workload, uint64_t* checksum);                                     \
    void ab_##v##_free_mesh(void* workload);                                                        \
    void ab_##v##_free_scene(void* workload);

extern "C" {
AB_DECLARE(a)
AB_DECLARE(b)
}

namespace {

struct options {
    std::string mesh, scene;
    std::vector<std::string> rays;
    int rounds = 10, width = 0, spp = 0;
};

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "ab_compare: %s\n", message.c_str());
    std::fprintf(stderr, "usage: ab_compare --mesh FILE.obj --rays FILE.rays [--rays ...] [--rounds N]\n"
                         "       ab_compare --scene FILE [--width N] [--spp N] [--rounds N]\n");
    std::exit(2);
}

int positive_int(const std::string& flag, const char* text) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < 1 || v > 1000000) usage_error(flag + " needs an integer from 1 to 1000000");
    return int(v);
}

options parse(int argc, char** argv) {
    options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> const char* {
            if (i + 1 >= argc) usage_error(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--mesh") o.mesh = value();
        else if (arg == "--rays") o.rays.push_back(value());
        else if (arg == "--scene") o.scene = value();
        else if (arg == "--rounds") o.rounds = positive_int(arg, value());
        else if (arg == "--width") o.width = positive_int(arg, value());
        else if (arg == "--spp") o.spp = positive_int(arg, value());
        else usage_error("unknown argument '" + arg + "'");
    }
    if (o.mesh.empty() == o.scene.empty()) usage_error("give --mesh (with --rays) or --scene");
    if (!o.mesh.empty() && o.rays.empty()) usage_error("--mesh needs at least one --rays file");
    return o;
}

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * double(v.size() - 1);
    const size_t lo = size_t(pos);
    const size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - double(lo)) * (v[hi] - v[lo]);
}

// One workload's rounds: a and b time A and B once each and say whether their outputs agree.
// Returns whether they agreed in every round.
template <class RunA, class RunB, class Same>
bool compare(const std::string& name, int rounds, const char* unit, RunA run_a, RunB run_b, Same same) {
    std::vector<double> ta, tb, ratio;
    bool identical = true;
    for (int r = 0; r < rounds; ++r) {
        double a, b;
        if (r % 2 == 0) {
            a = run_a();
            b = run_b();
        } else {
            b = run_b();
            a = run_a();
        }
        identical = identical && same();
        ta.push_back(a);
        tb.push_back(b);
        ratio.push_back(a / b); // > 1: B is faster
        std::fprintf(stderr, "ab_compare: %s: round %d/%d: A %.4f s, B %.4f s, A/B %.4f\n", name.c_str(), r + 1, rounds, a,
                     b, a / b);
    }
    std::printf("%s: A %.4f s, B %.4f s (medians of %d rounds, %s); speed B/A median %.4f, quartiles %.4f %.4f; %s\n",
                name.c_str(), quantile(ta, 0.5), quantile(tb, 0.5), rounds, unit, quantile(ratio, 0.5),
                quantile(ratio, 0.25), quantile(ratio, 0.75), identical ? "outputs identical" : "OUTPUTS DIFFER");
    if (!identical) std::fprintf(stderr, "ab_compare: error: %s: builds A and B gave different outputs\n", name.c_str());
    return identical;
}

} // namespace

int main(int argc, char** argv) {
    const options o = parse(argc, argv);
    char error[512] = "";
    if (!o.mesh.empty()) {
        void* a = ab_a_load_mesh(o.mesh.c_str(), error, sizeof error);
        void* b = a ? ab_b_load_mesh(o.mesh.c_str(), error, sizeof error) : nullptr;
        if (!a || !b) {
            std::fprintf(stderr, "ab_compare: error: %s\n", error);
            return 1;
        }
        for (const std::string& path : o.rays)
            if (!ab_a_add_rays(a, path.c_str(), error, sizeof error) || !ab_b_add_rays(b, path.c_str(), error, sizeof error)) {
                std::fprintf(stderr, "ab_compare: error: %s\n", error);
                return 1;
            }
        bool identical = true;
        for (size_t f = 0; f < o.rays.size(); ++f) {
            uint64_t hits_a = 0, hits_b = 0;
            double sum_a = 0, sum_b = 0;
            const int which = int(f);
            identical &= compare(
                o.rays[f] + " (" + std::to_string(ab_a_ray_count(a, which)) + " rays)", o.rounds, "one pass over the rays",
                [&] { return ab_a_trace(a, which, &hits_a, &sum_a); }, [&] { return ab_b_trace(b, which, &hits_b, &sum_b); },
                [&] { return hits_a == hits_b && sum_a == sum_b; });
        }
        ab_a_free_mesh(a);
        ab_b_free_mesh(b);
        return identical ? 0 : 1;
    }
    // Each build loads the scene as a new program would: Perlin noise draws its tables from the C
    // library's rand() (as the book's does), whose state the two builds share in this process.
    std::srand(1);
    void* a = ab_a_load_scene(o.scene.c_str(), o.width, o.spp, error, sizeof error);
    std::srand(1);
    void* b = a ? ab_b_load_scene(o.scene.c_str(), o.width, o.spp, error, sizeof error) : nullptr;
    if (!a || !b) {
        std::fprintf(stderr, "ab_compare: error: %s\n", error);
        return 1;
    }
    uint64_t sum_a = 0, sum_b = 0;
    const bool identical = compare(
        o.scene, o.rounds, "one render on one thread", [&] { return ab_a_render(a, &sum_a); },
        [&] { return ab_b_render(b, &sum_b); }, [&] { return sum_a == sum_b; });
    ab_a_free_scene(a);
    ab_b_free_scene(b);
    return identical ? 0 : 1;
}
