// 17_bouncing_spheres: motion blur (book 2, section 2, "Motion Blur").
//
// Book 1's cover, its diffuse spheres moving upward while the shutter is open: each camera ray
// carries a time in [0, 1), and a moving sphere, sphere(center1, center2, radius, material), is
// hit where its centre is at that time, so the spheres smear into streaks. The BVH bounds each
// moving sphere over its whole path. Scene file: tests/data/bouncing_spheres.txt.
//
//   17_bouncing_spheres > 17_bouncing_spheres.ppm
//   17_bouncing_spheres --spp 1000 -o 17_bouncing_spheres.png

#include "app_options.h"
#include "next_week_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"17_bouncing_spheres", "Path traces book 2's bouncing spheres (motion blur).", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        next_week_scene s = make_bouncing_spheres();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
