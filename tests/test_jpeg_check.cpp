// JPEG textures: libjpeg-turbo reads a JPEG's entropy-coded data through before stb_image decodes
// it (core/jpeg_check.h). Sound files of every kind pass and decode to stb_image's pixels, exactly;
// damaged and cut-short ones are refused. The test JPEGs are encoded here by libjpeg itself, so
// these cases need the library; without it (RTWEEKEND_HAVE_LIBJPEG unset) stb_image alone reads
// JPEG files, as test_fuzz_inputs.cpp checks.

#include <rtweekend/core/file.h>
#include <rtweekend/core/jpeg_check.h>
#include <rtweekend/rtw_stb_image.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace test_jpeg_check {

using test::check_scene_error;

#if defined(RTWEEKEND_HAVE_LIBJPEG) && RTWEEKEND_HAVE_LIBJPEG

// Encodes w x h pixels of `components` bytes each in `space` (JCS_RGB, JCS_GRAYSCALE or JCS_CMYK)
// as a JPEG of the given quality (libjpeg's defaults: 2x2 chroma subsampling for RGB, an Adobe
// marker for CMYK), progressive when asked.
std::string encode_jpeg(const std::vector<unsigned char>& pixels, int w, int h, int components, J_COLOR_SPACE space,
                        int quality, bool progressive = false) {
    jpeg_compress_struct c{};
    jpeg_error_mgr err{};
    c.err = jpeg_std_error(&err); // errors exit: a test encoder's input is always sound
    jpeg_create_compress(&c);
    unsigned char* out = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&c, &out, &size);
    c.image_width = JDIMENSION(w);
    c.image_height = JDIMENSION(h);
    c.input_components = components;
    c.in_color_space = space;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, quality, TRUE);
    if (progressive) jpeg_simple_progression(&c);
    jpeg_start_compress(&c, TRUE);
    while (c.next_scanline < c.image_height) {
        JSAMPROW row = const_cast<unsigned char*>(&pixels[size_t(c.next_scanline) * size_t(w) * size_t(components)]);
        jpeg_write_scanlines(&c, &row, 1);
    }
    jpeg_finish_compress(&c);
    jpeg_destroy_compress(&c);
    std::string file(reinterpret_cast<const char*>(out), size);
    std::free(out);
    return file;
}

// stb_image's decode of the same bytes, three bytes a pixel.
std::vector<unsigned char> stb_decode(const std::string& file, int& w, int& h) {
    int channels = 0;
    unsigned char* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(file.data()), int(file.size()), &w,
                                                &h, &channels, 3);
    REQUIRE(data != nullptr);
    std::vector<unsigned char> out(data, data + size_t(w) * size_t(h) * 3);
    stbi_image_free(data);
    return out;
}

// The texture's bytes equal stb_image's decode of the file, every one.
void check_stb_pixels(const std::string& file, const std::string& name) {
    rtw_image img;
    img.decode(file, name);
    int w = 0, h = 0;
    const std::vector<unsigned char> stb = stb_decode(file, w, h);
    REQUIRE(img.width() == w);
    REQUIRE(img.height() == h);
    size_t differ = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) differ += img.pixel_data(x, y)[c] != stb[(size_t(y) * size_t(w) + size_t(x)) * 3 + size_t(c)];
    CAPTURE(name);
    CHECK(differ == 0);
}

TEST_CASE("JPEG textures: sound files of every kind pass the check, with stb_image's pixels") {
    // The project's earth map (smooth land, sharp coasts), as photographs are usually stored:
    // baseline and progressive, 2x2 chroma subsampling.
    rtw_image earth((std::string(RTWEEKEND_TEXTURE_DIR) + "/earthmap.png").c_str());
    const int w = earth.width(), h = earth.height();
    std::vector<unsigned char> rgb;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) rgb.insert(rgb.end(), earth.pixel_data(x, y), earth.pixel_data(x, y) + 3);
    check_stb_pixels(encode_jpeg(rgb, w, h, 3, JCS_RGB, 90), "earth.jpg");
    check_stb_pixels(encode_jpeg(rgb, w, h, 3, JCS_RGB, 75, true), "earth_progressive.jpg");
    // A solid colour at quality 100 comes back within a code.
    const int sw = 24, sh = 16;
    std::vector<unsigned char> solid;
    for (int i = 0; i < sw * sh; ++i) solid.insert(solid.end(), {200, 60, 30});
    rtw_image img;
    img.decode(encode_jpeg(solid, sw, sh, 3, JCS_RGB, 100), "solid.jpg");
    const unsigned char* p = img.pixel_data(11, 7);
    CHECK(std::abs(int(p[0]) - 200) <= 1);
    CHECK(std::abs(int(p[1]) - 60) <= 1);
    CHECK(std::abs(int(p[2]) - 30) <= 1);
    // Greyscale: a ramp of 8 per column, grey in all three channels, within 2 codes.
    std::vector<unsigned char> grey;
    for (int y = 0; y < sh; ++y)
        for (int x = 0; x < sw; ++x) grey.push_back(static_cast<unsigned char>(8 * x + 20));
    img.decode(encode_jpeg(grey, sw, sh, 1, JCS_GRAYSCALE, 100), "ramp.jpg");
    for (int x = 0; x < sw; ++x) {
        p = img.pixel_data(x, 7);
        CHECK(p[0] == p[1]);
        CHECK(p[1] == p[2]);
        CHECK(std::abs(int(p[0]) - (8 * x + 20)) <= 2);
    }
    // Adobe CMYK, which stores inverted ink amounts: stb_image makes it R = C K / 255 of the stored
    // values. By hand: 200 * 180 / 255 = 141.2, 100 * 180 / 255 = 70.6, 50 * 180 / 255 = 35.3.
    std::vector<unsigned char> cmyk;
    for (int i = 0; i < 16 * 16; ++i) cmyk.insert(cmyk.end(), {200, 100, 50, 180});
    img.decode(encode_jpeg(cmyk, 16, 16, 4, JCS_CMYK, 100), "cmyk.jpg");
    p = img.pixel_data(8, 8);
    CHECK(std::abs(int(p[0]) - 141) <= 1);
    CHECK(std::abs(int(p[1]) - 71) <= 1);
    CHECK(std::abs(int(p[2]) - 35) <= 1);
}

