#pragma once
// image_header: what a PNG, BMP or JPEG file's headers promise, checked before stb_image decodes it.
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
//     runs past the end of the file (or is above 2^31 - 1, the format's own limit), a file that
//     ends without IEND, and image data (IDAT chunks) too short to inflate to the rows the IHDR
//     describes even at deflate's best ratio, 1032:1;
//   - both: an image beyond the limits of input_limits.h (sides of 2^24, 2^28 pixels);
//   - binary PNM (P5, P6; read by stb_image for textures): a width or height above 2^24 or a
//     maxval above 65535 (stb_image 2.27 accumulates the header's numbers in an int without
//     checking, which overflows on a long run of digits), and 16 bits a sample (a maxval above
//     255): stb_image 2.27 expands 16-bit grey to RGB with its 8-bit routine, reading past its
//     buffer, and reads 16-bit samples little-endian where the format stores them big-endian;
//   - JPEG (read by stb_image for textures): a Huffman table (DHT segment) of more than 256 codes,
//     and a scan that uses a Huffman table the file has not defined. stb_image 2.27 (Debian 12's)
//     writes the code lengths of the first past the end of its 257-entry array, and decodes with
//     the second as it finds it in uninitialised memory; the segments are walked as stb_image
//     walks them (entropy-coded data is skipped to the next marker), so every table it would build
//     or use is checked first; and more than max_jpeg_scans (100) scans, each of which stb_image
//     decodes over the whole image even when it holds no data.
// Other formats (JPEG, TGA, HDR, PNM textures) are left to stb_image, whose stbi_info reads their
// size; the caller checks that size (rtw_stb_image.h) against the limits and against
//
//   std::string problem = image_data_problem(bytes, width, height);
//
// which refuses a file too short to hold that many pixels in the densest form its format has:
// JPEG one bit per 8x8 block (512 pixels a byte), Radiance HDR runs of 127 pixels in 8 bytes
// (16 pixels a byte), TGA runs of 128 pixels in a 1-byte header and one pixel (or a byte per
// pixel component uncompressed), binary PNM a byte per sample. stb_image allocates what the header
// describes, then reads missing data as zeros (JPEG, TGA) or fails only after allocating: without
// this, a 38-byte TGA claiming 770x65528 pixels took 750 MB and seconds to decode.

#include "input_limits.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace rt {

// What is wrong with the headers of the PNG, BMP, JPEG or binary PNM file `bytes`; "" when
// nothing is, or when it is none of these.
std::string image_header_problem(const std::string& bytes);

// What is wrong with a JPEG, Radiance HDR, TGA or binary PNM file `bytes` whose header says it is
// width x height pixels: "" when the file is long enough to hold them (see the top), or when it is
// none of these formats (PNG and BMP are image_header_problem's).
std::string image_data_problem(const std::string& bytes, uint64_t width, uint64_t height);

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

// A w x h image in `format` needs at least `need` bytes of data in its densest form (`densest`
// says what that is), and the file has `have` (`where`: " after its headers", say).
inline std::string too_short_problem(const char* format, uint64_t w, uint64_t h, uint64_t need, uint64_t have,
                                     const std::string& densest, const char* where = "") {
    return std::string(format) + " image of " + std::to_string(w) + "x" + std::to_string(h) + " pixels needs at least " +
           std::to_string(need) + " bytes of data (" + densest + "), the file has " + std::to_string(have) + where;
}

