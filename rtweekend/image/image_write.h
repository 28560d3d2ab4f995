#pragma once
// Writing images: the framebuffer (image/image.h) to files.
//
//   write_image(path, img)     format by extension: .ppm (P3, the book's exact layout), .png and
//                              .bmp (8-bit, via stb_image_write), .pfm and .exr (linear float;
//                              EXR through OpenEXR when the build has it, see exr.h). Writes a
//                              temporary file beside the target and renames it, so a reader
//                              never sees half an image. Throws scene_error naming the path.
//   check_output_path(path)    throws now if write_image(path, ...) could not succeed later.
//   write_ppm(out, img)        P3 to a stream, byte for byte what the book's code prints.
//
// Gamma (the book's square root) and 8-bit quantisation happen only here, at write time.
// Reading files back is image_read.h's job (kept apart so that this header needs no decoder).
// Atomic writing and the output-path check are core/file.h's.

#include "../core/engine_linkage.h"
#include "../color.h"
#include "image.h"
#include "../core/scene_error.h"
#include "exr.h"
#include "../core/file.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ostream>
#include <string>
#include <vector>

namespace rt {

// The image encoded the book's way: gamma 2, int(256 * clamp(x, 0, 0.999)), RGB bytes.
RTWEEKEND_ENGINE_FUNCTION std::vector<unsigned char> encode_8bit(const image& img);
// P3 PPM text of 8-bit RGB bytes: "P3\n<w> <h>\n255\n" then one "r g b" line per pixel, rows top
// to bottom.
RTWEEKEND_ENGINE_FUNCTION std::string ppm_text(int width, int height, const std::vector<unsigned char>& bytes);
// The image as P3 PPM, encoded the book's way: byte for byte what the book's code prints.
RTWEEKEND_ENGINE_FUNCTION void write_ppm(std::ostream& out, const image& img);
// PFM: "PF\n<w> <h>\n-1.0\n" (negative scale = little-endian), float RGB rows bottom to top.
RTWEEKEND_ENGINE_FUNCTION std::string encode_pfm(const image& img);
// The file contents of 8-bit RGB bytes (rows top to bottom) for `path`'s extension: .ppm (P3),
// .png or .bmp. Throws scene_error for other extensions.
RTWEEKEND_ENGINE_FUNCTION std::string encode_8bit_image(const std::string& path, int width, int height,
                                                        const std::vector<unsigned char>& bytes);
// The file contents write_image would write for `path`'s extension.
RTWEEKEND_ENGINE_FUNCTION std::string encode_image(const std::string& path, const image& img);
RTWEEKEND_ENGINE_FUNCTION void write_image(const std::string& path, const image& img);
// Throws scene_error now if write_image(path, ...) would fail for want of a known format or a
// writable directory, so a program can refuse before a long render rather than after it. It
// creates and removes a temporary file beside `path`; `path` itself is not touched.
RTWEEKEND_ENGINE_FUNCTION void check_output_path(const std::string& path);

} // namespace rt

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#ifndef STB_IMAGE_WRITE_IMPLEMENTATION
// Private, static copies of stb's functions, so that any number of translation units can
// include this header.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#endif
#if __has_include(<stb_image_write.h>)
#include <stb_image_write.h>
#else
#include <stb/stb_image_write.h>
#endif
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace rt {

RTWEEKEND_ENGINE_FUNCTION std::vector<unsigned char> encode_8bit(const image& img) {
    std::vector<unsigned char> bytes(img.data().size());
    std::transform(img.data().begin(), img.data().end(), bytes.begin(),
                   [](float v) { return static_cast<unsigned char>(encode_byte(v)); });
    return bytes;
}

RTWEEKEND_ENGINE_FUNCTION std::string ppm_text(int width, int height, const std::vector<unsigned char>& bytes) {
    std::string text = "P3\n" + std::to_string(width) + ' ' + std::to_string(height) + "\n255\n";
    // The decimal digits of every byte value, written by table: snprintf per pixel was a twentieth
    // of the whole cover render (400x225, 10 spp) on one core.
    struct digits {
        char text[256][4];
        unsigned char size[256];
        digits() {
            for (int v = 0; v < 256; ++v) size[v] = (unsigned char)std::snprintf(text[v], sizeof text[v], "%d", v);
        }
    };
    static const digits table;
    const size_t start = text.size();
    text.resize(start + bytes.size() / 3 * 12); // at most "255 255 255\n" a pixel
    char* out = &text[start];
    for (size_t i = 0; i + 2 < bytes.size(); i += 3) {
        for (size_t k = 0; k < 3; ++k) {
            const unsigned char v = bytes[i + k];
            std::memcpy(out, table.text[v], 4); // the fourth byte is overwritten next
            out += table.size[v];
            *out++ = k < 2 ? ' ' : '\n';
        }
    }
    text.resize(size_t(out - text.data()));
    return text;
}

RTWEEKEND_ENGINE_FUNCTION void write_ppm(std::ostream& out, const image& img) {
    out << ppm_text(img.width(), img.height(), encode_8bit(img));
}

RTWEEKEND_ENGINE_FUNCTION std::string encode_pfm(const image& img) {
    std::string out = "PF\n" + std::to_string(img.width()) + " " + std::to_string(img.height()) + "\n-1.0\n";
    size_t row_floats = size_t(img.width()) * 3;
    for (int y = img.height() - 1; y >= 0; --y) {
        const float* row = img.data().data() + size_t(y) * row_floats;
        for (size_t i = 0; i < row_floats; ++i) {
            uint32_t bits;
            std::memcpy(&bits, &row[i], 4);
            char le[4] = {char(bits & 0xff), char((bits >> 8) & 0xff), char((bits >> 16) & 0xff), char(bits >> 24)};
            out.append(le, 4);
        }
    }
    return out;
}

namespace detail {

inline void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::string*>(context);
    out->append(static_cast<const char*>(data), size_t(size));
}

// The extension of `path` if write_image knows it; throws scene_error otherwise.
inline std::string image_format(const std::string& path) {
    std::string ext = lowercase_extension(path);
    if (ext != ".ppm" && ext != ".png" && ext != ".bmp" && ext != ".pfm" && ext != ".exr")
        throw scene_error("cannot write '" + path + "': unknown image format '" + ext +
                          "' (use .ppm, .png, .bmp, .pfm or .exr)");
    // Refused here, not after the render: check_output_path comes through this function.
    if (ext == ".exr" && !exr_supported) throw scene_error("cannot write '" + path + "': " + exr_not_built_text());
    return ext;
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION std::string encode_8bit_image(const std::string& path, int width, int height,
                                     const std::vector<unsigned char>& bytes) {
    std::string ext = detail::image_format(path);
    if (width <= 0 || height <= 0 || bytes.size() != size_t(width) * size_t(height) * 3)
        throw scene_error("cannot write '" + path + "': the image is empty or its size does not match its pixels");
    if (ext == ".ppm") return ppm_text(width, height, bytes);
    if (ext == ".pfm" || ext == ".exr")
        throw scene_error("cannot write '" + path + "': 8-bit pixels cannot be written as " + (ext == ".pfm" ? "PFM" : "EXR"));
    std::string out;
    int ok = ext == ".png" ? stbi_write_png_to_func(detail::append_bytes, &out, width, height, 3, bytes.data(), width * 3)
                           : stbi_write_bmp_to_func(detail::append_bytes, &out, width, height, 3, bytes.data());
    if (!ok) throw scene_error("cannot encode '" + path + "'");
    return out;
}

RTWEEKEND_ENGINE_FUNCTION std::string encode_image(const std::string& path, const image& img) {
    if (img.empty())
        throw scene_error("cannot write '" + path + "': the image is empty (" + std::to_string(img.width()) + "x" +
                          std::to_string(img.height()) + ")");
    const std::string ext = detail::image_format(path);
    if (ext == ".pfm") return encode_pfm(img);
    if (ext == ".exr") return encode_exr(img, path);
    return encode_8bit_image(path, img.width(), img.height(), encode_8bit(img));
}

RTWEEKEND_ENGINE_FUNCTION void write_image(const std::string& path, const image& img) {
    write_file_atomically(path, encode_image(path, img));
}

RTWEEKEND_ENGINE_FUNCTION void check_output_path(const std::string& path) {
    detail::image_format(path);
    check_writable(path);
}

} // namespace rt

#endif // RTWEEKEND_ENGINE_BODIES
