// OpenEXR images (rtweekend/image/exr.h through image_write.h and image_read.h): our float files read
// back bit for bit; files written by the OpenEXR library itself in other layouts (half channels,
// a data window away from the origin, luminance only) decode to hand-computed values; truncated,
// garbage and oversized files give one scene_error naming the file. Without the library, .exr
// gives the "not built" error instead.

#include <rtweekend/image/image_read.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/measure/metrics.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#endif

namespace test_exr {

using namespace rt;

namespace {

void check_error(const std::string& path, const std::string& problem) {
    test::check_one_line_error([&] { read_image(path); }, path, problem);
}

} // namespace

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR

namespace {

// 3x2 (not square, so a transposed read shows) with 0, the smallest normal and a subnormal float,
// 1e6, values that are not dyadic fractions (0.1, 1/3, pi, 1e-7), negatives, NaN and infinity:
// a float file must keep every one of them bit for bit.
image exact_test_image() {
    image img(3, 2);
    const float values[18] = {0.0f,    std::numeric_limits<float>::min(), 1e-40f, 1e6f,  0.1f,  1.0f / 3.0f,
                              3.14159265f, 1e-7f, -2.5f, 123456.789f, 0.7f, -0.0f,
                              std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 65504.0f,
                              1e-30f, 0.3f, 2.0e5f};
    std::memcpy(img.data().data(), values, sizeof values);
    return img;
}

// Writes a file with the OpenEXR library directly: each channel of `header` from a float plane
// (w*h values, rows top to bottom). The library writes only what the frame buffer's type is, so
// planes of HALF channels are converted to half first (Imath's half(float) rounds to nearest).
void write_planes(const std::string& path, const Imf::Header& header, const std::map<std::string, std::vector<float>>& planes) {
    const Imath::Box2i dw = header.dataWindow();
    const size_t w = size_t(dw.max.x - dw.min.x + 1);
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer fb;
    std::map<std::string, std::vector<Imath::half>> halves;
    for (const auto& [name, plane] : planes) {
        if (header.channels().findChannel(name)->type == Imf::HALF) {
            std::vector<Imath::half>& h = halves[name];
            for (float v : plane) h.push_back(Imath::half(v));
            fb.insert(name, Imf::Slice::Make(Imf::HALF, h.data(), dw, sizeof(Imath::half), sizeof(Imath::half) * w));
        } else {
            fb.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), dw, sizeof(float), sizeof(float) * w));
        }
    }
    file.setFrameBuffer(fb);
    file.writePixels(dw.max.y - dw.min.y + 1);
}

// The bytes of the 16-byte value of the dataWindow attribute (xmin, ymin, xmax, ymax, int32
// little-endian), found by the attribute's name and type as they are spelled in the header.
size_t data_window_offset(const std::string& bytes) {
    const std::string key("dataWindow\0box2i\0\x10\0\0\0", 21);
    size_t at = bytes.find(key);
    REQUIRE(at != std::string::npos);
    return at + key.size();
}

void put_int32(std::string& bytes, size_t at, int32_t v) {
    uint32_t u = uint32_t(v);
    for (int i = 0; i < 4; ++i) bytes[at + size_t(i)] = char((u >> (8 * i)) & 0xff);
}

} // namespace

