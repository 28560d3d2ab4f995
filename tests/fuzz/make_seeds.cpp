// make_seeds: writes the binary seed inputs of the fuzzing corpus, those not copied from
// tests/data or written by hand: small images and textures in every format and variant the
// readers take (PPM P3/P6, PFM both byte orders, PNG grey/RGB/RGBA, BMP 1/4/8/16/24/32 bits,
// EXR float/half/Y-only/tiled in several compressions, TGA, JPEG, Radiance HDR, PGM), binary PLY
// meshes in both byte orders and ray files. Built in the fuzz build (target fuzz_make_seeds);
// run once from the checkout root, its files are committed:
//
//   build-fuzz/tests/fuzz/fuzz_make_seeds tests/fuzz/corpus
//
// Every file is named gen_*; running it again rewrites the same bytes.

#include <rtweekend/io/ply.h>
#include <rtweekend/io/ray_file.h>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#endif

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

std::string corpus;

void put(const std::string& harness, const std::string& name, const std::string& bytes) {
    const std::filesystem::path dir = std::filesystem::path(corpus) / harness;
    std::filesystem::create_directories(dir);
    std::ofstream(dir / ("gen_" + name), std::ios::binary) << bytes;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void u16le(std::string& s, uint32_t v) {
    s += char(v & 0xff);
    s += char((v >> 8) & 0xff);
}
void u32le(std::string& s, uint32_t v) {
    for (int i = 0; i < 4; ++i) s += char((v >> (8 * i)) & 0xff);
}
void f32(std::string& s, float f, bool big_endian) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    for (int i = 0; i < 4; ++i) s += char((bits >> (8 * (big_endian ? 3 - i : i))) & 0xff);
}

// A w x h RGB test pattern of bytes.
std::vector<unsigned char> pattern(int w, int h, int channels) {
    std::vector<unsigned char> p(size_t(w) * size_t(h) * size_t(channels));
    for (size_t i = 0; i < p.size(); ++i) p[i] = static_cast<unsigned char>((i * 37 + 11) & 0xff);
    return p;
}

// stb_image_write writes to a callback; this collects the bytes.
void collect(void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<char*>(data), size_t(size)); }

// A BMP with a BITMAPINFOHEADER: `bits` per pixel, a palette of `palette` entries, rows of
// `row_bytes` (padded to 4) filled with a pattern; compression 3 (bit fields) for 16 and 32 bits.
std::string bmp(int w, int h, int bits, int palette) {
    const uint32_t row = uint32_t((w * bits + 31) / 32 * 4);
    const bool fields = bits == 16 || bits == 32;
    const uint32_t header = 14 + 40 + (fields ? 12 : 0) + uint32_t(palette) * 4;
    std::string s = "BM";
    u32le(s, header + row * uint32_t(h));
    u32le(s, 0);
    u32le(s, header);
    u32le(s, 40);
    u32le(s, uint32_t(w));
    u32le(s, uint32_t(h));
    u16le(s, 1);
    u16le(s, uint32_t(bits));
    u32le(s, fields ? 3 : 0);
    u32le(s, row * uint32_t(h));
    u32le(s, 2835);
    u32le(s, 2835);
    u32le(s, uint32_t(palette));
    u32le(s, 0);
    if (bits == 16) u32le(s, 0x7c00), u32le(s, 0x03e0), u32le(s, 0x001f);
    if (bits == 32) u32le(s, 0x00ff0000), u32le(s, 0x0000ff00), u32le(s, 0x000000ff);
    for (int i = 0; i < palette; ++i) u32le(s, uint32_t(i * 0x010203 + 0x102030) & 0xffffff);
    const std::vector<unsigned char> p = pattern(int(row), h, 1);
    s.append(reinterpret_cast<const char*>(p.data()), p.size());
    return s;
}

