// Inputs found by fuzzing (issue 14), each of which once crashed, hung, allocated gigabytes or was
// accepted silently. Each must now give one scene_error naming the problem (or, for the Whitted
// scenes, render with bounded work), quickly. The inputs are tests/data/fuzz/ (see its README) or
// are built here where they are large or depend on the machine (a FIFO, a 1025-corner polygon).
// Sections 1-6 are the findings of the first, hand-driven round; section 7 those of the libFuzzer
// harnesses (tests/fuzz), and the in-memory entry points and the command-line parser those
// harnesses call.

#include <rtweekend/scene/light_set.h>
#include <rtweekend/scene/scene_compiler.h>
#include <rtweekend/course/whitted.h>
#include <rtweekend/image/exr.h>
#include <rtweekend/core/file.h>
#include <rtweekend/image/image_read.h>
#include <rtweekend/image/image_write.h>
#include <rtweekend/io/obj.h>
#include <rtweekend/io/ply.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/io/xml_scene.h>
#include <rtweekend/perlin.h>
#include <rtweekend/rtw_stb_image.h>
#include <rtweekend/sphere.h>

#include <doctest/doctest.h>

#include "render_command.h"
#include "test_helpers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace test_fuzz_inputs {

using namespace rt;

namespace {

const std::string fuzz_dir = std::string(RTWEEKEND_TEST_DATA) + "/fuzz/";

// `load` must throw one scene_error, on one line, containing every fragment.
const auto check_refused = test::check_scene_error;

whitted_render render_one_thread(const whitted_scene& scene, whitted_settings w = {}) {
    render_settings opt = whitted_renderer::defaults();
    opt.threads = 1;
    opt.whitted = w;
    return render_whitted(scene, 0, opt);
}

} // namespace

// --- 1. the Whitted tracer: deep mirror chains and glass between mirrors --------------------------

TEST_CASE("fuzz: two facing mirrors at MaxRecursionDepth 10000 render (no stack overflow)") {
    // Each of the 10001 surfaces the pixel sees (the camera ray's and 10000 bounces) adds
    // ka * Ia = 0.001 * 10; there are no point lights, so no shadow rays.
    whitted_scene scene = load_xml_scene(fuzz_dir + "facing_mirrors.xml");
    REQUIRE(scene.max_recursion_depth == 10000);
    whitted_render r = render_one_thread(scene);
    CHECK(r.stats.rays == 1 + 10000);
    CHECK(r.img.data()[0] == doctest::Approx(10001 * 0.01).epsilon(1e-4));

    // At the loader's largest depth the tree is cut at max_branch_rays (2^14) rays after the
    // camera ray: 16385 surfaces.
    scene.max_recursion_depth = 1000000;
    r = render_one_thread(scene);
    CHECK(r.stats.rays == 1 + (1u << 14));
    CHECK(r.img.data()[0] == doctest::Approx(16385 * 0.01).epsilon(1e-4));
}

TEST_CASE("fuzz: a glass sphere between two mirrors at depth 60 takes bounded work") {
    // Unbounded, the pixel's tree would hold 2^61 rays.
    whitted_scene scene = load_xml_scene(fuzz_dir + "glass_between_mirrors.xml");
    whitted_render r = render_one_thread(scene);
    CHECK(r.stats.rays <= 1 + (1u << 14));
    CHECK(r.stats.rays > 1000); // it does follow the glass
    CHECK(std::isfinite(r.img.data()[0]));
    CHECK(r.img.data()[0] > 0);

    whitted_settings small;
    small.max_branch_rays = 100;
    CHECK(render_one_thread(scene, small).stats.rays == 1 + 100);
}

TEST_CASE("fuzz: the Whitted bounds leave the test scenes' images unchanged, bit for bit" * doctest::test_suite("heavy")) {
    whitted_settings unbounded;
    unbounded.min_branch_weight = 0;
    unbounded.max_branch_rays = std::numeric_limits<uint32_t>::max();
    for (const char* name : {"whitted/showcase.xml", "ceng795/glass_slab.xml", "ceng795/mirror.xml"}) {
        CAPTURE(name);
        whitted_scene scene = load_xml_scene(std::string(RTWEEKEND_TEST_DATA) + "/" + name);
        const image bounded = render_one_thread(scene).img, full = render_one_thread(scene, unbounded).img;
        REQUIRE(bounded.data().size() == full.data().size());
        CHECK(std::memcmp(bounded.data().data(), full.data().data(), full.data().size() * sizeof(float)) == 0);
    }
}

TEST_CASE("fuzz: Whitted options out of range are refused") {
    whitted_scene scene = load_xml_scene(fuzz_dir + "facing_mirrors.xml");
    render_settings bad = whitted_renderer::defaults();
    bad.whitted.min_branch_weight = std::numeric_limits<float>::quiet_NaN();
    const whitted_renderer renderer(scene);
    check_refused([&] { renderer.render(0, bad); }, {"min_branch_weight"});
}

// --- 2. images: headers that promise what the file does not hold ---------------------------------

TEST_CASE("fuzz: BMP and PNG headers are checked before stb_image allocates") {
    auto read = [](const std::string& name) { return [name] { read_image(fuzz_dir + name); }; };
    // 66 bytes claiming 4096x16384 with compression 0x80000000 (stb_image reads it as negative and
    // let it through): 3 GB and a "perfect match" from compare.
    check_refused(read("bmp_compression_negative.bmp"), {"bmp_compression_negative.bmp", "compression 2147483648"});
    check_refused(read("bmp_48_bits.bmp"), {"bits per pixel is 48"});
    check_refused(read("bmp_zero_width.bmp"), {"BMP image is 0x1", "a side of 0 pixels"});
    check_refused(read("png_long_chunk.png"), {"PNG chunk 'IDAT'", "past the end of the file"});
    check_refused(read("png_zero_height.png"), {"PNG image is 1x0"});
    check_refused(read("png_huge.png"), {"20000x20000", "limit of 268435456 (2^28) pixels"});
    // The same checks guard textures, which are decoded through rtw_image.
    check_refused([] { rtw_image img((fuzz_dir + "bmp_48_bits.bmp").c_str()); }, {"image texture", "bits per pixel is 48"});
    check_refused([] { rtw_image img((fuzz_dir + "png_long_chunk.png").c_str()); }, {"past the end of the file"});
}

