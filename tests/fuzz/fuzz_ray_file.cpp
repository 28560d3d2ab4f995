// libFuzzer harness: ray files (.rays, rtweekend/io/ray_file.h), what `bench --rays` reads, and
// the tracer on the rays they hold.
//
// The input is a ray file, read from memory by rt::decode_rays. A batch it accepts must encode
// back to the same bytes (rt::encode_rays), and each of its first 256 rays is traced against a
// small fixed scene (a mesh, spheres, a quad, a moving sphere) as bench does, closest hit and any
// hit: a closest hit must have a finite t within the ray's [tmin, tmax], and a ray with a closest
// hit must be occluded. A refused file must give one clear error line.

#include "fuzz_support.h"

#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/hittable_list.h>
#include <rtweekend/io/ray_file.h>
#include <rtweekend/material.h>
#include <rtweekend/mesh.h>
#include <rtweekend/quad.h>
#include <rtweekend/sphere.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace {

// A tetrahedron on a ground square, two spheres, a quad and a moving sphere, about the origin;
// built once, never destroyed.
struct fixed_scene {
    rt::hittable_list world;
    rt::compiled_scene compiled;

    fixed_scene() {
        auto grey = std::make_shared<rt::lambertian>(rt::color(0.5, 0.5, 0.5));
        auto mesh = std::make_shared<rt::triangle_mesh>();
        mesh->mat = grey;
        mesh->positions = {{-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}, {0, 0.1, 0}, {1, 0.1, 0}, {0, 1.1, 0}, {0, 0.1, 1}};
        mesh->faces = {{0, 1, 2}, {0, 2, 3}, {4, 6, 5}, {4, 5, 7}, {4, 7, 6}, {5, 6, 7}};
        world.add(mesh);
        world.add(std::make_shared<rt::sphere>(rt::point3(-2, 1, 0), 1, grey));
        world.add(std::make_shared<rt::sphere>(rt::point3(0, -1000, 0), 999, grey));
        world.add(std::make_shared<rt::quad>(rt::point3(-1, 0, 2), rt::vec3(2, 0, 0), rt::vec3(0, 2, 0), grey));
        world.add(std::make_shared<rt::sphere>(rt::point3(2, 1, 0), rt::point3(2, 2, 0), 0.5, grey));
        compiled = rt::compile_scene(world, rt::point3(0, 0, 0));
    }
};

const rt::compiled_scene& target() {
    static const fixed_scene* const scene = new fixed_scene();
    return scene->compiled;
}

[[noreturn]] void wrong(const char* what, size_t i, const rt::ray3f& r, float t) {
    std::fprintf(stderr, "fuzz: ray %zu (origin %g %g %g, direction %g %g %g, t in [%g, %g]): %s (t = %g)\n", i,
                 double(r.origin.x), double(r.origin.y), double(r.origin.z), double(r.dir.x), double(r.dir.y),
                 double(r.dir.z), double(r.tmin), double(r.tmax), what, double(t));
    std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string input = fuzz::bytes(data, size);
    rt::ray_batch batch;
    try {
        batch = rt::decode_rays(input, "fuzz.rays");
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    try {
        if (rt::encode_rays(batch, "fuzz.rays") != input) {
            std::fprintf(stderr, "fuzz: a ray file does not encode back to its bytes\n");
            std::abort();
        }
    } catch (const rt::scene_error& e) {
        std::fprintf(stderr, "fuzz: a batch decode_rays accepted does not encode: %s\n", e.what());
        std::abort();
    }
    const rt::compiled_scene& scene = target();
    for (size_t i = 0; i < std::min<size_t>(batch.rays.size(), 256); ++i) {
        const rt::ray3f& r = batch.rays[i];
        rt::surface_hit hit;
        const bool found = scene.intersect(r, hit);
        const bool blocked = scene.occluded(r);
        if (found && !(std::isfinite(hit.t) && hit.t >= r.tmin && hit.t <= r.tmax)) wrong("closest hit outside the ray", i, r, hit.t);
        if (found && !blocked) wrong("a closest hit, but not occluded", i, r, hit.t);
    }
    return 0;
}
