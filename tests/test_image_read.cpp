// Reading images back (rtweekend/image/image_read.h): every writer round-trips, hand-written PPM and
// PFM files in each variant decode to hand-computed values, malformed files throw naming the
// path, and the committed reference reads as the cover scene.

#include <rtweekend/image/image_write.h>
#include <rtweekend/image/image_read.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

namespace test_image_read {

using namespace rt;
namespace fs = std::filesystem;

namespace {

const float nan_f = std::numeric_limits<float>::quiet_NaN();
const float inf_f = std::numeric_limits<float>::infinity();

// 2x3 (not square, not symmetric, so a flipped or transposed read shows), with the book's
// encoding of each value worked out by hand, byte = int(256 * clamp(sqrt(v), 0, 0.999)):
//   row 0: (0.25, 1, 0) -> 128 255 0        (0.0625, 0.5625, 4) -> 64 192 255
//   row 1: (0.9, -1, 1e-6) -> 242 0 0        (0.01, NaN, inf) -> 25 0 255
//   row 2: (0.140625, 0, 0) -> 96 0 0        (0, 0, 0.390625^2) -> 0 0 100
// (0.9: sqrt 0.948683 -> 242.86 -> 242; 0.01: 0.1 -> 25.6 -> 25; 0.140625: 0.375 -> 96.)
image test_image() {
    image img(2, 3);
    const float values[18] = {0.25f, 1.0f, 0.0f,  0.0625f, 0.5625f, 4.0f,  0.9f, -1.0f, 1e-6f,
                              0.01f, nan_f, inf_f, 0.140625f, 0.0f, 0.0f,  0.0f, 0.0f, 0.152587890625f};
    std::memcpy(img.data().data(), values, sizeof values);
    return img;
}
const float expected_codes[18] = {128, 255, 0, 64, 192, 255, 242, 0, 0, 25, 0, 255, 96, 0, 0, 0, 0, 100};

std::string bytes_of(std::initializer_list<int> values) {
    std::string s;
    for (int v : values) s.push_back(char(v));
    return s;
}

// The four bytes of a float, little- or big-endian.
std::string float_bytes(float f, bool little_endian) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    std::string le = bytes_of({int(bits & 0xff), int((bits >> 8) & 0xff), int((bits >> 16) & 0xff), int(bits >> 24)});
    return little_endian ? le : std::string(le.rbegin(), le.rend());
}

void check_pixels(const image& img, int width, int height, const std::vector<float>& expected) {
    REQUIRE(img.width() == width);
    REQUIRE(img.height() == height);
    REQUIRE(img.data().size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        CAPTURE(i);
        if (std::isnan(expected[i])) CHECK(std::isnan(img.data()[i]));
        else CHECK(img.data()[i] == expected[i]);
    }
}

// Expects read_image(path) to throw scene_error with one line naming the path and `problem`.
void check_read_error(const std::string& path, const std::string& problem) {
    test::check_one_line_error([&] { read_image(path); }, path, problem);
}

} // namespace

TEST_CASE("read_image: every writer round-trips") {
    test::scratch_dir dir;
    const image img = test_image();
    const std::vector<float> codes(std::begin(expected_codes), std::end(expected_codes));

    SUBCASE("PFM: the exact floats, NaN and inf included, rows in order") {
        std::string p = (dir.path / "out.pfm").string();
        write_image(p, img);
        loaded_image back = read_image(p);
        CHECK_FALSE(back.display_encoded);
        CHECK(back.format == "PFM");
        check_pixels(back.pixels, 2, 3, img.data());
        // Bit for bit, not just equal.
        CHECK(std::memcmp(back.pixels.data().data(), img.data().data(), 18 * 4) == 0);
    }
    SUBCASE("PPM P3, PNG and BMP: the 8-bit codes the writer stored") {
        for (const char* name : {"out.ppm", "out.png", "out.bmp"}) {
            CAPTURE(name);
            std::string p = (dir.path / name).string();
            write_image(p, img);
            loaded_image back = read_image(p);
            CHECK(back.display_encoded);
            check_pixels(back.pixels, 2, 3, codes);
        }
        CHECK(read_image((dir.path / "out.ppm").string()).format == "PPM P3");
        CHECK(read_image((dir.path / "out.png").string()).format == "PNG");
        CHECK(read_image((dir.path / "out.bmp").string()).format == "BMP");
    }
    SUBCASE("PNG with an empty data chunk first (legal; stb_image would memcpy to a null pointer)") {
        std::string png = encode_image("x.png", img);
        REQUIRE(png.compare(12, 4, "IHDR") == 0);
        // After the signature (8) and IHDR (4 length + 4 type + 13 data + 4 CRC = 25): an IDAT of
        // length 0, whose CRC is CRC-32("IDAT") = 0x35af061e.
        png.insert(33, bytes_of({0, 0, 0, 0, 'I', 'D', 'A', 'T', 0x35, 0xaf, 0x06, 0x1e}));
        check_pixels(decode_image(png, "empty_idat.png").pixels, 2, 3, codes);
    }
    SUBCASE("the format follows the contents, not the name") {
        std::string p = (dir.path / "really_a_png.ppm").string();
        std::ofstream(p, std::ios::binary) << encode_image("x.png", img);
        loaded_image back = read_image(p);
        CHECK(back.format == "PNG");
        check_pixels(back.pixels, 2, 3, codes);
    }
}

