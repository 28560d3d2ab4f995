// embree_bench: times Intel Embree 3 on ray files (.rays, shared/formats/rays.md), as the
// reference to compare this project's own tracer with. Benchmark only: built when the CMake
// option RTWEEKEND_EMBREE is ON; nothing else in the project depends on Embree.
//
//   embree_bench --mesh FILE.obj --rays FILE.rays [--rays MORE.rays ...] [--runs N] [--side-by-side]
//   embree_bench --mesh FILE.obj --make-rays PREFIX [--size N]
//
// Tracing: one Embree device with one thread ("threads=1"), one triangle geometry, scene built
// with RTC_BUILD_QUALITY_HIGH; every ray traced alone with rtcIntersect1 (kind 0, closest hit)
// or rtcOccluded1 (kind 1, any hit), N runs (default 5). Per ray file, exactly one line on
// stdout, the speed being the median over the runs:
//   rays N hits H sum_t S mrays_per_s X        (closest hit; S = sum of t over hits, in double)
//   rays N occluded H mrays_per_s X            (any hit)
// The mesh, the build time and, per file, the median speed by thread CPU time as well (steadier
// when other processes share the cores) go to stderr, so stdout holds only the per-file lines.
//
// --side-by-side also compiles the mesh for this project's tracer (the same triangles) and times
// the two in turns, a whole ray file each (tens of milliseconds), the one going first alternating
// from run to run, so that both run through the same stretches of whatever else the machine is
// doing: on a shared machine whose load comes in bursts, two processes timed one after the other
// can differ by 20 % from one minute to the next, and the ratio of this mode is far steadier.
// (Turns of 16384 rays measured the cost of sharing the caches with Embree too: 1-2 % more for
// this project's tracer, whose data Embree's turns evicted; BENCHMARKS.md section 18.) Both must
// find the same number of hits. Per ray file, one line on stdout, each speed and the ratio the
// median over runs:
//   rays N hits H ours_mrays_per_s X embree_mrays_per_s Y ours_over_embree R
//
// --make-rays writes PREFIX.primary.rays, PREFIX.diffuse.rays and PREFIX.shadow.rays: the
// standard mesh workload (apps/ray_workload.h) at N x N pixels (default 1024), with Embree as
// the closest-hit tracer and the bounding box of the triangles' corners.

#include "compiled_mesh.h"
#include "loop_subdivision.h"
#include "ray_workload.h"

#include <rtweekend/io/ray_file.h>
#include <rtweekend/material.h>
#include <rtweekend/core/scene_error.h>

#include <embree3/rtcore.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <new>
#include <string>
#include <system_error>
#include <vector>

namespace {

const char* const program = "embree_bench";

void print_usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: embree_bench --mesh FILE.obj --rays FILE.rays [--rays FILE.rays ...] [--runs N] [--side-by-side]\n"
                 "       embree_bench --mesh FILE.obj --make-rays PREFIX [--size N]\n"
                 "Times Embree (one thread, one ray at a time) on ray files, or writes the standard mesh workload.\n"
                 "  --mesh FILE       the OBJ mesh\n"
                 "  --rays FILE       a .rays file to trace; one line on stdout per file\n"
                 "  --runs N          timed runs per file, the median is reported (default 5)\n"
                 "  --side-by-side    also time this project's tracer on the same rays, the two in turns\n"
                 "  --make-rays P     write P.primary.rays, P.diffuse.rays, P.shadow.rays\n"
                 "  --size N          image size of the workload, N x N primary rays (default 1024)\n"
                 "  --help            show this help\n");
}

[[noreturn]] void usage_error(const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program, message.c_str());
    print_usage(stderr);
    std::exit(2);
}

int parse_int(const std::string& flag, const std::string& text, long min, long max) {
    char* end = nullptr;
    errno = 0;
    long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE) usage_error(flag + " needs an integer, got '" + text + "'");
    if (v < min || v > max)
        usage_error(flag + " must be between " + std::to_string(min) + " and " + std::to_string(max) + ", got " + text);
    return int(v);
}

struct arguments {
    std::string mesh, make_rays;
    std::vector<std::string> rays;
    int runs = 5;
    int size = 1024;
    bool side_by_side = false;
};

