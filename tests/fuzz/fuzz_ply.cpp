// libFuzzer harness: PLY meshes (rtweekend/io/ply.h).
//
// The input is a PLY file, read from memory by rt::decode_ply. A mesh it accepts is written back
// with rt::write_ply (binary for inputs of even length, ASCII for odd; for half of each, after
// rt::set_smooth_normals has given it normals, as an XML <Mesh shadingMode="smooth"> does): what
// write_ply writes must read back, with the same number of faces (write_ply may refuse a value a
// float cannot hold, with one error line, as a loader does). A refused file must give one clear
// error line.

#include "fuzz_support.h"

#include <rtweekend/io/ply.h>
#include <rtweekend/io/xml_scene.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::shared_ptr<rt::triangle_mesh> mesh;
    try {
        mesh = rt::decode_ply(fuzz::bytes(data, size), "fuzz.ply", nullptr);
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    if ((size / 2) % 2 == 0) rt::set_smooth_normals(*mesh);
    const std::string path = (fuzz::scratch() / "written.ply").string();
    try {
        rt::write_ply(path, *mesh, size % 2 == 0);
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    try {
        std::shared_ptr<rt::triangle_mesh> again = rt::load_ply(path, nullptr);
        if (again->faces.size() != mesh->faces.size()) {
            std::fprintf(stderr, "fuzz: write_ply wrote %zu faces, load_ply read %zu back\n", mesh->faces.size(),
                         again->faces.size());
            std::abort();
        }
    } catch (const rt::scene_error& e) {
        std::fprintf(stderr, "fuzz: what write_ply wrote does not read back: %s\n", e.what());
        std::abort();
    }
    return 0;
}
