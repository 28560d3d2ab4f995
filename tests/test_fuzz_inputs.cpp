// Inputs found by fuzzing (issue 14), each of which once crashed, hung, allocated gigabytes or was
// accepted silently. Each must now give one scene_error naming the problem (or, for the Whitted
// scenes, render with bounded work), quickly. The inputs are tests/data/fuzz/ (see its README) or
// are built here where they are large or depend on the machine (a FIFO, a 1025-corner polygon).

#include <rtweekend/engine/whitted.h>
#include <rtweekend/io/file.h>
#include <rtweekend/io/image_read.h>
#include <rtweekend/io/obj.h>
#include <rtweekend/io/ply.h>
#include <rtweekend/io/scene_file.h>
#include <rtweekend/io/xml_scene.h>
#include <rtweekend/rtw_stb_image.h>

#include <doctest/doctest.h>

#include "test_helpers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include <sys/stat.h>

namespace test_fuzz_inputs {

using namespace rt;

namespace {

const std::string fuzz_dir = std::string(RTWEEKEND_TEST_DATA) + "/fuzz/";

// `load` must throw one scene_error, on one line, containing every fragment.
void check_refused(const std::function<void()>& load, std::initializer_list<std::string> fragments) {
    bool threw = false;
    try {
        load();
    } catch (const scene_error& e) {
        threw = true;
        const std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.find('\n') == std::string::npos);
        CHECK(msg.find('\0') == std::string::npos);
        for (const std::string& f : fragments) {
            CAPTURE(f);
            CHECK(msg.find(f) != std::string::npos);
        }
    }
    CHECK(threw);
}

whitted_render render_one_thread(const whitted_scene& scene, whitted_options opt = {}) {
    opt.threads = 1;
    opt.quiet = true;
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

    whitted_options small;
    small.max_branch_rays = 100;
    CHECK(render_one_thread(scene, small).stats.rays == 1 + 100);
}

TEST_CASE("fuzz: the Whitted bounds leave the test scenes' images unchanged, bit for bit") {
    whitted_options unbounded;
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
    whitted_options bad;
    bad.min_branch_weight = std::numeric_limits<float>::quiet_NaN();
    check_refused([&] { whitted_renderer renderer(scene, bad); }, {"min_branch_weight"});
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
                  {"big.txt: the image", "65536x65536 = 4294967296 pixels", "limit of 268435456 (2^28) pixels"});
    CHECK_NOTHROW(load_scene(dir.write("ok.txt", "camera image_width 16384\ncamera image_height 16384\n" + sphere)));
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
                  {"<ImageResolution> 1000000 1000000 is 1000000000000 pixels, more than the limit of 268435456"});
}

} // namespace test_fuzz_inputs
