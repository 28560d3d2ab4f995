// image and the writers (rtweekend/image/image_write.h, rtweekend/color.h): byte-exact P3 text, PFM layout,
// PNG/BMP round trips through stb_image, and the error paths of write_image.

#include <rtweekend/color.h>
#include <rtweekend/image/image_write.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

// stb_image reads the PNGs back: the copy rtw_stb_image.h compiles (camera.h, through
// test_helpers.h and texture.h, already includes it).
#include <rtweekend/rtw_stb_image.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace test_image {

using namespace rt;
namespace fs = std::filesystem;

namespace {

const float inf_f = std::numeric_limits<float>::infinity();
const float nan_f = std::numeric_limits<float>::quiet_NaN();

// The 2x2 test image and its 8-bit encoding, worked out by hand with the book's rule
// byte = int(256 * clamp(sqrt(x), 0, 0.999)), and 0 for x <= 0 or NaN:
//   (0,0) = ( 0.25,  1.0,   0.0   ): sqrt 0.5 -> 128;  1 -> 0.999 -> 255.74 -> 255;  0 -> 0
//   (1,0) = (-1.0,   NaN,   0.5   ): negative -> 0;  NaN -> 0;  sqrt 0.5 = 0.70711 -> 181.02 -> 181
//   (0,1) = ( 4.0,   0.01,  0.0625): sqrt 4 = 2 -> 0.999 -> 255;  0.1 -> 25.6 -> 25;  0.25 -> 64
//   (1,1) = ( 1e-6,  0.9,   +inf  ): 0.001 -> 0.256 -> 0;  0.948683 -> 242.86 -> 242;  inf -> 255
// (The float values 0.01f = 0.0099999998 and 0.9f = 0.89999998 do not move any byte.)
image test_image() {
    image img(2, 2);
    std::vector<float>& d = img.data();
    const float values[12] = {0.25f, 1.0f, 0.0f, -1.0f, nan_f, 0.5f, 4.0f, 0.01f, 0.0625f, 1e-6f, 0.9f, inf_f};
    std::memcpy(d.data(), values, sizeof values);
    return img;
}

const unsigned char expected_bytes[12] = {128, 255, 0, 0, 0, 181, 255, 25, 64, 0, 242, 255};
const char expected_ppm[] = "P3\n2 2\n255\n"
                            "128 255 0\n"
                            "0 0 181\n"
                            "255 25 64\n"
                            "0 242 255\n";

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

using test::check_scene_error;

} // namespace

TEST_CASE("image: pixel access, rows top to bottom, interleaved RGB") {
    image img(3, 2);
    CHECK(img.width() == 3);
    CHECK(img.height() == 2);
    CHECK_FALSE(img.empty());
    CHECK(img.data().size() == 18);
    for (float v : img.data()) CHECK(v == 0);
    img.set_pixel(2, 1, color(0.5, 0.25, 2));
    // (y * width + x) * 3 = (1 * 3 + 2) * 3 = 15
    CHECK(img.data()[15] == 0.5f);
    CHECK(img.data()[16] == 0.25f);
    CHECK(img.data()[17] == 2.0f);
    CHECK(img.pixel(2, 1).z() == 2);
    CHECK(image().empty());
    CHECK(image(0, 4).empty());
    CHECK(image(4, 0).empty());
}

TEST_CASE("write_color and encode_byte: the book's gamma-2, 8-bit encoding") {
    std::ostringstream out;
    write_color(out, color(0.25, 1.0, 0.0));
    CHECK(out.str() == "128 255 0\n");
    CHECK(encode_byte(0.0) == 0);
    CHECK(encode_byte(-3.0) == 0);
    CHECK(encode_byte(std::nan("")) == 0);
    CHECK(encode_byte(1.0) == 255);
    CHECK(encode_byte(0.25) == 128);
    // (100/256)^2: sqrt gives exactly 100/256 = 0.390625 -> int(100) = 100.
    CHECK(encode_byte((100.0 / 256) * (100.0 / 256)) == 100);
    CHECK(linear_to_gamma(0.81) == doctest::Approx(0.9));
    CHECK(linear_to_gamma(-0.5) == 0);
}