arguments parse(int argc, char** argv) {
    arguments a;
    bool size_given = false, runs_given = false;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i], value;
        bool inline_value = false;
        if (auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
            value = arg.substr(eq + 1);
            arg = arg.substr(0, eq);
            inline_value = true;
        }
        auto next = [&]() -> std::string {
            if (inline_value) return value;
            if (i + 1 >= argc) usage_error(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--help" || arg == "-h") {
            print_usage(stdout);
            std::exit(0);
        } else if (arg == "--mesh") {
            a.mesh = next();
        } else if (arg == "--rays") {
            a.rays.push_back(next());
        } else if (arg == "--runs") {
            a.runs = parse_int(arg, next(), 1, 1000);
            runs_given = true;
        } else if (arg == "--side-by-side") {
            if (inline_value) usage_error("--side-by-side takes no value");
            a.side_by_side = true;
        } else if (arg == "--make-rays") {
            a.make_rays = next();
        } else if (arg == "--size") {
            a.size = parse_int(arg, next(), 1, 1 << 14);
            size_given = true;
        } else if (arg.size() > 1 && arg[0] == '-') {
            usage_error("unknown option '" + arg + "'");
        } else {
            usage_error("unexpected argument '" + arg + "'");
        }
    }
    if (a.mesh.empty()) usage_error("--mesh FILE.obj is required");
    if (a.rays.empty() == a.make_rays.empty()) usage_error("give either --rays FILE or --make-rays PREFIX");
    if (!a.make_rays.empty() && runs_given) usage_error("--runs goes with --rays, not --make-rays");
    if (!a.rays.empty() && size_given) usage_error("--size goes with --make-rays, not --rays");
    if (a.side_by_side && a.rays.empty()) usage_error("--side-by-side goes with --rays");
    return a;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The first error Embree reports on the device, kept for the exception that follows.
void remember_error(void* user, RTCError code, const char* message) {
    auto* first = static_cast<std::string*>(user);
    if (first->empty()) *first = "Embree error " + std::to_string(int(code)) + (message ? std::string(": ") + message : "");
}

// An Embree device and a committed scene of one triangle geometry, released on destruction.
class embree_scene {
  public:
    explicit embree_scene(const app::tri_mesh& mesh) {
        device_ = rtcNewDevice("threads=1");
        if (!device_) throw rt::scene_error("cannot create an Embree device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
        rtcSetDeviceErrorFunction(device_, remember_error, &error_);
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                     3 * sizeof(float), mesh.positions.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                       3 * sizeof(unsigned), mesh.triangles.size()));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geometry);
            throw rt::scene_error("cannot allocate Embree buffers: " + error_);
        }
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            for (int k = 0; k < 3; ++k) vertices[3 * i + k] = float(mesh.positions[i][k]);
        for (size_t f = 0; f < mesh.triangles.size(); ++f)
            for (int k = 0; k < 3; ++k) indices[3 * f + k] = mesh.triangles[f][k];
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene_, geometry);
        rtcReleaseGeometry(geometry);

        auto start = std::chrono::steady_clock::now();
        rtcCommitScene(scene_);
        build_seconds_ = seconds_since(start);
        if (!error_.empty()) throw rt::scene_error(error_);
    }
    ~embree_scene() {
        if (scene_) rtcReleaseScene(scene_);
        if (device_) rtcReleaseDevice(device_);
    }
    embree_scene(const embree_scene&) = delete;
    embree_scene& operator=(const embree_scene&) = delete;

    double build_seconds() const { return build_seconds_; }

    // Closest hit: t and the unnormalised geometric normal.
    bool intersect(const rt::ray3f& r, float& t, rt::vec3f& normal) const {
        RTCRayHit rh = make_ray_hit(r);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcIntersect1(scene_, &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
        t = rh.ray.tfar;
        normal = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
        return true;
    }

    bool occluded(const rt::ray3f& r) const {
        RTCRay ray = make_ray(r);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcOccluded1(scene_, &context, &ray);
        return ray.tfar < 0; // Embree sets tfar to -inf on a hit
    }

  private:
    static RTCRay make_ray(const rt::ray3f& r) {
        RTCRay ray{};
        ray.org_x = r.origin.x;
        ray.org_y = r.origin.y;
        ray.org_z = r.origin.z;
        ray.tnear = r.tmin;
        ray.dir_x = r.dir.x;
        ray.dir_y = r.dir.y;
        ray.dir_z = r.dir.z;
        ray.time = 0;
        ray.tfar = r.tmax;
        ray.mask = ~0u;
        ray.id = 0;
        ray.flags = 0;
        return ray;
    }
    static RTCRayHit make_ray_hit(const rt::ray3f& r) {
        RTCRayHit rh{};
        rh.ray = make_ray(r);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        return rh;
    }

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::string error_;
    double build_seconds_ = 0;
};