TEST_CASE("fuzz: a BMP whose pixel data does not fit the file, and image_header_problem on sound files") {
    // A 2x2 24-bit BMP needs 54 + 2 rows of 8 bytes = 70 bytes; 69 is one short.
    std::string bmp = "BM";
    auto u32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i) bmp += char((v >> (8 * i)) & 0xff);
    };
    auto u16 = [&](uint16_t v) {
        bmp += char(v & 0xff);
        bmp += char(v >> 8);
    };
    for (uint32_t v : {70u, 0u, 54u, 40u, 2u, 2u}) u32(v); // file header, then info header size, width, height
    u16(1), u16(24);                                     // planes, bits per pixel
    for (uint32_t v : {0u, 16u, 2835u, 2835u, 0u, 0u}) u32(v); // compression, image size, resolution, palette
    bmp += std::string(16, '\x7f');
    CHECK(image_header_problem(bmp).empty());
    CHECK(decode_image(bmp, "ok.bmp").pixels.width() == 2);
    bmp.pop_back();
    check_refused([&] { decode_image(bmp, "short.bmp"); }, {"BMP raster is truncated", "needs 70 bytes, the file has 69"});
    CHECK(image_header_problem("P3\n1 1\n255\n0 0 0\n").empty()); // not PNG or BMP: not its business
}

TEST_CASE("fuzz: a PFM scale with a NUL byte, and a device as an image") {
    check_refused([] { read_image(fuzz_dir + "pfm_scale_nul.pfm"); }, {"PFM scale '-1.0\\x00junk' is not a non-zero number"});
    if (std::filesystem::exists("/dev/zero"))
        check_refused([] { read_image("/dev/zero"); }, {"/dev/zero", "character device, not a regular file"});
}

// --- 3. files: only regular files, of bounded size ------------------------------------------------

TEST_CASE("fuzz: read_file refuses directories, devices, FIFOs and files over its limit") {
    test::scratch_dir dir("fuzz_files");
    check_refused([&] { read_file(dir.path.string(), "scene file"); }, {"is a directory"});
    const std::string fifo = dir.file("pipe.txt");
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    check_refused([&] { read_file(fifo, "scene file"); }, {"pipe.txt", "FIFO", "not a regular file"}); // must not block
    const std::string ten = dir.write("ten.txt", "0123456789");
    CHECK(read_file(ten, "scene file", 10) == "0123456789");
    check_refused([&] { read_file(ten, "scene file", 9); }, {"ten.txt", "is 10 bytes, more than the limit of 9 bytes"});
    CHECK(byte_limit_text(max_input_file_bytes) == "4 GiB (4294967296 bytes)");
}

// --- 4. text scenes --------------------------------------------------------------------------------

TEST_CASE("fuzz: scene files: NUL bytes, nothing to render, a device as a mesh, an image too large") {
    check_refused([] { load_scene(fuzz_dir + "scene_nul_number.txt"); }, {"scene_nul_number.txt:2: a NUL byte"});
    check_refused([] { load_scene(fuzz_dir + "scene_empty.txt"); }, {"scene_empty.txt: scene file is empty"});
    check_refused([] { load_scene(fuzz_dir + "scene_no_objects.txt"); }, {"scene_no_objects.txt: the scene has no objects"});
    if (std::filesystem::exists("/dev/zero"))
        check_refused([] { load_scene(fuzz_dir + "scene_mesh_dev_zero.txt"); },
                      {"scene_mesh_dev_zero.txt:2: ", "/dev/zero: cannot read OBJ file: it is a character device"});

    test::scratch_dir dir("fuzz_scenes");
    const std::string sphere = "sphere 0 0 -1 0.5 lambertian 0.5 0.5 0.5 0 0\n";
    check_refused([&] { load_scene(dir.write("big.txt", "camera image_width 65536\ncamera aspect_ratio 1\n" + sphere)); },
                  {"big.txt: the image", "65536x65536 = 4294967296 pixels", "limit of 67108864 (2^26) pixels for a render"});
    check_refused([&] { load_scene(dir.write("big2.txt", "camera image_width 8192\ncamera image_height 8193\n" + sphere)); },
                  {"big2.txt: the image", "8192x8193 = 67117056 pixels", "limit of 67108864 (2^26) pixels for a render"});
    CHECK_NOTHROW(load_scene(dir.write("ok.txt", "camera image_width 8192\ncamera image_height 8192\n" + sphere)));
    // The same limits as render's --spp and --depth.
    check_refused([&] { load_scene(dir.write("spp.txt", "camera samples_per_pixel 16777217\n" + sphere)); },
                  {"samples_per_pixel", "at most 16777216"});
    check_refused([&] { load_scene(dir.write("depth.txt", "camera max_depth 65537\n" + sphere)); },
                  {"max_depth", "at most 65536"});
    // Only groups, never placed: nothing in the world.
    check_refused([&] { load_scene(dir.write("group.txt", "group g\n" + sphere + "end\n")); }, {"has no objects"});
}

// --- 5. meshes -------------------------------------------------------------------------------------

TEST_CASE("fuzz: PLY values must fit their declared type, write_ply refuses what a float cannot hold") {
    check_refused([] { load_ply(fuzz_dir + "ply_uchar_out_of_range.ply", nullptr); },
                  {"ply_uchar_out_of_range.ply:12: vertex 0: '-70000' (property 'red') does not fit its type uchar"});
    check_refused([] { load_ply(fuzz_dir + "ply_float_out_of_range.ply", nullptr); },
                  {"'1e300' (property 'x') does not fit its type float"});

    test::scratch_dir dir("fuzz_ply");
    triangle_mesh mesh;
    mesh.positions = {point3(1e300, 0, 0), point3(1, 0, 0), point3(0, 1, 0)};
    mesh.faces = {{0, 1, 2}};
    check_refused([&] { write_ply(dir.file("out.ply"), mesh, false); },
                  {"position 0 has the value 1e+300, which a PLY float cannot hold"});
    CHECK(dir.entries().empty()); // nothing written, not even a temporary file
    // A NUL byte in an ASCII PLY file.
    std::string text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    text.insert(text.find("1 0 0") + 1, std::string(1, '\0'));
    check_refused([&] { load_ply(dir.write("nul.ply", text), nullptr); }, {"nul.ply:11: a NUL byte"});
}

