// bench: how fast the renderer is. Never a test: machines are shared and noisy, so every figure
// is the median of several runs, and comparisons are made side by side in one run.
//
//   bench --scene FILE [--width N] [--spp N] [--depth N] [--threads N] [--runs N]
//       renders the scene file; prints rays, seconds and Mrays/s (median), BVH size, peak memory
//   bench --mesh FILE.obj --rays FILE.rays [--rays ...] [--threads N] [--runs N]
//       traces ray files (format: docs/apps.md, "bench") against the mesh; one line per file:
//       rays N hits H sum_t S mrays_per_s X          (closest-hit files)
//       rays N occluded H mrays_per_s X              (any-hit files)
//   bench --mesh FILE.obj --make-rays PREFIX [--size N]
//       writes PREFIX.primary.rays, PREFIX.diffuse.rays, PREFIX.shadow.rays: the standard mesh
//       workload (ray_workload.h), traced with this renderer
//   bench --scaling [--mesh FILE.obj] [--levels N] [--size N] [--runs N]
//       time per ray for 1k, 10k, 100k and 1M random spheres, and for the mesh (default: the
//       small bunny) and its Loop subdivisions up to N levels; one table
//   bench --user-shapes N [--threads N] [--runs N]
//       renders N spheres written as user hittables (a book-style class, not the built-in
//       sphere) on a grid, once with bounding_box() (they go into the BVH) and once without (each
//       ray tests every one), interleaved; prints the medians and their ratio
//   bench --error REF.pfm|REF.exr --scene FILE [--width N] [--max-spp N] [--adaptive] [--threads N] [--runs N] [--csv F]
//         [--plot F.svg] [--book-seconds S --book-rmse8 E]
//       renders at 1, 2, 4, ... N samples per pixel (and, with --adaptive, with adaptive
//       sampling at halving error targets), and records wall time, rays and the error against
//       the reference; writes a CSV and a log-log plot of error against seconds; prints the rays
//       and time uniform sampling needs to reach each adaptive image's error; with the book's
//       measured time and 8-bit error, prints the equal-time and equal-error comparisons. With
//       --runs N (default 1 here) every image is rendered N times, interleaved, and timed by the
//       median. With --estimators nee,bsdf,mixture (any of them) the uniform images are rendered
//       with each estimator in turn and compared by efficiency, 1 / (MSE * seconds); with
//       --samplers independent,stratified,sobol (any of them) likewise with each sampler, and
//       each one's convergence slope (MSE against spp) and MSE at equal spp and equal time

#include "app_options.h"
#include "compiled_mesh.h"
#include "loop_subdivision.h"
#include "ray_workload.h"
#include "user_sphere.h"

#include "plot_svg.h"

#include <rtweekend/image/image_read.h>
#include <rtweekend/io/obj.h>
#include <rtweekend/mesh.h>
#include <rtweekend/measure/metrics.h>
#include <rtweekend/io/ray_file.h>
#include <rtweekend/camera.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/io/scene_file.h>

#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

namespace {

const app::description bench_description{"bench", "Measures rendering and ray tracing speed.", "", 0, 0};

[[noreturn]] void usage(const std::string& message) {
    std::fprintf(stderr, "bench: error: %s\n", message.c_str());
    std::fprintf(stderr,
                 "usage: bench --scene FILE [--width N] [--spp N] [--depth N] [--threads N] [--runs N]\n"
                 "       bench --mesh FILE.obj --rays FILE.rays [--rays FILE.rays ...] [--threads N] [--runs N]\n"
                 "       bench --mesh FILE.obj --make-rays PREFIX [--size N]\n"
                 "       bench --scaling [--mesh FILE.obj] [--levels N] [--size N] [--runs N]\n"
                 "       bench --user-shapes N [--threads N] [--runs N]\n"
                 "       bench --error REF.pfm|REF.exr --scene FILE [--width N] [--max-spp N] [--adaptive] [--threads N] [--runs N] [--csv F]\n"
                 "             [--plot F.svg] [--book-seconds S --book-rmse8 E] [--estimators E,E,...] [--samplers S,S,...]\n");
    std::exit(2);
}

struct bench_options {
    std::string scene, mesh, make_rays, error_ref, csv, plot;
    int max_spp = 1024;
    bool adaptive = false;
    std::optional<double> book_seconds, book_rmse8;
    std::vector<std::string> rays;
    bool scaling = false;
    int user_shapes = 0;
    int runs = 5, threads = 1, size = 1024, levels = 4;
    std::optional<int> width, spp, depth;
    bool threads_given = false, runs_given = false;
    std::vector<rt::path_estimator> estimators; // --estimators: compare these (bench --error)
    std::vector<rt::sampler_kind> samplers;     // --samplers: compare these (bench --error)
};

// "a,b,c" -> {"a", "b", "c"} (an empty item stays, and is then refused as a name).
std::vector<std::string> comma_separated(const std::string& list) {
    std::vector<std::string> items;
    for (size_t start = 0;;) {
        const size_t comma = list.find(',', start);
        items.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) return items;
        start = comma + 1;
    }
}

