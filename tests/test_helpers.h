#pragma once
// What several test files need: a scratch directory, a small quiet camera, a checked render,
// bit-for-bit image comparison, one material sample in the terms of an incoming ray.

#include <rtweekend/camera.h>
#include <rtweekend/core/bsdf.h>
#include <rtweekend/core/material_kinds.h>
#include <rtweekend/image/image.h>
#include <rtweekend/core/rng.h>
#include <rtweekend/core/scene_error.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace test {

// True in a build with AddressSanitizer (CI's second pass, at -O0), where a render runs some 40
// times slower than in the first pass. The few statistical tests that render most take a
// `sanitized_share` of their samples there, and check only what fewer samples can: the mean
// within its measured standard errors, not how small those errors are. The sanitizers look for
// memory errors and undefined behaviour on the same code paths; the first pass holds the full
// statistics.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool sanitized_build = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool sanitized_build = true;
#else
inline constexpr bool sanitized_build = false;
#endif
#else
inline constexpr bool sanitized_build = false;
#endif
// `samples`, or an eighth of it (at least 1) in a sanitized build.
inline int sanitized_share(int samples) { return sanitized_build ? std::max(1, samples / 8) : samples; }

// Runs `f`, which must throw one scene_error whose message is one line (no line break or NUL)
// holding every fragment.
inline void check_scene_error(const std::function<void()>& f, std::initializer_list<std::string> fragments) {
    bool threw = false;
    try {
        f();
    } catch (const rt::scene_error& e) {
        threw = true;
        const std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find('\n') == std::string::npos);
        CHECK(msg.find('\0') == std::string::npos);
        for (const std::string& fragment : fragments) {
            CAPTURE(fragment);
            CHECK(msg.find(fragment) != std::string::npos);
        }
    }
    CHECK(threw);
}

// A fresh, empty directory under the system's temporary directory, removed with everything in it
// at scope exit. Unique per process, object and moment, so tests may run in parallel.
struct scratch_dir {
    std::filesystem::path path;

    explicit scratch_dir(const std::string& label = "dir") {
        static std::atomic<int> counter{0};
        auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
        path = std::filesystem::temp_directory_path() /
               ("rtweekend_test_" + label + "_" + std::to_string(::getpid()) + "_" + std::to_string(stamp) + "_" +
                std::to_string(counter++));
        std::filesystem::create_directories(path);
    }
    ~scratch_dir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    scratch_dir(const scratch_dir&) = delete;
    scratch_dir& operator=(const scratch_dir&) = delete;

    // The path of `name` inside the directory.
    std::string file(const std::string& name) const { return (path / name).string(); }
    // Writes `bytes` to `name` inside the directory and returns its path.
    std::string write(const std::string& name, const std::string& bytes) const {
        std::ofstream(path / name, std::ios::binary) << bytes;
        return file(name);
    }
    // The names of the entries in the directory.
    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& e : std::filesystem::directory_iterator(path)) names.push_back(e.path().filename().string());
        return names;
    }
};

// A w x h camera at the book's defaults otherwise, quiet, on two threads.
inline rt::camera test_camera(int w, int h, int spp, int depth) {
    rt::camera cam;
    cam.image_width = w;
    cam.image_height = h;
    cam.samples_per_pixel = spp;
    cam.max_depth = depth;
    cam.settings.quiet = true;
    cam.settings.threads = 2;
    return cam;
}

// The number of camera samples a render with `cam` takes without adaptive sampling.
inline uint64_t sample_count(const rt::camera& cam) {
    return uint64_t(cam.image_width) * uint64_t(cam.height()) * uint64_t(cam.samples_per_pixel);
}

// Renders and checks what every render must satisfy: no NaN/Inf sample was dropped, and every
// pixel is finite and non-negative.
inline rt::render_result render_checked(const rt::camera& cam, const rt::hittable& world) {
    rt::render_result r = rt::render(cam, world);
    CHECK(r.stats.nonfinite_samples == 0);
    long bad = 0;
    for (float v : r.img.data())
        if (!(std::isfinite(v) && v >= 0)) ++bad;
    CHECK(bad == 0);
    return r;
}

// Expects action() to throw scene_error: one line that names `path` and says `problem`.
template <class Action>
void check_one_line_error(Action&& action, const std::string& path, const std::string& problem) {
    bool threw = false;
    try {
        action();
    } catch (const rt::scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find('\n') == std::string::npos);
        CHECK(msg.find(path) != std::string::npos);
        CHECK(msg.find(problem) != std::string::npos);
    }
    CHECK(threw);
}

// Whether two images have the same size and the same bits in every float.
inline bool same_bits(const rt::image& a, const rt::image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.data().size() == b.data().size() &&
           std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)) == 0;
}

// One sample of the material contract in the terms of an incoming ray: its unit direction `d`
// (wo is -d), the unit normal n facing it, and which face it hit; the scattered direction and its
// weight (f |cos| / pdf). False when the light is absorbed.
inline bool sample_direction(const rt::compiled_material& m, const rt::vec3f& d, const rt::vec3f& n, bool front_face,
                             rt::pcg32& rng, rt::vec3f& dir, rt::vec3f& weight) {
    rt::material_sample s;
    if (!m.sample(-d, rt::shading_point{n, front_face}, rng, s)) return false;
    dir = s.wi;
    weight = s.value;
    return true;
}

} // namespace test