TEST_CASE("write_color with a sample count (the book's earlier form) averages first") {
    // Four samples summing to (1.0, 4.0, 0.0) average to (0.25, 1.0, 0.0): "128 255 0" as above.
    std::ostringstream out;
    write_color(out, color(1.0, 4.0, 0.0), 4);
    CHECK(out.str() == "128 255 0\n");
}

TEST_CASE("write_ppm: byte-exact P3 text") {
    std::ostringstream out;
    write_ppm(out, test_image());
    CHECK(out.str() == expected_ppm);

    // A 3x1 image: "P3\n3 1\n255\n" and one line per pixel, left to right.
    image row(3, 1);
    row.set_pixel(0, 0, color(1, 1, 1));
    row.set_pixel(2, 0, color(0.25, 0.25, 0.25));
    std::ostringstream out2;
    write_ppm(out2, row);
    CHECK(out2.str() == "P3\n3 1\n255\n255 255 255\n0 0 0\n128 128 128\n");
}

TEST_CASE("write_image: .ppm, .pfm, .png, .bmp, and uppercase extensions") {
    test::scratch_dir dir;
    const image img = test_image();

    SUBCASE("ppm") {
        fs::path p = dir.path / "out.ppm";
        write_image(p.string(), img);
        CHECK(read_file(p) == expected_ppm);
        // Uppercase extension: same format.
        fs::path q = dir.path / "OUT.PPM";
        write_image(q.string(), img);
        CHECK(read_file(q) == expected_ppm);
        // Overwriting an existing file replaces it.
        image black(1, 1);
        write_image(p.string(), black);
        CHECK(read_file(p) == "P3\n1 1\n255\n0 0 0\n");
    }

    SUBCASE("pfm: header, little-endian floats, rows bottom to top") {
        fs::path p = dir.path / "out.Pfm";
        write_image(p.string(), img);
        std::string bytes = read_file(p);
        const std::string header = "PF\n2 2\n-1.0\n"; // negative scale = little-endian
        REQUIRE(bytes.size() == header.size() + 2 * 2 * 3 * 4);
        CHECK(bytes.substr(0, header.size()) == header);
        auto float_at = [&](size_t k) {
            const unsigned char* b = reinterpret_cast<const unsigned char*>(bytes.data() + header.size() + 4 * k);
            uint32_t bits = uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
            float f;
            std::memcpy(&f, &bits, 4);
            return f;
        };
        // The bottom row (y = 1) comes first, left to right, then the top row (y = 0).
        const float bottom_then_top[12] = {4.0f, 0.01f, 0.0625f, 1e-6f, 0.9f, inf_f,
                                           0.25f, 1.0f, 0.0f, -1.0f, nan_f, 0.5f};
        for (size_t k = 0; k < 12; ++k) {
            CAPTURE(k);
            if (std::isnan(bottom_then_top[k]))
                CHECK(std::isnan(float_at(k)));
            else
                CHECK(float_at(k) == bottom_then_top[k]);
        }
    }

    SUBCASE("png and bmp decode to the same 8-bit values") {
        for (const char* name : {"out.png", "out.bmp", "UPPER.PNG", "Upper.Bmp"}) {
            CAPTURE(name);
            fs::path p = dir.path / name;
            write_image(p.string(), img);
            int w = 0, h = 0, n = 0;
            unsigned char* pixels = stbi_load(p.string().c_str(), &w, &h, &n, 3);
            REQUIRE(pixels != nullptr);
            CHECK(w == 2);
            CHECK(h == 2);
            CHECK(n == 3);
            for (int k = 0; k < 12; ++k) {
                CAPTURE(k);
                CHECK(int(pixels[k]) == int(expected_bytes[k]));
            }
            stbi_image_free(pixels);
        }
        // The PNG signature, to be sure the format follows the extension.
        std::string png = read_file(dir.path / "out.png");
        CHECK(png.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
        CHECK(read_file(dir.path / "out.bmp").substr(0, 2) == "BM");
    }

    // Only the files written remain: no temporaries left beside them.
    for (const std::string& name : dir.entries()) {
        CAPTURE(name);
        CHECK(name.find(".tmp") == std::string::npos);
    }
}

TEST_CASE("write_image: unknown extensions are rejected, naming the extension and path") {
    test::scratch_dir dir;
    const image img = test_image();
    std::string jpg = (dir.path / "out.jpg").string();
    check_scene_error([&] { write_image(jpg, img); }, {jpg, ".jpg"});
    std::string none = (dir.path / "noextension").string();
    check_scene_error([&] { write_image(none, img); }, {none});
    // A dot in a directory name is not an extension.
    fs::create_directories(dir.path / "dir.png");
    std::string dotted_dir = (dir.path / "dir.png" / "file").string();
    check_scene_error([&] { write_image(dotted_dir, img); }, {dotted_dir});
    CHECK_THROWS_AS((void)encode_image("x.tiff", img), scene_error);
    // Nothing was written.
    CHECK(dir.entries() == std::vector<std::string>{"dir.png"});
    CHECK(fs::is_empty(dir.path / "dir.png"));
}

TEST_CASE("write_image: unwritable paths throw, naming the path, and leave nothing behind") {
    test::scratch_dir dir;
    const image img = test_image();

    // A directory that does not exist.
    const std::string missing = "/nonexistent-dir/x.png";
    REQUIRE_FALSE(fs::exists("/nonexistent-dir"));
    check_scene_error([&] { write_image(missing, img); }, {missing});
    CHECK_FALSE(fs::exists("/nonexistent-dir"));

    // The target is an existing directory.
    fs::path target = dir.path / "taken.ppm";
    fs::create_directories(target);
    check_scene_error([&] { write_image(target.string(), img); }, {target.string()});
    CHECK(fs::is_directory(target));
    CHECK(fs::is_empty(target));
    // No temporary file was left in the parent directory.
    CHECK(dir.entries() == std::vector<std::string>{"taken.ppm"});

    // A path below a regular file.
    fs::path file = dir.path / "plain";
    { std::ofstream(file) << "x"; }
    std::string below = (file / "x.ppm").string();
    check_scene_error([&] { write_image(below, img); }, {below});
    CHECK(read_file(file) == "x");
}

TEST_CASE("write_image and encode_image: an empty image throws") {
    test::scratch_dir dir;
    std::string p = (dir.path / "empty.png").string();
    check_scene_error([&] { write_image(p, image()); }, {p, "empty"});
    check_scene_error([&] { write_image(p, image(0, 3)); }, {p});
    check_scene_error([&] { write_image(p, image(3, 0)); }, {p});
    check_scene_error([&] { (void)encode_image("e.ppm", image()); }, {"e.ppm"});
    CHECK(dir.entries().empty());
}

TEST_CASE("check_output_path: refuses what write_image would refuse, touches nothing") {
    test::scratch_dir dir;
    // A writable path with a known format: no error, and neither the file nor a probe remains.
    fs::path ok = dir.path / "fine.png";
    CHECK_NOTHROW(check_output_path(ok.string()));
    CHECK_FALSE(fs::exists(ok));
    CHECK(dir.entries().empty());
    // An existing file is not modified.
    fs::path existing = dir.path / "old.ppm";
    { std::ofstream(existing) << "keep"; }
    CHECK_NOTHROW(check_output_path(existing.string()));
    CHECK(read_file(existing) == "keep");

    std::string jpg = (dir.path / "x.jpg").string();
    check_scene_error([&] { check_output_path(jpg); }, {jpg, ".jpg"});
    const std::string missing = "/nonexistent-dir/x.png";
    check_scene_error([&] { check_output_path(missing); }, {missing});
    CHECK_FALSE(fs::exists("/nonexistent-dir"));
    fs::path target = dir.path / "taken.bmp";
    fs::create_directories(target);
    check_scene_error([&] { check_output_path(target.string()); }, {target.string()});

    // Only what this test created is left.
    std::vector<std::string> names = dir.entries();
    std::sort(names.begin(), names.end());
    CHECK(names == std::vector<std::string>{"old.ppm", "taken.bmp"});
}

} // namespace test_image