TEST_CASE("JPEG textures: damaged or cut-short data is refused, not decoded to grey") {
    const int w = 32, h = 32;
    std::vector<unsigned char> rgb;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            rgb.insert(rgb.end(), {static_cast<unsigned char>(7 * x), static_cast<unsigned char>(7 * y), 90});
    for (bool progressive : {false, true}) {
        const std::string file = encode_jpeg(rgb, w, h, 3, JCS_RGB, 95, progressive);
        CAPTURE(progressive);
        CHECK_NOTHROW(rtw_image().decode(file, "whole.jpg"));
        // Cut in the middle of the entropy-coded data: stb_image alone fills the rest with grey.
        check_scene_error([&] { rtw_image().decode(file.substr(0, file.size() / 2), "cut.jpg"); },
                          {"cannot read image texture 'cut.jpg'", "JPEG data refused by libjpeg-turbo: Premature end of JPEG file"});
    }
    // A code that no Huffman table holds: sixteen 1 bits (stuffed 0xff 0x00 pairs) in the middle of
    // the entropy-coded data, which no table of libjpeg's, or any, assigns (ITU T.81 C).
    std::string file = encode_jpeg(rgb, w, h, 3, JCS_RGB, 95);
    const size_t sos = file.find("\xff\xda");
    REQUIRE(sos != std::string::npos);
    const size_t data = sos + 2 + (size_t(static_cast<unsigned char>(file[sos + 2])) << 8 | static_cast<unsigned char>(file[sos + 3]));
    file.replace((data + file.size() - 2) / 2, 6, std::string("\xff\x00\xff\x00\xff\x00", 6));
    check_scene_error([&] { rtw_image().decode(file, "bad_code.jpg"); },
                      {"bad_code.jpg", "JPEG data refused by libjpeg-turbo: Corrupt JPEG data: bad Huffman code"});
    // libjpeg checks the frame stb_image decodes, or nothing: told another size, it refuses
    // before it allocates.
    std::string sound = encode_jpeg(rgb, w, h, 3, JCS_RGB, 95);
    CHECK(rt::detail::jpeg_data_problem(sound, w, h).empty());
    const std::string mismatch = rt::detail::jpeg_data_problem(sound, w, h + 8);
    CHECK(mismatch == "JPEG frame is 32x32 pixels to libjpeg-turbo but 32x40 to stb_image: the file's markers are damaged");
    // A fuzzing find: an APP0 segment of length 0, which stb_image refuses and libjpeg walks past,
    // into a quantisation table holding what it takes for a frame of 16724x18756 pixels (it asked
    // 600 MB for their coefficients). stb_image cannot read the headers, so libjpeg is not asked.
    check_scene_error([] { rtw_image img((std::string(RTWEEKEND_TEST_DATA) + "/fuzz/jpeg_app0_length_0.jpg").c_str()); },
                      {"jpeg_app0_length_0.jpg", "bad APP len"});
    // The fuzzing find that stb_image 2.27 decodes with a shift by 34 bits (undefined behaviour):
    // a second scan in a baseline file.
    check_scene_error([] { rtw_image img((std::string(RTWEEKEND_TEST_DATA) + "/fuzz/jpeg_bit_reader_shift.jpg").c_str()); },
                      {"jpeg_bit_reader_shift.jpg", "JPEG data refused by libjpeg-turbo: "});
}

#endif
} // namespace test_jpeg_check