void images() {
    // Netpbm and PFM, by hand.
    put("image", "p3.ppm", "P3\n# a comment\n2 2\n255\n255 0 0  0 255 0\n0 0 255  128 128 128\n");
    put("image", "p3_maxval_7.ppm", "P3 1 2 7 7 0 3 1 2 6\n");
    std::string p6 = "P6\n2 1\n255\n";
    p6 += std::string("\x01\x02\x03\xfd\xfe\xff", 6);
    put("image", "p6.ppm", p6);
    std::string p6_16 = "P6 1 1 65535\n";
    p6_16 += std::string("\x00\x01\x80\x00\xff\xff", 6);
    put("image", "p6_16bit.ppm", p6_16);
    std::string pf = "PF\n2 1\n-1.0\n";
    for (float v : {0.5f, 1.0f, 2.0f, 0.0f, -0.0f, 1e-3f}) f32(pf, v, false);
    put("image", "pf_little.pfm", pf);
    std::string pf_grey = "Pf\n1 2\n1.0\n";
    for (float v : {0.25f, 4.0f}) f32(pf_grey, v, true);
    put("image", "pf_grey_big.pfm", pf_grey);

    // PNG and BMP through stb_image_write; BMPs of other depths by hand.
    for (int channels : {1, 2, 3, 4}) {
        std::string png;
        const std::vector<unsigned char> p = pattern(3, 2, channels);
        stbi_write_png_to_func(collect, &png, 3, 2, channels, p.data(), 3 * channels);
        put("image", "png_" + std::to_string(channels) + "ch.png", png);
        put("texture", "png_" + std::to_string(channels) + "ch.png", png);
    }
    std::string bmp24;
    const std::vector<unsigned char> rgb = pattern(3, 2, 3);
    stbi_write_bmp_to_func(collect, &bmp24, 3, 2, 3, rgb.data());
    put("image", "bmp_24.bmp", bmp24);
    put("texture", "bmp_24.bmp", bmp24);
    for (int bits : {1, 4, 8, 16, 32}) {
        const std::string b = bmp(3, 2, bits, bits <= 8 ? 1 << bits : 0);
        put("image", "bmp_" + std::to_string(bits) + ".bmp", b);
        put("texture", "bmp_" + std::to_string(bits) + ".bmp", b);
    }

    // Texture-only formats: TGA (plain and RLE), JPEG, Radiance HDR (flat and RLE rows), PGM.
    std::string tga, tga_rle, jpg, hdr, hdr_rle;
    stbi_write_tga_with_rle = 0;
    stbi_write_tga_to_func(collect, &tga, 3, 2, 3, rgb.data());
    stbi_write_tga_with_rle = 1;
    stbi_write_tga_to_func(collect, &tga_rle, 3, 2, 3, rgb.data());
    const std::vector<unsigned char> rgb16 = pattern(16, 16, 3);
    stbi_write_jpg_to_func(collect, &jpg, 16, 16, 3, rgb16.data(), 80);
    std::vector<float> lin(size_t(3) * 2 * 3), wide(size_t(16) * 2 * 3);
    for (size_t i = 0; i < lin.size(); ++i) lin[i] = float(i) * 0.25f;
    for (size_t i = 0; i < wide.size(); ++i) wide[i] = i % 5 == 0 ? 8.0f : 0.5f;
    stbi_write_hdr_to_func(collect, &hdr, 3, 2, 3, lin.data());
    stbi_write_hdr_to_func(collect, &hdr_rle, 16, 2, 3, wide.data());
    put("texture", "tga.tga", tga);
    put("texture", "tga_rle.tga", tga_rle);
    put("texture", "jpeg.jpg", jpg);
    put("texture", "hdr.hdr", hdr);
    put("texture", "hdr_rle.hdr", hdr_rle);
    put("image", "hdr.hdr", hdr); // the images read_image takes too (environment maps)
    put("image", "hdr_rle.hdr", hdr_rle);
    put("texture", "pgm.pgm", std::string("P5 2 2 255\n", 11) + std::string("\x00\x40\x80\xff", 4));
    put("texture", "ppm.ppm", p6);

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
    // EXR: float RGB (as write_image writes), half RGB in other compressions, Y only, an offset
    // data window, a tiled file.
    const std::string tmp = (std::filesystem::temp_directory_path() / "rtweekend_make_seeds.exr").string();
    const int w = 4, h = 3;
    std::vector<float> px(size_t(w) * h * 3);
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 7) * 0.5f;
    auto write = [&](const std::string& name, Imf::Compression compression, Imf::PixelType type, bool grey,
                     bool offset, bool tiled) {
        Imath::Box2i window(Imath::V2i(offset ? -2 : 0, offset ? 5 : 0),
                            Imath::V2i((offset ? -2 : 0) + w - 1, (offset ? 5 : 0) + h - 1));
        Imf::Header header(window, window, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y, compression);
        const std::vector<const char*> names = grey ? std::vector<const char*>{"Y"} : std::vector<const char*>{"R", "G", "B"};
        for (const char* c : names) header.channels().insert(c, Imf::Channel(type));
        std::vector<half> halves(px.size());
        std::vector<uint32_t> uints(px.size());
        for (size_t i = 0; i < px.size(); ++i) halves[i] = half(px[i]), uints[i] = uint32_t(px[i] * 2);
        char* base = type == Imf::HALF   ? reinterpret_cast<char*>(halves.data())
                     : type == Imf::UINT ? reinterpret_cast<char*>(uints.data())
                                         : reinterpret_cast<char*>(px.data());
        const size_t size = type == Imf::HALF ? 2 : 4, xs = 3 * size, ys = xs * w;
        Imf::FrameBuffer fb;
        for (size_t c = 0; c < names.size(); ++c)
            fb.insert(names[c], Imf::Slice::Make(type, base + c * size, window, xs, ys));
        if (tiled) {
            header.setTileDescription(Imf::TileDescription(2, 2, Imf::ONE_LEVEL));
            Imf::TiledOutputFile file(tmp.c_str(), header);
            file.setFrameBuffer(fb);
            file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
        } else {
            Imf::OutputFile file(tmp.c_str(), header);
            file.setFrameBuffer(fb);
            file.writePixels(h);
        }
        put("image", name, slurp(tmp));
    };
    write("exr_float_zip.exr", Imf::ZIP_COMPRESSION, Imf::FLOAT, false, false, false);
    write("exr_half_none.exr", Imf::NO_COMPRESSION, Imf::HALF, false, false, false);
    write("exr_half_rle.exr", Imf::RLE_COMPRESSION, Imf::HALF, false, false, false);
    write("exr_half_piz.exr", Imf::PIZ_COMPRESSION, Imf::HALF, false, false, false);
    write("exr_half_pxr24.exr", Imf::PXR24_COMPRESSION, Imf::HALF, false, false, false);
    write("exr_half_b44.exr", Imf::B44_COMPRESSION, Imf::HALF, false, false, false);
    write("exr_y_zips.exr", Imf::ZIPS_COMPRESSION, Imf::HALF, true, false, false);
    write("exr_uint_offset.exr", Imf::NO_COMPRESSION, Imf::UINT, false, true, false);
    write("exr_tiled.exr", Imf::ZIP_COMPRESSION, Imf::HALF, false, false, true);
    std::filesystem::remove(tmp);
