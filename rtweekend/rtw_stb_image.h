#pragma once
// rtw_image: an image file read for texturing (book 2's rtw_stb_image.h), decoded by stb_image.
//
//   rtw_image img("earthmap.jpg");   throws scene_error naming the file when it is missing or
//                                    cannot be decoded (the book prints a message and goes on)
//   img.width(), img.height()        in pixels (0 for a default-constructed image)
//   img.pixel_data(x, y)             the pixel's three bytes, red first, sRGB-encoded; x and y are
//                                    clamped into the image; row 0 is the top
//   img.linear(x, y)                 the pixel's linear RGB, what a texture returns
//   img.linear_pixels()              every pixel's linear RGB, rows top to bottom, shared so that the
//                                    renderer can keep them alive (scene/texture_table.h)
//   img.decode(bytes, name)          the same from a file's bytes in memory (name for messages)
//
// Where the file is looked for, as in the book: in $RTW_IMAGES if that is set, then the name as
// given, then images/, ../images/, and so on up to six parents.
//
// What the numbers mean. An 8-bit file (PNG, JPEG, BMP, TGA, PNM) stores sRGB-encoded values:
// linear() decodes them with the exact sRGB curve (IEC 61966-2-1), so the byte 128 is 0.2158605,
// not the 0.5 a plain division gives. The book instead asks stb_image for floats, which applies
// a 2.2 power, then quantises them to linear bytes; ours keeps the file's bytes and decodes once.
// A Radiance .hdr file stores linear radiance: linear() returns it unchanged (and unclamped), and
// pixel_data() holds its sRGB encoding, clamped to [0, 1].
//
// The file is read whole by core/file.h's read_file (a regular file of at most 4 GiB), and its
// headers are checked before stb_image decodes it (core/image_header.h for PNG and BMP, then the
// size stb_image reports against core/input_limits.h's 2^28 pixels): stb_image allocates the image a
// header describes before it finds out whether the file holds it. A JPEG file's entropy-coded data
// is then read through by libjpeg-turbo when the build has it (core/jpeg_check.h): stb_image 2.27
// misbehaves on some damaged data, and a cut-short JPEG is refused rather than filled with grey.
// The pixels are stb_image's either way.

#include "core/file.h"
#include "core/image_header.h"
#include "core/jpeg_check.h"
#include "core/text_lines.h"
#include "core/scene_error.h"

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

namespace rt {

class rtw_image {
  public:
    rtw_image() = default;
    explicit rtw_image(const char* image_filename);

    // Reads `filename`: false when it cannot be opened; throws scene_error when it can but is not
    // an image stb_image decodes.
    bool load(const std::string& filename);
    // Decodes the bytes of an image file already in memory, as load() does the file's; `filename`
    // names it in messages. Throws scene_error when they are not an image stb_image decodes.
    void decode(const std::string& encoded, const std::string& filename);

    int width() const { return width_; }
    int height() const { return height_; }
    const unsigned char* pixel_data(int x, int y) const;

    struct rgb {
        float r, g, b;
    };
    rgb linear(int x, int y) const;
    const std::shared_ptr<const std::vector<float>>& linear_pixels() const { return linear_; }
    const std::string& path() const { return path_; }
    // A copy whose linear values are the 8-bit codes / 255, not sRGB-decoded: for pictures that
    // hold data (a normal map, metallic and roughness) rather than colour. A Radiance HDR picture,
    // linear already, is copied as it is.
    rtw_image as_data() const {
        rtw_image copy = *this;
        if (!hdr_ && !bytes_.empty()) {
            auto values = std::make_shared<std::vector<float>>(bytes_.size()); // -> shared_ptr<const ...>
            for (size_t i = 0; i < bytes_.size(); ++i) (*values)[i] = bytes_[i] / 255.0f;
            copy.linear_ = std::move(values);
        }
        return copy;
    }

  private:
    int width_ = 0, height_ = 0;
    std::vector<unsigned char> bytes_;               // sRGB-encoded RGB, 3 per pixel
    std::shared_ptr<const std::vector<float>> linear_; // linear RGB, 3 per pixel
    std::string path_;                               // where it was read from
    bool hdr_ = false;                               // decoded from Radiance HDR: linear_ is the file's

