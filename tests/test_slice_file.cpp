// Sample slices (rtweekend/io/slice_file.h): the file round-trips; it reads as a PFM of the slice's
// mean; slices of a render merge into the whole render's image byte for byte; and every way a
// set of slices can be wrong (overlap, gaps, another render, a damaged or foreign file) is one
// error line naming the file.

#include <rtweekend/camera.h>
#include <rtweekend/render/fixed_point.h>
#include <rtweekend/render/path_tracer.h>
#include <rtweekend/image/image_read.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/io/slice_file.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace test_slice_file {

using namespace rt;

namespace {

// A hand-made 3x2 slice: samples [2, 6) of 8, pixel i's channel k summing to (i + k) units of
// radiance per sample (so its mean is i + k), one channel negative and one at the largest sum 4
// samples may reach.
sample_slice hand_slice() {
    sample_slice s;
    s.render = {3, 2, 8, 42, "sobol", "max_depth 5, estimator nee", "0123456789abcdef"};
    s.first_sample = 2;
    s.end_sample = 6;
    s.rays = 1234;
    s.nonfinite = 1;
    s.saturated = 0;
    for (int i = 0; i < 6; ++i)
        for (int k = 0; k < 3; ++k) s.sums.push_back(int64_t(4) * int64_t(i + k) << 32);
    s.sums[4] = -(int64_t(4) << 31);          // pixel 1, green: mean -0.5
    s.sums[17] = sample_limit(8) * int64_t(4); // pixel 5, blue: the bound
    return s;
}

void check_same_slice(const sample_slice& a, const sample_slice& b) {
    CHECK(a.render.width == b.render.width);
    CHECK(a.render.height == b.render.height);
    CHECK(a.render.samples_per_pixel == b.render.samples_per_pixel);
    CHECK(a.render.seed == b.render.seed);
    CHECK(a.render.sampler == b.render.sampler);
    CHECK(a.render.settings == b.render.settings);
    CHECK(a.render.scene == b.render.scene);
    CHECK(a.first_sample == b.first_sample);
    CHECK(a.end_sample == b.end_sample);
    CHECK(a.rays == b.rays);
    CHECK(a.nonfinite == b.nonfinite);
    CHECK(a.saturated == b.saturated);
    CHECK(a.sums == b.sums);
}

// A file made from `bytes` must be refused with one line naming it and saying `problem`.
void check_refused(const test::scratch_dir& dir, const std::string& name, const std::string& bytes,
                   const std::string& problem) {
    const std::string path = dir.write(name, bytes);
    test::check_one_line_error([&] { read_slice(path); }, path, problem);
}

// Replaces the trailer line `key value` by `key replacement` and fixes the checksum, so that only
// the field is wrong.
std::string with_field(std::string bytes, const std::string& key, const std::string& replacement) {
    const size_t at = bytes.find("\n" + key + " ", bytes.find("rtweekend-slice"));
    REQUIRE(at != std::string::npos);
    const size_t start = at + key.size() + 2, end = bytes.find('\n', start);
    bytes.replace(start, end - start, replacement);
    const size_t tail = bytes.size() - (std::strlen("\nchecksum ") + 17);
    bytes.replace(tail + 10, 16, hex64(fnv1a64(bytes.data(), tail)));
    return bytes;
}

// The cover scene, small, as `render` renders it with these settings.
struct cover_render {
    scene_description scene = load_scene(std::string(RTWEEKEND_TEST_DATA) + "/rtiow_cover.txt");
    render_settings settings;
    cover_render() {
        scene.cam.image_width = 40;
        scene.cam.image_height = 0;
        scene.cam.samples_per_pixel = 6;
        scene.cam.max_depth = 4;
        scene.cam.settings.seed = 11;
        scene.cam.settings.quiet = true;
        scene.cam.settings.threads = 2;
        settings = scene.cam.effective_settings();
    }
    render_result run(int first, int end) const {
        render_settings s = settings;
        s.first_sample = first;
        s.end_sample = end;
        s.keep_sums = true;
        return path_trace(scene.world, scene.cam.frame(), scene.cam.sky(), s, scene.point_lights);
    }
    sample_slice slice(int first, int end) const {
        render_result r = run(first, end);
        sample_slice s;
        s.render = {r.sums.width, r.sums.height, settings.samples_per_pixel, settings.seed,
                    sampler_name(settings.sampler), "max_depth 4, estimator nee", scene_fingerprint(scene.files)};
        s.first_sample = first;
        s.end_sample = end;
        s.rays = r.stats.rays;
        s.nonfinite = r.stats.nonfinite_samples;
        s.saturated = r.stats.saturated_samples;
        s.sums = r.sums.rgb;
        return s;
    }
};

} // namespace

