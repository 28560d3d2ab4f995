// libFuzzer harness: image textures (rtweekend/rtw_stb_image.h), the files a scene's
// `texture NAME image FILE` line names: PNG, JPEG, BMP, TGA, PNM and Radiance HDR through
// stb_image, after the project's header checks (and, for JPEG, libjpeg-turbo's reading of the
// entropy-coded data, when the build has it: core/jpeg_check.h).
//
// The input is an image file, decoded from memory by rt::rtw_image::decode. A texture it accepts
// must have width x height pixels, each reachable by pixel_data() and linear() (corners, and
// coordinates outside the image, which are clamped). A refused file must give one clear error
// line. An image that passes the project's checks (rt::detail::stb_input_problem) but is larger
// than 2^22 pixels is not decoded (fuzz::too_large_to_decode): a few kilobytes of PNG or JPEG can
// legitimately hold that much, and decoding it under the sanitizers takes seconds.

#include "fuzz_support.h"
#include "large_images.h"

#include <rtweekend/rtw_stb_image.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string input = fuzz::bytes(data, size);
    if (fuzz::too_large_to_decode(input)) return 0;
    rt::rtw_image texture;
    try {
        texture.decode(input, "fuzz.tex");
    } catch (const rt::scene_error& e) {
        fuzz::refused(e);
        return 0;
    }
    const int w = texture.width(), h = texture.height();
    if (w < 1 || h < 1 || !texture.linear_pixels() || texture.linear_pixels()->size() != size_t(w) * size_t(h) * 3) {
        std::fprintf(stderr, "fuzz: a texture of %dx%d\n", w, h);
        std::abort();
    }
    volatile float sink = 0; // keeps the reads
    for (int y : {-1, 0, h - 1, h}) {
        for (int x : {-1, 0, w - 1, w}) {
            const rt::rtw_image::rgb c = texture.linear(x, y);
            sink = sink + c.r + c.g + c.b + float(texture.pixel_data(x, y)[2]);
        }
    }
    return 0;
}
