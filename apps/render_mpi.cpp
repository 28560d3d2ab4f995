// render_mpi: render's scenes and flags, the render split over MPI ranks (rtweekend/render/
// mpi_render.h says how), and the same output, byte for byte, as render writes with the same seed.
//
//   mpirun -n 4 render_mpi scene.txt --spp 256 -o scene.png
//   mpirun -n 4 render_mpi scene.xml -o out/                        (the Whitted integrator, by tiles)
//   mpirun -n 4 render_mpi scene.txt --spp 64 --samples 0:32 -o part.pfm   (a slice, for merge)
//
// Every rank reads the scene itself (give each machine the files), checks that its command line
// and its scene's files are the same as rank 0's, and renders its part with all its threads;
// rank 0 writes the output (atomically) and is the only one to print (progress, statistics,
// errors). A failure on any rank, wherever it happens, is one line from rank 0,
//   render_mpi: rank R: error: <what went wrong on rank R>
// (R the lowest rank that failed), and every rank exits with status 1 (2 for bad usage), with no
// output written. Ctrl-C is mpirun's: it ends the job, and no output is written.

#include "render_command.h"

#include <rtweekend/course/whitted_mpi.h>
#include <rtweekend/render/mpi_render.h>

#include <mpi.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

// Every way out of the program passes here (std::exit included): a rank that left without
// MPI_Finalize would make mpirun report the job as broken.
extern "C" void finalize_mpi() {
    int initialized = 0, finalized = 0;
    MPI_Initialized(&initialized);
    MPI_Finalized(&finalized);
    if (initialized && !finalized) MPI_Finalize();
}

// The command line without the program's name, as text: ranks must all have been given the same.
std::string command_line(int argc, char** argv) {
    std::string line;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (!line.empty()) line += ' ';
        line += arg.empty() || arg.find_first_of(" \t'\"") != std::string::npos ? "'" + arg + "'" : arg;
    }
    return line;
}

// Parses the options on every rank alike (the command lines are the same), but lets only rank 0
// speak: a usage error or --help prints once, and every rank exits with the same status.
app::options parse_quietly(int argc, char** argv, const app::description& d, int rank) {
    int saved_out = -1, saved_err = -1;
    if (rank != 0) {
        std::fflush(nullptr);
        const int null = open("/dev/null", O_WRONLY);
        if (null >= 0) {
            saved_out = dup(1);
            saved_err = dup(2);
            dup2(null, 1);
            dup2(null, 2);
            close(null);
        }
    }
    app::options opt = app::parse(argc, argv, d);
    if (saved_out >= 0) {
        dup2(saved_out, 1);
        dup2(saved_err, 2);
        close(saved_out);
        close(saved_err);
    }
    return opt;
}

void render_text(MPI_Comm comm, const app::options& opt, int rank) {
    rt::scene_description scene = rt::mpi::together(comm, [&] { return app::read_text_scene(opt); });
    // mpirun owns Ctrl-C: the ranks take the default action (it ends the job), and the render
    // cannot stop part-way (mpi_render.h).
    std::signal(SIGINT, SIG_DFL);
    scene.cam.settings.stop = nullptr;
    const std::string fingerprint = rt::mpi::together(comm, [&] { return rt::scene_fingerprint(scene.files); });
    rt::mpi::require_same(comm, fingerprint, "scene (the contents of its files)");
    const rt::render_settings settings = rt::mpi::together(comm, [&] {
        if (rank == 0 && !opt.output.empty()) rt::check_output_path(opt.output);
        return app::text_scene_settings(opt, scene.cam);
    });
    const rt::render_result r =
        rt::mpi::path_trace(comm, scene.world, scene.cam.frame(), scene.cam.sky(), settings, scene.point_lights,
                            scene.directional_lights);
    rt::mpi::together(comm, [&] {
        if (rank != 0) return;
        if (opt.samples) rt::write_slice(opt.output, app::make_slice(settings, r, fingerprint, opt.filter.value_or(rt::pixel_filter::box())));
        else app::write_output(opt, r.img);
    });
}

