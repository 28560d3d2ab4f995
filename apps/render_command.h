#pragma once
// The body of apps/render, in steps: a text scene is loaded with the flags applied, then rendered
// and written; an XML scene is loaded, its output paths are checked, then each camera is rendered
// and written. render.cpp runs the steps in a row; the command-line fuzzer
// (tests/fuzz/fuzz_render_cli.cpp) runs the same steps and makes the image small in between; and
// render_mpi takes the same scenes and flags through the same settings (text_scene_settings,
// xml_path_settings, whitted_settings) and writes the same slices (write_slice_output), so that
// it makes the same images.
//
//   description render_description()               the app's name, summary and operands
//   rt::scene_description read_text_scene(opt)      load_scene(opt.positional[0]) or, for a .obj, .gltf or
//                                                   .glb, the model (io/model_scene.h), the flags applied
//                                                   (opt.apply), the image size checked after --width
//   render_text_scene(opt, scene)                   renders, writes -o FILE or a PPM on stdout, or with
//                                                   --samples A:B the slice (io/slice_file.h); --time S:
//                                                   passes until S seconds are spent; --preview S: -o
//                                                   rewritten as passes complete (render_in_passes)
//   rt::whitted_scene read_xml_scene(opt)           load_xml_scene(opt.positional[0]), at least one camera,
//                                                   --spp as every camera's NumSamples (apply_xml_samples)
//   xml_output_paths(scene, scene_path, dir)        each camera's image path inside -o DIR, all checked
//   render_xml_scene(opt, scene, outputs)           every camera, Whitted or (--integrator path) path traced
//
// All throw rt::scene_error; app::run turns it into the one error line.

#include "app_options.h"

#include <rtweekend/camera.h>
#include <rtweekend/image/exr.h>
#include <rtweekend/render/guides.h>
#include <rtweekend/render/path_tracer.h>
#include <rtweekend/scene/compiled_scene.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/course/whitted.h>
#include <rtweekend/io/model_scene.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/io/slice_file.h>
#include <rtweekend/core/text_lines.h>
#include <rtweekend/io/xml_scene.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace app {

inline description render_description() {
    description d{"render", "Renders a scene file: a text scene or a model (OBJ, glTF) with the path tracer, or a "
                            "CENG795 XML scene with the Whitted ray tracer.",
                  "SCENE.txt|SCENE.xml|SCENE.json|MODEL.obj|MODEL.gltf|MODEL.glb", 1, 1};
    d.xml_scenes = true;
    d.slices = true;
    d.time_budget = true;
    d.aovs = true;
    return d;
}