inline std::string png_header_problem(const std::string& b) {
    size_t pos = 8; // after the signature
    bool first = true;
    uint64_t width = 0, height = 0, bits_per_pixel = 0, data_bytes = 0;
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
            width = header_u32_be(b, pos + 8);
            height = header_u32_be(b, pos + 12);
            std::string size = image_size_problem(width, height, "PNG");
            if (!size.empty()) return size;
            // Samples a pixel by colour type (grey, -, RGB, palette, grey + alpha, -, RGBA); an
            // unknown type is stb_image's to refuse.
            static const uint64_t samples[7] = {1, 0, 3, 1, 2, 0, 4};
            const unsigned depth = static_cast<unsigned char>(b[pos + 16]), colour = static_cast<unsigned char>(b[pos + 17]);
            bits_per_pixel = colour < 7 ? samples[colour] * depth : 0;
            first = false;
        }
        if (type == "IDAT") data_bytes += length;
        pos += size_t(12 + length);
        if (type == "IEND") break;
    }
    // Deflate stores at most 1032 bytes in one (a 258-byte match in under 2 bits); the rows hold a
    // filter byte each (interlaced images hold more). Sides are at most 2^24 and bits_per_pixel at
    // most 64, so nothing here overflows.
    const uint64_t rows = height * (1 + (width * bits_per_pixel + 7) / 8), need = (rows + 1031) / 1032;
    if (bits_per_pixel > 0 && data_bytes < need)
        return too_short_problem("PNG", width, height, need, data_bytes,
                                 std::to_string(rows) + " bytes of rows deflated at the best ratio, 1032:1",
                                 " in its IDAT chunks");
    return {};
}

// The width, height and maxval of a P5 or P6 file, read as stb_image reads them (whitespace and
// '#' comments between), checked before stb_image adds up their digits in an int.
inline std::string pnm_header_problem(const std::string& b) {
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; };
    const char* names[3] = {"width", "height", "maxval"};
    const uint64_t limits[3] = {max_image_side, max_image_side, 65535};
    size_t pos = 2;
    for (int i = 0; i < 3; ++i) {
        for (;;) {
            while (pos < b.size() && space(b[pos])) ++pos;
            if (pos >= b.size() || b[pos] != '#') break;
            while (pos < b.size() && b[pos] != '\n' && b[pos] != '\r') ++pos;
        }
        const size_t start = pos;
        uint64_t value = 0;
        for (; pos < b.size() && b[pos] >= '0' && b[pos] <= '9'; ++pos)
            if (value <= limits[i]) value = value * 10 + uint64_t(b[pos] - '0');
        if (value > limits[i]) {
            std::string digits = b.substr(start, std::min<size_t>(pos - start, 24));
            if (pos - start > 24) digits += "...";
            return "PNM " + std::string(names[i]) + " " + digits + " is more than " + std::to_string(limits[i]);
        }
        if (i == 2 && value > 255)
            return "PNM of 16 bits (maxval " + std::to_string(value) +
                   ") is not supported as a texture (stb_image 2.27 reads a P5 past its buffer and a P6 with "
                   "its bytes swapped); convert it to 8 bits or to PNG";
    }
    return {};
}

// Where a JPEG file's data starts after its SOI marker, as stb_image finds it (any number of 0xff
// bytes, then 0xd8); 0 when the file does not start so.
inline size_t jpeg_after_soi(const std::string& b) {
    size_t pos = 0;
    while (pos < b.size() && static_cast<unsigned char>(b[pos]) == 0xff) ++pos;
    return pos >= 1 && pos < b.size() && static_cast<unsigned char>(b[pos]) == 0xd8 ? pos + 1 : 0;
}