TEST_CASE("slice file: every field and sum round-trips") {
    const sample_slice s = hand_slice();
    check_same_slice(decode_slice(encode_slice(s), "hand.pfm"), s);
    test::scratch_dir dir("slice");
    write_slice(dir.file("hand.pfm"), s);
    check_same_slice(read_slice(dir.file("hand.pfm")), s);
    CHECK(dir.entries().size() == 1); // written atomically: no temporary file left
}

TEST_CASE("slice file: it is a PFM of the slice's mean, which read_image reads") {
    const sample_slice s = hand_slice();
    const std::string bytes = encode_slice(s);
    REQUIRE(bytes.compare(0, 11, "PF\n3 2\n-1.0") == 0);
    loaded_image img = decode_image(bytes, "hand.pfm");
    CHECK(img.format == "PFM");
    CHECK_FALSE(img.display_encoded);
    REQUIRE(img.pixels.width() == 3);
    REQUIRE(img.pixels.height() == 2);
    // Pixel i's channel k is i + k (the sums are 4 (i + k) per 4 samples), except the two set apart.
    for (int i = 0; i < 6; ++i) {
        const color c = img.pixels.pixel(i % 3, i / 3);
        CHECK(c.x() == i);
        CHECK(c.y() == (i == 1 ? -0.5 : i + 1));
        if (i != 5) CHECK(c.z() == i + 2);
    }
    CHECK(img.pixels.pixel(2, 1).z() == doctest::Approx(std::ldexp(1.0, 31) / 8)); // the bound's mean
    // Bytes after a raster that are not a slice trailer are still refused, and a cut trailer magic too.
    const std::string pfm = encode_pfm(img.pixels);
    CHECK_THROWS_WITH_AS(decode_image(pfm + "\nsomething else", "x.pfm"), doctest::Contains("bytes after the raster"),
                         scene_error);
    CHECK_THROWS_WITH_AS(decode_image(pfm + "\nrtweekend-sli", "x.pfm"), doctest::Contains("bytes after the raster"),
                         scene_error);
    // ... and a slice cut inside its raster is a truncated PFM.
    CHECK_THROWS_WITH_AS(decode_image(bytes.substr(0, 40), "x.pfm"), doctest::Contains("raster is truncated"),
                         scene_error);
}