TEST_CASE("fuzz: OBJ text is checked before tinyobjloader sees it") {
    check_refused([] { load_obj(fuzz_dir + "obj_index_overflow.obj", nullptr); },
                  {"obj_index_overflow.obj:6: malformed OBJ file: texture coordinate index 4294967296 is out of range"});

    test::scratch_dir dir("fuzz_obj");
    // A polygon of n corners on a circle (tinyobjloader splits one in time quadratic in n).
    auto polygon = [](size_t n) {
        std::string s;
        for (size_t i = 0; i < n; ++i) {
            const double a = 2 * 3.14159265358979323846 * double(i) / double(n);
            s += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
        }
        s += "f";
        for (size_t i = 1; i <= n; ++i) s += " " + std::to_string(i);
        return s + "\n";
    };
    CHECK(load_obj(dir.write("ok.obj", polygon(max_obj_face_corners)), nullptr)->faces.size() == max_obj_face_corners - 2);
    check_refused([&] { load_obj(dir.write("big.obj", polygon(max_obj_face_corners + 1)), nullptr); },
                  {"big.obj:1026: malformed OBJ file: a face has more than 1024 corners"});

    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    check_refused([&] { load_obj(dir.write("vbig.obj", "v 1e300 0 0\n" + tri + "f 2 3 4\n"), nullptr); },
                  {"vbig.obj:1: ", "'1e300'", "float's range"});
    check_refused([&] { load_obj(dir.write("s.obj", tri + "s 99999999999\nf 1 2 3\n"), nullptr); },
                  {"s.obj:4: ", "'99999999999' in a 's' line is out of range"});
    check_refused([&] { load_obj(dir.write("n.obj", tri + "vn 0 0 1\nf 1//1 2//2 3//1\n"), nullptr); },
                  {"n.obj:5: ", "normal index 2 is out of range (1 normal so far)"});
    check_refused([&] { load_obj(dir.write("l.obj", tri + "f 1 2 3\nl 1 -2147483648\n"), nullptr); },
                  {"l.obj:5: ", "vertex index -2147483648 is out of range"});
    std::string nul = tri + "f 1 2 3\n";
    nul[2] = '\0';
    check_refused([&] { load_obj(dir.write("nul.obj", nul), nullptr); }, {"nul.obj:1: malformed OBJ file: a NUL byte"});
}

// --- 6. XML scenes -----------------------------------------------------------------------------------

TEST_CASE("fuzz: a JSON number beyond a double is one error line (json_scene's finding)") {
    check_refused([] { load_xml_scene(fuzz_dir + "json_number_overflow.json"); },
                  {"json_number_overflow.json: malformed JSON: number overflow parsing '8888880E"});
}

TEST_CASE("fuzz: XML vertex ids and vertexOffset near the 64-bit limits") {
    check_refused([] { load_xml_scene(fuzz_dir + "vertex_offset_overflow.xml"); },
                  {"<Faces> vertex 1 + vertexOffset 9223372036854775807 overflows a 64-bit integer"});
    check_refused([] { load_xml_scene(fuzz_dir + "vertex_id_min.xml"); },
                  {"<Faces> vertex -9223372036854775808 (triangle 1) does not exist"});
}

TEST_CASE("fuzz: an ImageName must stay inside the output directory") {
    check_refused([] { load_xml_scene(fuzz_dir + "image_name_dotdot.xml"); },
                  {"image_name_dotdot.xml:12: <Camera id=\"1\">: <ImageName> '../escaped.png' has a '..' component"});
    check_refused([] { load_xml_scene(fuzz_dir + "image_name_absolute.xml"); },
                  {"<ImageName> '/tmp/rtweekend_escaped.png' is an absolute path"});
    CHECK(image_name_problem("a.png").empty());
    CHECK(image_name_problem("sub/dir/a.png").empty());
    CHECK(image_name_problem("..a.png").empty());
    CHECK(image_name_problem("a..png").empty());
    CHECK_FALSE(image_name_problem("sub/../../a.png").empty());
    CHECK_FALSE(image_name_problem("sub\\..\\a.png").empty());
    CHECK_FALSE(image_name_problem("..").empty());
    CHECK_FALSE(image_name_problem("\\a.png").empty());
}

TEST_CASE("fuzz: XML NUL bytes and resolutions beyond the pixel limit") {
    test::scratch_dir dir("fuzz_xml");
    std::string text = read_file(fuzz_dir + "facing_mirrors.xml", "test scene");
    std::string nul = text;
    nul.insert(nul.find("<MaxRecursionDepth>10000") + 24, std::string(1, '\0')); // line 5
    check_refused([&] { load_xml_scene(dir.write("nul.xml", nul)); }, {"nul.xml:5: a NUL byte"});
    std::string big = text;
    big.replace(big.find("<ImageResolution>1 1<"), 21, "<ImageResolution>1000000 1000000<");
    check_refused([&] { load_xml_scene(dir.write("big.xml", big)); },
                  {"<ImageResolution> 1000000 1000000 is 1000000000000 pixels, more than the limit of 67108864 (2^26) pixels for a render"});
}

// --- 7. the libFuzzer harnesses (tests/fuzz) --------------------------------------------------------

namespace {

// An 18-byte TGA header: no image ID, no colour map, image `type`, w x h, 24 bits per pixel.
std::string tga_header(unsigned type, unsigned w, unsigned h) {
    std::string t(18, '\0');
    t[2] = char(type);
    t[12] = char(w & 0xff), t[13] = char(w >> 8), t[14] = char(h & 0xff), t[15] = char(h >> 8);
    t[16] = 24;
    return t;
}

// The current directory set to `dir` for the scope (doctest runs test cases one at a time).
struct working_directory {
    std::filesystem::path previous = std::filesystem::current_path();
    explicit working_directory(const std::filesystem::path& dir) { std::filesystem::current_path(dir); }
    ~working_directory() {
        std::error_code ec;
        std::filesystem::current_path(previous, ec);
    }
};

} // namespace

TEST_CASE("fuzz: a 20-byte TGA claiming 16384x16384 is refused before stb_image decodes it") {
    // Before: stb_image allocated the image and read the missing pixels as zeros: render took 5 s
    // and 3.9 GB (the limit of the shell), and textured the sphere black. A run-length packet holds
    // at most 128 pixels in a header byte and one 3-byte pixel: 2^28 / 128 * 4 bytes at least.
    check_refused([] { rtw_image img((fuzz_dir + "tga_rle_huge.tga").c_str()); },
                  {"tga_rle_huge.tga", "TGA image of 16384x16384 pixels needs at least 8388608 bytes of data",
                   "the file has 2 after its headers"});

    // At the bound: 16x16 pixels in two packets of 128 (8 bytes) decode; a byte less is refused.
    std::string rle = tga_header(10, 16, 16);
    for (int packet = 0; packet < 2; ++packet) rle += std::string("\xff\x0a\x14\x1e", 4); // 128 x (b 10, g 20, r 30)
    rtw_image img;
    img.decode(rle, "rle.tga");
    REQUIRE(img.width() == 16);
    REQUIRE(img.height() == 16);
    for (int y : {0, 15})
        for (int x : {0, 15}) {
            CHECK(int(img.pixel_data(x, y)[0]) == 30);
            CHECK(int(img.pixel_data(x, y)[2]) == 10);
        }
    rle.pop_back();
    check_refused([&] { rtw_image t; t.decode(rle, "rle.tga"); }, {"needs at least 8 bytes", "the file has 7 after its headers"});
    // Uncompressed: 16 x 16 x 3 bytes.
    const std::string raw = tga_header(2, 16, 16) + std::string(767, '\x40');
    check_refused([&] { rtw_image t; t.decode(raw, "raw.tga"); }, {"needs at least 768 bytes", "(uncompressed pixels)"});
    CHECK_NOTHROW(rtw_image().decode(raw + "\x40", "raw.tga"));
}