    static int clamp_index(int i, int n) { return i < 0 ? 0 : i < n ? i : n - 1; }
};

// The sRGB transfer functions (IEC 61966-2-1): code value in [0, 1] to linear light and back.
double srgb_to_linear(double encoded);
double linear_to_srgb(double linear);

} // namespace rt

// --- IMPLEMENTATION -----------------------------------------------------------------------------

// stb_image decodes the files. As image.h does with stb_image_write, this compiles a private,
// static copy, unless the program brings its own: if stb_image.h was already included, its
// declarations are used; if STB_IMAGE_IMPLEMENTATION is defined before this header, that
// implementation is compiled here instead of ours. image/image_read.h uses this same copy. The
// decoders are those a texture is likely to come in; functions a program never calls are not
// compiled into it (they are static), so the cost is parsing them.
#ifndef STBI_INCLUDE_STB_IMAGE_H
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#if !defined(__clang__) // a GCC-only warning: clang warns about the pragma itself
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#endif
#ifndef STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_BMP
#define STBI_ONLY_JPEG
#define STBI_ONLY_TGA
#define STBI_ONLY_PNM
#define STBI_ONLY_HDR
#endif
#if __has_include(<stb_image.h>)
#include <stb_image.h>
#else
#include <stb/stb_image.h>
#endif
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#endif

namespace rt {

namespace detail {

// What is wrong with an encoded image before stb_image may decode it, "" if nothing: the PNG and
// BMP headers (image_header.h), then, for every format stb_image knows, the size it reads from
// the header (stbi_info parses headers only) against the limits of input_limits.h and against
// what the file's length can hold (image_data_problem, image_header.h); last, when the build has
// libjpeg-turbo, a JPEG's entropy-coded data read through in that frame (core/jpeg_check.h says why).
inline std::string stb_input_problem(const std::string& bytes) {
    std::string problem = image_header_problem(bytes);
    if (!problem.empty()) return problem;
    if (bytes.size() > size_t(INT_MAX)) return "the file is larger than stb_image can decode (2 GiB)";
    int w = 0, h = 0, channels = 0;
    if (!stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h, &channels))
        return {}; // not an image stb_image knows, or headers it cannot read: decoding says so
    // A BMP's height is negative when its rows are stored top first (valid, and common from Windows
    // tools); stb_image's info passes it on as it is, and decodes such files the right way up.
    const bool bmp = bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M';
    if (bmp && h < 0 && h != INT_MIN) h = -h;
    const uint64_t width = uint64_t(w < 0 ? 0 : w), height = uint64_t(h < 0 ? 0 : h);
    problem = image_size_problem(width, height, stb_format_name(bytes));
    if (problem.empty()) problem = image_data_problem(bytes, width, height);
#if defined(RTWEEKEND_HAVE_LIBJPEG) && RTWEEKEND_HAVE_LIBJPEG
    if (problem.empty() && jpeg_after_soi(bytes)) problem = jpeg_data_problem(bytes, w, h);
#endif
    return problem;
}

// stb_image copies the first IDAT chunk of a PNG into a buffer it has not allocated yet when that
// chunk is empty: memcpy to a null pointer, harmless in practice but undefined behaviour, which
// the sanitizer builds stop on. Empty IDAT chunks carry no data, so they are dropped first.
inline std::string without_empty_png_data_chunks(const std::string& png) {
    if (png.size() < 8) return png;
    std::string out = png.substr(0, 8); // the signature
    size_t pos = 8;
    while (png.size() - pos >= 12) { // length, type, CRC
        const auto* b = reinterpret_cast<const unsigned char*>(png.data() + pos);
        const uint64_t length = uint64_t(b[0]) << 24 | uint64_t(b[1]) << 16 | uint64_t(b[2]) << 8 | b[3];
        if (length > png.size() - pos - 12) break; // cut short: stb_image reports it
        if (length != 0 || png.compare(pos + 4, 4, "IDAT") != 0) out.append(png, pos, size_t(12 + length));
        pos += size_t(12 + length);
    }
    out.append(png, pos, std::string::npos);
    return out;
}

} // namespace detail

inline double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

