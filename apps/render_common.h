#pragma once
// What render and render_mpi share, so that both take exactly the same scenes and flags and make
// the same images: where an XML scene's images go, the settings of each kind of render, and the
// sample slices of `render --samples A:B` (rtweekend/io/slice_file.h).

#include "app_options.h"

#include <rtweekend/camera.h>
#include <rtweekend/engine/path_tracer.h>
#include <rtweekend/engine/whitted.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/io/slice_file.h>
#include <rtweekend/io/xml_scene.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace app {

// Where each camera's image goes: ImageName inside the output directory. All are checked (inside
// that directory, known format, writable, no two cameras on one file) before anything is rendered.
inline std::vector<std::string> output_paths(const rt::whitted_scene& scene, const std::string& scene_path,
                                      const std::string& directory) {
    namespace fs = std::filesystem;
    fs::path dir = directory.empty() ? fs::path(".") : fs::path(directory);
    std::error_code ec;
    if (!directory.empty()) {
        if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
            throw rt::scene_error("-o " + directory + ": not a directory (an XML scene writes one image per camera)");
        fs::create_directories(dir, ec);
        if (ec) throw rt::scene_error("cannot create directory '" + directory + "': " + ec.message());
    }
    std::vector<std::string> paths;
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        const std::string& name = scene.cameras[i].image_name;
        if (name.empty())
            throw rt::scene_error(scene_path + ": camera " + std::to_string(i + 1) + " has no <ImageName>");
        // The loader refuses such names already; a scene built in code reaches here unchecked.
        std::string unsafe = rt::image_name_problem(name);
        if (!unsafe.empty())
            throw rt::scene_error(scene_path + ": camera " + std::to_string(i + 1) + ": <ImageName> '" + name + "' " +
                                  unsafe);
        std::string path = (dir / name).lexically_normal().string();
        std::string ext = rt::lowercase_extension(path);
        if (ext != ".png" && ext != ".ppm")
            throw rt::scene_error(scene_path + ": camera " + std::to_string(i + 1) + ": <ImageName> '" + name +
                                  "' must end in .png or .ppm");
        for (size_t j = 0; j < i; ++j)
            if (paths[j] == path)
                throw rt::scene_error(scene_path + ": cameras " + std::to_string(j + 1) + " and " + std::to_string(i + 1) +
                                      " would both write '" + path + "'");
        fs::path parent = fs::path(path).parent_path();
        if (!parent.empty()) fs::create_directories(parent, ec);
        // A symbolic link inside the directory could still lead out of it: where the file really
        // goes must lie under where the directory really is.
        const fs::path real_dir = fs::weakly_canonical(dir, ec), real_path = fs::weakly_canonical(path, ec);
        if (!ec) {
            auto rel = real_path.lexically_relative(real_dir);
            if (rel.empty() || rel.is_absolute() || *rel.begin() == "..")
                throw rt::scene_error(scene_path + ": camera " + std::to_string(i + 1) + ": <ImageName> '" + name +
                                      "' resolves to '" + real_path.string() + "', outside the output directory '" +
                                      real_dir.string() + "'");
        }
        rt::check_output_path(path);
        paths.push_back(path);
    }
    return paths;
}

// A text scene, loaded and with the flags applied: its camera, world and lights, checked.
inline rt::scene_description load_text_scene(const options& opt) {
    rt::scene_description scene = rt::load_scene(opt.positional[0]);
    opt.apply(scene.cam);
    // --width may make the image larger than the file did: the pixel limit again, before the
    // image is allocated.
    try {
        rt::check_camera_image_size(scene.cam);
    } catch (const rt::scene_error& e) {
        if (!opt.width) throw;
        throw rt::scene_error("--width " + std::to_string(*opt.width) + ": " + e.what());
    }
    return scene;
}

// A text scene's render settings: the camera's, with --samples A:B as the sample range (checked
// against the render's samples per pixel) and the sums kept for the slice.
inline rt::render_settings text_scene_settings(const options& opt, const rt::camera& cam) {
    rt::render_settings settings = cam.settings();
    if (opt.samples) {
        if (opt.samples->second > settings.samples_per_pixel)
            throw rt::scene_error("--samples " + std::to_string(opt.samples->first) + ":" +
                                  std::to_string(opt.samples->second) + ": the render has only " +
                                  std::to_string(settings.samples_per_pixel) + " samples per pixel (--spp)");
        settings.first_sample = opt.samples->first;
        settings.end_sample = opt.samples->second;
        settings.keep_sums = true;
    }
    return settings;
}

