#pragma once
// image_read: reading image files back, to compare a render with a reference (metrics.h).
//
//   read_image(path)            PPM (P3 and P6, maxval 1..65535, '#' comments in the header),
//                               PFM ('PF' colour and 'Pf' grey, either byte order), PNG, BMP and
//                               JPEG (through stb_image; a JPEG's data read through by libjpeg
//                               first when the build has it), OpenEXR (through the OpenEXR library, when
//                               the build has it: exr.h), Radiance HDR (through stb_image). The format is recognised by the file's first
//                               bytes, not by its name. Throws scene_error naming the path.
//   decode_image(bytes, name)   the same, from bytes in memory; `name` goes in the messages.
//
// What comes back is what the file stores, and whether that is display-encoded:
//   - PFM, EXR and HDR hold linear radiance: `pixels` are their values as float (EXR half and uint
//     channels converted exactly, HDR's shared-exponent RGBE as stb_image expands it),
//     display_encoded = false.
//   - PPM, PNG, BMP and JPEG hold display-encoded values (our writers apply gamma 2 and the book's
//     8-bit quantisation): `pixels` are the stored codes on the 8-bit scale 0..255, as floats,
//     display_encoded = true. A PPM with maxval M other than 255 is put on that scale as
//     code * 255 / M, so its values need not be whole numbers.
//   - Nothing is decoded back to linear: 8 bits of gamma-encoded data do not say what radiance
//     produced them (the book's encoding clamps at 1 and maps an interval to each code), so
//     metrics.h compares a linear image with an 8-bit one by encoding the linear one instead.
//   - Grey and palette images (Pf, PNG, BMP) are expanded to RGB. PNG alpha is dropped, not
//     composited; 16-bit PNGs are reduced to 8 bits by stb_image.
//   - Netpbm allows several images in one file: a P6 file is read up to the end of its first
//     raster. A P3 file must end after its raster, because extra values there almost always mean
//     a header whose size is wrong. A PFM file must be exactly its header and raster, or be
//     followed by a sample slice's trailer (io/slice_file.h: `render --samples` writes a PFM of the
//     slice's mean, then the exact sums for `merge`), which starts with slice_trailer_magic and is
//     not read here: any other bytes after the raster are refused as before.
//
// This header, not image.h, holds the readers. stb_image comes through rtw_stb_image.h (which
// texture.h includes too): a program that brings its own stb_image must define
// STB_IMAGE_IMPLEMENTATION or include it before these headers.

#include "image.h"
#include "../core/scene_error.h"
#include "exr.h"
#include "../core/file.h"
#include "../core/text_lines.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

namespace rt {

// What a sample slice's trailer starts with, right after the PFM raster (io/slice_file.h).
inline constexpr char slice_trailer_magic[] = "\nrtweekend-slice ";

struct loaded_image {
    image pixels;                  // linear radiance, or codes on the 8-bit scale 0..255
    bool display_encoded = false;  // true for PPM, PNG, BMP and JPEG files
    std::string format;            // "PPM P3", "PPM P6", "PFM", "EXR", "PNG", "BMP", "JPEG" or "HDR", for messages
};

loaded_image read_image(const std::string& path);
loaded_image decode_image(const std::string& bytes, const std::string& name);

} // namespace rt

// --- IMPLEMENTATION ---

// stb_image decodes PNG and BMP: the copy rtw_stb_image.h compiles (or the program's own), so
// that a program reading images and textures has one.
#include "../rtw_stb_image.h"

namespace rt {
namespace detail {

[[noreturn]] inline void read_error(const std::string& name, const std::string& problem) {
    throw scene_error("cannot read '" + name + "': " + problem);
}

// One byte of a malformed file, as text a message can show.
inline std::string printable(char c) {
    if (c >= 0x20 && c < 0x7f) return std::string(1, c);
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(static_cast<unsigned char>(c)));
    return hex;
}

inline bool is_header_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// A cursor over the text header of a PPM or PFM file.
struct header_cursor {
    const std::string& bytes;
    const std::string& name;
    const char* format;
    bool allow_comments; // Netpbm allows '#' comments in the header, PFM does not
    size_t pos = 0;

    [[noreturn]] void fail(const std::string& problem) const { read_error(name, std::string(format) + " " + problem); }

    void skip_space() {
        while (pos < bytes.size()) {
            if (is_header_space(bytes[pos])) ++pos;
            else if (allow_comments && bytes[pos] == '#')
                while (pos < bytes.size() && bytes[pos] != '\n' && bytes[pos] != '\r') ++pos;
            else break;
        }
    }