// `scans`, when given, receives the number of scans (SOS segments) walked, at most
// max_jpeg_scans + 1.
inline std::string jpeg_header_problem(const std::string& b, size_t* scans = nullptr) {
    auto at = [&](size_t i) { return static_cast<unsigned char>(b[i]); };
    const size_t size = b.size();
    size_t pos = jpeg_after_soi(b);
    bool defined[2][4] = {}; // Huffman tables defined so far: [DC, AC][id]
    bool progressive = false;
    size_t scan_count = 0;
    if (scans) *scans = 0;
    while (pos < size) {
        // A marker: 0xff (fill bytes 0xff may repeat), then its code; stb_image skips other bytes
        // between segments.
        if (at(pos) != 0xff) {
            ++pos;
            continue;
        }
        while (pos < size && at(pos) == 0xff) ++pos;
        if (pos >= size) break;
        const unsigned marker = at(pos++);
        if (marker == 0xd9) break;                                                     // EOI
        if (marker == 0x00 || marker == 0x01 || marker == 0xd8 || (marker >= 0xd0 && marker <= 0xd7)) continue; // no length
        if (size - pos < 2) break;
        const size_t length = size_t(at(pos)) << 8 | at(pos + 1);
        if (marker == 0xc4) { // DHT: tables of a class/id byte, 16 code counts, then the codes
            // stb_image reads each table's codes even where they run past the segment's length,
            // and reads zeros past the end of the file.
            ptrdiff_t left = ptrdiff_t(length) - 2;
            size_t table = pos + 2;
            while (left > 0 && table < size) {
                unsigned codes = 0;
                for (size_t i = table + 1; i <= table + 16 && i < size; ++i) codes += at(i);
                if ((at(table) >> 4) > 1 || (at(table) & 15) > 3) break; // stb_image refuses the table
                if (codes > 256)
                    return "JPEG Huffman table at byte " + std::to_string(table) + " has " + std::to_string(codes) +
                           " codes, more than 256 (the file is damaged)";
                defined[at(table) >> 4][at(table) & 15] = true;
                left -= ptrdiff_t(17 + codes);
                table += 17 + codes;
                if (table > size) break;
            }
        }
        if (marker >= 0xc0 && marker <= 0xc2) progressive = marker == 0xc2; // the frames stb_image reads
        if (marker == 0xda) {
            // stb_image decodes every scan over all the blocks of its components, whatever data it
            // holds, so its time grows as scans x pixels: a few kilobytes of empty scans took
            // seconds. libjpeg's progressive script writes 10 scans.
            ++scan_count;
            if (scans) *scans = scan_count;
            if (scan_count > max_jpeg_scans)
                return "JPEG has more than " + std::to_string(max_jpeg_scans) + " scans (the next at byte " +
                       std::to_string(pos - 2) + "); encoders write a few dozen at most, and each costs a pass over the image";
        }
        if (marker == 0xda && size - pos >= 3) {
            // A scan's components name the Huffman tables its data is decoded with; stb_image 2.27
            // uses a table the file never defined as it finds it in uninitialised memory (and
            // indexes past its arrays). Which tables a scan uses, as stb_image decodes it: both
            // in a sequential frame; in a progressive one, DC in a first DC scan (spectral start
            // 0, Ah 0), none in a DC refinement, AC in an AC scan.
            const size_t count = at(pos + 2), params = pos + 3 + 2 * count;
            if (params + 3 <= size && params <= pos + length) {
                const unsigned spectral_start = at(params), ah = at(params + 2) >> 4;
                const bool dc = !progressive || (spectral_start == 0 && ah == 0), ac = !progressive || spectral_start > 0;
                for (size_t c = 0; c < count; ++c) {
                    const unsigned dc_id = at(pos + 4 + 2 * c) >> 4, ac_id = at(pos + 4 + 2 * c) & 15;
                    if (dc_id > 3 || ac_id > 3) break; // stb_image refuses the scan
                    for (int k = 0; k < 2; ++k) {
                        const unsigned id = k == 0 ? dc_id : ac_id;
                        if ((k == 0 ? dc : ac) && !defined[k][id])
                            return "JPEG scan at byte " + std::to_string(pos - 2) + " uses Huffman table " +
                                   (k == 0 ? "DC " : "AC ") + std::to_string(id) +
                                   ", which the file does not define before it (the file is damaged)";
                    }
                }
            }
        }
        if (length < 2) break;
        pos += length;
        if (marker == 0xda) { // SOS: entropy-coded data up to the next marker (0xff 0x00 is a data byte, RSTn is inside)
            while (pos < size) {
                if (at(pos) != 0xff) {
                    ++pos;
                    continue;
                }
                size_t next = pos;
                while (next < size && at(next) == 0xff) ++next;
                if (next < size && at(next) != 0x00 && !(at(next) >= 0xd0 && at(next) <= 0xd7)) break; // a marker at pos
                pos = next + 1;
            }
        }
    }
    return {};
}