TEST_CASE("slice file: slices of a render merge into the whole render's image, byte for byte, in any order") {
    const cover_render cover;
    const render_result whole = path_trace(cover.scene.world, cover.scene.cam.frame(), cover.scene.cam.sky(),
                                           cover.settings, cover.scene.point_lights);
    test::scratch_dir dir("merge");
    const std::vector<std::pair<int, int>> ranges = {{4, 6}, {0, 1}, {1, 4}};
    std::vector<std::string> files;
    for (auto [first, end] : ranges) {
        files.push_back(dir.file("part" + std::to_string(first) + ".pfm"));
        write_slice(files.back(), cover.slice(first, end));
    }
    for (const std::vector<int>& order : std::vector<std::vector<int>>{{0, 1, 2}, {2, 0, 1}}) {
        slice_merger m;
        for (int i : order) m.add(read_slice(files[size_t(i)]), files[size_t(i)]);
        const merged_render r = m.result(false);
        CHECK(r.gaps.empty());
        CHECK(r.slices == 3);
        CHECK(r.rays == whole.stats.rays);
        const image merged = mean_image(r.sums);
        for (const char* ext : {".png", ".pfm", ".ppm"}) {
            CAPTURE(ext);
            CHECK(encode_image(std::string("out") + ext, merged) == encode_image(std::string("out") + ext, whole.img));
        }
    }
    // One slice of the whole range is the whole render too.
    slice_merger all;
    all.add(cover.slice(0, 6), "all.pfm");
    CHECK(test::same_bits(mean_image(all.result(false).sums), whole.img));
}

TEST_CASE("slice file: merging refuses overlaps, gaps (unless allowed) and slices of other renders") {
    const sample_slice s = hand_slice(); // samples [2, 6) of 8
    auto with_range = [&](int first, int end) {
        sample_slice t = s;
        t.first_sample = first;
        t.end_sample = end;
        return t;
    };
    SUBCASE("overlap: both files named, with their ranges") {
        slice_merger m;
        m.add(s, "a.pfm");
        test::check_one_line_error([&] { m.add(with_range(5, 8), "b.pfm"); }, "b.pfm",
                                   "'b.pfm' (samples 5 to 7) and 'a.pfm' (samples 2 to 5) overlap");
        test::check_one_line_error([&] { m.add(s, "c.pfm"); }, "a.pfm", "overlap");
    }
    SUBCASE("gaps: an error naming the missing samples, or with --allow-gaps the mean of those present") {
        slice_merger m;
        m.add(s, "a.pfm");
        m.add(with_range(7, 8), "b.pfm");
        test::check_one_line_error([&] { m.result(false); }, "samples 0 to 1, samples 6 to 6 are missing",
                                   "--allow-gaps");
        const merged_render r = m.result(true);
        CHECK(r.gaps == std::vector<std::pair<int, int>>{{0, 2}, {6, 7}});
        CHECK(r.sums.counts == std::vector<int32_t>(6, 5));
        // Pixel 0: 4 * (0, 1, 2) units from a.pfm and 4 * (0, 1, 2) from b.pfm, over 5 samples.
        const image img = mean_image(r.sums);
        CHECK(img.pixel(0, 0).y() == double(static_cast<float>(8.0 / 5.0)));
        CHECK(img.pixel(0, 0).z() == double(static_cast<float>(16.0 / 5.0)));
    }
    SUBCASE("another render: the field and both files named") {
        auto refused = [&](sample_slice other, const std::string& problem) {
            slice_merger m;
            m.add(s, "a.pfm");
            other.first_sample = 0;
            other.end_sample = 2;
            test::check_one_line_error([&] { m.add(other, "b.pfm"); }, "'b.pfm' is a slice of another render than 'a.pfm'",
                                       problem);
        };
        sample_slice t = s;
        t.render.width = 2;
        t.sums.resize(2 * 2 * 3);
        refused(t, "size 2x2 against 3x2");
        t = s;
        t.render.samples_per_pixel = 16;
        refused(t, "samples per pixel 16 against 8");
        t = s;
        t.render.seed = 43;
        refused(t, "seed 43 against 42");
        t = s;
        t.render.sampler = "independent";
        refused(t, "sampler independent against sobol");
        t = s;
        t.render.settings = "max_depth 6, estimator nee";
        refused(t, "settings 'max_depth 6, estimator nee' against 'max_depth 5, estimator nee'");
        t = s;
        t.render.scene = "fedcba9876543210";
        refused(t, "scene (its files' contents) fedcba9876543210 against 0123456789abcdef");
    }
    SUBCASE("nothing to merge") {
        slice_merger m;
        CHECK_THROWS_WITH_AS(m.result(true), "no slices to merge", scene_error);
    }
}