// Where each camera's image goes: ImageName inside the output directory. All are checked (inside
// that directory, known format, writable, no two cameras on one file) before anything is rendered.
inline std::vector<std::string> xml_output_paths(const rt::whitted_scene& scene, const std::string& scene_path,
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
            throw rt::scene_error(rt::one_line(scene_path + ": camera " + std::to_string(i + 1) + ": <ImageName> '" +
                                               name + "' " + unsafe));
        std::string path = (dir / name).lexically_normal().string();
        std::string ext = rt::lowercase_extension(path);
        // .png and .ppm in the course's 8-bit encoding; .pfm and .exr with the linear radiance
        // (write_whitted_image), as the course's HDR scenes name theirs.
        if (ext != ".png" && ext != ".ppm" && ext != ".pfm" && ext != ".exr")
            throw rt::scene_error(scene_path + ": camera " + std::to_string(i + 1) + ": <ImageName> '" + name +
                                  "' must end in .png, .ppm, .pfm or .exr");
        for (size_t j = 0; j < i; ++j)
            if (paths[j] == path)
                throw rt::scene_error(scene_path + ": cameras " + std::to_string(j + 1) + " and " + std::to_string(i + 1) +
                                      " would both write '" + path + "'");
        fs::path parent = fs::path(path).parent_path();
        if (!parent.empty()) fs::create_directories(parent, ec);
        // A symbolic link inside the directory could still lead out of it: where the file really
        // goes must lie under where the directory really is.
        // Both made absolute first: weakly_canonical leaves a relative path relative when none of it
        // exists yet (an image about to be written in the current directory), and a relative path
        // is never inside an absolute one.
        std::error_code resolve;
        fs::path real_dir = fs::absolute(dir, resolve), real_path;
        if (!resolve) real_path = fs::absolute(path, resolve);
        if (!resolve) real_dir = fs::weakly_canonical(real_dir, resolve);
        if (!resolve) real_path = fs::weakly_canonical(real_path, resolve);
        if (!resolve) {
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

// A text scene's render settings: the camera's, with --samples A:B as the sample range (checked
// against the render's samples per pixel) and the sums kept for the slice.
inline rt::render_settings text_scene_settings(const options& opt, const rt::camera& cam) {
    rt::render_settings settings = cam.effective_settings();
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
// The samples per pixel of course camera c through the path tracer: --spp, else the camera's
// <NumSamples> when it asks for more than one, else 64 (a camera of homework 1 or 2 takes one
// sample, made for the Whitted integrator).
inline int xml_path_samples(const options& opt, const rt::view_camera& c) {
    if (opt.spp) return *opt.spp;
    return c.samples > 1 ? c.samples : 64;
}

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
    // Spot lights (course_lights.h): a point light with a cone, half the course's full angles,
    // falling off as a^4 between them. One that covers no angle sends no light.
    for (const rt::spot_light& s : scene.spot_lights) {
        if (!(s.coverage_degrees > 0)) continue;
        rt::point_light l{s.position, s.intensity * rt::pi};
        l.spot_direction = s.direction;
        l.inner_cone = s.falloff_degrees * rt::pi / 360;
        l.outer_cone = s.coverage_degrees * rt::pi / 360;
        l.cone_exponent = 4;
        lights.push_back(l);
    }
    return lights;
}
// The same for directional lights: E cos kd in the course's shading, E pi cos kd / pi here.
inline std::vector<rt::directional_light> xml_path_directional_lights(const rt::whitted_scene& scene) {
    std::vector<rt::directional_light> lights = scene.directional_lights;
    for (rt::directional_light& l : lights) l.irradiance *= rt::pi;
    return lights;
}

// The course scene's world for the path tracer: its light meshes and light spheres (homework 6)
// as emitters of the path tracer's own, two-sided diffuse_lights of radiance L times pi (the
// course's units, as its other lights), in place of the course materials that carry L (which the
// path tracer does not see). A light mesh becomes its world-space triangles, light-sampled by
// area; a light sphere its sphere under its map.
inline rt::hittable_list xml_path_world(const rt::whitted_scene& scene) {
    if (scene.light_meshes.empty() && scene.light_spheres.empty()) return scene.world;
    std::vector<const rt::hittable*> replaced;
    rt::hittable_list world;
    for (const rt::light_mesh& l : scene.light_meshes) {
        replaced.push_back(l.shape.get());
        auto mesh = std::make_shared<rt::triangle_mesh>();
        for (const auto& t : l.triangles) {
            const auto first = uint32_t(mesh->positions.size());
            mesh->positions.insert(mesh->positions.end(), t.begin(), t.end());
            mesh->faces.push_back({first, first + 1, first + 2});
        }
        mesh->mat = std::make_shared<rt::diffuse_light>(l.radiance * rt::pi, true);
        world.add(mesh);
    }
    for (const rt::light_sphere& l : scene.light_spheres) {
        replaced.push_back(l.shape.get());
        auto light = std::make_shared<rt::diffuse_light>(l.radiance * rt::pi, true);
        // A map that keeps it a sphere (a rotation, a uniform scale) places a sphere in the world,
        // which is light-sampled; an ellipsoid stays under its map, found by the rays that hit it.
        const rt::mat3 gram = l.linear.transpose() * l.linear;
        const double scale2 = gram(0, 0);
        bool similar = scale2 > 0 && std::isfinite(scale2);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) similar = similar && std::fabs(gram(i, j) - (i == j ? scale2 : 0)) <= 1e-12 * scale2;
        if (similar) {
            world.add(std::make_shared<rt::sphere>(l.linear * l.center + l.offset, std::sqrt(scale2) * l.radius, light));
        } else {
            world.add(std::make_shared<rt::transform>(std::make_shared<rt::sphere>(l.center, l.radius, light), l.linear, l.offset));
        }
    }
    for (const auto& object : scene.world.objects)
        if (std::find(replaced.begin(), replaced.end(), object.get()) == replaced.end()) world.add(object);
    return world;
}

// A course scene compiled for the path tracer around its first camera, with its point,
// directional and spot lights (above), its light objects (xml_path_world), its area lights:
// squares no ray hits, radiance times pi as for the others, their sides along the course's frame
// about the normal (course_lights.h), and its kd texture maps and meshes' normal maps.
inline rt::compiled_scene xml_path_compiled(const rt::whitted_scene& scene) {
    rt::compiled_scene compiled = rt::compile_scene(xml_path_world(scene), scene.cameras[0].position, xml_path_lights(scene),
                                                    xml_path_directional_lights(scene));
    for (const rt::area_light& l : scene.area_lights) {
        const double len = l.normal.length();
        if (!(len > 0) || !std::isfinite(len)) throw rt::scene_error("area light normal must be a non-zero finite vector");
        rt::vec3 u, v;
        rt::course_frame(l.normal / len, u, v);
        rt::add_hidden_square_light(compiled, l.position, l.size * u, l.size * v, l.radiance * rt::pi);
    }
    // Texture maps: each textured object's material (its own copy) gets the object's maps as a
    // surface map (course_surface_map.h), which the path tracer asks at each hit: colour maps on
    // any course material, normal and bump maps in the course's frames, replace_all.
    for (const rt::textured_object& o : scene.textured_objects) {
        auto map = std::make_shared<const rt::course_surface_map>(o);
        for (size_t k = 0; k < compiled.materials.size(); ++k)
            if (compiled.materials[k].source == o.surface.get()) {
                compiled.surface_maps.resize(compiled.materials.size());
                compiled.surface_maps[k] = map;
            }
    }
    return compiled;
}

inline rt::render_settings whitted_settings(const options& opt) {
    rt::render_settings settings = rt::whitted_renderer::defaults();
    settings.threads = opt.threads.value_or(0);
    settings.whitted.cull_back_faces = opt.cull_back_faces.value_or(false);
    settings.quiet = opt.quiet;
    return settings;
}

// The settings that decide a sample's value besides those a slice records on their own (size,
// samples per pixel, seed, sampler) and the scene's files: two slices merge only if this text is
// the same. The camera's geometry comes from the scene file (in its fingerprint); the flags can
// change only these.
inline std::string slice_settings_text(const rt::render_settings& s, const rt::pixel_filter& filter) {
    return "max_depth " + std::to_string(s.max_depth) + ", estimator " + rt::estimator_name(s.estimator) +
           (filter.is_box() ? std::string() : ", filter " + filter.name()); // the box: as before filters
}

// The slice a render of a part of the sample range makes (settings.keep_sums must have been set).
inline rt::sample_slice make_slice(const rt::render_settings& settings, const rt::render_result& r,
                                   const std::string& scene_fingerprint,
                                   const rt::pixel_filter& filter = rt::pixel_filter::box()) {
    rt::sample_slice slice;
    slice.render.width = r.sums.width;
    slice.render.height = r.sums.height;
    slice.render.samples_per_pixel = settings.samples_per_pixel;
    slice.render.seed = settings.seed;
    slice.render.sampler = rt::sampler_name(settings.sampler);
    slice.render.settings = slice_settings_text(settings, filter);
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
    render_over();
    if (r.stats.interrupted) {
        std::fprintf(stderr,
                     "%s: interrupted after %d %% of the slice; nothing written (a slice must hold every sample of "
                     "its range)\n",
                     o.program.c_str(), int(r.stats.completed * 100));
        std::fflush(nullptr);
        std::exit(130);
    }
    rt::write_slice(o.output, make_slice(settings, r, scene_fingerprint, o.filter.value_or(rt::pixel_filter::box())));
}

// Which cameras after `camera` (0-based) were not rendered: "" when none, else "; camera 3 not
// rendered" or "; cameras 2 to 4 not rendered".
inline std::string cameras_left(size_t camera, size_t cameras) {
    if (camera + 1 >= cameras) return "";
    if (camera + 2 == cameras) return "; camera " + std::to_string(cameras) + " not rendered";
    return "; cameras " + std::to_string(camera + 2) + " to " + std::to_string(cameras) + " not rendered";
}

// Ctrl-C between two cameras: the images written so far stay, the rest are not rendered.
inline void exit_if_interrupted_before(size_t camera, size_t cameras) {
    if (camera == 0 || !interrupt_requested.load()) return;
    std::fprintf(stderr, "render: interrupted after camera %zu%s\n", camera, cameras_left(camera - 1, cameras).c_str());
    std::fflush(nullptr);
    std::exit(130);
}

// What the path tracer does not take from a course scene, refused before rendering (an image
// without it would be wrong): more than one environment light. Everything else carries over:
// point, directional, spot, area, object and environment lights (xml_path_compiled,
// xml_path_environment), texture maps and the background image.
inline void check_xml_path_scene(const std::string& path, const rt::whitted_scene& scene) {
    if (scene.environment_lights.size() > 1)
        throw rt::scene_error(path + ": --integrator path takes one environment light; this scene has " +
                              std::to_string(scene.environment_lights.size()) + ": render it in Whitted mode (without --integrator)");
    if (scene.background_texture) rt::check_texture_map(*scene.background_texture);
}

// What the path tracer's rays that leave a course scene see through `camera`: its environment
// light, radiance times pi as for every course light, seen by every ray and light-sampled
// (environment_map.h: the course's orientation and nearest texels); else the background, seen by
// camera rays alone: its image (replace_background, pixel (x, y) reading (x / nx, y / ny) as the
// Whitted integrator does) or its colour.
inline rt::environment xml_path_environment(const rt::whitted_scene& scene, const rt::view_camera& camera) {
    if (scene.environment_lights.empty() && scene.background_texture) {
        const rt::texture_map& map = *scene.background_texture;
        auto film = std::make_shared<rt::image>(camera.width, camera.height);
        for (int y = 0; y < camera.height; ++y)
            for (int x = 0; x < camera.width; ++x)
                film->set_pixel(x, y, map.lookup(double(x) / camera.width, double(y) / camera.height).to_double());
        return rt::environment::film_backdrop(std::move(film));
    }
    if (scene.environment_lights.empty()) return rt::environment::backdrop(rt::vec3f(scene.background));
    const rt::environment_light& e = scene.environment_lights[0];
    if (!e.map) throw rt::scene_error("environment light has no image");
    try {
        return rt::environment::image_based(std::make_shared<const rt::environment_map>(*e.map, float(rt::pi)));
    } catch (const rt::scene_error& error) {
        throw rt::scene_error(e.path + ": " + error.what());
    }
}

// A course scene through the path tracer (xml_path_settings says how), camera by camera.
inline void render_xml_path_traced(const options& opt, const rt::whitted_scene& scene,
                                   const std::vector<std::string>& outputs) {
    check_xml_path_scene(opt.positional[0], scene);
    rt::render_settings settings = xml_path_settings(opt);
    catch_interrupts(); // Ctrl-C: the current camera's image so far, then exit 130
    settings.stop = &interrupt_requested;
    // One compiled scene for every camera, around the first (as the Whitted integrator's).
    const rt::compiled_scene compiled = xml_path_compiled(scene);
    const size_t cameras = scene.cameras.size();
    for (size_t i = 0; i < cameras; ++i) {
        exit_if_interrupted_before(i, cameras);
        rt::camera_frame frame = rt::view_camera_frame(scene.cameras[i]);
        if (opt.filter) frame.filter = *opt.filter;
        settings.samples_per_pixel = xml_path_samples(opt, scene.cameras[i]);
        rt::render_result r = rt::path_trace(compiled, frame, xml_path_environment(scene, scene.cameras[i]), settings);
        const std::string also = rt::write_course_image(outputs[i], r.img, scene.cameras[i]);
        if (r.stats.interrupted) {
            std::fprintf(stderr,
                         "render: interrupted after %d %% of camera %zu (average %.1f samples per pixel); wrote %s "
                         "with the samples taken%s\n",
                         int(r.stats.completed * 100), i + 1, r.stats.mean_pixel_samples(), outputs[i].c_str(),
                         cameras_left(i, cameras).c_str());
            std::fflush(nullptr);
            std::exit(130);
        }
        if (!opt.quiet) std::fprintf(stderr, "render: wrote %s\n", outputs[i].c_str());
        if (!also.empty() && !opt.quiet) std::fprintf(stderr, "render: wrote %s\n", also.c_str());
    }
}

// --spp N on an XML scene: every camera's NumSamples, whichever renderer it names (with
// --integrator path, the path tracer's samples: xml_path_samples). A preview of a render of
// thousands of samples needs no edited copy of the file.
inline void apply_xml_samples(const options& opt, rt::whitted_scene& scene) {
    if (!opt.spp) return;
    for (rt::view_camera& c : scene.cameras) c.samples = *opt.spp;
}

inline rt::whitted_scene read_xml_scene(const options& opt) {
    const std::string& scene_path = opt.positional[0];
    rt::whitted_scene scene = rt::load_xml_scene(scene_path);
    if (scene.cameras.empty()) throw rt::scene_error(scene_path + ": the scene has no <Camera>: nothing to render");
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "render: warning: %s\n", w.c_str());
    apply_xml_samples(opt, scene);
    return scene;
}