void render_xml(MPI_Comm comm, const app::options& opt, int rank) {
    const std::string& scene_path = opt.positional[0];
    rt::whitted_scene scene = rt::mpi::together(comm, [&] { return rt::load_xml_scene(scene_path); });
    if (rank == 0)
        for (const std::string& w : scene.warnings) std::fprintf(stderr, "render_mpi: warning: %s\n", w.c_str());
    app::apply_xml_samples(opt, scene); // --spp: every camera's NumSamples, on every rank alike
    std::signal(SIGINT, SIG_DFL);
    const std::string fingerprint = rt::mpi::together(comm, [&] { return rt::scene_fingerprint(scene.files); });
    rt::mpi::require_same(comm, fingerprint, "scene (the contents of its files)");
    // Only rank 0 writes: only it makes the output directory and checks the images' paths.
    const std::vector<std::string> outputs = rt::mpi::together(comm, [&] {
        return rank == 0 ? app::xml_output_paths(scene, scene_path, opt.output) : std::vector<std::string>();
    });
    // Every image is rendered before any is written: a failure leaves none of them behind.
    std::vector<rt::image> images;
    if (opt.path_integrator) {
        // Refused as render refuses it.
        rt::mpi::together(comm, [&] {
            app::check_xml_path_scene(scene_path, scene);
            return 0;
        });
        rt::render_settings settings = app::xml_path_settings(opt);
        // One compiled scene for every camera, around the first, as render compiles it (every
        // rank compiles it; a failure anywhere is agreed on).
        const rt::compiled_scene compiled = rt::mpi::together(comm, [&] { return app::xml_path_compiled(scene); });
        for (const rt::view_camera& c : scene.cameras) {
            rt::camera_frame frame = rt::view_camera_frame(c);
            if (opt.filter) frame.filter = *opt.filter;
            settings.samples_per_pixel = app::xml_path_samples(opt, c);
            const rt::environment env = rt::mpi::together(comm, [&] { return app::xml_path_environment(scene, c); });
            rt::render_result r = rt::mpi::path_trace(comm, compiled, frame, env, settings);
            images.push_back(std::move(r.img));
        }
    } else {
        for (rt::whitted_render& r : rt::mpi::render_whitted(comm, scene, app::whitted_settings(opt)))
            images.push_back(std::move(r.img));
    }
    rt::mpi::together(comm, [&] {
        if (rank != 0) return;
        for (size_t i = 0; i < images.size(); ++i) {
            const std::string also = rt::write_course_image(outputs[i], images[i], scene.cameras[i]);
            if (!opt.quiet) std::fprintf(stderr, "render_mpi: wrote %s\n", outputs[i].c_str());
            if (!also.empty() && !opt.quiet) std::fprintf(stderr, "render_mpi: wrote %s\n", also.c_str());
        }
    });
}

} // namespace

int main(int argc, char** argv) {
    int provided = 0;
    // The worker threads of a rank never call MPI; the main thread does all of it.
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        std::fprintf(stderr, "render_mpi: error: MPI_Init_thread failed\n");
        return 1;
    }
    std::atexit(finalize_mpi);
    const MPI_Comm comm = MPI_COMM_WORLD;
    const int rank = rt::mpi::rank_of(comm);

    app::description d{"render_mpi",
                       "Renders a scene file over MPI ranks: a text scene with the path tracer, or a CENG795 XML "
                       "scene with the Whitted ray tracer; the same image as render.",
                       "SCENE.txt|SCENE.xml|SCENE.json", 1, 1};
    d.xml_scenes = true;
    d.slices = true;
    d.check_output = false; // rank 0's to check, agreed with the others (render_text, render_xml)
    try {
        if (provided < MPI_THREAD_FUNNELED)
            rt::mpi::agree(comm, "the MPI library does not allow threads (MPI_THREAD_FUNNELED)");
        // Before anything else: ranks given different command lines would render different things,
        // or some would stop at a usage error while the others wait.
        rt::mpi::require_same(comm, command_line(argc, argv), "command line");
        const app::options opt = parse_quietly(argc, argv, d, rank);
        if (app::is_xml_scene(opt.positional[0])) render_xml(comm, opt, rank);
        else render_text(comm, opt, rank);
        return 0;
    } catch (const rt::mpi::rank_error& e) {
        if (rank == 0) std::fprintf(stderr, "render_mpi: rank %d: error: %s\n", e.rank(), e.problem().c_str());
    } catch (const std::bad_alloc&) {
        if (rank == 0) std::fprintf(stderr, "render_mpi: error: out of memory\n");
    } catch (const std::exception& e) {
        if (rank == 0) std::fprintf(stderr, "render_mpi: error: %s\n", e.what());
    }
    return 1;
}
