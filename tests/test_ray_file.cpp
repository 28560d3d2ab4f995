// Ray files (rtweekend/io/ray_file.h): a file built byte by byte from the format table, round trips
// through disk, and one scene_error per kind of malformed file, each naming the file.

#include <rtweekend/io/ray_file.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <unistd.h>

namespace test_ray_file {

using namespace rt;

namespace {

namespace fs = std::filesystem;

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

// 0x3f800000 = 1.0f, 0x40000000 = 2.0f, 0xbf000000 = -0.5f, 0x3f19999a = 0.6f (nearest float),
// 0x3f4ccccd = 0.8f, 0x7f800000 = +inf, 0x41200000 = 10.0f; all little-endian.
const std::string header_any_one_ray("RTRAYS1\0"
                                     "\x01\0\0\0"
                                     "\0\0\0\0"
                                     "\x01\0\0\0\0\0\0\0",
                                     24);
const std::string ray_bytes("\0\0\x80\x3f"  // ox 1
                            "\0\0\0\x40"    // oy 2
                            "\0\0\0\xbf"    // oz -0.5
                            "\0\0\0\0"      // tmin 0
                            "\x9a\x99\x19\x3f" // dx 0.6
                            "\xcd\xcc\x4c\x3f" // dy 0.8
                            "\0\0\0\0"      // dz 0
                            "\0\0\x20\x41", // tmax 10
                            32);

// Reading `bytes` from a file must throw a one-line scene_error naming the file and `fragment`.
void check_rejected(const std::string& bytes, const std::string& fragment) {
    test::scratch_dir dir("bad");
    std::string path = dir.file("bad.rays");
    write_bytes(path, bytes);
    CAPTURE(fragment);
    bool threw = false;
    try {
        read_rays(path);
    } catch (const scene_error& e) {
        threw = true;
        std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find(path) != std::string::npos);
        CHECK(msg.find(fragment) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
    CHECK(threw);
}

std::string with_float(std::string bytes, size_t offset, float value) {
    std::memcpy(&bytes[offset], &value, 4); // the test machine is little-endian (x86-64)
    return bytes;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, 4) == 0; }

} // namespace

TEST_CASE("ray file: a hand-built file decodes to the rays in it, and encodes back to the same bytes") {
    ray_batch b = decode_rays(header_any_one_ray + ray_bytes, "hand.rays");
    CHECK(b.kind == ray_query::any);
    REQUIRE(b.rays.size() == 1);
    const ray3f& r = b.rays[0];
    CHECK(r.origin.x == 1.0f);
    CHECK(r.origin.y == 2.0f);
    CHECK(r.origin.z == -0.5f);
    CHECK(r.tmin == 0.0f);
    CHECK(r.dir.x == 0.6f);
    CHECK(r.dir.y == 0.8f);
    CHECK(r.dir.z == 0.0f);
    CHECK(r.tmax == 10.0f);
    CHECK(encode_rays(b) == header_any_one_ray + ray_bytes);
}

TEST_CASE("ray file: write_rays then read_rays gives the same rays bit for bit, for both kinds") {
    test::scratch_dir dir("roundtrip");
    ray_batch closest;
    closest.kind = ray_query::closest;
    const float inf = std::numeric_limits<float>::infinity();
    closest.rays.push_back({{0.1f, -2.5f, 1e6f}, {0.0f, 0.0f, -1.0f}, 0.0f, inf});
    closest.rays.push_back({{-1e-7f, 3.0f, 0.0f}, normalize(vec3f{1.0f, 2.0f, 3.0f}), 0.0f, 1234.5f});
    closest.rays.push_back({{0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 0.25f, 0.25f}); // empty range is allowed
    const std::string path = dir.file("closest.rays");
    write_rays(path, closest);
    CHECK(fs::file_size(path) == 24 + 32 * 3);
    ray_batch back = read_rays(path);
    CHECK(back.kind == ray_query::closest);
    REQUIRE(back.rays.size() == closest.rays.size());
    for (size_t i = 0; i < back.rays.size(); ++i) {
        const ray3f &a = closest.rays[i], &b = back.rays[i];
        CAPTURE(i);
        CHECK(same_bits(a.origin.x, b.origin.x));
        CHECK(same_bits(a.origin.y, b.origin.y));
        CHECK(same_bits(a.origin.z, b.origin.z));
        CHECK(same_bits(a.dir.x, b.dir.x));
        CHECK(same_bits(a.dir.y, b.dir.y));
        CHECK(same_bits(a.dir.z, b.dir.z));
        CHECK(same_bits(a.tmin, b.tmin));
        CHECK(same_bits(a.tmax, b.tmax));
    }

    ray_batch empty;
    empty.kind = ray_query::any;
    write_rays(dir.file("empty.rays"), empty);
    CHECK(fs::file_size(dir.file("empty.rays")) == 24);
    ray_batch empty_back = read_rays(dir.file("empty.rays"));
    CHECK(empty_back.kind == ray_query::any);
    CHECK(empty_back.rays.empty());
}

TEST_CASE("ray file: each kind of malformed file is refused with the file's name") {
    const std::string good = header_any_one_ray + ray_bytes;
    CHECK_NOTHROW(decode_rays(good));

    std::string bad_magic = good;
    bad_magic[6] = '2';
    check_rejected(bad_magic, "bad magic");

    std::string bad_kind = good;
    bad_kind[8] = 2;
    check_rejected(bad_kind, "unknown ray kind 2");

    std::string bad_reserved = good;
    bad_reserved[13] = 1; // reserved = 256
    check_rejected(bad_reserved, "reserved field is 256");

    check_rejected(good.substr(0, 10), "truncated header");
    check_rejected("", "truncated header");
    check_rejected(good.substr(0, good.size() - 1), "header says 1 rays");      // truncated ray
    check_rejected(good + ray_bytes, "header says 1 rays");                      // more rays than counted
    check_rejected(good + "x", "header says 1 rays");                            // trailing byte

    std::string huge_count = good;
    huge_count[23] = '\x7f'; // count near 2^63: would overflow count * 32
    check_rejected(huge_count, "bytes of rays");

    const float nan = std::numeric_limits<float>::quiet_NaN();
    check_rejected(with_float(good, 24 + 4, nan), "NaN");      // oy
    check_rejected(with_float(good, 24 + 16, nan), "NaN");     // dx
    check_rejected(with_float(good, 24 + 28, nan), "NaN");     // tmax
    check_rejected(with_float(good, 24 + 0, std::numeric_limits<float>::infinity()), "infinite origin");
    check_rejected(with_float(good, 24 + 16, 0.7f), "length");  // direction (0.7, 0.8, 0): |d| = 1.063
    check_rejected(with_float(good, 24 + 12, -1.0f), "tmin");
    check_rejected(with_float(good, 24 + 28, -1.0f), "below tmin");
}

TEST_CASE("ray file: missing files, directories and unwritable paths are errors naming the path") {
    test::scratch_dir dir("paths");
    CHECK_THROWS_WITH_AS(read_rays(dir.file("missing.rays")),
                         doctest::Contains("missing.rays"), scene_error);
    CHECK_THROWS_WITH_AS(read_rays(dir.path.string()), doctest::Contains("directory"), scene_error);

    ray_batch b;
    b.rays.push_back({{0, 0, 0}, {0, 0, 1}, 0, 1});
    CHECK_THROWS_WITH_AS(write_rays(dir.file("no-such-dir/out.rays"), b), doctest::Contains("no-such-dir/out.rays"),
                         scene_error);
}

TEST_CASE("ray file: write_rays refuses a bad ray and leaves no file behind") {
    test::scratch_dir dir("refuse");
    ray_batch b;
    b.rays.push_back({{0, 0, 0}, {0, 0, 1}, 0, 1});
    b.rays.push_back({{0, std::numeric_limits<float>::quiet_NaN(), 0}, {0, 0, 1}, 0, 1});
    const std::string path = dir.file("out.rays");
    CHECK_THROWS_WITH_AS(write_rays(path, b), doctest::Contains("ray 1 has a NaN component"), scene_error);
    CHECK_FALSE(fs::exists(path));
    CHECK(fs::is_empty(dir.path)); // no temporary file either

    ray_batch unnormalised;
    unnormalised.rays.push_back({{0, 0, 0}, {0, 0, 2}, 0, 1});
    CHECK_THROWS_WITH_AS(encode_rays(unnormalised), doctest::Contains("length"), scene_error);
}

} // namespace test_ray_file