TEST_CASE("slice file: a missing, truncated, damaged or foreign file is one error line naming it") {
    test::scratch_dir dir("bad_slices");
    const std::string good = encode_slice(hand_slice());
    test::check_one_line_error([&] { read_slice(dir.file("missing.pfm")); }, "missing.pfm", "cannot open slice file");
    check_refused(dir, "empty.pfm", "", "not a slice file");
    check_refused(dir, "text.pfm", "hello, world\n", "not a slice file");
    check_refused(dir, "png.pfm", "\x89PNG\r\n\x1a\n", "not a slice file");
    check_refused(dir, "plain.pfm", encode_pfm(image(3, 2)), "a PFM image without a slice trailer");
    // Cut anywhere: in the PFM header, in the raster, in the trailer's text, in the sums, in the checksum.
    for (size_t cut : {size_t(5), size_t(30), good.find("rtweekend-slice") + 3, good.find("\nseed") + 2,
                       good.find("\nsums ") + 20, good.size() - 5, good.size() - 1}) {
        CAPTURE(cut);
        const std::string path = dir.write("cut.pfm", good.substr(0, cut));
        CHECK_THROWS_AS(read_slice(path), scene_error);
        try {
            read_slice(path);
        } catch (const scene_error& e) {
            CHECK(std::string(e.what()).find("cut.pfm") != std::string::npos);
            CHECK(std::string(e.what()).find('\n') == std::string::npos);
        }
    }
    check_refused(dir, "short.pfm", good.substr(0, good.size() - 3), "checksum line");
    // One byte changed, in the raster or in the sums: the checksum.
    std::string flipped = good;
    flipped[20] ^= 0x10;
    check_refused(dir, "flip1.pfm", flipped, "checksum mismatch");
    flipped = good;
    flipped[good.find("\nsums ") + 30] ^= 0x01;
    check_refused(dir, "flip2.pfm", flipped, "checksum mismatch");
    // Garbage after a real PFM header and raster, then the magic.
    check_refused(dir, "garbage.pfm", encode_pfm(image(3, 2)) + slice_trailer_magic + "1\n\x01\x02garbage",
                  "checksum line");
    // Fields that are wrong, with a correct checksum: only the reader's own checks stand.
    check_refused(dir, "version.pfm", [&] {
        std::string b = good;
        b.replace(b.find("rtweekend-slice 1") + 16, 1, "9");
        const size_t tail = b.size() - 27;
        b.replace(tail + 10, 16, hex64(fnv1a64(b.data(), tail)));
        return b;
    }(), "version '9' is not supported");
    check_refused(dir, "width.pfm", with_field(good, "width", "4"), "the trailer says 4x2, the PFM header 3x2");
    check_refused(dir, "range.pfm", with_field(good, "end_sample", "9"), "not a non-empty part of [0, 8)");
    check_refused(dir, "order.pfm", with_field(good, "first_sample", "6"), "not a non-empty part");
    check_refused(dir, "number.pfm", with_field(good, "seed", "4x2"), "seed '4x2' is not a number");
    check_refused(dir, "huge.pfm", with_field(good, "rays", "99999999999999999999999"), "rays");
    check_refused(dir, "sums.pfm", with_field(good, "sums", "16"), "its sums hold 16 bytes, a 3x2 slice has 144");
    // A sum beyond what its samples can add up to (one sample fewer makes the bound-sized sum too big).
    check_refused(dir, "bound.pfm", with_field(good, "first_sample", "3"), "beyond what 3 samples can add up to");
}