bench_options parse(int argc, char** argv) {
    bench_options o;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) usage(arg + " needs a value");
            return argv[++i];
        };
        auto integer = [&](long long min, long long max) {
            return int(app::parse_integer(bench_description, arg, next(), min, max));
        };
        if (arg == "--help" || arg == "-h") {
            std::printf("usage: bench --scene FILE [--width N] [--spp N] [--depth N] [--threads N] [--runs N]\n"
                        "       bench --mesh FILE.obj --rays FILE.rays [--rays FILE.rays ...] [--threads N] [--runs N]\n"
                        "       bench --mesh FILE.obj --make-rays PREFIX [--size N]\n"
                        "       bench --scaling [--mesh FILE.obj] [--levels N] [--size N] [--runs N]\n"
                        "       bench --user-shapes N [--threads N] [--runs N]\n"
                        "       bench --error REF.pfm|REF.exr --scene FILE [--width N] [--max-spp N] [--adaptive] [--threads N] [--runs N]\n"
                        "             [--csv F] [--plot F.svg] [--book-seconds S --book-rmse8 E] [--estimators E,...] [--samplers S,...]\n"
                        "Medians of --runs runs (default 5; 1 for --error); one thread unless --threads (0 = all cores;\n"
                        "--error: all cores unless --threads).\n");
            std::exit(0);
        } else if (arg == "--scene") o.scene = next();
        else if (arg == "--mesh") o.mesh = next();
        else if (arg == "--rays") o.rays.push_back(next());
        else if (arg == "--make-rays") o.make_rays = next();
        else if (arg == "--scaling") o.scaling = true;
        else if (arg == "--user-shapes") o.user_shapes = integer(1, 1 << 22);
        else if (arg == "--error") o.error_ref = next();
        else if (arg == "--estimators") {
            for (const std::string& name : comma_separated(next())) {
                rt::path_estimator e;
                if (!rt::parse_estimator(name, e)) usage("--estimators: '" + name + "' is not nee, bsdf or mixture");
                o.estimators.push_back(e);
            }
        } else if (arg == "--samplers") {
            for (const std::string& name : comma_separated(next())) {
                rt::sampler_kind k;
                if (!rt::parse_sampler(name, k))
                    usage("--samplers: '" + name + "' is not independent, stratified or sobol");
                o.samplers.push_back(k);
            }
        }
        else if (arg == "--csv") o.csv = next();
        else if (arg == "--plot") o.plot = next();
        else if (arg == "--max-spp") o.max_spp = integer(1, 1 << 20);
        else if (arg == "--adaptive") o.adaptive = true;
        else if (arg == "--book-seconds") o.book_seconds = app::parse_real(bench_description, arg, next(), 1e-6, 1e9);
        else if (arg == "--book-rmse8") o.book_rmse8 = app::parse_real(bench_description, arg, next(), 1e-9, 255);
        else if (arg == "--runs") {
            o.runs = integer(1, 1000);
            o.runs_given = true;
        }
        else if (arg == "--threads") {
            o.threads = integer(0, 1024);
            o.threads_given = true;
        } else if (arg == "--size") o.size = integer(1, 1 << 14);
        else if (arg == "--levels") o.levels = integer(0, 6);
        else if (arg == "--width") o.width = integer(1, 1 << 16);
        else if (arg == "--spp") o.spp = integer(1, 1 << 24);
        else if (arg == "--depth") o.depth = integer(1, 1 << 16);
        else usage("unknown option '" + arg + "'");
    }
    int modes = (!o.scene.empty() && o.error_ref.empty()) + (!o.rays.empty() || !o.make_rays.empty()) + o.scaling +
                !o.error_ref.empty() + (o.user_shapes > 0);
    if (modes != 1)
        usage("give exactly one of --scene, --mesh with --rays or --make-rays, --scaling, --user-shapes, or --error");
    if (!o.error_ref.empty() && o.scene.empty()) usage("--error needs --scene");
    if (!o.estimators.empty() && o.scene.empty()) usage("--estimators goes with --scene (one: render with it) or --error");
    if (o.estimators.size() > 1 && o.error_ref.empty()) usage("several --estimators go with --error");
    if (!o.samplers.empty() && o.scene.empty()) usage("--samplers goes with --scene (one: render with it) or --error");
    if (o.samplers.size() > 1 && o.error_ref.empty()) usage("several --samplers go with --error");
    if (o.samplers.size() > 1 && o.estimators.size() > 1) usage("compare either estimators or samplers, not both");
    if (o.book_seconds.has_value() != o.book_rmse8.has_value()) usage("--book-seconds and --book-rmse8 go together");
    if ((!o.rays.empty() || !o.make_rays.empty()) && o.mesh.empty()) usage("--rays and --make-rays need --mesh");
    if (!o.rays.empty() && !o.make_rays.empty()) usage("--rays and --make-rays are separate runs");
    if (o.threads == 0) o.threads = rt::processors_available();
    return o;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double peak_memory_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0; // Linux reports kibibytes
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// --- one scene file ---------------------------------------------------------------------------