inline double linear_to_srgb(double x) {
    if (!(x > 0)) return 0;
    if (x >= 1) return 1;
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

inline rtw_image::rtw_image(const char* image_filename) {
    const std::string name(image_filename ? image_filename : "");
    if (name.empty()) throw scene_error("image texture: no file name given");
    const char* dir = std::getenv("RTW_IMAGES");
    if (dir && load(std::string(dir) + "/" + name)) return;
    if (load(name)) return;
    std::string prefix;
    for (int up = 0; up <= 6; ++up, prefix += "../")
        if (load(prefix + "images/" + name)) return;
    throw scene_error("cannot read image texture '" + name + "': file not found (looked " +
                      (dir ? "in $RTW_IMAGES, " : "") + "here and in images/ up to six parents)");
}

inline bool rtw_image::load(const std::string& filename) {
    std::error_code ec;
    if (!std::filesystem::exists(filename, ec)) return false;
    decode(read_file(filename, "image texture"), filename);
    return true;
}

inline void rtw_image::decode(const std::string& encoded, const std::string& filename) {
    const std::string problem = detail::stb_input_problem(encoded);
    if (!problem.empty()) throw scene_error("cannot read image texture '" + filename + "': " + problem);
    std::string png_copy; // a PNG without its empty IDAT chunks (see without_empty_png_data_chunks)
    if (encoded.compare(0, 8, "\x89PNG\r\n\x1a\n", 8) == 0) png_copy = detail::without_empty_png_data_chunks(encoded);
    const std::string& stb_bytes = png_copy.empty() ? encoded : png_copy;
    const auto* file = reinterpret_cast<const stbi_uc*>(stb_bytes.data());
    const int file_size = int(stb_bytes.size()); // at most INT_MAX: checked above
    int w = 0, h = 0, channels = 0;
    const bool hdr = stbi_is_hdr_from_memory(file, file_size) != 0;
    std::vector<float> lin;
    std::vector<unsigned char> bytes;
    if (hdr) {
        float* data = stbi_loadf_from_memory(file, file_size, &w, &h, &channels, 3);
        if (data) {
            lin.assign(data, data + size_t(w) * size_t(h) * 3);
            stbi_image_free(data);
            bytes.resize(lin.size());
            for (size_t i = 0; i < lin.size(); ++i)
                bytes[i] = static_cast<unsigned char>(std::lround(255 * linear_to_srgb(lin[i])));
        }
    } else {
        unsigned char* data = stbi_load_from_memory(file, file_size, &w, &h, &channels, 3);
        if (data) {
            bytes.assign(data, data + size_t(w) * size_t(h) * 3);
            stbi_image_free(data);
            // Decoded once per byte value, not once per pixel.
            float table[256];
            for (int c = 0; c < 256; ++c) table[c] = static_cast<float>(srgb_to_linear(c / 255.0));
            lin.resize(bytes.size());
            for (size_t i = 0; i < bytes.size(); ++i) lin[i] = table[bytes[i]];
        }
    }
    if (bytes.empty()) {
        const char* reason = stbi_failure_reason();
        // stb_image's message may quote bytes of the file (an unknown PNG chunk's type): one line.
        throw scene_error("cannot read image texture '" + filename + "': " +
                          one_line(reason && *reason ? reason : "not an image stb_image can decode"));
    }
    width_ = w;
    height_ = h;
    hdr_ = hdr;
    bytes_ = std::move(bytes);
    linear_ = std::make_shared<const std::vector<float>>(std::move(lin));
    path_ = filename;
}

inline const unsigned char* rtw_image::pixel_data(int x, int y) const {
    // The book shows magenta where there is no image; a loaded rtw_image always has pixels.
    static const unsigned char magenta[] = {255, 0, 255};
    if (bytes_.empty()) return magenta;
    return &bytes_[(size_t(clamp_index(y, height_)) * size_t(width_) + size_t(clamp_index(x, width_))) * 3];
}

inline rtw_image::rgb rtw_image::linear(int x, int y) const {
    if (!linear_) return {1, 0, 1};
    const float* p = &(*linear_)[(size_t(clamp_index(y, height_)) * size_t(width_) + size_t(clamp_index(x, width_))) * 3];
    return {p[0], p[1], p[2]};
}

} // namespace rt

#ifndef RTWEEKEND_NO_GLOBAL_NAMES
using rt::rtw_image;
#endif