TEST_CASE("fuzz: a PNG, JPEG, HDR or PNM header claiming more pixels than its file can hold") {
    // PNG, 16384x16384 RGBA of 16 bits: each of the 16384 rows is a filter byte and 16384 x 8
    // bytes, and deflate packs at most 1032 bytes in one: ceil(16384 * 131073 / 1032) bytes of
    // IDAT at least; the file has one IDAT of 11. Before: stb_image allocated 2 GB, then failed,
    // and the message was another decoder's ("PNG no SOI").
    check_refused([] { read_image(fuzz_dir + "png_idat_too_short.png"); },
                  {"PNG image of 16384x16384 pixels needs at least 2080911 bytes of data",
                   "2147500032 bytes of rows deflated at the best ratio, 1032:1", "the file has 11 in its IDAT chunks"});
    check_refused([] { rtw_image img((fuzz_dir + "png_idat_too_short.png").c_str()); }, {"needs at least 2080911 bytes"});

    auto refused = [](const std::string& bytes, std::initializer_list<std::string> fragments) {
        check_refused([&] { rtw_image().decode(bytes, "big"); }, fragments);
    };
    // JPEG: SOI, a baseline frame header of 16384x16384 with one component, EOI; at least one bit
    // per 8x8 block: 2^28 / 64 / 8 bytes.
    const std::string jpeg = std::string("\xff\xd8\xff\xc0\x00\x0b\x08\x40\x00\x40\x00\x01\x01\x11\x00\xff\xd9", 17);
    refused(jpeg, {"JPEG image of 16384x16384 pixels needs at least 524288 bytes", "one bit per 8x8 block", "the file has 17"});
    // Radiance HDR: a run of 127 pixels takes 2 bytes in each of 4 channels: 2^28 / 16 at least.
    const std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16384 +X 16384\n";
    refused(hdr, {"HDR image of 16384x16384 pixels needs at least 16777216 bytes"});
    // Binary PNM: a byte per sample, three samples a pixel.
    refused("P6 16384 16384 255\n", {"PNM image of 16384x16384 pixels needs at least 805306368 bytes"});
    // A 0-pixel side names the format (it said "the image image is 0x1").
    refused("P5 0 1 255\n", {"PNM image is 0x1: a side of 0 pixels"});
}

TEST_CASE("fuzz: a JPEG Huffman table of more than 256 codes is refused (stb_image 2.27 writes past its table)") {
    check_refused([] { rtw_image img((fuzz_dir + "jpeg_dht_4080_codes.jpg").c_str()); },
                  {"jpeg_dht_4080_codes.jpg", "JPEG Huffman table at byte 6 has 4080 codes, more than 256"});

    // A sound 16x16 JPEG (jpeg_16x16.jpg, made by stb_image_write: see tests/data/fuzz/README.md;
    // not made here, as stb_image_write's JPEG encoder shifts negative values, which UBSan
    // refuses) decodes; the same file with two code counts of its first table raised to 255 is
    // refused, with the sum counted here.
    std::string jpeg = rt::read_file(fuzz_dir + "jpeg_16x16.jpg", "JPEG file");
    rtw_image good;
    CHECK_NOTHROW(good.decode(jpeg, "good.jpg"));
    CHECK(good.width() == 16);
    const size_t dht = jpeg.find("\xff\xc4");
    REQUIRE(dht != std::string::npos);
    const size_t counts = dht + 5; // marker, 2-byte length, class and id
    unsigned sum = 0;
    for (size_t i = 0; i < 14; ++i) sum += static_cast<unsigned char>(jpeg[counts + i]);
    jpeg[counts + 14] = jpeg[counts + 15] = '\xff';
    check_refused([&] { rtw_image().decode(jpeg, "bad.jpg"); },
                  {"JPEG Huffman table at byte " + std::to_string(dht + 4) + " has " + std::to_string(sum + 510) + " codes"});
}

TEST_CASE("fuzz: a JPEG scan that uses a Huffman table the file never defines") {
    // The third component's scan selector names AC table 3; the file defines tables 0 and 1.
    // stb_image 2.27 decodes with the undefined table's uninitialised memory and indexes past its
    // arrays (before: render exit 0 with a garbage texture; UBSan: index -1344943079 out of bounds).
    check_refused([] { rtw_image img((fuzz_dir + "jpeg_undefined_huffman_table.jpg").c_str()); },
                  {"jpeg_undefined_huffman_table.jpg", "JPEG scan at byte 593 uses Huffman table AC 3, which the file does not define"});
    // A file stb_image_write made (jpeg_16x16.jpg: see the test above) decodes; its scan pointed
    // at DC table 2 instead is refused.
    std::string jpeg = rt::read_file(fuzz_dir + "jpeg_16x16.jpg", "JPEG file");
    CHECK_NOTHROW(rtw_image().decode(jpeg, "ok.jpg"));
    const size_t sos = jpeg.find("\xff\xda");
    REQUIRE(sos != std::string::npos);
    jpeg[sos + 6] = char(0x20); // the first component's selectors: DC 2, AC 0
    check_refused([&] { rtw_image().decode(jpeg, "dc2.jpg"); },
                  {"JPEG scan at byte " + std::to_string(sos) + " uses Huffman table DC 2"});
}

namespace {

// A 16x16 grey progressive JPEG of `scans` scans (at most 127), in a sequence that the standard
// allows (ITU T.81 G.1.1.1): quantisation table 0 of ones, one Huffman table of each class holding
// one 1-bit code (symbol 0), a first DC scan, first AC scans of one coefficient each (k = 1..63,
// Ah 0, Al 1), then refinements of one coefficient each (Ah 1, Al 0). Each scan's data is three
// zero bytes: DC differences of 0, and end-of-band runs. Every coefficient stays 0, so every pixel
// is the level shift, 128.
std::string progressive_grey_jpeg(int scans) {
    auto segment = [](unsigned marker, const std::string& payload) {
        const size_t length = payload.size() + 2;
        return std::string{'\xff', char(marker), char(length >> 8), char(length & 0xff)} + payload;
    };
    const std::string one_code = std::string(1, '\x01') + std::string(15, '\0') + std::string(1, '\0');
    std::string j = std::string("\xff\xd8", 2);
    j += segment(0xdb, std::string(1, '\0') + std::string(64, '\x01'));
    j += segment(0xc2, std::string("\x08\x00\x10\x00\x10\x01\x01\x11\x00", 9)); // 8 bits, 16x16, 1 component
    j += segment(0xc4, std::string(1, '\x00') + one_code);                       // DC table 0
    j += segment(0xc4, std::string(1, '\x10') + one_code);                       // AC table 0
    const std::string zeros(3, '\0');
    j += segment(0xda, std::string("\x01\x01\x00\x00\x00\x00", 6)) + zeros; // DC first scan
    for (int s = 1; s < scans; ++s) {
        const char k = char(s <= 63 ? s : s - 63), successive = s <= 63 ? '\x01' : '\x10';
        j += segment(0xda, std::string("\x01\x01\x00", 3) + k + k + successive) + zeros;
    }
    return j + "\xff\xd9";
}

} // namespace