    // Whitespace must separate fields; this checks there is some before skipping it.
    void require_space(const char* after) {
        if (pos >= bytes.size()) fail(std::string("header is truncated after the ") + after);
        if (!is_header_space(bytes[pos]) && !(allow_comments && bytes[pos] == '#'))
            fail(std::string("header needs whitespace after the ") + after);
        skip_space();
    }

    // A decimal integer in [min, max]; `what` names the field in messages.
    uint64_t read_integer(const char* what, uint64_t min, uint64_t max) {
        if (pos >= bytes.size()) fail(std::string("header is truncated before the ") + what);
        uint64_t v = 0;
        size_t start = pos;
        while (pos < bytes.size() && bytes[pos] >= '0' && bytes[pos] <= '9') {
            v = v * 10 + uint64_t(bytes[pos] - '0');
            if (v > max) fail(std::string(what) + " must be at most " + std::to_string(max));
            ++pos;
        }
        if (pos == start) fail(std::string(what) + " is not a number (found '" + printable(bytes[pos]) + "')");
        if (v < min) fail(std::string(what) + " must be at least " + std::to_string(min) + ", got " + std::to_string(v));
        return v;
    }

    // The single whitespace character that ends a header; the raster starts right after it.
    void end_header(const char* after) {
        if (pos >= bytes.size()) fail(std::string("header is truncated after the ") + after);
        if (allow_comments && bytes[pos] == '#') {
            while (pos < bytes.size() && bytes[pos] != '\n' && bytes[pos] != '\r') ++pos;
            if (pos >= bytes.size()) fail("header is truncated in a comment");
        } else if (!is_header_space(bytes[pos])) {
            fail(std::string("header needs one whitespace character after the ") + after);
        }
        ++pos;
    }
};

inline std::string size_text(uint64_t w, uint64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

// The pixel limit of input_limits.h, before a PPM or PFM raster is allocated.
inline void check_size(uint64_t w, uint64_t h, const std::string& name, const char* format) {
    try {
        check_image_size(w, h, std::string(format) + " image");
    } catch (const scene_error& e) {
        read_error(name, e.what());
    }
}

inline loaded_image decode_ppm(const std::string& bytes, const std::string& name) {
    const bool binary = bytes[1] == '6';
    header_cursor c{bytes, name, binary ? "PPM P6" : "PPM P3", true};
    c.pos = 2;
    c.require_space("magic number");
    uint64_t w = c.read_integer("width", 1, max_image_side);
    c.require_space("width");
    uint64_t h = c.read_integer("height", 1, max_image_side);
    c.require_space("height");
    uint64_t maxval = c.read_integer("maxval", 1, 65535);

    loaded_image out{image(0, 0), true, c.format};
    const uint64_t count = w * h * 3;
    const double to_8bit = 255.0 / double(maxval);
    auto scaled = [&](uint64_t code) { return maxval == 255 ? float(code) : float(double(code) * to_8bit); };

    if (binary) {
        c.end_header("maxval");
        const uint64_t sample_bytes = maxval > 255 ? 2 : 1;
        const uint64_t needed = count * sample_bytes, available = bytes.size() - c.pos;
        if (available < needed)
            c.fail("raster is truncated: " + size_text(w, h) + " needs " + std::to_string(needed) + " bytes, the file has " +
                   std::to_string(available));
        check_size(w, h, name, c.format); // a file that does hold so many pixels
        out.pixels = image(int(w), int(h));
        float* dst = out.pixels.data().data();
        const auto* src = reinterpret_cast<const unsigned char*>(bytes.data() + c.pos);
        for (uint64_t i = 0; i < count; ++i) {
            // 16-bit samples are big-endian, most significant byte first.
            uint64_t code = sample_bytes == 2 ? (uint64_t(src[2 * i]) << 8) | src[2 * i + 1] : src[i];
            if (code > maxval)
                c.fail("sample " + std::to_string(i) + " is " + std::to_string(code) + ", above maxval " + std::to_string(maxval));
            dst[i] = scaled(code);
        }
        return out;
    }

    // P3: each value takes at least one digit and one separator, so a file shorter than that is
    // truncated; checking first keeps a malformed header from allocating a huge image.
    if (count * 2 - 1 > bytes.size() - c.pos)
        c.fail("raster is truncated: " + size_text(w, h) + " needs " + std::to_string(count) + " values, the file is too short");
    check_size(w, h, name, c.format);
    out.pixels = image(int(w), int(h));
    float* dst = out.pixels.data().data();
    for (uint64_t i = 0; i < count; ++i) {
        c.skip_space();
        if (c.pos >= bytes.size())
            c.fail("raster is truncated: " + size_text(w, h) + " needs " + std::to_string(count) + " values, the file has " +
                   std::to_string(i));
        uint64_t code = c.read_integer(("value " + std::to_string(i)).c_str(), 0, maxval);
        dst[i] = scaled(code);
    }
    c.skip_space();
    if (c.pos < bytes.size())
        c.fail("has more data after the " + std::to_string(count) + " values of a " + size_text(w, h) +
               " image (is the size in the header right?)");
    return out;
}

// A PFM file's header, checked, and where its raster lies.
struct pfm_layout {
    uint64_t width = 0, height = 0, channels = 3;
    bool little_endian = true;
    size_t raster = 0, raster_end = 0; // byte offsets: the raster is [raster, raster_end)
};

// Reads and checks a PFM header, and that the file holds the raster it describes. Bytes after the
// raster are allowed only when they are a slice trailer (slice_trailer_magic).
inline pfm_layout read_pfm_layout(const std::string& bytes, const std::string& name) {
    const bool colour = bytes[1] == 'F';
    header_cursor c{bytes, name, "PFM", false};
    c.pos = 2;
    c.require_space("magic number");
    uint64_t w = c.read_integer("width", 1, max_image_side);
    c.require_space("width");
    uint64_t h = c.read_integer("height", 1, max_image_side);
    c.require_space("height");

    // The scale: its sign gives the byte order (negative = little-endian); its magnitude is
    // not applied, as most readers do not.
    size_t start = c.pos;
    while (c.pos < bytes.size() && !is_header_space(bytes[c.pos])) ++c.pos;
    std::string scale_text = bytes.substr(start, c.pos - start);
    if (scale_text.empty()) c.fail("header is truncated before the scale");
    // The whole token must be the number: strtod would stop at a NUL byte and take "-1\0junk"
    // for -1. from_chars takes no '+', which a scale may have.
    const char* first = scale_text.data() + (scale_text[0] == '+' ? 1 : 0);
    const char* last = scale_text.data() + scale_text.size();
    double scale = 0;
    auto parsed = std::from_chars(first, last, scale, std::chars_format::general);
    if (parsed.ec != std::errc() || parsed.ptr != last || !std::isfinite(scale) || scale == 0) {
        std::string shown;
        for (char ch : scale_text) shown += printable(ch);
        c.fail("scale '" + shown + "' is not a non-zero number");
    }
    c.end_header("scale");

    const uint64_t channels = colour ? 3 : 1;
    const uint64_t needed = w * h * channels * 4, available = bytes.size() - c.pos;
    if (available < needed)
        c.fail("raster is truncated: " + size_text(w, h) + " needs " + std::to_string(needed) + " bytes, the file has " +
               std::to_string(available));
    const size_t end = c.pos + size_t(needed);
    const size_t magic_size = sizeof slice_trailer_magic - 1;
    if (available > needed && bytes.compare(end, magic_size, slice_trailer_magic) != 0)
        c.fail("has " + std::to_string(available - needed) + " bytes after the raster of a " + size_text(w, h) + " image");
    check_size(w, h, name, c.format);
    return {w, h, channels, scale < 0, c.pos, end};
}

inline loaded_image decode_pfm(const std::string& bytes, const std::string& name) {
    const pfm_layout layout = read_pfm_layout(bytes, name);
    const uint64_t w = layout.width, h = layout.height, channels = layout.channels;
    const bool colour = channels == 3;
    const bool little_endian = layout.little_endian;
    loaded_image out{image(int(w), int(h)), false, "PFM"};
    const auto* src = reinterpret_cast<const unsigned char*>(bytes.data() + layout.raster);
    float* dst = out.pixels.data().data();
    for (uint64_t file_row = 0; file_row < h; ++file_row) {
        // PFM stores rows bottom to top; the image's row 0 is the top.
        float* row = dst + (h - 1 - file_row) * w * 3;
        for (uint64_t x = 0; x < w; ++x) {
            for (uint64_t ch = 0; ch < channels; ++ch) {
                const unsigned char* b = src + ((file_row * w + x) * channels + ch) * 4;
                uint32_t bits = little_endian ? uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24
                                              : uint32_t(b[3]) | uint32_t(b[2]) << 8 | uint32_t(b[1]) << 16 | uint32_t(b[0]) << 24;
                float v;
                std::memcpy(&v, &bits, 4);
                if (colour) row[x * 3 + ch] = v;
                else row[x * 3] = row[x * 3 + 1] = row[x * 3 + 2] = v;
            }
        }
    }
    return out;
}

inline loaded_image decode_with_stb(const std::string& bytes, const std::string& name, const char* format) {
    if (bytes.size() > size_t(INT32_MAX)) read_error(name, std::string(format) + " file is too large");
    // The headers are checked here, not by stb_image, which allocates what they describe first.
    std::string problem = stb_input_problem(bytes);
    if (!problem.empty()) read_error(name, problem);
    int w = 0, h = 0, channels_in_file = 0;
    unsigned char* rgb = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w,
                                               &h, &channels_in_file, 3);
    if (!rgb) {
        const char* reason = stbi_failure_reason();
        // stb_image's message may quote bytes of the file (an unknown chunk's type): one line.
        read_error(name, std::string(format) + " " + one_line(reason && *reason ? reason : "cannot be decoded"));
    }
    loaded_image out{image(w, h), true, format};
    std::vector<float>& dst = out.pixels.data();
    for (size_t i = 0; i < dst.size(); ++i) dst[i] = float(rgb[i]);
    stbi_image_free(rgb);
    return out;
}

inline loaded_image decode_png(const std::string& bytes, const std::string& name) {
    return decode_with_stb(without_empty_png_data_chunks(bytes), name, "PNG");
}

// stb_image reads past the end of a BMP as zeros instead of failing, so an uncompressed BMP cut
// short would come back with black rows: image_header_problem (through decode_with_stb) refuses a
// BMP whose headers promise more pixel data than the file holds.
inline loaded_image decode_bmp(const std::string& bytes, const std::string& name) {
    return decode_with_stb(bytes, name, "BMP");
}

// Radiance HDR (RGBE; Greg Ward's format, "#?RADIANCE" or "#?RGBE"): linear floats, as stb_image
// decodes them, after the same checks of its header, size and run-length data as the 8-bit
// formats (stb_input_problem: image_header.h walks the scanlines).
inline loaded_image decode_hdr(const std::string& bytes, const std::string& name) {
    if (bytes.size() > size_t(INT32_MAX)) read_error(name, "HDR file is too large");
    std::string problem = stb_input_problem(bytes);
    if (!problem.empty()) read_error(name, problem);
    int w = 0, h = 0, channels_in_file = 0;
    float* rgb = stbi_loadf_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h,
                                        &channels_in_file, 3);
    if (!rgb) {
        const char* reason = stbi_failure_reason();
        read_error(name, std::string("HDR ") + one_line(reason && *reason ? reason : "cannot be decoded"));
    }
    loaded_image out{image(w, h), false, "HDR"};
    std::vector<float>& dst = out.pixels.data();
    for (size_t i = 0; i < dst.size(); ++i) dst[i] = rgb[i];
    stbi_image_free(rgb);
    return out;
}

} // namespace detail