TEST_CASE("read_image: a top-down BMP (negative height) reads as its bottom-up twin") {
    // 2x3, 24 bits: rows of 2 pixels padded to 8 bytes, stored B, G, R. Top row first: red,
    // green; then blue, white; then (10, 20, 30), (40, 50, 60).
    const int pixels[3][2][3] = {{{255, 0, 0}, {0, 255, 0}}, {{0, 0, 255}, {255, 255, 255}}, {{10, 20, 30}, {40, 50, 60}}};
    auto bmp = [&](bool top_down) {
        std::string rows;
        for (int k = 0; k < 3; ++k) {
            const int y = top_down ? k : 2 - k; // bottom-up files store the last row first
            for (int x = 0; x < 2; ++x) rows += bytes_of({pixels[y][x][2], pixels[y][x][1], pixels[y][x][0]});
            rows += bytes_of({0, 0});
        }
        const int height = top_down ? -3 : 3;
        const uint32_t h = uint32_t(height);
        std::string b = bytes_of({'B', 'M', 54 + 24, 0, 0, 0, 0, 0, 0, 0, 54, 0, 0, 0, // file header
                                  40, 0, 0, 0, 2, 0, 0, 0});                               // size, width
        b += bytes_of({int(h & 0xff), int((h >> 8) & 0xff), int((h >> 16) & 0xff), int(h >> 24)});
        b += bytes_of({1, 0, 24, 0, 0, 0, 0, 0, 24, 0, 0, 0, 0x13, 0x0b, 0, 0, 0x13, 0x0b, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
        return b + rows;
    };
    std::vector<float> expected;
    for (const auto& row : pixels)
        for (const auto& px : row)
            for (int c : px) expected.push_back(float(c));
    const loaded_image bottom_up = decode_image(bmp(false), "bottom_up.bmp");
    const loaded_image top_down = decode_image(bmp(true), "top_down.bmp");
    check_pixels(bottom_up.pixels, 2, 3, expected);
    check_pixels(top_down.pixels, 2, 3, expected);
    CHECK(top_down.display_encoded);
}

TEST_CASE("read_image: hand-written PPM files") {
    SUBCASE("P6 with a comment in the header") {
        std::string file = "P6\n# made by hand\n2 1\n255\n" + bytes_of({0, 1, 2, 253, 254, 255});
        loaded_image img = decode_image(file, "p6.ppm");
        CHECK(img.display_encoded);
        CHECK(img.format == "PPM P6");
        check_pixels(img.pixels, 2, 1, {0, 1, 2, 253, 254, 255});
    }
    SUBCASE("P6 ends at its raster: trailing bytes (a second image) are not read") {
        std::string file = "P6 1 1 255 " + bytes_of({10, 20, 30}) + "P6 1 1 255 " + bytes_of({1, 2, 3});
        check_pixels(decode_image(file, "two.ppm").pixels, 1, 1, {10, 20, 30});
    }
    SUBCASE("P6 with 16-bit samples, big-endian, rescaled to 0..255") {
        // maxval 65535: 0x0100 = 256 -> 256 * 255/65535 = 0.99610895; 0xffff -> 255; 0x8000 = 32768 -> 127.50195
        std::string file = "P6\n1 1\n65535\n" + bytes_of({0x01, 0x00, 0xff, 0xff, 0x80, 0x00});
        loaded_image img = decode_image(file, "p6_16.ppm");
        REQUIRE(img.pixels.width() == 1);
        CHECK(img.pixels.data()[0] == doctest::Approx(0.99610895).epsilon(1e-6));
        CHECK(img.pixels.data()[1] == 255.0f);
        CHECK(img.pixels.data()[2] == doctest::Approx(127.50195).epsilon(1e-6));
    }
    SUBCASE("P3 with comments everywhere and maxval 15") {
        // maxval 15: each code times 255/15 = 17.
        std::string file = "P3 # plain\n# width and height:\n2 1 # two pixels\n15\n0 5 10\n# second pixel\n15 3 0\n";
        loaded_image img = decode_image(file, "p3.ppm");
        CHECK(img.format == "PPM P3");
        check_pixels(img.pixels, 2, 1, {0, 85, 170, 255, 51, 0});
    }
    SUBCASE("P3 values may share lines and use any whitespace") {
        check_pixels(decode_image("P3\n1 2\n255\n1\t2  3\r\n4\n5\n6", "ws.ppm").pixels, 1, 2, {1, 2, 3, 4, 5, 6});
    }
}

TEST_CASE("read_image: hand-written PFM files, both byte orders, colour and grey") {
    // A 1x2 colour image. PFM rows go bottom to top: the file's first row is the image's bottom.
    //   top    (y = 0) = (0.25, 0, 1)
    //   bottom (y = 1) = (1, 0.5, -2)
    for (bool little : {true, false}) {
        CAPTURE(little);
        std::string file = std::string("PF\n1 2\n") + (little ? "-1.0" : "1.0") + "\n";
        for (float f : {1.0f, 0.5f, -2.0f, 0.25f, 0.0f, 1.0f}) file += float_bytes(f, little);
        loaded_image img = decode_image(file, "hand.pfm");
        CHECK_FALSE(img.display_encoded);
        check_pixels(img.pixels, 1, 2, {0.25f, 0, 1, 1, 0.5f, -2});
    }
    // The scale's magnitude is not applied; only its sign matters.
    std::string scaled = "PF\n1 1\n4.5\n" + float_bytes(3.0f, false) + float_bytes(2.0f, false) + float_bytes(1.0f, false);
    check_pixels(decode_image(scaled, "scaled.pfm").pixels, 1, 1, {3, 2, 1});

    // Pf: one grey value per pixel, copied to R, G and B. A 2x2 image, bottom row first.
    std::string grey = "Pf\n2 2\n-1\n";
    for (float f : {0.5f, 2.0f, 0.125f, 8.0f}) grey += float_bytes(f, true);
    check_pixels(decode_image(grey, "grey.pfm").pixels, 2, 2,
                 {0.125f, 0.125f, 0.125f, 8, 8, 8, 0.5f, 0.5f, 0.5f, 2, 2, 2});
}

TEST_CASE("read_image: missing, truncated and malformed files throw, naming the path") {
    test::scratch_dir dir;
    const image img = test_image();
    const std::string png = encode_image("x.png", img), bmp = encode_image("x.bmp", img), pfm = encode_image("x.pfm", img);

    check_read_error((dir.path / "missing.pfm").string(), "No such file");
    check_read_error(dir.path.string(), "directory");
    check_read_error(dir.write("empty.ppm", ""), "empty");
    check_read_error(dir.write("text.ppm", "hello world\n"), "not a PPM (P3/P6), PFM, EXR, PNG, BMP, JPEG or Radiance HDR file");
    check_read_error(dir.write("p5.ppm", "P5\n1 1\n255\n\x01"), "not a PPM");

    // PPM headers.
    check_read_error(dir.write("no_size.ppm", "P3\n"), "truncated before the width");
    check_read_error(dir.write("bad_width.ppm", "P3\nabc 2\n255\n"), "width is not a number (found 'a')");
    check_read_error(dir.write("zero_width.ppm", "P6\n0 2\n255\n"), "width must be at least 1");
    check_read_error(dir.write("huge_width.ppm", "P6\n99999999 1\n255\n"), "width must be at most 16777216");
    check_read_error(dir.write("maxval.ppm", "P3\n1 1\n70000\n1 2 3\n"), "maxval must be at most 65535");
    check_read_error(dir.write("glued.ppm", "P62 2 255\n"), "whitespace after the magic number");
    // A header promising a huge image over a few bytes is refused before anything is allocated.
    check_read_error(dir.write("big.ppm", "P6\n16777216 16777216\n255\n\x01\x02\x03"), "raster is truncated");
    check_read_error(dir.write("big3.ppm", "P3\n16777216 16777216\n255\n1 2 3\n"), "raster is truncated");

    // PPM rasters.
    check_read_error(dir.write("short6.ppm", "P6\n2 1\n255\n" + bytes_of({1, 2, 3, 4, 5})), "raster is truncated");
    check_read_error(dir.write("short3.ppm", "P3\n2 2\n255\n1 2 3 4 5 6 7 8 9 10 11\n"), "needs 12 values, the file has 11");
    check_read_error(dir.write("over.ppm", "P3\n1 1\n255\n1 2 256\n"), "value 2 must be at most 255");
    check_read_error(dir.write("over6.ppm", "P6\n1 1\n100\n" + bytes_of({1, 101, 3})), "above maxval 100");
    check_read_error(dir.write("word.ppm", "P3\n1 1\n255\n1 x 3\n"), "value 1 is not a number (found 'x')");
    check_read_error(dir.write("extra.ppm", "P3\n1 1\n255\n1 2 3 4\n"), "more data after the 3 values of a 1x1 image");

    // PFM.
    check_read_error(dir.write("short.pfm", pfm.substr(0, pfm.size() - 1)), "raster is truncated");
    check_read_error(dir.write("header_only.pfm", "PF\n2 3\n-1.0\n"), "raster is truncated");
    check_read_error(dir.write("long.pfm", pfm + "x"), "1 bytes after the raster");
    check_read_error(dir.write("scale0.pfm", "PF\n1 1\n0.0\n" + std::string(12, '\0')), "scale '0.0' is not a non-zero number");
    check_read_error(dir.write("scalex.pfm", "PF\n1 1\nabc\n" + std::string(12, '\0')), "scale 'abc'");
    check_read_error(dir.write("noscale.pfm", "PF\n1 1\n"), "truncated before the scale");
    check_read_error(dir.write("comment.pfm", "PF\n# no comments in PFM\n1 1\n-1\n" + std::string(12, '\0')),
                     "width is not a number");

    // PNG and BMP, cut short: stb_image's reason comes after the format.
    check_read_error(dir.write("short.png", png.substr(0, png.size() / 2)), "PNG ");
    // stb_image fills a short BMP with zeros rather than failing, so the reader checks the size.
    // stb writes 24-bit rows padded to 4 bytes: 2 pixels = 6 bytes -> 8, 3 rows, after a 54-byte header.
    REQUIRE(bmp.size() == 54 + 3 * 8);
    check_read_error(dir.write("short.bmp", bmp.substr(0, bmp.size() - 1)), "BMP raster is truncated: needs 78 bytes, the file has 77");
    check_read_error(dir.write("header.bmp", bmp.substr(0, 20)), "BMP ");
    check_read_error(dir.write("sig.png", png.substr(0, 8)), "PNG ");
}

TEST_CASE("read_image: the committed cover reference is the 400x225 linear cover") {
    loaded_image ref = read_image(std::string(RTWEEKEND_TEST_DATA) + "/rtiow_cover_400x225_ref.pfm");
    CHECK(ref.format == "PFM");
    CHECK_FALSE(ref.display_encoded);
    REQUIRE(ref.pixels.width() == 400);
    REQUIRE(ref.pixels.height() == 225);
    // Values read from the file's bytes with an independent script (Python's struct): the top-left
    // pixel is sky, the file's last row; the bottom-right pixel, its first row.
    CHECK(ref.pixels.pixel(0, 0).x() == doctest::Approx(0.744040549).epsilon(1e-7));
    CHECK(ref.pixels.pixel(0, 0).y() == doctest::Approx(0.846424341).epsilon(1e-7));
    CHECK(ref.pixels.pixel(0, 0).z() == 1.0);
    CHECK(ref.pixels.pixel(399, 224).x() == doctest::Approx(0.0544296764).epsilon(1e-7));
    CHECK(ref.pixels.pixel(399, 224).y() == doctest::Approx(0.409528255).epsilon(1e-7));
    // The same script's channel means: 0.29690, 0.34719, 0.44028 (a blue sky over the ground).
    double sum[3] = {0, 0, 0};
    for (size_t i = 0; i < ref.pixels.data().size(); ++i) sum[i % 3] += ref.pixels.data()[i];
    const double pixels = 400.0 * 225.0;
    CHECK(sum[0] / pixels == doctest::Approx(0.296903).epsilon(1e-5));
    CHECK(sum[1] / pixels == doctest::Approx(0.347191).epsilon(1e-5));
    CHECK(sum[2] / pixels == doctest::Approx(0.440283).epsilon(1e-5));
}

} // namespace test_image_read
