// One build of the library for ab_compare (see ab_compare.cpp). This file is compiled twice, once
// against each source tree, with the library's namespaces renamed on the command line
// (-Drt=rt_ab_a -Dapp=app_ab_a, and _b): both builds then live in one program without a clash,
// and each is reached through the C functions below, named by AB_VARIANT (a or b).
//
// Only the library's public entry points are used (load_obj, read_rays, compile_mesh,
// load_scene, render), so an older tree of the project builds here as well as this one.

#include <apps/compiled_mesh.h>
#include <rtweekend/camera.h>
#include <rtweekend/io/obj.h>
#include <rtweekend/io/ray_file.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/material.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <vector>

#define AB_JOIN2(a, b) a##b
#define AB_JOIN(a, b) AB_JOIN2(a, b)
#define AB_FUNCTION(name) AB_JOIN(AB_JOIN(ab_, AB_VARIANT), name)

namespace {

struct mesh_workload {
    app::compiled_mesh mesh;
    std::vector<rt::ray_batch> batches;
};

struct scene_workload {
    rt::scene_description scene;
};

// The camera's settings beyond the book: in cam.settings, or (in trees before 2026-12-06) the
// camera's own members.
template <class Camera>
auto settings_of(Camera& cam, int) -> decltype((cam.settings)) {
    return cam.settings;
}
template <class Camera>
Camera& settings_of(Camera& cam, long) {
    return cam;
}

void copy_error(const std::exception& e, char* error, size_t size) {
    std::snprintf(error, size, "%s", e.what());
}

} // namespace

extern "C" {

void* AB_FUNCTION(_load_mesh)(const char* obj, char* error, size_t error_size) {
    try {
        auto w = std::make_unique<mesh_workload>();
        w->mesh = app::compile_mesh(rt::load_obj(obj, std::make_shared<rt::lambertian>(rt::color(0.5, 0.5, 0.5))));
        return w.release();
    } catch (const std::exception& e) {
        copy_error(e, error, error_size);
        return nullptr;
    }
}

bool AB_FUNCTION(_add_rays)(void* workload, const char* path, char* error, size_t error_size) {
    try {
        static_cast<mesh_workload*>(workload)->batches.push_back(rt::read_rays(path));
        return true;
    } catch (const std::exception& e) {
        copy_error(e, error, error_size);
        return false;
    }
}

// Traces every ray of batch `which` once, one ray at a time on this thread, as bench does; returns
// the seconds taken, and the hits and the sum of their distances (closest-hit batches).
double AB_FUNCTION(_trace)(void* workload, int which, uint64_t* hits, double* sum_t) {
    const auto& w = *static_cast<mesh_workload*>(workload);
    const rt::ray_batch& batch = w.batches[size_t(which)];
    const bool any = batch.kind == rt::ray_query::any;
    rt::surface_hit hit;
    uint64_t found = 0;
    double sum = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const rt::ray3f& r : batch.rays) {
        if (any) {
            found += w.mesh.scene.occluded(r) ? 1 : 0;
        } else if (w.mesh.scene.intersect(r, hit)) {
            ++found;
            sum += hit.t;
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    *hits = found;
    *sum_t = sum;
    return seconds;
}

size_t AB_FUNCTION(_ray_count)(void* workload, int which) {
    return static_cast<mesh_workload*>(workload)->batches[size_t(which)].rays.size();
}

void* AB_FUNCTION(_load_scene)(const char* path, int width, int spp, char* error, size_t error_size) {
    try {
        auto w = std::make_unique<scene_workload>();
        w->scene = rt::load_scene(path);
        rt::camera& cam = w->scene.cam;
        if (width > 0) {
            cam.image_width = width;
            cam.image_height = 0;
        }
        if (spp > 0) cam.samples_per_pixel = spp;
        auto& settings = settings_of(cam, 0);
        settings.threads = 1;
        settings.quiet = true;
        return w.release();
    } catch (const std::exception& e) {
        copy_error(e, error, error_size);
        return nullptr;
    }
}

// Renders the scene once on one thread; returns the render's own seconds (the scene compiled and
// rendered, as render reports them), and a checksum of the image's bits (FNV-1a of its floats).
double AB_FUNCTION(_render)(void* workload, uint64_t* checksum) {
    auto& w = *static_cast<scene_workload*>(workload);
    const rt::render_result r = rt::render(w.scene.cam, w.scene.world, w.scene.point_lights, w.scene.directional_lights);
    uint64_t h = 1469598103934665603ull;
    for (int y = 0; y < r.img.height(); ++y)
        for (int x = 0; x < r.img.width(); ++x) {
            const rt::color c = r.img.pixel(x, y);
            for (int k = 0; k < 3; ++k) {
                const float f = float(c[k]);
                uint32_t bits;
                std::memcpy(&bits, &f, sizeof bits);
                h = (h ^ bits) * 1099511628211ull;
            }
        }
    *checksum = h;
    return r.stats.seconds;
}

void AB_FUNCTION(_free_mesh)(void* workload) { delete static_cast<mesh_workload*>(workload); }
void AB_FUNCTION(_free_scene)(void* workload) { delete static_cast<scene_workload*>(workload); }

} // extern "C"