void bench_scene(const bench_options& o) {
    rt::scene_description s = rt::load_scene(o.scene);
    rt::camera& cam = s.cam;
    if (o.width) {
        cam.image_width = *o.width;
        cam.image_height = 0;
    }
    if (o.spp) cam.samples_per_pixel = *o.spp;
    if (o.depth) cam.max_depth = *o.depth;
    if (!o.estimators.empty()) cam.settings.estimator = o.estimators[0];
    if (!o.samplers.empty()) cam.settings.sampler = o.samplers[0];
    cam.settings.threads = o.threads;
    cam.settings.quiet = true;

    auto compile_start = std::chrono::steady_clock::now();
    rt::compiled_scene compiled = rt::compile_scene(s.world, cam.lookfrom, s.point_lights, s.directional_lights);
    double compile_s = seconds_since(compile_start);
    const rt::bvh_stats& bs = compiled.bvh.stats;
    std::printf("scene %s: %zu spheres, %zu triangles, %zu quads, %zu lights; BVH built in %.2f ms (scene compiled in %.2f ms): "
                "%zu nodes, %zu leaves, depth %d, %zu bytes of geometry and BVH\n",
                o.scene.c_str(), compiled.set<rt::sphere_set>().count, compiled.set<rt::triangle_set>().distinct, compiled.set<rt::quad_set>().count,
                compiled.lights.lights.size(), bs.build_ms, compile_s * 1e3, bs.nodes,
                bs.leaves, bs.depth, compiled.geometry_bytes());

    std::vector<double> seconds, mrays;
    uint64_t rays = 0;
    for (int run = 0; run < o.runs; ++run) {
        rt::render_result r = rt::render(cam, s.world, s.point_lights, s.directional_lights);
        seconds.push_back(r.stats.seconds);
        mrays.push_back(r.stats.mrays_per_second());
        rays = r.stats.rays;
        std::fprintf(stderr, "bench: run %d/%d: %.3f s, %.2f Mrays/s\n", run + 1, o.runs, r.stats.seconds,
                     r.stats.mrays_per_second());
    }
    std::printf("%dx%d, %d spp, depth %d, %d thread%s: rays %llu seconds %.3f mrays_per_s %.2f (median of %d) "
                "peak_memory_mib %.1f\n",
                cam.frame().width, cam.frame().height, cam.samples_per_pixel, cam.max_depth, o.threads,
                o.threads == 1 ? "" : "s", static_cast<unsigned long long>(rays), median(seconds), median(mrays), o.runs,
                peak_memory_mib());
}

// --- ray files against a mesh -------------------------------------------------------------------

struct traced {
    uint64_t hits = 0;
    double sum_t = 0;
    double seconds = 0;
};