// The bounding box of the triangles' corners (vertices no triangle uses do not count).
void triangle_bounds(const app::tri_mesh& mesh, rt::vec3f& lo, rt::vec3f& hi) {
    const float inf = std::numeric_limits<float>::infinity();
    lo = {inf, inf, inf};
    hi = {-inf, -inf, -inf};
    for (const auto& t : mesh.triangles)
        for (uint32_t v : t) {
            const rt::vec3& p = mesh.positions[v];
            lo = {std::min(lo.x, float(p.x())), std::min(lo.y, float(p.y())), std::min(lo.z, float(p.z()))};
            hi = {std::max(hi.x, float(p.x())), std::max(hi.y, float(p.y())), std::max(hi.z, float(p.z()))};
        }
}

struct run_result {
    uint64_t hits = 0;
    double sum_t = 0;
    double seconds = 0;     // wall
    double cpu_seconds = 0; // this thread's CPU time: less disturbed when other processes share the cores
};

double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The closest hit's distance, by either tracer (`hit`: room for this project's hit record, kept
// from ray to ray as bench keeps it).
bool closest_t(const embree_scene& scene, const rt::ray3f& ray, float& t, rt::surface_hit&) {
    rt::vec3f n;
    return scene.intersect(ray, t, n);
}

bool closest_t(const rt::compiled_scene& scene, const rt::ray3f& ray, float& t, rt::surface_hit& hit) {
    if (!scene.intersect(ray, hit)) return false;
    t = hit.t;
    return true;
}

// Every ray of the batch through `scene`, Embree's or this project's (both have occluded(ray);
// intersect differs, see closest_t).
template <class Scene>
run_result trace_once(const Scene& scene, const rt::ray_batch& batch) {
    run_result r;
    const double cpu_start = thread_cpu_seconds();
    auto start = std::chrono::steady_clock::now();
    if (batch.kind == rt::ray_query::closest) {
        rt::surface_hit hit;
        for (const rt::ray3f& ray : batch.rays) {
            float t;
            if (closest_t(scene, ray, t, hit)) {
                ++r.hits;
                r.sum_t += t;
            }
        }
    } else {
        for (const rt::ray3f& ray : batch.rays) r.hits += scene.occluded(ray) ? 1 : 0;
    }
    r.seconds = seconds_since(start);
    r.cpu_seconds = thread_cpu_seconds() - cpu_start;
    return r;
}

void bench(const embree_scene& scene, const std::string& path, const rt::ray_batch& batch, int runs) {
    std::vector<double> speeds, cpu_speeds;
    run_result first;
    for (int run = 0; run < runs; ++run) {
        run_result r = trace_once(scene, batch);
        if (run == 0) first = r;
        else if (r.hits != first.hits || r.sum_t != first.sum_t)
            throw rt::scene_error("'" + path + "': Embree gave different answers on run " + std::to_string(run + 1));
        speeds.push_back(r.seconds > 0 ? double(batch.rays.size()) / r.seconds * 1e-6 : 0.0);
        cpu_speeds.push_back(r.cpu_seconds > 0 ? double(batch.rays.size()) / r.cpu_seconds * 1e-6 : 0.0);
    }
    const double wall = median(speeds);
    std::fprintf(stderr, "%s: %s: median %.3f Mrays/s by wall time, %.3f by thread CPU time, %d runs\n", program,
                 path.c_str(), wall, median(cpu_speeds), runs);
    if (batch.kind == rt::ray_query::closest)
        std::printf("rays %zu hits %llu sum_t %.9g mrays_per_s %.3f\n", batch.rays.size(),
                    static_cast<unsigned long long>(first.hits), first.sum_t, wall);
    else
        std::printf("rays %zu occluded %llu mrays_per_s %.3f\n", batch.rays.size(),
                    static_cast<unsigned long long>(first.hits), wall);
    std::fflush(stdout);
}