// A course scene through the path tracer: its point lights with indirect light, each material's
// DiffuseReflectance as a Lambertian albedo under its mirror, conductor or glass lobe. Ambient
// light has no meaning here (indirect light is computed, not approximated) and is ignored, as are
// the Blinn-Phong specular terms for now. The background is seen by camera rays only, as in the
// course; the images keep the course's units (0..255, no gamma). The course shades a point light
// as kd E cos: pi times the radiance a Lambertian surface of albedo kd reflects under a light of
// intensity I, so the lights' intensities are taken times pi, and the direct light matches the
// Whitted image's.
inline rt::render_settings xml_path_settings(const options& opt) {
    rt::render_settings settings;
    settings.samples_per_pixel = opt.spp.value_or(64);
    settings.max_depth = opt.depth.value_or(10);
    settings.seed = opt.seed.value_or(0);
    settings.threads = opt.threads.value_or(0);
    settings.quiet = opt.quiet;
    settings.adaptive_error = opt.adaptive.value_or(0);
    settings.estimator = opt.estimator.value_or(rt::path_estimator::nee);
    if (opt.sampler) settings.sampler = *opt.sampler;
    return settings;
}

inline std::vector<rt::point_light> xml_path_lights(const rt::whitted_scene& scene) {
    std::vector<rt::point_light> lights = scene.lights;
    for (rt::point_light& l : lights) l.intensity *= rt::pi;
    return lights;
}

inline rt::whitted_options whitted_settings(const options& opt) {
    rt::whitted_options options;
    options.threads = opt.threads.value_or(0);
    options.cull_back_faces = opt.cull_back_faces.value_or(false);
    options.quiet = opt.quiet;
    return options;
}

// The settings that decide a sample's value besides those a slice records on their own (size,
// samples per pixel, seed, sampler) and the scene's files: two slices merge only if this text is
// the same. The camera's geometry comes from the scene file (in its fingerprint); the flags can
// change only these.
inline std::string slice_settings_text(const rt::render_settings& s) {
    return "max_depth " + std::to_string(s.max_depth) + ", estimator " + rt::estimator_name(s.estimator);
}

// The slice a render of a part of the sample range makes (settings.keep_sums must have been set).
inline rt::sample_slice make_slice(const rt::render_settings& settings, const rt::render_result& r,
                                   const std::string& scene_fingerprint) {
    rt::sample_slice slice;
    slice.render.width = r.sums.width;
    slice.render.height = r.sums.height;
    slice.render.samples_per_pixel = settings.samples_per_pixel;
    slice.render.seed = settings.seed;
    slice.render.sampler = rt::sampler_name(settings.sampler);
    slice.render.settings = slice_settings_text(settings);
    slice.render.scene = scene_fingerprint;
    slice.first_sample = settings.first_sample;
    slice.end_sample = settings.sample_end();
    slice.rays = r.stats.rays;
    slice.nonfinite = r.stats.nonfinite_samples;
    slice.saturated = r.stats.saturated_samples;
    slice.sums = r.sums.rgb;
    return slice;
}

// Writes a slice; an interrupted render cannot make one (a slice must hold every sample of its
// range, or merging it would not give the whole render), so that is an exit with status 130 and
// nothing written.
inline void write_slice_output(const options& o, const rt::render_settings& settings, const rt::render_result& r,
                               const std::string& scene_fingerprint) {
    std::signal(SIGINT, SIG_DFL);
    if (r.stats.interrupted) {
        std::fprintf(stderr,
                     "%s: interrupted after %d %% of the slice; nothing written (a slice must hold every sample of "
                     "its range)\n",
                     o.program.c_str(), int(r.stats.completed * 100));
        std::fflush(nullptr);
        std::exit(130);
    }
    rt::write_slice(o.output, make_slice(settings, r, scene_fingerprint));
}

} // namespace app
