// write_next_week_scenes: writes book 2's two scenes with random content as scene files,
// bouncing_spheres.txt and next_week_final.txt, into a directory (tests/data keeps the copies
// this project ships). Each is drawn exactly as its milestone app draws it (the C library's
// rand(), from a new program's state), so `render FILE` and the app render the same scene.
//
//   write_next_week_scenes tests/data

#include "next_week_scenes.h"

#include <rtweekend/core/file.h>

#include <cstdio>
#include <sstream>
#include <string>

namespace {

std::string header(const char* comment, const rt::camera& cam) {
    std::ostringstream h;
    h << comment;
    auto v = [](const rt::vec3& x) { return next_week_detail::vec(x); };
    h << "camera aspect_ratio " << next_week_detail::num(cam.aspect_ratio) << "\n"
      << "camera image_width " << cam.image_width << "\n"
      << "camera samples_per_pixel " << cam.samples_per_pixel << "\n"
      << "camera max_depth " << cam.max_depth << "\n"
      << "camera vfov " << next_week_detail::num(cam.vfov) << "\n"
      << "camera lookfrom " << v(cam.lookfrom) << "\n"
      << "camera lookat " << v(cam.lookat) << "\n"
      << "camera vup " << v(cam.vup) << "\n"
      << "camera defocus_angle " << next_week_detail::num(cam.defocus_angle) << "\n"
      << "camera focus_dist " << next_week_detail::num(cam.focus_dist) << "\n"
      << "background " << v(*cam.background) << "\n";
    return h.str();
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_next_week_scenes DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    try {
        {
            std::srand(1);
            std::ostringstream body;
            next_week_scene s = make_bouncing_spheres(&body);
            rt::write_file_atomically(dir + "/bouncing_spheres.txt",
                                      header("# Book 2's bouncing spheres (\"Ray Tracing: The Next Week\", section 2): book 1's cover\n"
                                             "# with its diffuse spheres moving up while the shutter is open. Written by\n"
                                             "# apps/write_next_week_scenes.cpp from apps/next_week_scenes.h, make_bouncing_spheres().\n",
                                             s.cam) + body.str());
        }
        {
            std::srand(1);
            std::ostringstream body;
            next_week_scene s = make_next_week_final(400, 250, 4, &body);
            rt::write_file_atomically(dir + "/next_week_final.txt",
                                      header("# Book 2's final scene (\"Ray Tracing: The Next Week\", section 10) at the book's quick\n"
                                             "# settings (the full quality: --width 800 --spp 10000 --depth 40). Written by\n"
                                             "# apps/write_next_week_scenes.cpp from apps/next_week_scenes.h, make_next_week_final().\n"
                                             "# The marble's noise is built from rand() as a new program's first draws; the app\n"
                                             "# builds it after the boxes' 400 draws, as the book does, so its pattern differs.\n",
                                             s.cam) + body.str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "write_next_week_scenes: %s\n", e.what());
        return 1;
    }
    return 0;
}