inline void render_xml_scene(const options& opt, const rt::whitted_scene& scene, const std::vector<std::string>& outputs) {
    if (opt.path_integrator) {
        render_xml_path_traced(opt, scene, outputs);
        return;
    }
    rt::render_settings settings = whitted_settings(opt);
    // Ctrl-C: the current camera's image with the pixels traced so far (the others black), then
    // exit 130, as the path tracer does.
    catch_interrupts();
    settings.stop = &interrupt_requested;
    const rt::whitted_renderer renderer(scene);
    const size_t cameras = scene.cameras.size();
    for (size_t i = 0; i < cameras; ++i) {
        exit_if_interrupted_before(i, cameras);
        rt::whitted_render r = renderer.render(i, settings);
        const std::string also = rt::write_course_image(outputs[i], r.img, scene.cameras[i]);
        if (r.stats.interrupted) {
            const uint64_t pixels = uint64_t(r.img.width()) * uint64_t(r.img.height());
            std::fprintf(stderr,
                         "render: interrupted after %d %% of camera %zu (%llu of %llu pixels traced, the other %llu "
                         "black); wrote %s with the pixels traced%s\n",
                         int(r.stats.completed * 100), i + 1, static_cast<unsigned long long>(r.stats.samples),
                         static_cast<unsigned long long>(pixels),
                         static_cast<unsigned long long>(r.stats.pixels_without_samples), outputs[i].c_str(),
                         cameras_left(i, cameras).c_str());
            std::fflush(nullptr);
            std::exit(130);
        }
        if (!opt.quiet) std::fprintf(stderr, "render: wrote %s\n", outputs[i].c_str());
        if (!also.empty() && !opt.quiet) std::fprintf(stderr, "render: wrote %s\n", also.c_str());
    }
}