// Traces every ray of the batch on `threads` threads. Rays are taken in chunks; hits and sum_t
// are added chunk by chunk in order, so the checksums do not depend on the thread count.
traced trace_batch(const rt::compiled_scene& scene, const rt::ray_batch& batch, int threads) {
    constexpr size_t chunk = 4096;
    const size_t n = batch.rays.size(), chunks = (n + chunk - 1) / chunk;
    std::vector<uint64_t> chunk_hits(chunks);
    std::vector<double> chunk_sum(chunks);
    std::atomic<size_t> next{0};
    const bool any = batch.kind == rt::ray_query::any;
    auto start = std::chrono::steady_clock::now();
    auto worker = [&] {
        rt::surface_hit hit;
        for (size_t c = next++; c < chunks; c = next++) {
            uint64_t hits = 0;
            double sum = 0;
            for (size_t i = c * chunk, end = std::min(n, i + chunk); i < end; ++i) {
                const rt::ray3f& r = batch.rays[i];
                if (any) {
                    hits += scene.occluded(r);
                } else if (scene.intersect(r, hit)) {
                    ++hits;
                    sum += hit.t;
                }
            }
            chunk_hits[c] = hits;
            chunk_sum[c] = sum;
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    traced out;
    out.seconds = seconds_since(start);
    for (size_t c = 0; c < chunks; ++c) {
        out.hits += chunk_hits[c];
        out.sum_t += chunk_sum[c];
    }
    return out;
}

// The mesh as the only object of a world, compiled about the world origin (ray files are in
// the mesh's own coordinates).
using app::compiled_mesh;
using app::compile_mesh;

void print_mesh_summary(const std::string& name, const compiled_mesh& m) {
    const rt::bvh_stats& bs = m.scene.bvh.stats;
    std::printf("mesh %s: %zu triangles (%zu degenerate left out), loaded in %.0f ms; BVH built in %.0f ms: %zu nodes, "
                "%zu leaves, depth %d; bytes_per_triangle %.1f (BVH %.1f + triangles %.1f)\n",
                name.c_str(), m.triangles, m.scene.set<rt::triangle_set>().degenerate, m.load_ms, bs.build_ms, bs.nodes, bs.leaves,
                bs.depth, double(m.scene.geometry_bytes()) / double(m.scene.set<rt::triangle_set>().distinct),
                double(bs.bytes()) / double(m.scene.set<rt::triangle_set>().distinct),
                double(m.scene.geometry_bytes() - bs.bytes()) / double(m.scene.set<rt::triangle_set>().distinct));
}

compiled_mesh load_and_compile(const std::string& path) {
    auto start = std::chrono::steady_clock::now();
    auto mesh = rt::load_obj(path, std::make_shared<rt::lambertian>(rt::color(0.5, 0.5, 0.5)));
    double load_ms = seconds_since(start) * 1e3;
    compiled_mesh m = compile_mesh(std::move(mesh));
    m.load_ms = load_ms;
    return m;
}

void bench_rays(const bench_options& o) {
    compiled_mesh m = load_and_compile(o.mesh);
    print_mesh_summary(o.mesh, m);
    for (const std::string& file : o.rays) {
        rt::ray_batch batch = rt::read_rays(file);
        std::vector<double> rates;
        traced t;
        for (int run = 0; run < o.runs; ++run) {
            t = trace_batch(m.scene, batch, o.threads);
            rates.push_back(double(batch.rays.size()) / t.seconds * 1e-6);
        }
        if (batch.kind == rt::ray_query::any)
            std::printf("%s: rays %zu occluded %llu mrays_per_s %.2f\n", file.c_str(), batch.rays.size(),
                        static_cast<unsigned long long>(t.hits), median(rates));
        else
            std::printf("%s: rays %zu hits %llu sum_t %.9g mrays_per_s %.2f\n", file.c_str(), batch.rays.size(),
                        static_cast<unsigned long long>(t.hits), t.sum_t, median(rates));
    }
    std::printf("peak_memory_mib %.1f (%d thread%s, median of %d runs)\n", peak_memory_mib(), o.threads,
                o.threads == 1 ? "" : "s", o.runs);
}

// The closest-hit function the standard workload needs: t and the geometric normal.
auto closest_hit(const rt::compiled_scene& scene) {
    return [&scene](const rt::ray3f& r, float& t, rt::vec3f& normal) {
        rt::surface_hit hit;
        if (!scene.intersect(r, hit)) return false;
        t = hit.t;
        normal = hit.normal;
        return true;
    };
}

// The mesh's bounding box, in float.
void mesh_bounds(const rt::compiled_scene& s, rt::vec3f& lo, rt::vec3f& hi) {
    rt::box3f box;
    for (size_t i = 0; i < s.set<rt::triangle_set>().count; ++i)
        for (int v = 0; v < 3; ++v)
            box.grow(rt::vec3f{s.set<rt::triangle_set>().vertex[size_t(3 * v)][i], s.set<rt::triangle_set>().vertex[size_t(3 * v + 1)][i],
                               s.set<rt::triangle_set>().vertex[size_t(3 * v + 2)][i]});
    lo = box.lo;
    hi = box.hi;
}

void bench_make_rays(const bench_options& o) {
    compiled_mesh m = load_and_compile(o.mesh);
    print_mesh_summary(o.mesh, m);
    rt::vec3f lo, hi;
    mesh_bounds(m.scene, lo, hi);
    app::workload w = app::make_standard_workload(lo, hi, closest_hit(m.scene), o.size);
    const std::pair<const char*, const rt::ray_batch*> files[] = {
        {".primary.rays", &w.primary}, {".diffuse.rays", &w.diffuse}, {".shadow.rays", &w.shadow}};
    for (const auto& [suffix, batch] : files) {
        std::string path = o.make_rays + suffix;
        rt::write_rays(path, *batch);
        std::printf("wrote %s: %zu %s rays\n", path.c_str(), batch->rays.size(), rt::ray_query_name(batch->kind));
    }
}

// --- scaling ----------------------------------------------------------------------------------

struct scaling_row {
    std::string what;
    size_t primitives;
    double build_ms, bytes_per_primitive, ns_primary, ns_diffuse, ns_shadow;
};

double ns_per_ray(const rt::compiled_scene& scene, const rt::ray_batch& batch, int runs) {
    std::vector<double> ns;
    for (int run = 0; run < runs; ++run) ns.push_back(trace_batch(scene, batch, 1).seconds / double(batch.rays.size()) * 1e9);
    return median(ns);
}

scaling_row measure(const std::string& what, const rt::compiled_scene& scene, size_t primitives, const bench_options& o) {
    rt::vec3f lo, hi;
    rt::box3f box;
    // Bounds of everything: spheres and triangles.
    for (size_t i = 0; i < scene.set<rt::sphere_set>().count; ++i) {
        rt::vec3f c{scene.set<rt::sphere_set>().x[i], scene.set<rt::sphere_set>().y[i], scene.set<rt::sphere_set>().z[i]};
        rt::vec3f r{scene.set<rt::sphere_set>().r[i], scene.set<rt::sphere_set>().r[i], scene.set<rt::sphere_set>().r[i]};
        box.grow(c - r);
        box.grow(c + r);
    }
    if (scene.set<rt::triangle_set>().count > 0) {
        mesh_bounds(scene, lo, hi);
        box.grow(lo);
        box.grow(hi);
    }
    app::workload w = app::make_standard_workload(box.lo, box.hi, closest_hit(scene), o.size);
    scaling_row row{what, primitives, scene.bvh.stats.build_ms, double(scene.geometry_bytes()) / double(primitives), 0, 0, 0};
    row.ns_primary = ns_per_ray(scene, w.primary, o.runs);
    row.ns_diffuse = ns_per_ray(scene, w.diffuse, o.runs);
    row.ns_shadow = ns_per_ray(scene, w.shadow, o.runs);
    std::fprintf(stderr, "bench: %s done\n", what.c_str());
    return row;
}

void bench_scaling(const bench_options& o) {
    std::vector<scaling_row> rows;
    // Random spheres in the unit cube, the radius shrinking as n^(-1/3) so that they cover the
    // same fraction of the volume (about 5 %) at every count.
    for (size_t n : {size_t(1000), size_t(10000), size_t(100000), size_t(1000000)}) {
        rt::hittable_list world;
        auto mat = std::make_shared<rt::lambertian>(rt::color(0.5, 0.5, 0.5));
        rt::pcg32 rng = rt::sample_rng(2026, n, 0);
        double radius = std::cbrt(0.05 * 3 / (4 * rt::pi * double(n)));
        for (size_t i = 0; i < n; ++i)
            world.add(std::make_shared<rt::sphere>(rt::point3(rng.next_float(), rng.next_float(), rng.next_float()),
                                                   radius * (0.5 + rng.next_float()), mat));
        rt::compiled_scene scene = rt::compile_scene(world, rt::point3(0, 0, 0));
        rows.push_back(measure("random spheres", scene, n, o));
    }
    // The mesh and its Loop subdivisions (4x the triangles per level).
    std::string mesh_path = o.mesh.empty() ? std::string(RTWEEKEND_DATA_DIR) + "/meshes/bunny_npm.obj" : o.mesh;
    app::tri_mesh base = app::read_obj(mesh_path);
    for (int level = 0; level <= o.levels; ++level) {
        app::tri_mesh sub = app::loop_subdivide(base, level);
        compiled_mesh m = compile_mesh(app::to_triangle_mesh(sub, std::make_shared<rt::lambertian>(rt::color(0.5, 0.5, 0.5))));
        rows.push_back(measure("mesh, Loop x" + std::to_string(level), m.scene, m.scene.set<rt::triangle_set>().distinct, o));
    }

    std::printf("| primitives | scene | BVH build ms | bytes/primitive | ns/ray primary | ns/ray diffuse | ns/ray shadow |\n");
    std::printf("|---:|---|---:|---:|---:|---:|---:|\n");
    for (const scaling_row& r : rows)
        std::printf("| %zu | %s | %.1f | %.1f | %.0f | %.0f | %.0f |\n", r.primitives, r.what.c_str(), r.build_ms,
                    r.bytes_per_primitive, r.ns_primary, r.ns_diffuse, r.ns_shadow);
    std::printf("(standard workload at %dx%d, one thread, median of %d runs; mesh: %s)\n", o.size, o.size, o.runs,
                mesh_path.c_str());
}

// --- time against error -------------------------------------------------------------------------

struct error_point {
    std::string mode; // "uniform" or "adaptive", or the estimator's or sampler's name (--estimators, --samplers)
    int spp;          // samples per pixel (the most a pixel takes, for adaptive)
    double adaptive_error;
    double seconds;
    uint64_t rays, samples;
    rt::image_error linear, display;
};

// log-log interpolation of y at x along a curve sorted by x; nullopt outside its range.
std::optional<double> interpolate_loglog(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
        double x0 = xs[i], x1 = xs[i + 1];
        if ((x0 <= x && x <= x1) || (x1 <= x && x <= x0)) {
            if (x0 == x1) return ys[i];
            double f = std::log(x / x0) / std::log(x1 / x0);
            return std::exp(std::log(ys[i]) + f * (std::log(ys[i + 1]) - std::log(ys[i])));
        }
    }
    return std::nullopt;
}

void bench_error(const bench_options& o) {
    rt::loaded_image ref = rt::read_image(o.error_ref);
    if (ref.display_encoded)
        throw rt::scene_error(o.error_ref + ": the reference must be a linear image (PFM or EXR), not an 8-bit one");
    rt::scene_description s = rt::load_scene(o.scene);
    s.cam.settings.threads = o.threads_given ? o.threads : 0;
    s.cam.settings.quiet = true;
    if (o.depth) s.cam.max_depth = *o.depth;
    if (o.width) {
        s.cam.image_width = *o.width;
        s.cam.image_height = 0;
    }
    if (s.cam.frame().width != ref.pixels.width() || s.cam.frame().height != ref.pixels.height())
        throw rt::scene_error("the scene renders " + std::to_string(s.cam.frame().width) + "x" +
                              std::to_string(s.cam.frame().height) + " but the reference is " +
                              std::to_string(ref.pixels.width()) + "x" + std::to_string(ref.pixels.height()));

    // The images to render: uniform sampling at 1, 2, 4 ... max_spp samples per pixel, then
    // adaptive sampling (at most max_spp) at halving error targets, which span about the same
    // average sample counts as uniform's from 16 spp up.
    // The variants compared: several samplers, or several estimators (with one estimator and
    // one sampler, or none, the single variant is "uniform").
    std::vector<std::string> variants;
    if (o.samplers.size() > 1)
        for (rt::sampler_kind k : o.samplers) variants.push_back(rt::sampler_name(k));
    else if (o.estimators.size() > 1)
        for (rt::path_estimator e : o.estimators) variants.push_back(rt::estimator_name(e));
    if (!o.estimators.empty()) s.cam.settings.estimator = o.estimators[0];
    if (!o.samplers.empty()) s.cam.settings.sampler = o.samplers[0];
    std::vector<error_point> points;
    if (variants.empty()) {
        for (int spp = 1; spp <= o.max_spp; spp *= 2) points.push_back({"uniform", spp, 0, 0, 0, 0, {}, {}});
    } else {
        for (const std::string& v : variants)
            for (int spp = 1; spp <= o.max_spp; spp *= 2) points.push_back({v, spp, 0, 0, 0, 0, {}, {}});
    }
    if (o.adaptive)
        for (double e = 0.1; e > 5e-4; e /= 2) points.push_back({"adaptive", o.max_spp, e, 0, 0, 0, {}, {}});

    // Each image is rendered `runs` times, the passes interleaved so that a slow spell of the
    // machine falls on every kind alike; the time is the median. Images are identical each pass.
    const int runs = o.runs_given ? o.runs : 1;
    std::vector<std::vector<double>> seconds(points.size());
    for (int pass = 0; pass < runs; ++pass)
        for (size_t i = 0; i < points.size(); ++i) {
            error_point& p = points[i];
            rt::camera cam = s.cam;
            cam.samples_per_pixel = p.spp;
            cam.settings.adaptive_error = p.adaptive_error;
            for (rt::path_estimator e : o.estimators)
                if (p.mode == rt::estimator_name(e)) cam.settings.estimator = e;
            for (rt::sampler_kind k : o.samplers)
                if (p.mode == rt::sampler_name(k)) cam.settings.sampler = k;
            rt::render_result r = rt::render(cam, s.world, s.point_lights, s.directional_lights);
            seconds[i].push_back(r.stats.seconds);
            p.seconds = median(seconds[i]);
            p.rays = r.stats.rays;
            p.samples = r.stats.samples;
            if (pass == 0) {
                p.linear = rt::compare_linear(r.img, ref.pixels);
                p.display = rt::compare_8bit(r.img, ref.pixels);
            }
            std::fprintf(stderr, "bench: pass %d/%d: %s %d spp%s: %.2f s, rmse %.5f (8-bit %.3f)\n", pass + 1, runs,
                         p.mode.c_str(), p.spp,
                         p.adaptive_error > 0 ? (" error " + std::to_string(p.adaptive_error)).c_str() : "",
                         r.stats.seconds, p.linear.rmse, p.display.rmse);
        }

    // The table and the CSV.
    std::string csv = "mode,spp,adaptive_error,seconds,rays,samples,rmse,relmse,bias_r,bias_g,bias_b,rmse8\n";
    std::printf("| mode | spp | error target | seconds | Mrays | samples/pixel | RMSE (linear) | relMSE | mean bias (R, G, B) | RMSE (8-bit) |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---|---:|\n");
    const double pixels = double(ref.pixels.width()) * ref.pixels.height();
    for (const error_point& p : points) {
        char line[512];
        std::snprintf(line, sizeof line, "%s,%d,%g,%.4f,%llu,%llu,%.6g,%.6g,%.3g,%.3g,%.3g,%.5g\n", p.mode.c_str(), p.spp,
                      p.adaptive_error, p.seconds, static_cast<unsigned long long>(p.rays),
                      static_cast<unsigned long long>(p.samples), p.linear.rmse, p.linear.rel_mse, p.linear.bias[0],
                      p.linear.bias[1], p.linear.bias[2], p.display.rmse);
        csv += line;
        std::printf("| %s | %d | %s | %.2f | %.1f | %.1f | %.5f | %.2e | %.1e, %.1e, %.1e | %.3f |\n", p.mode.c_str(),
                    p.spp, p.adaptive_error > 0 ? std::to_string(p.adaptive_error).substr(0, 6).c_str() : "-",
                    p.seconds, double(p.rays) * 1e-6, double(p.samples) / pixels, p.linear.rmse, p.linear.rel_mse,
                    p.linear.bias[0], p.linear.bias[1], p.linear.bias[2], p.display.rmse);
    }
    if (!o.csv.empty()) rt::write_file_atomically(o.csv, csv);

    // Estimators: efficiency 1 / (MSE * seconds) at each sample count, and its median over the
    // sample counts from 16 up (below that, bias-free noise is not yet the whole error: a few
    // fireflies decide the MSE).
    if (!variants.empty()) {
        std::vector<double> medians;
        const std::string what = o.samplers.size() > 1 ? "sampler" : "estimator";
        auto mse_at = [&](const std::string& v, int spp) {
            for (const error_point& p : points)
                if (p.mode == v && p.spp == spp) return p.linear.rmse * p.linear.rmse;
            return 0.0;
        };
        for (const std::string& v : variants) {
            std::vector<double> eff, eff8;
            // The convergence slope: least squares of log MSE on log spp over spp >= 4 (MSE falls
            // as spp^-1 for independent samples; faster where stratification pays).
            double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
            for (const error_point& p : points)
                if (p.mode == v && p.spp >= 16) {
                    eff.push_back(1.0 / (p.linear.rmse * p.linear.rmse * p.seconds));
                    eff8.push_back(1.0 / (p.display.rmse * p.display.rmse * p.seconds));
                }
            for (const error_point& p : points)
                if (p.mode == v && p.spp >= 4) {
                    const double x = std::log(double(p.spp)), y = 2 * std::log(p.linear.rmse);
                    sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
                }
            const double slope = n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
            medians.push_back(eff.empty() ? 0.0 : median(eff));
            std::printf("%s %s: efficiency 1/(MSE*s) %.4g linear, %.4g in 8-bit (medians over spp >= 16); "
                        "MSE ~ spp^%.2f\n",
                        what.c_str(), v.c_str(), medians.back(), eff8.empty() ? 0.0 : median(eff8), slope);
        }
        for (size_t i = 1; i < medians.size(); ++i) {
            if (medians[i] > 0)
                std::printf("%s / %s efficiency: %.2fx\n", variants[0].c_str(), variants[i].c_str(),
                            medians[0] / medians[i]);
            std::vector<double> ratios;
            for (int spp = 16; spp <= o.max_spp; spp *= 2)
                if (mse_at(variants[i], spp) > 0) ratios.push_back(mse_at(variants[0], spp) / mse_at(variants[i], spp));
            if (!ratios.empty())
                std::printf("%s / %s MSE at equal spp (median over spp >= 16): %.3f\n", variants[0].c_str(),
                            variants[i].c_str(), median(ratios));
        }
    }

    // Adaptive against uniform: the rays and the time uniform sampling needs to reach each
    // adaptive image's error (interpolated on its curve), in RMSE and in relMSE.
    auto along = [&](const std::string& mode, auto x_of, auto y_of) {
        std::vector<double> x, y;
        for (const error_point& p : points)
            if (p.mode == mode) {
                x.push_back(x_of(p));
                y.push_back(y_of(p));
            }
        return std::make_pair(x, y);
    };
    auto rays_of = [](const error_point& p) { return double(p.rays); };
    auto seconds_of = [](const error_point& p) { return p.seconds; };
    auto rmse_of = [](const error_point& p) { return p.linear.rmse; };
    auto relmse_of = [](const error_point& p) { return p.linear.rel_mse; };
    auto rmse8_of = [](const error_point& p) { return p.display.rmse; };
    auto curve = [&](const std::string& mode, bool display) {
        return display ? along(mode, seconds_of, rmse8_of) : along(mode, seconds_of, rmse_of);
    };
    auto [u_rays, u_rmse] = along("uniform", rays_of, rmse_of);
    auto [u_secs, u_rmse2] = along("uniform", seconds_of, rmse_of);
    auto [u_rays2, u_relmse] = along("uniform", rays_of, relmse_of);
    for (const error_point& p : points) {
        if (p.mode != "adaptive") continue;
        std::optional<double> rays = interpolate_loglog(u_rmse, u_rays, p.linear.rmse);
        std::optional<double> secs = interpolate_loglog(u_rmse2, u_secs, p.linear.rmse);
        std::optional<double> rel_rays = interpolate_loglog(u_relmse, u_rays2, p.linear.rel_mse);
        if (!rays || !secs || !rel_rays) continue;
        std::printf("adaptive, error %g: RMSE %.5f with %.1f Mrays in %.2f s; uniform needs %.1f Mrays (%.2fx) and "
                    "%.2f s (%.2fx); at its relMSE %.3g uniform needs %.2fx the rays\n",
                    p.adaptive_error, p.linear.rmse, double(p.rays) * 1e-6, p.seconds, *rays * 1e-6,
                    *rays / double(p.rays), *secs, *secs / p.seconds, p.linear.rel_mse, *rel_rays / double(p.rays));
    }

    // The book's code: its 8-bit error at its time, against ours.
    if (o.book_seconds) {
        auto [dx, dy] = curve("uniform", true);
        std::optional<double> ours_at_book_time = interpolate_loglog(dx, dy, *o.book_seconds);
        if (ours_at_book_time)
            std::printf("equal time (%.2f s): the book's 8-bit RMSE %.3f, ours %.3f: MSE %.1fx lower\n", *o.book_seconds,
                        *o.book_rmse8, *ours_at_book_time,
                        (*o.book_rmse8 * *o.book_rmse8) / (*ours_at_book_time * *ours_at_book_time));
        std::optional<double> our_time = interpolate_loglog(dy, dx, *o.book_rmse8);
        if (our_time)
            std::printf("equal error (8-bit RMSE %.3f): the book %.2f s, ours %.3f s: %.1fx faster\n", *o.book_rmse8,
                        *o.book_seconds, *our_time, *o.book_seconds / *our_time);
    }

    if (!o.plot.empty()) {
        // Plotted in the 8-bit metric: the book's code writes 8-bit images only, so that is the
        // scale on which all three can be placed exactly.
        auto [udx, udy] = curve("uniform", true);
        auto [adx, ady] = curve("adaptive", true);
        std::vector<app::plot_series> series;
        if (variants.empty()) series.push_back({"rtweekend, uniform sampling", udx, udy});
        for (const std::string& v : variants) {
            auto [ex, ey] = curve(v, true);
            series.push_back({"rtweekend, " + std::string(o.samplers.size() > 1 ? "sampler " : "estimator ") + v, ex, ey});
        }
        if (!adx.empty()) series.push_back({"rtweekend, adaptive sampling", adx, ady});
        if (o.book_seconds) {
            app::plot_series book{"the book's code, 10 spp, 1 thread", {*o.book_seconds}, {*o.book_rmse8}};
            book.points_only = true;
            series.push_back(book);
        }
        app::plot_options po;
        int threads = s.cam.settings.threads == 0 ? rt::processors_available() : s.cam.settings.threads;
        const std::string scene_name = std::filesystem::path(o.scene).stem().string();
        po.title = "Error against render time, " + scene_name + " " + std::to_string(ref.pixels.width()) + "x" +
                   std::to_string(ref.pixels.height()) + " (rtweekend: " + std::to_string(threads) + " thread" +
                   (threads == 1 ? "" : "s") + ")";
        po.x_label = "wall-clock seconds";
        po.y_label = "RMSE against the reference (8-bit, gamma 2)";
        rt::write_file_atomically(o.plot, app::render_loglog_svg(series, po));
    }
}

// --- user shapes --------------------------------------------------------------------------------

void bench_user_shapes(const bench_options& o) {
    // N spheres of radius 0.2 on a square grid of pitch 0.5 on a ground sphere, two materials, a
    // 160x90 view from above at 4 samples per pixel, depth 8.
    auto world_of = [&](bool boxed) {
        rt::hittable_list world;
        world.add(std::make_shared<rt::sphere>(rt::point3(0, -1000, 0), 1000,
                                               std::make_shared<rt::lambertian>(rt::color(0.5, 0.5, 0.5))));
        std::shared_ptr<rt::material> red = std::make_shared<rt::lambertian>(rt::color(0.7, 0.3, 0.3));
        std::shared_ptr<rt::material> steel = std::make_shared<rt::metal>(rt::color(0.8, 0.8, 0.8), 0.2);
        int side = int(std::ceil(std::sqrt(double(o.user_shapes))));
        for (int i = 0; i < o.user_shapes; ++i) {
            double x = (i % side) - side / 2.0, z = (i / side) - side / 2.0;
            world.add(std::make_shared<app::user_sphere>(rt::point3(x * 0.5, 0.2, z * 0.5), 0.2, i % 3 ? red : steel,
                                                         boxed ? app::user_sphere::box_kind::exact
                                                               : app::user_sphere::box_kind::none));
        }
        return world;
    };
    const rt::hittable_list boxed = world_of(true), unboxed = world_of(false);
    rt::camera cam;
    cam.aspect_ratio = 16.0 / 9.0;
    cam.image_width = 160;
    cam.samples_per_pixel = 4;
    cam.max_depth = 8;
    cam.lookfrom = rt::point3(0, 12, 30);
    cam.lookat = rt::point3(0, 0, 0);
    cam.vfov = 40;
    cam.settings.threads = o.threads;
    cam.settings.quiet = true;
    std::vector<double> with_box, without_box;
    uint64_t rays = 0;
    for (int run = 0; run < o.runs; ++run) {
        rt::render_result a = rt::render(cam, boxed), b = rt::render(cam, unboxed);
        with_box.push_back(a.stats.mrays_per_second());
        without_box.push_back(b.stats.mrays_per_second());
        rays = a.stats.rays;
        std::fprintf(stderr, "bench: run %d/%d: with boxes %.3f Mrays/s, without %.3f Mrays/s\n", run + 1, o.runs,
                     with_box.back(), without_box.back());
    }
    std::printf("%d user shapes, 160x90, 4 spp, depth 8, %d thread%s, %llu rays: with bounding boxes (in the BVH) "
                "mrays_per_s %.3f; without (tested by every ray) mrays_per_s %.4f; ratio %.1f (medians of %d)\n",
                o.user_shapes, o.threads, o.threads == 1 ? "" : "s", static_cast<unsigned long long>(rays),
                median(with_box), median(without_box), median(with_box) / median(without_box), o.runs);
}

} // namespace

int main(int argc, char** argv) {
    bench_options o = parse(argc, argv);
    return app::run(bench_description, [&] {
        if (!o.error_ref.empty()) bench_error(o);
        else if (!o.scene.empty()) bench_scene(o);
        else if (!o.make_rays.empty()) bench_make_rays(o);
        else if (!o.rays.empty()) bench_rays(o);
        else if (o.user_shapes > 0) bench_user_shapes(o);
        else bench_scaling(o);
    });
}
