#pragma once
// image_header: what a PNG or BMP file's headers promise, checked before stb_image decodes it.
//
//   std::string problem = image_header_problem(bytes);   // "" when the headers are sound
//
// stb_image trusts the headers it reads: it allocates the image a header describes before it
// looks for the pixel data, reads a BMP's compression field as a signed number (so 0x80000000
// passes its "unsupported compression" test), allocates ~2 GB for a BMP of more than 32 bits per
// pixel before it refuses it, and a PNG chunk longer than the file is allocated before it is read.
// This reads the same fields as unsigned numbers and refuses, with the field named:
//   - BMP: a header size stb_image does not know (12, 40, 56, 108, 124 are known), planes other
//     than 1, bits per pixel outside {1, 4, 8, 16, 24, 32}, compression other than 0 (none) or 3
//     (bit fields, 16 or 32 bits only), a width or height of 0 (or a negative width), a pixel data
//     offset inside the headers, and pixel data (rows padded to 4 bytes) that the file is too short
//     to hold;
//   - PNG: a first chunk that is not a 13-byte IHDR, a width or height of 0, any chunk whose length
//     runs past the end of the file (or is above 2^31 - 1, the format's own limit), and a file that
//     ends without IEND;
//   - both: an image beyond the limits of input_limits.h (sides of 2^24, 2^28 pixels).
// Other formats (JPEG, TGA, HDR, PNM textures) are left to stb_image; their size is checked by
// the caller through stbi_info before decoding (rtw_stb_image.h).

#include "input_limits.h"

#include <cstdint>
#include <cstring>
#include <string>

namespace rt {

// What is wrong with the headers of the PNG or BMP file `bytes`; "" when nothing is, or when it is
// neither a PNG nor a BMP file.
std::string image_header_problem(const std::string& bytes);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

namespace detail {

inline uint32_t header_u16_le(const std::string& b, size_t at) {
    return uint32_t(static_cast<unsigned char>(b[at])) | uint32_t(static_cast<unsigned char>(b[at + 1])) << 8;
}
inline uint32_t header_u32_le(const std::string& b, size_t at) {
    return header_u16_le(b, at) | header_u16_le(b, at + 2) << 16;
}
inline uint32_t header_u32_be(const std::string& b, size_t at) {
    uint32_t v = 0;
    for (size_t i = 0; i < 4; ++i) v = v << 8 | uint32_t(static_cast<unsigned char>(b[at + i]));
    return v;
}

// The size check of input_limits.h, as a problem string rather than an exception.
inline std::string image_size_problem(uint64_t w, uint64_t h, const char* format) {
    try {
        check_image_size(w, h, std::string(format) + " image");
    } catch (const scene_error& e) {
        return e.what();
    }
    return {};
}

inline std::string bmp_header_problem(const std::string& b) {
    // File header (14 bytes): "BM", file size, reserved, pixel data offset; then the info header,
    // which starts with its own size.
    if (b.size() < 26) return "BMP file is " + std::to_string(b.size()) + " bytes, too short for its headers";
    const uint64_t data_offset = header_u32_le(b, 10), info_size = header_u32_le(b, 14);
    if (info_size != 12 && info_size != 40 && info_size != 56 && info_size != 108 && info_size != 124)
        return "BMP info header size " + std::to_string(info_size) + " is not supported (12, 40, 56, 108 or 124)";
    if (b.size() < 14 + info_size)
        return "BMP file is " + std::to_string(b.size()) + " bytes, too short for its " + std::to_string(info_size) +
               "-byte info header";
    uint64_t width, height, planes, bits, compression = 0;
    if (info_size == 12) { // OS/2 BITMAPCOREHEADER: unsigned 16-bit sizes, never compressed
        width = header_u16_le(b, 18);
        height = header_u16_le(b, 20);
        planes = header_u16_le(b, 22);
        bits = header_u16_le(b, 24);
    } else {
        const uint32_t w = header_u32_le(b, 18), h = header_u32_le(b, 22);
        if (w >= 0x80000000u) return "BMP width " + std::to_string(int64_t(w) - (int64_t(1) << 32)) + " is negative";
        width = w;
        // A negative height means rows stored top to bottom; its magnitude is the height.
        height = h >= 0x80000000u ? (uint64_t(1) << 32) - h : h;
        planes = header_u16_le(b, 26);
        bits = header_u16_le(b, 28);
        compression = header_u32_le(b, 30);
    }
    if (planes != 1) return "BMP planes field is " + std::to_string(planes) + ", not 1";
    if (bits != 1 && bits != 4 && bits != 8 && bits != 16 && bits != 24 && bits != 32)
        return "BMP bits per pixel is " + std::to_string(bits) + " (1, 4, 8, 16, 24 or 32 are supported)";
    if (compression == 1 || compression == 2)
        return "BMP compression " + std::to_string(compression) + " (run-length encoding) is not supported";
    if (compression != 0 && compression != 3)
        return "BMP compression " + std::to_string(compression) + " is not supported (0, none, or 3, bit fields)";
    if (compression == 3 && bits != 16 && bits != 32)
        return "BMP compression 3 (bit fields) needs 16 or 32 bits per pixel, not " + std::to_string(bits);
    std::string size = image_size_problem(width, height, "BMP");
    if (!size.empty()) return size;
    if (data_offset < 14 + info_size)
        return "BMP pixel data offset " + std::to_string(data_offset) + " points inside its headers";
    // Sizes are at most 2^24 and bits at most 32, so this cannot overflow.
    const uint64_t row_bytes = (width * bits + 31) / 32 * 4, needed = data_offset + row_bytes * height;
    if (needed > b.size())
        return "BMP raster is truncated: needs " + std::to_string(needed) + " bytes, the file has " +
               std::to_string(b.size()) + " (" + std::to_string(width) + "x" + std::to_string(height) + " at " +
               std::to_string(bits) + " bits per pixel)";
    return {};
}

inline std::string png_header_problem(const std::string& b) {
    size_t pos = 8; // after the signature
    bool first = true;
    while (true) {
        if (b.size() - pos < 12) // length, type and CRC of a chunk
            return pos == b.size() ? "PNG file ends without an IEND chunk (it is truncated)"
                                   : "PNG file ends inside a chunk header at byte " + std::to_string(pos);
        const uint64_t length = header_u32_be(b, pos);
        std::string type = b.substr(pos + 4, 4);
        for (char& c : type)
            if (!(c >= 'A' && c <= 'Z') && !(c >= 'a' && c <= 'z')) c = '?';
        if (length > 0x7fffffffu || length > b.size() - pos - 12)
            return "PNG chunk '" + type + "' at byte " + std::to_string(pos) + " is " + std::to_string(length) +
                   " bytes long, past the end of the file (" + std::to_string(b.size()) + " bytes)";
        if (first) {
            if (type != "IHDR" || length != 13) return "PNG file does not start with a 13-byte IHDR chunk";
            std::string size = image_size_problem(header_u32_be(b, pos + 8), header_u32_be(b, pos + 12), "PNG");
            if (!size.empty()) return size;
            first = false;
        }
        pos += size_t(12 + length);
        if (type == "IEND") return {};
    }
}

} // namespace detail

inline std::string image_header_problem(const std::string& bytes) {
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return detail::png_header_problem(bytes);
    if (bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M') return detail::bmp_header_problem(bytes);
    return {};
}

} // namespace rt
