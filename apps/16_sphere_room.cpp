// 16_sphere_room: the CENG795 course renderer's sphere room.
//
// A room whose walls are the insides of six huge spheres, lit by one small spherical light:
// soft shadows (the light has a size), reflections in the mirror sphere, and caustics where the
// glass spheres focus the light onto the floor. Sphere lights are sampled by the cone of
// directions they subtend, so every shadow ray goes towards the light. Scene file:
// tests/data/sphere_room.txt.
//
//   16_sphere_room > 16_sphere_room.ppm
//   16_sphere_room --estimator bsdf -o 16_sphere_room.png

#include "app_options.h"
#include "light_scenes.h"

int main(int argc, char** argv) {
    const app::description d{"16_sphere_room", "Path traces the course renderer's sphere room: mirror, glass and hollow glass under a sphere light.", ""};
    app::options opt = app::parse(argc, argv, d);
    return app::run(d, [&] {
        light_scene s = make_sphere_room();
        opt.apply(s.cam);
        app::write_output(opt, rt::render(s.cam, s.world));
    });
}