// A Radiance HDR file's run-length encoded scanlines, walked as stb_image 2.27 decodes them: it
// loops for ever on a count of 0, which is also what it reads past the end of the file, so a
// truncated file hung it. The header is lines up to an empty one, then the resolution line; a
// scanline is "2 2", its width in 2 bytes, then each of the 4 components as runs (a count above
// 128, then one byte) and literals (a count, then that many bytes). Widths below 8 or above 32767,
// and a scanline that does not start "2 2", are stored flat, which stb_image reads to the end: a
// file too short for its flat pixels is refused too.
inline std::string hdr_rle_problem(const std::string& b, uint64_t w, uint64_t h) {
    auto byte = [&](size_t i) -> unsigned { return i < b.size() ? static_cast<unsigned char>(b[i]) : 0u; };
    // The header's lines, read as stb_image reads them (stbi__hdr_gettoken): a byte, then, while the
    // file has more and that byte is not '\n', it is kept and the next read; at 1023 kept the rest
    // of the line is skipped. The header ends at the first line that keeps nothing, or whose first
    // byte is NUL (a string's end to stb_image): a line of NUL bytes ends it as an empty one does.
    size_t pos = 0;
    auto next_line = [&]() -> unsigned { // the line's first kept byte, 0 if none; pos moves past it
        unsigned first = 0, kept = 0;
        unsigned c = byte(pos);
        if (pos < b.size()) ++pos;
        while (pos < b.size() && c != '\n') {
            if (kept++ == 0) first = c;
            if (kept == 1023) {
                while (pos < b.size() && byte(pos++) != '\n') {
                }
                break;
            }
            c = byte(pos++);
        }
        return first;
    };
    next_line(); // "#?RADIANCE" or "#?RGBE": stbi_info checked it
    while (next_line() != 0) {
    }
    next_line(); // the resolution line, which stbi_info read as w x h
    // Flat pixels (4 bytes each) from `row` on: stb_image would read past the end as zeros, a
    // silently black part of the image, so a file too short for them is refused.
    auto flat_from = [&](uint64_t row) -> std::string {
        const uint64_t need = (h - row) * w * 4, have = b.size() > pos ? b.size() - pos : 0;
        if (have >= need) return {};
        return "HDR file is truncated: rows " + std::to_string(row) + " to " + std::to_string(h - 1) + " of " +
               std::to_string(w) + " flat pixels need " + std::to_string(need) + " bytes after byte " +
               std::to_string(pos) + ", the file has " + std::to_string(have);
    };
    if (w < 8 || w > 32767) return flat_from(0);
    for (uint64_t row = 0; row < h; ++row) {
        if (byte(pos) != 2 || byte(pos + 1) != 2 || (byte(pos + 2) & 0x80)) return flat_from(row); // flat from here on
        if ((uint64_t(byte(pos + 2)) << 8 | byte(pos + 3)) != w) return {};          // stb_image refuses it
        pos += 4;
        for (int component = 0; component < 4; ++component) {
            for (uint64_t i = 0; i < w;) {
                unsigned count = byte(pos++);
                if (count > 128) {
                    count -= 128;
                    ++pos;
                } else {
                    if (count == 0)
                        return "HDR scanline " + std::to_string(row) + " has a run-length count of 0 at byte " +
                               std::to_string(pos - 1) +
                               (pos - 1 >= b.size() ? " (the file ends there: it is truncated)" : "");
                    pos += count;
                }
                if (count > w - i) return {}; // stb_image refuses it
                i += count;
            }
        }
    }
    return {};
}

