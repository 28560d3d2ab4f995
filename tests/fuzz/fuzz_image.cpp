// libFuzzer harness: the image reader (rtweekend/image/image_read.h) on PPM (P3, P6), PFM, PNG, BMP
// and, when the build has OpenEXR, EXR files; the format is found from the first bytes, as
// rt::read_image does.
//
// The input is an image file, read from memory by rt::decode_image. An image it accepts must have
// width x height x 3 values; a linear one (PFM, EXR) written as PFM (rt::write_image's encoder)
// must read back bit for bit. A refused file must give one clear error line. A PNG or BMP file
// that passes the project's checks but is larger than 2^22 pixels is not decoded
// (fuzz::too_large_to_decode): see fuzz_texture.cpp.

#include "fuzz_support.h"
#include "large_images.h"

#include <rtweekend/image/image_read.h>
#include <rtweekend/image/image_write.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string input = fuzz::bytes(data, size);
    if (fuzz::too_large_to_decode(input)) return 0;
    rt::loaded_image loaded;
    try {
        loaded = rt::decode_image(input, "fuzz.img");
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    const rt::image& img = loaded.pixels;
    if (img.width() < 1 || img.height() < 1 || img.data().size() != size_t(img.width()) * size_t(img.height()) * 3) {
        std::fprintf(stderr, "fuzz: %s image of %dx%d with %zu values\n", loaded.format.c_str(), img.width(),
                     img.height(), img.data().size());
        std::abort();
    }
    if (loaded.display_encoded) return 0;
    try {
        const rt::image again = rt::decode_image(rt::encode_pfm(img), "fuzz.pfm").pixels;
        if (again.width() != img.width() || again.height() != img.height() ||
            std::memcmp(again.data().data(), img.data().data(), img.data().size() * sizeof(float)) != 0) {
            std::fprintf(stderr, "fuzz: a %s image written as PFM reads back different\n", loaded.format.c_str());
            std::abort();
        }
    } catch (const rt::scene_error& e) {
        std::fprintf(stderr, "fuzz: a %s image written as PFM does not read back: %s\n", loaded.format.c_str(), e.what());
        std::abort();
    }
    return 0;
}