TEST_CASE("fuzz: a JPEG of more than 100 scans is refused (stb_image decodes each over the whole image)") {
    // Found by the CI fuzz run: 4 KB of empty refinement scans over 2000x1024 pixels took 0.5 s to
    // decode at -O2 and 16 s under the sanitizers, and the time grows as scans x pixels.
    rtw_image good;
    good.decode(progressive_grey_jpeg(100), "100.jpg");
    REQUIRE(good.width() == 16);
    REQUIRE(good.height() == 16);
    for (int y : {0, 15})
        for (int x : {0, 15}) CHECK(int(good.pixel_data(x, y)[1]) == 128);
    // The 101st scan starts after SOI (2), DQT (69), SOF2 (13), two DHTs (22 each), the DC scan
    // (10 + 3) and 99 refinement scans (13 each).
    const size_t at = 2 + 69 + 13 + 2 * 22 + 13 + 99 * 13;
    check_refused([] { rtw_image().decode(progressive_grey_jpeg(101), "101.jpg"); },
                  {"JPEG has more than 100 scans (the next at byte " + std::to_string(at) + ")"});
    // The fuzz input, rebuilt by hand: the same layout, 2000x1024 pixels and 304 scans in 4095 bytes.
    check_refused([] { rtw_image img((fuzz_dir + "jpeg_304_empty_scans.jpg").c_str()); },
                  {"jpeg_304_empty_scans.jpg", "JPEG has more than 100 scans (the next at byte " + std::to_string(at) + ")"});
}

TEST_CASE("fuzz: a TGA shorter than its 18-byte header is checked with the zeros stb_image reads") {
    // Found by a fuzz run: 17 bytes that stb_image reads as a 77x43018 colour-mapped TGA of 16 bits
    // a pixel (the missing 18th byte read as 0), decoded in a second under the sanitizers.
    // Width 0x004d, height 0xa80a, 16 bits a pixel (2 bytes), uncompressed (image type 1).
    check_refused([] { rtw_image img((fuzz_dir + "tga_17_bytes.tga").c_str()); },
                  {"tga_17_bytes.tga", "TGA image of 77x43018 pixels needs at least " + std::to_string(77 * 43018 * 2) +
                                           " bytes of data (uncompressed pixels), the file has 0 after its headers"});
}

TEST_CASE("fuzz: a PNG texture whose first IDAT chunk is empty decodes (stb_image copied it to a null pointer)") {
    // Found by the texture harness's long run: the image reader dropped empty IDAT chunks before
    // stb_image saw them, the texture loader did not, and stb_image's memcpy of the empty chunk to
    // the buffer it had not yet allocated is undefined behaviour (UBSan stops on it). A 2x3 PNG
    // whose pixel (1, 2) is white and the rest black, with an empty IDAT inserted after the IHDR
    // (signature 8 + IHDR 25 bytes); its CRC is CRC-32("IDAT") = 0x35af061e.
    image img(2, 3);
    img.set_pixel(1, 2, color(1, 1, 1));
    std::string png = encode_image("x.png", img);
    REQUIRE(png.compare(12, 4, "IHDR") == 0);
    png.insert(33, std::string("\x00\x00\x00\x00IDAT\x35\xaf\x06\x1e", 12));
    rtw_image texture;
    texture.decode(png, "empty_idat.png");
    REQUIRE(texture.width() == 2);
    REQUIRE(texture.height() == 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c) CHECK(int(texture.pixel_data(x, y)[c]) == (x == 1 && y == 2 ? 255 : 0));
    // Found next, in the step written for it: 6 bytes that start like a PNG signature (an
    // out_of_range exception, where a texture must give one error line).
    check_refused([] { rtw_image().decode(std::string("\x89PNG\nR", 6), "short.png"); }, {"short.png"});
}

TEST_CASE("fuzz: a truncated run-length HDR texture is refused (stb_image 2.27 looped for ever)") {
    // The first scanline's header (2 2, width 8), then the file ends: stb_image reads zeros past
    // the end, and a count of 0 never advances. The header is 45 bytes, the scanline's 4 more.
    check_refused([] { rtw_image img((fuzz_dir + "hdr_rle_truncated.hdr").c_str()); },
                  {"hdr_rle_truncated.hdr", "HDR scanline 0 has a run-length count of 0 at byte 49 (the file ends there"});
    // The same scanline complete (each component one run of 8: 136, then the value) decodes.
    std::string hdr = read_file(fuzz_dir + "hdr_rle_truncated.hdr", "test file");
    for (unsigned char value : {128, 64, 32, 129}) hdr += std::string{char(136), char(value)};
    rtw_image img;
    img.decode(hdr, "ok.hdr");
    REQUIRE(img.width() == 8);
    // RGBE (128, 64, 32, exponent 129): value / 256 * 2^(129 - 128).
    CHECK(img.linear(7, 0).r == 1.0f);
    CHECK(img.linear(0, 0).b == 0.25f);
    // A literal run of 0 in the middle of a complete file is refused too.
    std::string zero = read_file(fuzz_dir + "hdr_rle_truncated.hdr", "test file") + std::string(1, '\0') + "rest";
    check_refused([&] { rtw_image().decode(zero, "zero.hdr"); }, {"run-length count of 0 at byte 49"});
}

TEST_CASE("fuzz: an HDR header ended by a line of NUL bytes is walked as stb_image reads it") {
    // Found by CI's 20 s fuzz run (a timeout; before the fix `render` never finished): stb_image
    // takes a line that starts with a NUL byte for the empty line ending the header (its token is
    // an empty C string), and strtol skips the second space of "-Y  1". The walk looked for two
    // '\n' in a row, found none, and let stb_image loop on the truncated scanline. Here: 11 bytes
    // of "#?RADIANCE\n", 23 of the FORMAT line, the NUL line (2), the resolution line (11), then
    // the 4 bytes of a scanline header: the first count would be at byte 51, past the end.
    const std::string hdr = std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\0\n-Y  1 +X 8\n\x02\x02\x00\x08", 51);
    check_refused([&] { rtw_image().decode(hdr, "nul_line.hdr"); },
                  {"HDR scanline 0 has a run-length count of 0 at byte 51 (the file ends there: it is truncated)"});
    // Completed with one run of 8 per component (136, then the value), it decodes: RGBE
    // (128, 64, 32, exponent 129) is 128 / 256 * 2 = 1 in red.
    std::string complete = hdr;
    for (unsigned char value : {128, 64, 32, 129}) complete += std::string{char(136), char(value)};
    rtw_image img;
    img.decode(complete, "complete.hdr");
    REQUIRE(img.width() == 8);
    REQUIRE(img.height() == 1);
    CHECK(img.linear(3, 0).r == 1.0f);
}