inline rt::scene_description read_text_scene(const options& opt) {
    const std::string& path = opt.positional[0];
    rt::scene_description scene = rt::is_model_file(path) ? rt::load_model_scene(path) : rt::load_scene(path);
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "render: warning: %s\n", w.c_str());
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

// --time S and --preview S: the render in passes of samples [k p, (k + 1) p) of the --spp N render
// (p = N / 16, at least 1), each pass's exact sums added (render/fixed_point.h). With --time, until
// the next pass would end past the budget (judged by the last pass's time) or all N samples are
// taken; at least one pass is rendered. With --preview, after each pass but the last, the image so
// far is written to -o (atomically, as every output is) once that many seconds have passed since it
// was last written. The image is the mean of the passes completed: the same bytes as
// `--samples 0:M` of them, M = the samples taken, at any thread count; a preview after M samples
// is that image too.
inline rt::render_result render_in_passes(const options& opt, const rt::scene_description& scene,
                                         const rt::compiled_scene& compiled) {
    const auto start = std::chrono::steady_clock::now();
    auto seconds_since = [](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    rt::render_settings settings = text_scene_settings(opt, scene.cam);
    const int spp = settings.samples_per_pixel, pass = std::max(1, spp / 16);
    settings.keep_sums = true;
    settings.quiet = true;
    const rt::camera_frame frame = scene.cam.frame();
    rt::render_result total;
    int done = 0, previews = 0;
    auto last_write = start;
    while (done < spp) {
        const auto pass_start = std::chrono::steady_clock::now();
        settings.first_sample = done;
        settings.end_sample = std::min(done + pass, spp);
        rt::render_result r = rt::path_trace(compiled, frame, scene.cam.sky(), settings);
        if (r.stats.interrupted) return r; // Ctrl-C: write_output says so
        if (done == 0) {
            total = std::move(r);
        } else {
            for (size_t i = 0; i < total.sums.rgb.size(); ++i) total.sums.rgb[i] += r.sums.rgb[i];
            for (size_t i = 0; i < total.sums.counts.size(); ++i) total.sums.counts[i] += r.sums.counts[i];
            total.stats.rays += r.stats.rays;
            total.stats.samples += r.stats.samples;
            total.stats.nonfinite_samples += r.stats.nonfinite_samples;
            total.stats.saturated_samples += r.stats.saturated_samples;
        }
        done = settings.end_sample;
        const double elapsed = seconds_since(start), last = seconds_since(pass_start);
        if (opt.time_budget && elapsed + last > *opt.time_budget) break;
        if (opt.preview && done < spp && seconds_since(last_write) >= *opt.preview) {
            write_output(opt, rt::mean_image(total.sums));
            last_write = std::chrono::steady_clock::now();
            ++previews;
            if (!opt.quiet)
                std::fprintf(stderr, "render: preview of %d of %d samples per pixel (%.0f %%) after %.1f s: wrote %s\n", done,
                             spp, 100.0 * done / spp, elapsed, opt.output.c_str());
        }
    }
    total.img = rt::mean_image(total.sums);
    total.stats.end_sample = done;
    total.stats.seconds = seconds_since(start);
    if (!opt.quiet) {
        std::string budget = opt.time_budget ? ", budget " + rt::number_text(*opt.time_budget) + " s" : "";
        if (opt.preview) budget += ", " + std::to_string(previews) + " previews";
        std::fprintf(stderr, "render: %d of %d samples per pixel (passes of %d) in %.3f s%s: %llu rays\n", done, spp, pass,
                     total.stats.seconds, budget.c_str(), (unsigned long long)total.stats.rays);
    }
    return total;
}

// --aov LIST: the guides of render/guides.h, with the render's first samples. Beside an .exr
// output, channels of the same file (albedo.R/G/B, N.X/Y/Z, Z, P.X/Y/Z after R, G, B); beside any
// other, one PFM each, FILE's stem + ".albedo.pfm" and so on. Each file is written atomically.
inline std::vector<std::string> write_guides(const options& opt, const rt::guide_images& g, const rt::image* beauty) {
    struct guide {
        const char* name;
        const rt::image* img;
        std::vector<std::string> channels;
    };
    const std::vector<guide> all = {{"albedo", &g.albedo, {"albedo.R", "albedo.G", "albedo.B"}},
                                    {"normal", &g.normal, {"N.X", "N.Y", "N.Z"}},
                                    {"depth", &g.depth, {"Z"}},
                                    {"position", &g.position, {"P.X", "P.Y", "P.Z"}}};
    std::vector<std::string> written;
    if (rt::lowercase_extension(opt.output) == ".exr") {
        std::vector<rt::exr_channels> channels;
        if (beauty) channels.push_back({beauty, {"R", "G", "B"}});
        for (const guide& x : all)
            if (std::find(opt.aovs.begin(), opt.aovs.end(), x.name) != opt.aovs.end()) channels.push_back({x.img, x.channels});
        rt::write_file_atomically(opt.output, rt::encode_exr(channels, opt.output));
        written.push_back(opt.output);
        return written;
    }
    if (beauty) write_output(opt, *beauty);
    const std::filesystem::path out(opt.output);
    for (const guide& x : all)
        if (std::find(opt.aovs.begin(), opt.aovs.end(), x.name) != opt.aovs.end()) {
            const std::string path = (out.parent_path() / (out.stem().string() + "." + x.name + ".pfm")).string();
            rt::write_image(path, *x.img);
            written.push_back(path);
        }
    return written;
}

inline void render_text_scene(const options& opt, const rt::scene_description& scene) {
    if (!opt.aovs.empty()) {
        const rt::camera_frame frame = scene.cam.frame();
        const rt::compiled_scene compiled = rt::compile_scene(scene.world, frame.position, scene.point_lights, scene.directional_lights);
        const rt::render_settings settings = text_scene_settings(opt, scene.cam);
        const auto start = std::chrono::steady_clock::now();
        const rt::guide_images g = rt::render_guides(compiled, frame, scene.cam.sky(), settings);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        rt::render_result beauty;
        if (!opt.aov_only)
            beauty = opt.time_budget || opt.preview ? render_in_passes(opt, scene, compiled)
                                                    : rt::path_trace(compiled, frame, scene.cam.sky(), settings);
        if (beauty.stats.interrupted) return write_output(opt, beauty); // Ctrl-C: the render as it stands
        const std::vector<std::string> written = write_guides(opt, g, opt.aov_only ? nullptr : &beauty.img);
        if (!opt.quiet)
            for (const std::string& w : written)
                std::fprintf(stderr, "render: wrote %s (guides: %d rays a pixel, %.3f s)\n", w.c_str(),
                             rt::guide_samples(settings.samples_per_pixel), seconds);
        return;
    }
    if (opt.time_budget || opt.preview) {
        const rt::camera_frame frame = scene.cam.frame();
        write_output(opt, render_in_passes(opt, scene, rt::compile_scene(scene.world, frame.position, scene.point_lights, scene.directional_lights)));
        return;
    }
    if (!opt.samples) {
        write_output(opt, rt::render(scene.cam, scene.world, scene.point_lights, scene.directional_lights));
        return;
    }
    // The fingerprint of what was read, taken now: the files could change during a long render.
    const std::string fingerprint = rt::scene_fingerprint(scene.files);
    const rt::render_settings settings = text_scene_settings(opt, scene.cam);
    rt::render_result r = rt::path_trace(scene.world, scene.cam.frame(), scene.cam.sky(), settings, scene.point_lights,
                                                 scene.directional_lights);
    write_slice_output(opt, settings, r, fingerprint);
}

} // namespace app