TEST_CASE("slice file: the reader takes what the writer writes, refuses the rest in one printable line") {
    test::scratch_dir dir("odd_slices");
    const std::string good = encode_slice(hand_slice());
    auto with_checksum = [](std::string b) {
        const size_t tail = b.size() - 27;
        b.replace(tail + 10, 16, hex64(fnv1a64(b.data(), tail)));
        return b;
    };
    // Control characters in a text field: the writer refuses them, so the reader does.
    check_refused(dir, "cr.pfm", with_field(good, "sampler", "sobol\r"), "the 'sampler' line holds a control character ('sobol\\x0d')");
    check_refused(dir, "nul.pfm", with_field(good, "settings", std::string("max_depth 4\0hidden", 18)),
                  "the 'settings' line holds a control character ('max_depth 4\\x00hidden')");
    sample_slice odd = hand_slice();
    odd.render.sampler = "sobol\x01";
    CHECK_THROWS_WITH_AS(encode_slice(odd), "slice sampler 'sobol\\x01' must be printable text on one line", scene_error);
    // A checksum field holding a line break: the message stays one printable line.
    std::string broken = good;
    broken.replace(broken.size() - 9, 1, "\n");
    check_refused(dir, "checksum.pfm", broken, "checksum");
    // The image edited and the checksum made right again: the image must be the sums' mean.
    std::string edited = good;
    const size_t raster = edited.find('\n', edited.find('\n', edited.find('\n') + 1) + 1) + 1; // after "PF\nW H\nscale\n"
    edited[raster + 2] ^= 0x01;                                                                 // a float's low bits
    check_refused(dir, "edited.pfm", with_checksum(edited), "its image is not the mean of its sums");
    // A slice larger than a render may be: refused before its sums are looked at.
    sample_slice huge = hand_slice();
    huge.render.width = 8192;
    huge.render.height = 8193;
    CHECK_THROWS_WITH_AS(encode_slice(huge),
                         "slice is 8192x8193 = 67117056 pixels, more than the limit of 67108864 (2^26) pixels for a render",
                         scene_error);
}

TEST_CASE("scene fingerprint: the files' contents, not their names or places") {
    test::scratch_dir dir("fingerprint");
    const std::string a = dir.write("a.txt", "sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0\n");
    const std::string b = dir.write("b.txt", "sphere 0 0 0 1 lambertian 0.5 0.5 0.5 0 0\n");
    const std::string c = dir.write("c.txt", "sphere 0 0 0 1 lambertian 0.5 0.5 0.6 0 0\n");
    const std::string m = dir.write("m.obj", "v 0 0 0\n");
    CHECK(scene_fingerprint({a}) == scene_fingerprint({b}));
    CHECK(scene_fingerprint({a}) != scene_fingerprint({c}));
    CHECK(scene_fingerprint({a, m}) != scene_fingerprint({a}));
    CHECK(scene_fingerprint({a, m}) != scene_fingerprint({m, a}));
    CHECK(scene_fingerprint({a}).size() == 16);
    // FNV-1a's published test values: the empty string and "a".
    CHECK(fnv1a64("", 0) == 0xcbf29ce484222325ULL);
    CHECK(fnv1a64("a", 1) == 0xaf63dc4c8601ec8cULL);
    test::check_one_line_error([&] { scene_fingerprint({dir.file("gone.txt")}); }, "gone.txt", "cannot open");
}

TEST_CASE("scene files: the files a scene was read from are listed, the scene file first") {
    const std::string data = RTWEEKEND_TEST_DATA;
    scene_description bunny = load_scene(data + "/bunny.txt");
    REQUIRE(bunny.files.size() == 2);
    CHECK(bunny.files[0] == data + "/bunny.txt");
    CHECK(bunny.files[1].find("bunny") != std::string::npos);
    CHECK(bunny.files[1].find(".obj") != std::string::npos);
    scene_description earth = load_scene(data + "/earth.txt");
    REQUIRE(earth.files.size() == 2);
    CHECK(earth.files[1].find("earthmap.png") != std::string::npos);
    CHECK(load_scene(data + "/rtiow_cover.txt").files.size() == 1);
}

} // namespace test_slice_file