// This project's tracer on the mesh (app::compiled_mesh, the same triangles as Embree's) and
// Embree, in turns.
void side_by_side(const embree_scene& embree, const app::compiled_mesh& ours, const std::string& path, const rt::ray_batch& batch,
                  int runs) {
    const size_t n = batch.rays.size();
    std::vector<double> ratios, our_speeds, embree_speeds;
    run_result first_ours;
    for (int run = 0; run < runs; ++run) {
        run_result o, e;
        if (run % 2 == 0) {
            o = trace_once(ours.scene, batch);
            e = trace_once(embree, batch);
        } else {
            e = trace_once(embree, batch);
            o = trace_once(ours.scene, batch);
        }
        if (run == 0) {
            first_ours = o;
            if (o.hits != e.hits)
                throw rt::scene_error("'" + path + "': this project's tracer found " + std::to_string(o.hits) +
                                      " hits, Embree " + std::to_string(e.hits) + ": the speeds would not compare like for like");
        }
        const double mo = o.seconds > 0 ? double(n) / o.seconds * 1e-6 : 0.0;
        const double me = e.seconds > 0 ? double(n) / e.seconds * 1e-6 : 0.0;
        our_speeds.push_back(mo);
        embree_speeds.push_back(me);
        ratios.push_back(me > 0 ? mo / me : 0.0);
        std::fprintf(stderr, "%s: %s: run %d: ours %.3f, Embree %.3f Mrays/s, ratio %.3f\n", program, path.c_str(),
                     run + 1, mo, me, ratios.back());
    }
    std::printf("rays %zu hits %llu ours_mrays_per_s %.3f embree_mrays_per_s %.3f ours_over_embree %.3f\n", n,
                static_cast<unsigned long long>(first_ours.hits), median(our_speeds), median(embree_speeds),
                median(ratios));
    std::fflush(stdout);
}

void make_rays(const embree_scene& scene, const app::tri_mesh& mesh, const std::string& prefix, int size) {
    rt::vec3f lo, hi;
    triangle_bounds(mesh, lo, hi);
    auto start = std::chrono::steady_clock::now();
    app::workload w = app::make_standard_workload(
        lo, hi, [&](const rt::ray3f& r, float& t, rt::vec3f& n) { return scene.intersect(r, t, n); }, size);
    double seconds = seconds_since(start);
    rt::write_rays(prefix + ".primary.rays", w.primary);
    rt::write_rays(prefix + ".diffuse.rays", w.diffuse);
    rt::write_rays(prefix + ".shadow.rays", w.shadow);
    std::fprintf(stderr, "%s: wrote %s.{primary,diffuse,shadow}.rays: %zu, %zu, %zu rays (%.2f s)\n", program,
                 prefix.c_str(), w.primary.rays.size(), w.diffuse.rays.size(), w.shadow.rays.size(), seconds);
}

} // namespace

int main(int argc, char** argv) {
    const arguments a = parse(argc, argv);
    try {
        if (!a.make_rays.empty())
            for (const char* part : {".primary.rays", ".diffuse.rays", ".shadow.rays"}) rt::check_writable(a.make_rays + part);
        // Every input is read and checked before the build, which takes seconds for big meshes.
        std::vector<rt::ray_batch> batches;
        for (const std::string& path : a.rays) batches.push_back(rt::read_rays(path));
        const app::tri_mesh mesh = app::read_obj(a.mesh);
        const embree_scene scene(mesh);
        std::fprintf(stderr, "%s: %s: %zu triangles, build %.1f ms (RTC_BUILD_QUALITY_HIGH, 1 thread)\n", program,
                     a.mesh.c_str(), mesh.triangles.size(), scene.build_seconds() * 1e3);
        if (!a.make_rays.empty()) make_rays(scene, mesh, a.make_rays, a.size);
        if (a.side_by_side) {
            auto start = std::chrono::steady_clock::now();
            const app::compiled_mesh ours =
                app::compile_mesh(app::to_triangle_mesh(mesh, std::make_shared<rt::lambertian>(rt::color(0.5, 0.5, 0.5))));
            std::fprintf(stderr, "%s: this project's BVH built in %.1f ms (1 thread)\n", program,
                         seconds_since(start) * 1e3);
            for (size_t i = 0; i < a.rays.size(); ++i) side_by_side(scene, ours, a.rays[i], batches[i], a.runs);
        } else {
            for (size_t i = 0; i < a.rays.size(); ++i) bench(scene, a.rays[i], batches[i], a.runs);
        }
        return 0;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: error: out of memory\n", program);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    }
    return 1;
}