#endif
}

// Binary PLY meshes: write_ply's little-endian form with normals and uvs, and a big-endian file
// with uchar colours and an extra element, by hand.
void ply_meshes() {
    rt::triangle_mesh mesh;
    mesh.positions = {rt::point3(0, 0, 0), rt::point3(1, 0, 0), rt::point3(1, 1, 0), rt::point3(0, 1, 0)};
    mesh.normals = {rt::vec3(0, 0, 1)};
    mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh.faces = {{0, 1, 2}, {0, 2, 3}};
    mesh.face_normals = {{0, 0, 0}, {0, 0, 0}};
    mesh.face_uvs = {{0, 1, 2}, {0, 2, 3}};
    const std::string tmp = (std::filesystem::temp_directory_path() / "rtweekend_make_seeds.ply").string();
    rt::write_ply(tmp, mesh, true);
    put("ply", "binary_little.ply", slurp(tmp));
    std::filesystem::remove(tmp);

    std::string big = "ply\nformat binary_big_endian 1.0\ncomment by hand\nelement vertex 3\nproperty float x\n"
                      "property float y\nproperty float z\nproperty uchar red\nelement face 1\n"
                      "property list uchar int vertex_indices\nelement extra 1\nproperty list ushort double stuff\n"
                      "end_header\n";
    const float v[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (const auto& p : v) {
        for (float c : p) f32(big, c, true);
        big += char(200);
    }
    big += char(3);
    for (uint32_t i : {0u, 1u, 2u}) big += std::string{0, 0, 0, char(i)};
    big += std::string{0, 1};
    big += std::string("\x3f\xf0\x00\x00\x00\x00\x00\x00", 8);
    put("ply", "binary_big.ply", big);
}

// Ray files: rays toward the harness's fixed scene (closest hit) and shadow rays (any hit).
void ray_files() {
    rt::ray_batch closest;
    const float s = 1 / std::sqrt(3.0f);
    closest.rays = {{{0, 5, 0}, {0, -1, 0}, 0, std::numeric_limits<float>::infinity(), 0},
                    {{-2, 1, 5}, {0, 0, -1}, 0.001f, 100, 0},
                    {{-2, 1, 0}, {1, 0, 0}, 0, std::numeric_limits<float>::infinity(), 0},
                    {{5, 5, 5}, {-s, -s, -s}, 0, 20, 0},
                    {{0, 1, 10}, {0, 0, -1}, 0, std::numeric_limits<float>::infinity(), 0}};
    put("ray_file", "closest.rays", rt::encode_rays(closest));
    rt::ray_batch any;
    any.kind = rt::ray_query::any;
    any.rays = {{{0.2f, 0.05f, 0.2f}, {0, 1, 0}, 0.0001f, 10, 0}, {{3, 0.5f, 3}, {0, 1, 0}, 0, 1, 0}};
    put("ray_file", "any.rays", rt::encode_rays(any));
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR   (tests/fuzz/corpus)\n");
        return 2;
    }
    corpus = argv[1];
    images();
    ply_meshes();
    ray_files();
    return 0;
}