// The name of a format stb_image reads, from the file's first bytes ("TGA" when it is none of the
// others: TGA has no magic number), for messages.
inline const char* stb_format_name(const std::string& b) {
    auto starts_with = [&](const char* magic) { return b.compare(0, std::strlen(magic), magic) == 0; };
    if (starts_with("\x89PNG")) return "PNG";
    if (starts_with("BM")) return "BMP";
    if (jpeg_after_soi(b)) return "JPEG";
    if (starts_with("#?RADIANCE") || starts_with("#?RGBE")) return "HDR";
    if (starts_with("P5") || starts_with("P6")) return "PNM";
    return "TGA";
}

} // namespace detail

inline std::string image_data_problem(const std::string& b, uint64_t w, uint64_t h) {
    using detail::too_short_problem;
    // Sides are at most 2^24 here (the caller checked), so products of a few of them fit.
    const uint64_t pixels = w * h, size = b.size();
    auto starts_with = [&](const char* magic) { return b.compare(0, std::strlen(magic), magic) == 0; };
    if (starts_with("\x89PNG") || starts_with("BM")) return {};
    if (detail::jpeg_after_soi(b)) {
        const uint64_t need = (pixels + 511) / 512;
        return size < need ? too_short_problem("JPEG", w, h, need, size, "one bit per 8x8 block") : std::string();
    }
    if (starts_with("#?RADIANCE") || starts_with("#?RGBE")) {
        const uint64_t need = (pixels + 15) / 16;
        if (size < need) return too_short_problem("HDR", w, h, need, size, "runs of 127 pixels in 8 bytes");
        return detail::hdr_rle_problem(b, w, h);
    }
    if (starts_with("P5") || starts_with("P6")) {
        const uint64_t need = pixels * (b[1] == '6' ? 3 : 1);
        return size < need ? too_short_problem("PNM", w, h, need, size, "a byte per sample") : std::string();
    }
    // Otherwise TGA, the one format stb_image knows without a magic number: an 18-byte header, an
    // image ID, a colour map, then the pixels, run-length encoded in image types 9 to 11.
    // stb_image reads bytes past the end of the file as zeros, the header's too: so does this.
    if (size < 18) return image_data_problem(b + std::string(18 - size, '\0'), w, h);
    const unsigned type = static_cast<unsigned char>(b[2]), bits = static_cast<unsigned char>(b[16]);
    const uint64_t map_bytes = static_cast<unsigned char>(b[1]) == 0
                                   ? 0
                                   : detail::header_u16_le(b, 5) * ((static_cast<unsigned char>(b[7]) + 7u) / 8u);
    const uint64_t header = 18 + static_cast<unsigned char>(b[0]) + map_bytes, pixel_bytes = (bits + 7) / 8;
    const uint64_t data = size > header ? size - header : 0;
    const bool rle = (type & 8) != 0;
    const uint64_t need = rle ? (pixels + 127) / 128 * (1 + pixel_bytes) : pixels * pixel_bytes;
    if (data < need)
        return too_short_problem("TGA", w, h, need, data,
                                 rle ? "runs of 128 pixels in a header byte and one pixel" : "uncompressed pixels",
                                 " after its headers");
    return {};
}

inline std::string image_header_problem(const std::string& bytes) {
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return detail::png_header_problem(bytes);
    if (bytes.size() >= 2 && bytes[0] == 'B' && bytes[1] == 'M') return detail::bmp_header_problem(bytes);
    if (detail::jpeg_after_soi(bytes)) return detail::jpeg_header_problem(bytes);
    if (bytes.size() >= 2 && (bytes.compare(0, 2, "P5") == 0 || bytes.compare(0, 2, "P6") == 0))
        return detail::pnm_header_problem(bytes);
    return {};
}

} // namespace rt