TEST_CASE("exr.h: a written image reads back bit for bit, as float channels") {
    test::scratch_dir dir("exr");
    const image img = exact_test_image();
    const std::string path = dir.file("exact.exr");
    check_output_path(path);
    write_image(path, img);

    loaded_image back = read_image(path);
    CHECK(back.format == "EXR");
    CHECK_FALSE(back.display_encoded);
    REQUIRE(back.pixels.width() == 3);
    REQUIRE(back.pixels.height() == 2);
    CHECK(test::same_bits(back.pixels, img));
    // Spelled out for the values the issue names, against the literals, not the image.
    CHECK(back.pixels.data()[0] == 0.0f);
    CHECK(back.pixels.data()[2] == 1e-40f);
    CHECK(back.pixels.data()[3] == 1e6f);
    CHECK(back.pixels.data()[4] == 0.1f);
    CHECK(back.pixels.data()[5] == 1.0f / 3.0f);
    CHECK(std::isnan(back.pixels.data()[12]));

    // The file itself, as the library sees it: 32-bit float R, G, B, lossless ZIP, and the G
    // channel of pixels 1 (x = 1, y = 0: 0.1, index 4 of the values) and 5 (x = 2, y = 1: 0.3,
    // index 16) where they should be.
    Imf::InputFile file(path.c_str());
    const Imf::ChannelList& channels = file.header().channels();
    for (const char* c : {"R", "G", "B"}) {
        CAPTURE(c);
        REQUIRE(channels.findChannel(c) != nullptr);
        CHECK(channels.findChannel(c)->type == Imf::FLOAT);
    }
    CHECK(file.header().compression() == Imf::ZIP_COMPRESSION);
    std::vector<float> g(6);
    Imf::FrameBuffer fb;
    fb.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), sizeof(float), 3 * sizeof(float)));
    file.setFrameBuffer(fb);
    file.readPixels(0, 1);
    CHECK(g[1] == 0.1f);
    CHECK(g[5] == 0.3f);
}