TEST_CASE("fuzz: a JPEG that starts with fill bytes before its SOI is checked as stb_image reads it") {
    check_refused([] { rtw_image img((fuzz_dir + "jpeg_fill_dht.jpg").c_str()); },
                  {"jpeg_fill_dht.jpg", "JPEG Huffman table at byte 7 has 4080 codes"});
}

TEST_CASE("fuzz: stb_image's messages quote the file's bytes on one line") {
    // An unknown critical chunk named "G\r\n\x1a": stb_image's message quotes the name.
    check_refused([] { read_image(fuzz_dir + "png_chunk_type_line_break.png"); },
                  {"png_chunk_type_line_break.png': PNG G\\x0d\\x0a\\x1a PNG chunk not known"});
    check_refused([] { rtw_image img((fuzz_dir + "png_chunk_type_line_break.png").c_str()); },
                  {"G\\x0d\\x0a\\x1a PNG chunk not known"});
}

TEST_CASE("fuzz: 16-bit PNM textures are refused (stb_image 2.27 reads them wrongly)") {
    // P5: expanded to RGB by the 8-bit routine, past the end of its buffer (found by the harness).
    check_refused([] { rtw_image img((fuzz_dir + "pgm16_texture.pgm").c_str()); },
                  {"pgm16_texture.pgm", "PNM of 16 bits (maxval 525) is not supported as a texture"});
    // P6: the sample 0x8000 came back as 0 (its bytes read little-endian; found writing this test).
    check_refused([] { rtw_image().decode(std::string("P6 1 1 65535\n\x80\x00\x00\x00\xff\xff", 19), "rgb16.ppm"); },
                  {"PNM of 16 bits (maxval 65535)"});
    // 8-bit PGM still decodes, grey to all three channels.
    rtw_image grey;
    grey.decode(std::string("P5 2 1 255\n\x10\x80", 13), "grey.pgm");
    CHECK(int(grey.pixel_data(1, 0)[0]) == 0x80);
    CHECK(int(grey.pixel_data(1, 0)[2]) == 0x80);
    CHECK(int(grey.pixel_data(0, 0)[1]) == 0x10);
}

TEST_CASE("fuzz: a binary PNM header whose numbers overflow stb_image's int") {
    // stb_image 2.27 adds up the digits in an int (undefined behaviour past 2^31 - 1); before, the
    // wrapped width said "the image image is 0x1".
    check_refused([] { rtw_image img((fuzz_dir + "pgm_width_digits.pgm").c_str()); },
                  {"pgm_width_digits.pgm", "PNM width 999999999999 is more than 16777216"});
    check_refused([] { rtw_image().decode("P6 1 1\n# a comment\n 70000\n", "maxval.ppm"); }, {"PNM maxval 70000 is more than 65535"});
}

TEST_CASE("fuzz: EXR files are read by OpenEXRCore, which checks attribute sizes and chunks before allocating") {
    if (!exr_supported) {
        check_refused([] { read_image(fuzz_dir + "exr_attribute_1gb.exr"); }, {"EXR support was not built"});
        return;
    }
    // An attribute of unknown type declared 1,000,000,000 bytes long in a 334-byte file: the C++
    // library, which read EXR files before, allocated it before finding the file too short.
    check_refused([] { read_image(fuzz_dir + "exr_attribute_1gb.exr"); }, {"exr_attribute_1gb.exr", "EXR"});

    // A 1x1 image of write_image's layout (ZIP: 16 scanlines a chunk), whose data window is then
    // made taller or wider in the header. 16384 rows: 1024 chunks, whose offsets alone take 8192 bytes.
    image one(1, 1);
    one.data() = {0.25f, 0.5f, 1.0f};
    const std::string good = encode_exr(one, "one.exr");
    CHECK(decode_exr(good, "one.exr").data() == one.data());
    const size_t window = good.find(std::string("dataWindow\0box2i\0", 17));
    REQUIRE(window != std::string::npos);
    const size_t max_x = window + 17 + 4 + 8, max_y = max_x + 4; // after the size, min.x and min.y
    auto with = [&](size_t at, uint32_t v) {
        std::string b = good;
        for (int i = 0; i < 4; ++i) b[at + size_t(i)] = char((v >> (8 * i)) & 0xff);
        return b;
    };
    const std::string tall = with(max_y, 16383);
    check_refused([&] { decode_exr(tall, "tall.exr"); },
                  {"EXR header promises 1024 chunks of pixels, whose offsets alone need 8192 bytes; the file has " +
                   std::to_string(tall.size())});
    // 4096 pixels in one row: one chunk that must unpack to 4096 x 3 floats, from the few bytes
    // the 1x1 image deflated to.
    check_refused([&] { decode_exr(with(max_x, 4095), "wide.exr"); },
                  {"EXR chunk 0 holds", "which cannot unpack to the 49152 its pixels need (at most 1032 bytes a byte"});
}

TEST_CASE("fuzz: a line break in a quoted XML value stays inside one error line") {
    // type="mir&#10;ror": before, the message spanned two lines.
    check_refused([] { load_xml_scene(fuzz_dir + "xml_line_break_in_value.xml"); },
                  {"xml_line_break_in_value.xml:21: <Material id=\"1\">: unknown material type 'mir\\x0aror'"});
    CHECK(one_line("a\nb\rc\td\x7f" + std::string(1, '\0')) == "a\\x0ab\\x0dc\td\\x7f\\x00");
    CHECK(one_line("plain text, 'quoted' (and more)") == "plain text, 'quoted' (and more)");
}

