#pragma once
// jpeg_check: a JPEG file's entropy-coded data read through by libjpeg-turbo (Debian's
// libjpeg-dev) before stb_image decodes it, for image textures.
//
//   detail::jpeg_data_problem(bytes, width, height)
//                                  "" when libjpeg reads every scan of the JPEG file `bytes` to
//                                  its end with every code sound, in a frame of width x height
//                                  pixels (the size stb_image reads from the file); else what is
//                                  wrong
//
// Why: stb_image, which decodes the textures, says of itself that it is not written for untrusted
// files, and the stb_image 2.27 that Debian 12 ships shifts a 32-bit word by 34 bits, undefined
// behaviour, when a file's entropy-coded data holds a code that is no code of its Huffman table
// near the end of the data (upstream nothings/stb#1293; our fuzzing found such a file,
// tests/data/fuzz/jpeg_bit_reader_shift.jpg). No check of a file's headers can see that coming:
// it takes decoding the entropy-coded data. libjpeg-turbo does that well: it is the JPEG library
// of nearly every Linux program, maintained, and fuzzed continuously (OSS-Fuzz).
//
// Why not let libjpeg decode the pixels too: two correct JPEG decoders need not agree to the last
// bit (the standard bounds the IDCT's error and leaves chroma upsampling open), and on
// photographs libjpeg's pixels differ from stb_image's by up to 6 codes in 5-13 % of values. The
// book's code and the course renderers whose reference images we match decode with stb_image, so
// the pixels stay stb_image's. The check decodes only as far as the DCT coefficients
// (jpeg_read_coefficients: no inverse DCT, upsampling or colour conversion).
//
// What is refused: whatever libjpeg reports as an error (a bad marker, an unsupported precision,
// and so on), and the warnings that mean lost pixels, after which libjpeg would go on and fill in
// grey: a bad Huffman or arithmetic code, a premature end of the data or of the file, an
// inconsistent progressive sequence. So a cut-short file is an error message, not a texture half
// grey (stb_image fills it in silently). Warnings that lose nothing (extra bytes before a marker,
// an unknown JFIF or Adobe version, a bad ICC profile) pass.
//
// The library is optional: CMake defines RTWEEKEND_HAVE_LIBJPEG=1 on the rtweekend target when it
// finds it, and every JPEG texture is checked here (detail::stb_input_problem, rtw_stb_image.h).
// Without that define this header declares nothing, and stb_image alone reads JPEG files, so the
// headers can be used with nothing but stb_image, as the book's are.
//
// The caller checks the file's headers first (image_header.h, input_limits.h), so this check is
// given only files whose size, as stb_image reads it, is within the limits and the file's length
// (a bit per 8x8 block), with at most max_jpeg_scans scans. The two libraries walk the markers
// their own ways, and a damaged file can show them different frames (the fuzzing found one: an
// APP0 segment of length 0, where stb_image stops and libjpeg walks on, to a frame header of
// 16724x18756 pixels no check had seen, for whose coefficients it asked 600 MB). So the caller
// asks only about files whose headers stb_image reads, and libjpeg must find the frame stb_image
// found, width x height, or the file is refused before libjpeg allocates for it: then what it
// checks is what stb_image decodes, and its memory (two bytes a sample) is bounded by the checks.

#include "image_header.h"
#include "text_lines.h"

#include <string>

#if defined(RTWEEKEND_HAVE_LIBJPEG) && RTWEEKEND_HAVE_LIBJPEG
#include <csetjmp>
#include <cstddef>
#include <cstdio> // jpeglib.h uses FILE and size_t without declaring them
#include <cstring>

#include <jpeglib.h>
// after jpeglib.h, whose types its macros use
#include <jerror.h>
#endif

namespace rt {

#if defined(RTWEEKEND_HAVE_LIBJPEG) && RTWEEKEND_HAVE_LIBJPEG
namespace detail {

// libjpeg reports errors by calling error_exit, which must not return: it jumps back into
// jpeg_data_problem (setjmp/longjmp, as libjpeg's own example program does). `manager` comes
// first so that the jpeg_error_mgr* libjpeg hands back is this struct's address.
struct jpeg_error_escape {
    jpeg_error_mgr manager;
    std::jmp_buf back;
    char message[JMSG_LENGTH_MAX];
};

inline void jpeg_escape(j_common_ptr cinfo) {
    auto* escape = reinterpret_cast<jpeg_error_escape*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, escape->message);
    std::longjmp(escape->back, 1);
}

// A warning (level -1) that means lost pixels is an error; other warnings and the trace messages
// (levels 0 and up) are dropped, so libjpeg prints nothing.
inline void jpeg_on_message(j_common_ptr cinfo, int level) {
    if (level >= 0) return;
    switch (cinfo->err->msg_code) {
    case JWRN_ARITH_BAD_CODE:
    case JWRN_BOGUS_PROGRESSION:
    case JWRN_HIT_MARKER:
    case JWRN_HUFF_BAD_CODE:
    case JWRN_JPEG_EOF:
    case JWRN_MUST_RESYNC:
    case JWRN_NOT_SEQUENTIAL: jpeg_escape(cinfo); break;
    default: break;
    }
}

// Owns the decompressor: destroyed on every way out, an error's jump included (jpeg_destroy on a
// zeroed, never-created struct does nothing).
struct jpeg_decompressor {
    jpeg_decompress_struct cinfo;
    jpeg_error_escape escape;
    jpeg_decompressor() {
        std::memset(&cinfo, 0, sizeof cinfo);
        std::memset(&escape, 0, sizeof escape);
    }
    ~jpeg_decompressor() { jpeg_destroy_decompress(&cinfo); }
    jpeg_decompressor(const jpeg_decompressor&) = delete;
    jpeg_decompressor& operator=(const jpeg_decompressor&) = delete;
};

// After setjmp, nothing with a destructor is created here: a jump back must not skip one (C++17
// [csetjmp.syn]).
inline std::string jpeg_data_problem(const std::string& bytes, int width, int height) {
    // libjpeg wants 0xff 0xd8 first; stb_image, and so image_header.h, allow more 0xff before it.
    const size_t after_soi = jpeg_after_soi(bytes);
    if (after_soi == 0) return "not a JPEG file (no SOI marker)";
    const size_t start = after_soi - 2;
    jpeg_decompressor d;
    d.cinfo.err = jpeg_std_error(&d.escape.manager);
    d.escape.manager.error_exit = jpeg_escape;
    d.escape.manager.emit_message = jpeg_on_message;
    if (setjmp(d.escape.back)) return "JPEG data refused by libjpeg-turbo: " + one_line(d.escape.message);
    jpeg_create_decompress(&d.cinfo);
    jpeg_mem_src(&d.cinfo, reinterpret_cast<const unsigned char*>(bytes.data()) + start,
                 static_cast<unsigned long>(bytes.size() - start));
    jpeg_read_header(&d.cinfo, TRUE);
    if (d.cinfo.image_width != JDIMENSION(width) || d.cinfo.image_height != JDIMENSION(height))
        return "JPEG frame is " + std::to_string(d.cinfo.image_width) + "x" + std::to_string(d.cinfo.image_height) +
               " pixels to libjpeg-turbo but " + std::to_string(width) + "x" + std::to_string(height) +
               " to stb_image: the file's markers are damaged";
    jpeg_read_coefficients(&d.cinfo); // every scan, to the end of the image
    jpeg_finish_decompress(&d.cinfo);
    return {};
}

} // namespace detail
#endif

} // namespace rt