TEST_CASE("exr.h: half channels, an offset data window and luminance decode to the values the file holds") {
    test::scratch_dir dir("exr");

    SUBCASE("half: each value rounded to 11 significant bits, as the file stores it") {
        // Hand-rounded to half (10 fraction bits, round to nearest even):
        //   0.1   = 1.6 * 2^-4,     0.6 * 1024 = 614.4 -> 614: 1638 / 16384 = 0.0999755859375
        //   1/3   = 1.333 * 2^-2,   0.333 * 1024 = 341.3 -> 341: 1365 / 4096 = 0.333251953125
        //   1000.3 = 1.9537 * 2^9,  0.9537 * 1024 = 976.6 -> 977: 2001 / 2 = 1000.5
        //   65504, the largest half, 0.5 and 0 are exact; 1e6 overflows to infinity.
        Imf::Header header(2, 3);
        for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::HALF));
        const std::vector<float> r = {0.1f, 1.0f / 3.0f, 1000.3f, 65504.0f, 0.5f, 0.0f};
        const std::vector<float> g = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 1e6f};
        const std::vector<float> b = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
        const std::string path = dir.file("half.exr");
        write_planes(path, header, {{"R", r}, {"G", g}, {"B", b}});

        loaded_image back = read_image(path);
        REQUIRE(back.pixels.width() == 2);
        REQUIRE(back.pixels.height() == 3);
        const std::vector<float>& p = back.pixels.data();
        CHECK(p[0] == 0.0999755859375f);
        CHECK(p[3] == 0.333251953125f);
        CHECK(p[6] == 1000.5f);
        CHECK(p[9] == 65504.0f);
        CHECK(p[12] == 0.5f);
        CHECK(p[15] == 0.0f);
        CHECK(p[1] == 0.5f);
        CHECK(std::isinf(p[16]));
        CHECK(p[2] == 0.0f);
    }

    SUBCASE("a data window at (10, 20): the image is the window, its first pixel the window's corner") {
        Imf::Header header(Imath::Box2i({0, 0}, {99, 99}), Imath::Box2i({10, 20}, {11, 22}));
        for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        const std::vector<float> r = {1, 2, 3, 4, 5, 6}, g = {10, 20, 30, 40, 50, 60}, b = {0.25f, 0, 0, 0, 0, 7};
        const std::string path = dir.file("window.exr");
        write_planes(path, header, {{"R", r}, {"G", g}, {"B", b}});

        loaded_image back = read_image(path);
        REQUIRE(back.pixels.width() == 2);
        REQUIRE(back.pixels.height() == 3);
        const std::vector<float> expected = {1, 10, 0.25f, 2, 20, 0, 3, 30, 0, 4, 40, 0, 5, 50, 0, 6, 60, 7};
        CHECK(back.pixels.data() == expected);
    }

    SUBCASE("Y only: grey, copied to R, G and B") {
        Imf::Header header(1, 2);
        header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
        const std::string path = dir.file("grey.exr");
        write_planes(path, header, {{"Y", {0.7f, 1e6f}}});
        loaded_image back = read_image(path);
        const std::vector<float> expected = {0.7f, 0.7f, 0.7f, 1e6f, 1e6f, 1e6f};
        CHECK(back.pixels.data() == expected);
    }

    SUBCASE("three channels of which one is used (Y, A, Z in half): Y, the others skipped") {
        // Three channels, one of them wanted: OpenEXRCore's three-channel fast path wrote through
        // the null destination of the two skipped ones (compare crashed with SIGSEGV).
        Imf::Header header(3, 2);
        for (const char* c : {"Y", "A", "Z"}) header.channels().insert(c, Imf::Channel(Imf::HALF));
        const std::string path = dir.file("yaz.exr");
        // 0.75, 0.5, 2, -1, 0.125 and 1024 are exact in half.
        write_planes(path, header, {{"Y", {0.75f, 0.5f, 2, -1, 0.125f, 1024}}, {"A", {1, 1, 1, 1, 1, 1}},
                                    {"Z", {3, 4, 5, 6, 7, 8}}});
        loaded_image back = read_image(path);
        const std::vector<float> expected = {0.75f, 0.75f, 0.75f, 0.5f, 0.5f, 0.5f, 2, 2, 2,
                                             -1, -1, -1, 0.125f, 0.125f, 0.125f, 1024, 1024, 1024};
        CHECK(back.pixels.data() == expected);
    }

    SUBCASE("R, G, B and three more channels: the colour channels, the others skipped") {
        Imf::Header header(2, 1);
        for (const char* c : {"A", "B", "G", "R", "Z", "u"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        const std::string path = dir.file("rgbazu.exr");
        write_planes(path, header, {{"R", {1, 2}}, {"G", {3, 4}}, {"B", {5, 6}}, {"A", {7, 8}}, {"Z", {9, 10}}, {"u", {11, 12}}});
        loaded_image back = read_image(path);
        const std::vector<float> expected = {1, 3, 5, 2, 4, 6};
        CHECK(back.pixels.data() == expected);
    }

    SUBCASE("luminance and chroma (Y, RY, BY, as OpenEXR writes them): refused in one line") {
        // Chroma at half resolution both ways. OpenEXRCore 3.1 decodes such channels into the
        // wrong rows, and the C++ reader that would rebuild RGB trusts a header's attribute sizes
        // (a fuzzed file made it allocate 1.8 GB): refused, saying what to do.
        for (const Imf::RgbaChannels mode : {Imf::WRITE_YC, Imf::WRITE_YCA}) {
            const int w = 6, h = 4;
            std::vector<Imf::Rgba> pixels(size_t(w * h), Imf::Rgba(0.5f, 0.25f, 0.125f, 1.0f));
            const std::string path = dir.file(mode == Imf::WRITE_YC ? "yc.exr" : "yca.exr");
            {
                Imf::RgbaOutputFile file(path.c_str(), w, h, mode);
                file.setFrameBuffer(pixels.data(), 1, size_t(w));
                file.writePixels(h);
            }
            check_error(path, "is subsampled (2 x 2), as in luminance/chroma images, which are not supported: save the image as RGB");
        }
    }

    SUBCASE("no colour channels: refused by name") {
        Imf::Header header(1, 1);
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        const std::string path = dir.file("depth.exr");
        write_planes(path, header, {{"Z", {1.0f}}});
        check_error(path, "neither R, G and B channels nor a Y");
    }
}

TEST_CASE("exr.h: an EXR and a PFM of the same image compare as equal") {
    test::scratch_dir dir("exr");
    image img(4, 2);
    for (size_t i = 0; i < img.data().size(); ++i) img.data()[i] = 0.05f * float(i) + 0.01f;
    write_image(dir.file("a.exr"), img);
    write_image(dir.file("a.pfm"), img);
    image_comparison c = compare_loaded(read_image(dir.file("a.exr")), read_image(dir.file("a.pfm")));
    REQUIRE(c.linear);
    CHECK(c.linear->rmse == 0.0);
    CHECK(c.display.rmse == 0.0);
}

TEST_CASE("exr.h: truncated, garbage and oversized files give one error naming the file") {
    test::scratch_dir dir("exr");
    image img(16, 16);
    for (size_t i = 0; i < img.data().size(); ++i) img.data()[i] = float(i % 7) * 0.3f;
    const std::string good = encode_image("good.exr", img);
    REQUIRE(good.size() > 200);

    SUBCASE("truncated in the pixels, in the offset table and in the header") {
        for (size_t keep : {good.size() - 1, good.size() / 2, size_t(300), size_t(40), size_t(8), size_t(4)}) {
            CAPTURE(keep);
            check_error(dir.write("cut.exr", good.substr(0, keep)), "EXR");
        }
    }
    SUBCASE("garbage after the magic number") {
        std::string junk = good.substr(0, 4);
        for (int i = 0; i < 500; ++i) junk += char((i * 37 + 11) & 0xff);
        check_error(dir.write("junk.exr", junk), "EXR");
    }
    SUBCASE("garbage in the pixel data") {
        std::string bad = good;
        for (size_t i = bad.size() - 100; i < bad.size(); ++i) bad[i] = char(0x5a);
        check_error(dir.write("bad.exr", bad), "EXR");
    }
    SUBCASE("not an EXR at all, named .exr") {
        check_error(dir.write("text.exr", "hello world\n"), "not a PPM (P3/P6), PFM, EXR, PNG, BMP, JPEG or Radiance HDR file");
    }
    SUBCASE("a data window of 65536 x 65536, more pixels than the limit, refused before decoding") {
        std::string huge = good;
        const size_t at = data_window_offset(huge);
        put_int32(huge, at + 8, 65535);
        put_int32(huge, at + 12, 65535);
        check_error(dir.write("huge.exr", huge), "EXR image is 65536x65536 = 4294967296 pixels, more than the limit");
    }
    SUBCASE("a data window wider than the library's per-file limit of 2^24") {
        std::string wide = good;
        const size_t at = data_window_offset(wide);
        put_int32(wide, at + 0, -2000000000);
        put_int32(wide, at + 8, 2000000000);
        check_error(dir.write("wide.exr", wide), "EXR");
    }
    SUBCASE("an empty data window") {
        std::string empty = good;
        const size_t at = data_window_offset(empty);
        put_int32(empty, at + 8, -5);
        check_error(dir.write("empty.exr", empty), "EXR");
    }
}

TEST_CASE("exr.h: 8-bit pixels cannot be written as EXR") {
    CHECK_THROWS_WITH_AS(encode_8bit_image("x.exr", 1, 1, {1, 2, 3}), "cannot write 'x.exr': 8-bit pixels cannot be written as EXR",
                         scene_error);
}

#else

TEST_CASE("exr.h: without the OpenEXR library, .exr gives the not-built error") {
    test::scratch_dir dir("exr");
    CHECK_THROWS_WITH_AS(check_output_path(dir.file("a.exr")),
                         ("cannot write '" + dir.file("a.exr") + "': " + exr_not_built_text()).c_str(), scene_error);
    check_error(dir.write("a.exr", std::string("\x76\x2f\x31\x01", 4) + "rest"), "EXR support was not built");
}

#endif

} // namespace test_exr