TEST_CASE("fuzz: an OBJ vw joint id that an int cannot hold once read as a float") {
    // tinyobjloader reads joint ids as floats and converts them to int: 2147483647 rounds to 2^31,
    // which no int holds (undefined behaviour; Debian's library loaded the mesh).
    check_refused([] { load_obj(fuzz_dir + "obj_vw_joint_overflow.obj", nullptr); },
                  {"obj_vw_joint_overflow.obj:5: malformed OBJ file: '2147483647' in a 'vw' line is out of range"});
    CHECK(decode_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nvw 0 2147482000 1\n", "ok.obj", nullptr)->faces.size() == 1);
    check_refused([] { decode_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nvw 0 3e9x 1\n", "x.obj", nullptr); },
                  {"x.obj:5: ", "'3e9x' in a 'vw' line is out of range"});
}

TEST_CASE("fuzz: OBJ lines end at a lone carriage return, as tinyobjloader splits them") {
    // Before, "# a comment\rvw 0 1e300 1" was one comment line to the check and two lines to
    // tinyobjloader, which converted 1e300 to an int (undefined behaviour).
    check_refused([] { load_obj(fuzz_dir + "obj_cr_smuggled_line.obj", nullptr); },
                  {"obj_cr_smuggled_line.obj:2: malformed OBJ file: '1e300' in a 'vw' line is out of range"});
    // A file with old Mac line ends loads (before: "'v' in a 'v' line is not a finite number").
    CHECK(decode_obj("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r", "mac.obj", nullptr)->faces.size() == 1);
    // Line numbers count "\r\n" once.
    check_refused([] { decode_obj("v 0 0 0\r\nv 1 0 0\rv 0 1 x\n", "n.obj", nullptr); }, {"n.obj:3: "});
}

TEST_CASE("fuzz: OBJ numbers tinyobjloader would overflow on (an exponent of 3000, 65 digits)") {
    // tinyobjloader scales by pow(5, exponent): 0e3000 is 0 * inf = NaN, which a vw line then
    // converted to an int. strtod reads 0e3000 as 0, so the range checks let it through.
    check_refused([] { load_obj(fuzz_dir + "obj_vw_exponent.obj", nullptr); },
                  {"obj_vw_exponent.obj:5: malformed OBJ file: '0e3000' in a 'vw' line is out of range"});
    const std::string tri = "v 1 0 0\nv 0 1 0\nf 1 2 3\n";
    check_refused([&] { decode_obj("v 0e400 0 0\n" + tri, "e.obj", nullptr); },
                  {"e.obj:1: ", "'0e400' in a 'v' line has more digits than a number needs"});
    check_refused([&] { decode_obj("v 0 0 0e99999999999\n" + tri, "i.obj", nullptr); }, {"i.obj:1: ", "'0e99999999999'"});
    const std::string digits65 = "0." + std::string(63, '0') + "1"; // 65 digits, a tiny number
    check_refused([&] { decode_obj("v " + digits65 + " 0 0\n" + tri, "d.obj", nullptr); }, {"d.obj:1: "});
    // At the bounds: 64 digits and an exponent of 300 (here a number of ordinary size) load.
    const std::string digits64 = "0." + std::string(62, '0') + "1", e300 = "1" + std::string(10, '0') + "e-300";
    CHECK(decode_obj("v " + digits64 + " " + e300 + " 0e300\n" + tri, "ok.obj", nullptr)->faces.size() == 1);
}

TEST_CASE("fuzz: Perlin noise far from the origin (the lattice index was an int conversion out of range)") {
    // The noise repeats every 256 cells along each axis: whole multiples of 256 added to a point
    // whose fraction a double keeps exactly give the same value, far beyond an int.
    const perlin noise;
    const double x = 3.25, y = 0.5, z = -7.75;
    for (double shift : {256.0, 1099511627776.0 /* 2^40 */, -1125899906842624.0 /* -2^50 */}) {
        CAPTURE(shift);
        CHECK(noise.noise(point3(x + shift, y, z)) == noise.noise(point3(x, y, z)));
        CHECK(noise.noise(point3(x, y + shift, z)) == noise.noise(point3(x, y, z)));
    }
    // Non-finite coordinates give a value rather than undefined behaviour (NaN: the renderer drops it).
    CHECK_FALSE(std::isfinite(noise.noise(point3(std::numeric_limits<double>::infinity(), 0, 0))));
    // The scene that found it: a marble sphere ten billion units away renders.
    scene_description scene = load_scene(fuzz_dir + "scene_noise_far.txt");
    scene.cam.settings.quiet = true;
    scene.cam.settings.threads = 1;
    const render_result r = render(scene.cam, scene.world);
    CHECK(r.img.width() == 4);
}

TEST_CASE("fuzz: an XML ImageName with a line break is refused") {
    // Before, render wrote a file named "facing<line break>mirrors.png", exit 0.
    check_refused([] { load_xml_scene(fuzz_dir + "xml_image_name_line_break.xml"); },
                  {"xml_image_name_line_break.xml:14: <Camera id=\"1\">: <ImageName> 'facing\\x0amirrors.png' has a control character"});
    CHECK_FALSE(image_name_problem("a\tb.png").empty());
    CHECK(image_name_problem("caf\xc3\xa9.png").empty()); // UTF-8 is not a control character
}

TEST_CASE("fuzz: a shadow ray offset by ShadowRayEpsilon 1e23 (the BVH entered a node's empty slots)") {
    // The offset origin is 5.8e22 in every coordinate, so the direction to the light rounds to
    // (-0, -0, -0) and origin / direction overflows: the slab test found +inf <= +inf for the
    // empty slots of a node and followed them (render: segmentation fault). The scene renders.
    whitted_scene scene = load_xml_scene(fuzz_dir + "shadow_epsilon_huge.xml");
    REQUIRE(scene.shadow_ray_epsilon == 1e23);
    const whitted_render r = render_one_thread(scene);
    CHECK(std::isfinite(r.img.data()[0]));

    // The same rays straight at the engine: 21 spheres (more than a leaf), such rays hit nothing,
    // nor do rays with a NaN component; an ordinary ray still hits.
    hittable_list world;
    auto grey = std::make_shared<lambertian>(color(0.5, 0.5, 0.5));
    for (int i = 0; i < 21; ++i) world.add(std::make_shared<sphere>(point3(i - 10, 0, -5), 0.4, grey));
    const compiled_scene compiled = compile_scene(world, point3(0, 0, 0));
    REQUIRE(compiled.bvh.nodes.size() > 0);
    const float far_out = 5.8e22f, inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    surface_hit hit;
    for (const ray3f& bad : {ray3f{{far_out, far_out, far_out}, {-0.0f, -0.0f, -0.0f}, 0, inf, 0},
                             ray3f{{0, 0, 0}, {nan, 0, -1}, 0, inf, 0}, ray3f{{nan, 0, 0}, {0, 0, -1}, 0, inf, 0}}) {
        CHECK_FALSE(compiled.occluded(bad));
        CHECK_FALSE(compiled.intersect(bad, hit));
    }
    const ray3f good{{0, 0, 0}, {0, 0, -1}, 0, inf, 0};
    CHECK(compiled.occluded(good));
    REQUIRE(compiled.intersect(good, hit));
    CHECK(hit.t == doctest::Approx(4.6).epsilon(1e-5));
}

TEST_CASE("fuzz: a light whose power overflows a float (the light table threw an internal exception)") {
    // Radiance 3e38 over a 2x2 quad: 3e38 x 4 x pi is beyond float's range; the alias table
    // refused the infinite weight with std::invalid_argument ("render: error: alias_table: weights
    // must be finite and non-negative"). The power is now taken in double there, and it renders.
    scene_description scene = load_scene(fuzz_dir + "scene_light_power_overflow.txt");
    scene.cam.settings.quiet = true;
    scene.cam.settings.threads = 1;
    render_result r;
    CHECK_NOTHROW(r = render(scene.cam, scene.world));
    CHECK(r.img.width() == 8);
    // A power a float holds is the float product, as before (the same light choices, the same images).
    light l;
    l.emitter = quad_emitter{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    l.emission = {3, 3, 3};
    CHECK(l.power() == double(3.0f * 4.0f * pi_f));
    l.emission = {3e38f, 3e38f, 3e38f};
    CHECK(l.power() == doctest::Approx(3e38 * 4 * 3.14159265358979323846).epsilon(1e-6));
}

TEST_CASE("fuzz: render writes an XML scene's images in the current directory when -o is not given") {
    // Before, every image not yet on disk was refused: "<ImageName> 'facing_mirrors.png' resolves
    // to 'facing_mirrors.png', outside the output directory '/current/directory'".
    const whitted_scene scene = load_xml_scene(fuzz_dir + "facing_mirrors.xml");
    test::scratch_dir dir("fuzz_cwd");
    {
        working_directory inside(dir.path);
        CHECK(app::xml_output_paths(scene, "facing_mirrors.xml", "") == std::vector<std::string>{"facing_mirrors.png"});
        CHECK(app::xml_output_paths(scene, "facing_mirrors.xml", ".") == std::vector<std::string>{"facing_mirrors.png"});
        CHECK(app::xml_output_paths(scene, "facing_mirrors.xml", "out") == std::vector<std::string>{"out/facing_mirrors.png"});
    }
    // A symbolic link inside the output directory still may not lead out of it.
    test::scratch_dir elsewhere("fuzz_elsewhere");
    std::filesystem::create_directory_symlink(elsewhere.path, dir.path / "link");
    whitted_scene linked = scene;
    linked.cameras[0].image_name = "link/escaped.png";
    check_refused([&] { app::xml_output_paths(linked, "s.xml", dir.path.string()); },
                  {"<ImageName> 'link/escaped.png' resolves to", "outside the output directory"});
}

TEST_CASE("fuzz: an XML ImageName may end in .pfm or .exr, as render --help says") {
    // render --help promised .pfm and .exr ImageNames, and render refused them ("must end in .png
    // or .ppm"). They are written with the linear radiance: read back, the values are the render's.
    whitted_scene scene = load_xml_scene(fuzz_dir + "facing_mirrors.xml");
    test::scratch_dir dir("fuzz_hdr_names");
    for (const std::string name : {"hdr.pfm", "hdr.exr", "plain.png", "plain.ppm"}) {
        scene.cameras[0].image_name = name;
        CHECK(app::xml_output_paths(scene, "s.xml", dir.path.string()) ==
              std::vector<std::string>{(dir.path / name).string()});
    }
    scene.cameras[0].image_name = "photo.jpg";
    check_refused([&] { app::xml_output_paths(scene, "s.xml", dir.path.string()); },
                  {"<ImageName> 'photo.jpg' must end in .png, .ppm, .pfm or .exr"});

    render_settings settings = whitted_renderer::defaults();
    settings.threads = 1;
    settings.quiet = true;
    const whitted_render r = render_whitted(scene, 0, settings);
    std::vector<std::string> hdr_names{"hdr.pfm"};
#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
    hdr_names.push_back("hdr.exr");
#endif
    for (const std::string& name : hdr_names) {
        const std::string path = (dir.path / name).string();
        write_whitted_image(path, r.img);
        const loaded_image back = read_image(path);
        CHECK_FALSE(back.display_encoded);
        REQUIRE(back.pixels.width() == r.img.width());
        REQUIRE(back.pixels.height() == r.img.height());
        CHECK(back.pixels.data() == r.img.data());
    }
}

TEST_CASE("fuzz: the in-memory entry points read what the file readers read") {
    const std::string data = std::string(RTWEEKEND_TEST_DATA) + "/";
    auto bytes = [&](const std::string& name) { return read_file(data + name, "test file"); };
    CHECK(decode_scene(bytes("cornell_box.txt"), data + "cornell_box.txt").world.objects.size() ==
          load_scene(data + "cornell_box.txt").world.objects.size());
    check_refused([&] { decode_scene("", "empty.txt"); }, {"empty.txt: scene file is empty"});
    CHECK(decode_ply(bytes("ply/extras.ply"), "extras.ply", nullptr)->faces ==
          load_ply(data + "ply/extras.ply", nullptr)->faces);
    CHECK(decode_obj(bytes("meshes/teapot_npm.obj"), "teapot.obj", nullptr)->faces ==
          load_obj(data + "meshes/teapot_npm.obj", nullptr)->faces);
    const whitted_scene from_memory = decode_xml_scene(bytes("xml/scene.xml"), data + "xml/scene.xml"); // plyFile relative to it
    CHECK(from_memory.world.objects.size() == load_xml_scene(data + "xml/scene.xml").world.objects.size());
    rtw_image from_file((data + "textures/rows_4x2.png").c_str()), decoded;
    decoded.decode(bytes("textures/rows_4x2.png"), "rows.png");
    CHECK(*decoded.linear_pixels() == *from_file.linear_pixels());
}

TEST_CASE("fuzz: app::parse_arguments throws what app::parse prints and exits with") {
    const app::description d = app::render_description();
    auto parse = [&](std::vector<std::string> words) {
        words.insert(words.begin(), "render");
        std::vector<char*> argv;
        for (std::string& w : words) argv.push_back(w.data());
        return app::parse_arguments(int(argv.size()), argv.data(), d);
    };
    auto stop = [&](std::vector<std::string> words) {
        try {
            parse(std::move(words));
        } catch (const app::parse_stop& s) {
            return s;
        }
        return app::parse_stop{-1, "no stop"};
    };
    app::parse_stop s = stop({"s.txt", "--width", "0"});
    CHECK(s.status == 2);
    CHECK(s.message == "--width must be between 1 and 65536, got 0");
    s = stop({"--help", "--width", "0"}); // --help first: the usage, nothing else
    CHECK(s.status == 0);
    CHECK(s.message.empty());
    s = stop({"s.txt", "-o", "/nonexistent-dir/out.png"});
    CHECK(s.status == 1);
    CHECK(s.message.find("'/nonexistent-dir/out.png'") != std::string::npos);
    s = stop({"s.xml", "--depth", "4"});
    CHECK(s.status == 2);
    CHECK(s.message.find("apply to XML scenes only with --integrator path") != std::string::npos);
    CHECK(*parse({"s.xml", "--spp", "4"}).spp == 4); // every camera's NumSamples
    CHECK(stop({"--spp"}).message == "--spp needs a value");
    const app::options o = parse({"s.txt", "--spp=4", "-q", "--seed", "9"});
    CHECK(*o.spp == 4);
    CHECK(*o.seed == 9);
    CHECK(o.quiet);
    CHECK(o.positional == std::vector<std::string>{"s.txt"});
}

} // namespace test_fuzz_inputs