inline loaded_image decode_image(const std::string& bytes, const std::string& name) {
    if (bytes.empty()) detail::read_error(name, "the file is empty");
    auto starts_with = [&](const char* magic, size_t n) { return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0; };
    if (starts_with("P3", 2) || starts_with("P6", 2)) return detail::decode_ppm(bytes, name);
    if (starts_with("PF", 2) || starts_with("Pf", 2)) return detail::decode_pfm(bytes, name);
    if (starts_with("\x89PNG\r\n\x1a\n", 8)) return detail::decode_png(bytes, name);
    if (starts_with("BM", 2)) return detail::decode_bmp(bytes, name);
    if (starts_with("\xff\xd8\xff", 3)) return detail::decode_with_stb(bytes, name, "JPEG");
    if (starts_with("\x76\x2f\x31\x01", 4)) return loaded_image{decode_exr(bytes, name), false, "EXR"};
    if (starts_with("#?RADIANCE\n", 11) || starts_with("#?RGBE\n", 7)) return detail::decode_hdr(bytes, name);
    detail::read_error(name, "not a PPM (P3/P6), PFM, EXR, PNG, BMP, JPEG or Radiance HDR file");
}

inline loaded_image read_image(const std::string& path) {
    return decode_image(read_file(path, "image file"), path);
}

} // namespace rt
