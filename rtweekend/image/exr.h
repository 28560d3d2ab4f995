#pragma once
// exr: OpenEXR images in and out, through the OpenEXR library (Debian's libopenexr-dev).
//
//   exr_supported                  whether this build has the library (see below)
//   encode_exr(img, name)          the bytes of an EXR file holding `img`: one scanline part, 32-bit
//                                  float R, G, B channels, ZIP compression (lossless), data and
//                                  display window 0,0 .. w-1,h-1. Float rather than half because
//                                  the framebuffer is float: a file read back equals the image
//                                  bit for bit, which a reference image for error metrics needs
//                                  (half would round every value to 11 bits and clip above 65504)
//   encode_exr(channels, name)     the same with any channels of several images of one size: each
//                                  exr_channels names the channels of one image (its first one to
//                                  three), as "albedo.R", "N.X", "Z" (render --aov writes the
//                                  denoiser guides so, beside R, G, B)
//   decode_exr(bytes, name)        the linear RGB pixels of an EXR file's first part, as float:
//                                  R, G and B channels of any pixel type (half, float, uint), or a
//                                  lone Y channel (luminance) copied to all three. Subsampled
//                                  channels (luminance/chroma images) are refused. Other channels
//                                  (alpha, depth, ...) are ignored. The image is the data window,
//                                  whatever its origin.
//
// Why OpenEXR and not tinyexr: it is the reference implementation, maintained by the Academy
// Software Foundation, fuzzed continuously (OSS-Fuzz), and Debian ships it with a CMake config
// (OpenEXR::OpenEXR). Files are read by its C API, OpenEXRCore, which reads each header attribute
// within its declared size, applies per-file size limits and allocates nothing for the pixels
// until asked: a claimed size beyond max_image_pixels is refused, and every chunk of pixel data is
// found in the file and its unpacked size checked against the best ratio of its compression,
// before the image is allocated; then OpenEXRCore decodes every pixel type, compression and
// scanline or tiled layout into float. (The C++ API, which writes, read headers its own way: it
// allocated an attribute's declared size, up to 2 GB, before finding the file too short.)
//
// The library is optional: CMake defines RTWEEKEND_HAVE_OPENEXR=1 on the rtweekend target when it
// finds it. Without that define this header still compiles, and both functions throw
// scene_error("... EXR support was not built: install libopenexr-dev ..."), so programs that never
// see an EXR file need nothing more.
//
// Errors are scene_error: "cannot write 'NAME': ..." and "cannot read 'NAME': EXR ...".

#include "../core/engine_linkage.h"
#include "image.h"
#include "../core/scene_error.h"
#include "../core/input_limits.h"

#include <string>
#include <vector>

namespace rt {

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
inline constexpr bool exr_supported = true;
#else
inline constexpr bool exr_supported = false;
#endif

inline const char* exr_not_built_text() {
    return "EXR support was not built: install libopenexr-dev and reconfigure with CMake";
}

RTWEEKEND_ENGINE_FUNCTION std::string encode_exr(const image& img, const std::string& name);
// Channel k of *img (k < names.size() <= 3) is written as names[k].
struct exr_channels {
    const image* img;
    std::vector<std::string> names;
};
RTWEEKEND_ENGINE_FUNCTION std::string encode_exr(const std::vector<exr_channels>& channels, const std::string& name);
RTWEEKEND_ENGINE_FUNCTION image decode_exr(const std::string& bytes, const std::string& name);

} // namespace rt

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/openexr.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <vector>
#endif

namespace rt {

#if !(defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR)

RTWEEKEND_ENGINE_FUNCTION std::string encode_exr(const image&, const std::string& name) {
    throw scene_error("cannot write '" + name + "': " + exr_not_built_text());
}
RTWEEKEND_ENGINE_FUNCTION std::string encode_exr(const std::vector<exr_channels>&, const std::string& name) {
    throw scene_error("cannot write '" + name + "': " + exr_not_built_text());
}

RTWEEKEND_ENGINE_FUNCTION image decode_exr(const std::string&, const std::string& name) {
    throw scene_error("cannot read '" + name + "': " + exr_not_built_text());
}

#else

namespace detail {

// OpenEXR's C++ output goes to a stream; this one fills a string, so that the file itself is
// written by write_file_atomically like every other format. The library seeks back to fill in
// the table of chunk offsets, hence a position rather than plain appending.
class exr_string_ostream final : public Imf::OStream {
public:
    explicit exr_string_ostream(const std::string& name) : Imf::OStream(name.c_str()) {}
    void write(const char c[], int n) override {
        const size_t end = pos_ + size_t(n);
        if (end > bytes_.size()) bytes_.resize(end);
        std::memcpy(&bytes_[pos_], c, size_t(n));
        pos_ = end;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = size_t(pos); }
    std::string& bytes() { return bytes_; }

private:
    std::string bytes_;
    size_t pos_ = 0;
};

// What OpenEXRCore reads from: the bytes, and the library's last message.
struct exr_core_source {
    const std::string& bytes;
    std::string message;
};

// The library's messages as part of one error line: a line break would split it.
inline std::string exr_one_line(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

// OpenEXRCore's read callback: pread semantics over the bytes in memory.
inline int64_t exr_core_read(exr_const_context_t, void* userdata, void* buffer, uint64_t size, uint64_t offset,
                             exr_stream_error_func_ptr_t) {
    const std::string& bytes = static_cast<exr_core_source*>(userdata)->bytes;
    if (offset >= bytes.size()) return 0;
    const uint64_t n = std::min<uint64_t>(size, bytes.size() - offset);
    std::memcpy(buffer, bytes.data() + offset, size_t(n));
    return int64_t(n);
}

// With the size known the library checks every attribute's claimed length against the file.
inline int64_t exr_core_size(exr_const_context_t, void* userdata) {
    return int64_t(static_cast<exr_core_source*>(userdata)->bytes.size());
}

// The library would print its messages to stderr; they are kept for the one error line instead.
inline void exr_core_error(exr_const_context_t ctxt, exr_result_t code, const char* msg) {
    void* userdata = nullptr;
    if (exr_get_user_data(ctxt, &userdata) != EXR_ERR_SUCCESS || !userdata) return;
    auto* source = static_cast<exr_core_source*>(userdata);
    if (source->message.empty()) source->message = msg && *msg ? msg : exr_get_error_code_as_string(code);
}

// What the header check found: the data window, whether the file has R, G, B or only Y, and how
// its pixels are stored.
struct exr_layout {
    int min_x = 0, min_y = 0, width = 0, height = 0;
    bool grey = false;         // a Y channel without R, G and B
    bool tiled = false;
    exr_compression_t compression = EXR_COMPRESSION_NONE;
};

// An OpenEXRCore read context over bytes in memory, finished at scope exit. Errors throw
// "cannot read 'NAME': EXR WHAT: the library's message".
class exr_core_reader {
  public:
    exr_core_reader(const std::string& bytes, const std::string& name) : source_{bytes, {}}, name_(name) {
        exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
        init.user_data = &source_;
        init.read_fn = exr_core_read;
        init.size_fn = exr_core_size;
        init.error_handler_fn = exr_core_error;
        // Per-file limits (not the library's global defaults, which other code may own). The
        // sides are limited here, their product by check_exr_header.
        init.max_image_width = int(max_image_side);
        init.max_image_height = int(max_image_side);
        init.max_tile_width = int(max_image_side);
        init.max_tile_height = int(max_image_side);
        check(exr_start_read(&ctxt_, name.c_str(), &init), "header cannot be read");
    }
    ~exr_core_reader() {
        if (ctxt_) exr_finish(&ctxt_);
    }
    exr_core_reader(const exr_core_reader&) = delete;
    exr_core_reader& operator=(const exr_core_reader&) = delete;

    exr_context_t context() const { return ctxt_; }
    [[noreturn]] void fail(const std::string& problem) const {
        throw scene_error("cannot read '" + name_ + "': EXR " + problem);
    }
    void check(exr_result_t r, const std::string& what) {
        if (r == EXR_ERR_SUCCESS) { // the library may have reported a problem it then tolerated
            source_.message.clear();
            return;
        }
        const std::string message = source_.message.empty() ? exr_get_error_code_as_string(r) : source_.message;
        source_.message.clear();
        fail(what + ": " + exr_one_line(message));
    }

  private:
    exr_core_source source_;
    std::string name_;
    exr_context_t ctxt_ = nullptr;
};

// Reads the header of the first part and checks what decode_exr will need before anything is
// allocated for the pixels: a data window within the limits, R, G and B (or Y) channels, not
// subsampled, not deep data.
inline exr_layout check_exr_header(exr_core_reader& exr) {
    exr_context_t ctxt = exr.context();
    exr_storage_t storage{};
    exr.check(exr_get_storage(ctxt, 0, &storage), "header has no storage type");
    if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
        exr.fail("file holds deep data (several samples a pixel), which cannot be read as an image");

    exr_attr_box2i_t dw{};
    exr.check(exr_get_data_window(ctxt, 0, &dw), "header has no data window");
    // 64-bit arithmetic: a hostile window's corners can be anywhere in int32.
    const int64_t w = int64_t(dw.max.x) - int64_t(dw.min.x) + 1, h = int64_t(dw.max.y) - int64_t(dw.min.y) + 1;
    if (w <= 0 || h <= 0)
        exr.fail("data window " + std::to_string(dw.min.x) + "," + std::to_string(dw.min.y) + " .. " +
                 std::to_string(dw.max.x) + "," + std::to_string(dw.max.y) + " is empty");
    try {
        check_image_size(uint64_t(w), uint64_t(h), "EXR image");
    } catch (const scene_error& e) {
        exr.fail(std::string(e.what()).substr(4)); // "EXR image is ..." without its "EXR "
    }

    const exr_attr_chlist_t* channels = nullptr;
    exr.check(exr_get_channels(ctxt, 0, &channels), "header has no channel list");
    bool r = false, g = false, b = false, y = false;
    for (int i = 0; channels && i < channels->num_channels; ++i) {
        const exr_attr_chlist_entry_t& c = channels->entries[i];
        const std::string channel(c.name.str ? c.name.str : "", c.name.str ? size_t(c.name.length) : 0);
        // Subsampled channels (OpenEXR's luminance/chroma images: RY and BY at every second pixel
        // both ways) are refused: OpenEXRCore 3.1 decodes them into the wrong rows, and the C++
        // RgbaInputFile, which would rebuild RGB, allocates what a hostile header's attributes
        // claim before reading them (the fuzzer found 1.8 GB).
        if (c.x_sampling != 1 || c.y_sampling != 1)
            exr.fail("channel " + token_text(channel) + " is subsampled (" + std::to_string(c.x_sampling) + " x " +
                     std::to_string(c.y_sampling) +
                     "), as in luminance/chroma images, which are not supported: save the image as RGB");
        r |= channel == "R", g |= channel == "G", b |= channel == "B", y |= channel == "Y";
    }
    if (!(r && g && b) && !y) exr.fail("file has neither R, G and B channels nor a Y (luminance) channel");
    exr_layout layout{dw.min.x, dw.min.y, int(w), int(h), !(r && g && b), storage == EXR_STORAGE_TILED};
    exr.check(exr_get_compression(ctxt, 0, &layout.compression), "header has no compression");
    return layout;
}

// The most bytes one byte of a chunk can unpack to in each compression, so that a chunk whose
// header claims more is refused before anything is allocated for it: none 1; RLE 64 (a run of at
// most 128 equal bytes in 2); ZIP, ZIPS and PIZ 1032 (deflate's best ratio; PIZ's Huffman code with
// runs reaches about 410); PXR24 1376 (deflate over floats cut to 24 bits); B44 and B44A 11 (a 4x4
// block of halves, 32 bytes, in 14, or 3 when flat); DWAA and DWAB 66048 (lossy: a flat 8x8 block's
// 63 AC coefficients are one 2-byte end-of-block code, deflated). Unknown compressions: the library
// refuses them when it decodes.
inline uint64_t exr_best_ratio(exr_compression_t compression) {
    switch (compression) {
    case EXR_COMPRESSION_NONE: return 1;
    case EXR_COMPRESSION_RLE: return 64;
    case EXR_COMPRESSION_ZIPS:
    case EXR_COMPRESSION_ZIP:
    case EXR_COMPRESSION_PIZ: return 1032;
    case EXR_COMPRESSION_PXR24: return 1376;
    case EXR_COMPRESSION_B44:
    case EXR_COMPRESSION_B44A: return 11;
    default: return 66048;
    }
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION std::string encode_exr(const image& img, const std::string& name) {
    return encode_exr(std::vector<exr_channels>{{&img, {"R", "G", "B"}}}, name);
}

RTWEEKEND_ENGINE_FUNCTION std::string encode_exr(const std::vector<exr_channels>& channels, const std::string& name) {
    if (channels.empty() || !channels[0].img || channels[0].img->empty())
        throw scene_error("cannot write '" + name + "': the image is empty");
    const image& first = *channels[0].img;
    for (const exr_channels& c : channels)
        if (!c.img || c.img->width() != first.width() || c.img->height() != first.height() || c.names.empty() ||
            c.names.size() > 3)
            throw scene_error("cannot write '" + name + "': its channels' images differ in size");
    try {
        Imf::Header header(first.width(), first.height(), 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                           Imf::ZIP_COMPRESSION);
        for (const exr_channels& c : channels)
            for (const std::string& n : c.names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
        detail::exr_string_ostream out(name);
        {
            Imf::OutputFile file(out, header);
            // Each framebuffer is interleaved RGB floats, rows top to bottom: EXR's y grows
            // downwards too, so the slices point straight at it.
            // (The library only reads through this pointer; Slice takes it non-const.)
            Imf::FrameBuffer fb;
            for (const exr_channels& c : channels) {
                auto* base = const_cast<char*>(reinterpret_cast<const char*>(c.img->data().data()));
                const size_t x_stride = 3 * sizeof(float), y_stride = x_stride * size_t(c.img->width());
                for (size_t k = 0; k < c.names.size(); ++k)
                    fb.insert(c.names[k], Imf::Slice(Imf::FLOAT, base + k * sizeof(float), x_stride, y_stride));
            }
            file.setFrameBuffer(fb);
            file.writePixels(first.height());
        } // the file's destructor writes the table of chunk offsets, so the bytes are complete after it
        return std::move(out.bytes());
    } catch (const scene_error&) {
        throw;
    } catch (const std::exception& e) {
        throw scene_error("cannot write '" + name + "': EXR " + detail::exr_one_line(e.what()));
    }
}

RTWEEKEND_ENGINE_FUNCTION image decode_exr(const std::string& bytes, const std::string& name) {
    detail::exr_core_reader exr(bytes, name);
    const detail::exr_layout layout = detail::check_exr_header(exr);
    exr_context_t ctxt = exr.context();

    // Every chunk of the image (scanline blocks, or the tiles of level 0), found and checked before
    // the image is allocated: its place in the file (OpenEXRCore checks the offset table and the
    // chunk's header against the file's size) and its unpacked size against its packed size.
    int32_t chunk_count = 0;
    exr.check(exr_get_chunk_count(ctxt, 0, &chunk_count), "header gives no chunk count");
    if (chunk_count <= 0 || uint64_t(chunk_count) * 8 > bytes.size())
        exr.fail("header promises " + std::to_string(chunk_count) + " chunks of pixels, whose offsets alone need " +
                 std::to_string(uint64_t(chunk_count < 0 ? 0 : chunk_count) * 8) + " bytes; the file has " +
                 std::to_string(bytes.size()));
    std::vector<exr_chunk_info_t> chunks;
    auto add = [&](exr_result_t r, const exr_chunk_info_t& chunk) {
        exr.check(r, "chunk " + std::to_string(chunks.size()) + " cannot be read");
        const uint64_t ratio = detail::exr_best_ratio(layout.compression);
        if (chunk.unpacked_size / ratio > chunk.packed_size)
            exr.fail("chunk " + std::to_string(chunks.size()) + " holds " + std::to_string(chunk.packed_size) +
                     " bytes, which cannot unpack to the " + std::to_string(chunk.unpacked_size) +
                     " its pixels need (at most " + std::to_string(ratio) + " bytes a byte in its compression)");
        chunks.push_back(chunk);
    };
    exr_chunk_info_t chunk{};
    if (layout.tiled) {
        int32_t level_w = 0, level_h = 0, tw = 0, th = 0;
        exr.check(exr_get_level_sizes(ctxt, 0, 0, 0, &level_w, &level_h), "header gives no level size");
        exr.check(exr_get_tile_sizes(ctxt, 0, 0, 0, &tw, &th), "header gives no tile size");
        if (tw <= 0 || th <= 0 || level_w <= 0 || level_h <= 0) exr.fail("header gives an empty tile or level");
        const int32_t tiles_x = int32_t((int64_t(level_w) + tw - 1) / tw), tiles_y = int32_t((int64_t(level_h) + th - 1) / th);
        if (int64_t(tiles_x) * int64_t(tiles_y) > chunk_count)
            exr.fail("level 0 has " + std::to_string(int64_t(tiles_x) * int64_t(tiles_y)) + " tiles, more than the " +
                     std::to_string(chunk_count) + " chunks of the file");
        for (int32_t ty = 0; ty < tiles_y; ++ty)
            for (int32_t tx = 0; tx < tiles_x; ++tx) add(exr_read_tile_chunk_info(ctxt, 0, tx, ty, 0, 0, &chunk), chunk);
    } else {
        int32_t lines = 0;
        exr.check(exr_get_scanlines_per_chunk(ctxt, 0, &lines), "header gives no scanlines per chunk");
        if (lines <= 0) exr.fail("header gives " + std::to_string(lines) + " scanlines per chunk");
        for (int64_t y = layout.min_y; y < int64_t(layout.min_y) + layout.height; y += lines)
            add(exr_read_scanline_chunk_info(ctxt, 0, int(y), &chunk), chunk);
    }

    image out(layout.width, layout.height);
    // OpenEXRCore decodes each chunk into planes of float, one a channel (converting half and uint),
    // which are then copied into the image: R, G and B, or Y. Every channel gets a plane of its
    // own, the unused ones too: a channel left without a destination led the library's
    // three-channel fast path to write through a null pointer (a Y, A, Z file crashed).
    struct pipeline {
        exr_context_t ctxt;
        exr_decode_pipeline_t decode{}; // EXR_DECODE_PIPELINE_INITIALIZER, without its warning
        bool started = false;
        ~pipeline() {
            if (started) exr_decoding_destroy(ctxt, &decode);
        }
    } p{ctxt};
    float* const pixels = out.data().data();
    std::vector<float> scratch;
    int32_t tile_w = 0, tile_h = 0;
    if (layout.tiled) exr.check(exr_get_tile_sizes(ctxt, 0, 0, 0, &tile_w, &tile_h), "header gives no tile size");
    for (size_t i = 0; i < chunks.size(); ++i) {
        const exr_chunk_info_t& c = chunks[i];
        const std::string what = "chunk " + std::to_string(i) + " cannot be decoded";
        if (!p.started) {
            exr.check(exr_decoding_initialize(ctxt, 0, &c, &p.decode), what);
            p.started = true;
        } else {
            exr.check(exr_decoding_update(ctxt, 0, &c, &p.decode), what);
        }
        // The chunk's first pixel in the image: tiles are numbered, scanline chunks start at a row.
        const int64_t x0 = layout.tiled ? int64_t(c.start_x) * tile_w : 0;
        const int64_t y0 = layout.tiled ? int64_t(c.start_y) * tile_h : int64_t(c.start_y) - layout.min_y;
        if (x0 < 0 || y0 < 0 || x0 + c.width > layout.width || y0 + c.height > layout.height)
            exr.fail("chunk " + std::to_string(i) + " lies outside the data window");
        const size_t plane = size_t(c.width) * size_t(c.height);
        scratch.assign(plane * size_t(p.decode.channel_count), 0.0f);
        for (int16_t k = 0; k < p.decode.channel_count; ++k) {
            exr_coding_channel_info_t& channel = p.decode.channels[k];
            if (channel.width != c.width || channel.height != c.height) exr.fail(what);
            channel.decode_to_ptr = reinterpret_cast<uint8_t*>(scratch.data() + plane * size_t(k));
            channel.user_pixel_stride = int32_t(sizeof(float));
            channel.user_line_stride = int32_t(sizeof(float)) * c.width;
            channel.user_data_type = EXR_PIXEL_FLOAT;
            channel.user_bytes_per_element = int16_t(sizeof(float));
        }
        exr.check(exr_decoding_choose_default_routines(ctxt, 0, &p.decode), what);
        exr.check(exr_decoding_run(ctxt, 0, &p.decode), what);
        for (int16_t k = 0; k < p.decode.channel_count; ++k) {
            const std::string name = p.decode.channels[k].channel_name ? p.decode.channels[k].channel_name : "";
            int offset = name == "R" ? 0 : name == "G" ? 1 : name == "B" ? 2 : -1;
            if (layout.grey) offset = name == "Y" ? 0 : -1;
            if (offset < 0) continue; // alpha, depth, ...: read and left out
            for (int32_t yy = 0; yy < c.height; ++yy) {
                float* row = pixels + (size_t(y0 + yy) * size_t(layout.width) + size_t(x0)) * 3 + size_t(offset);
                const float* from = scratch.data() + plane * size_t(k) + size_t(yy) * size_t(c.width);
                for (int32_t xx = 0; xx < c.width; ++xx) row[3 * size_t(xx)] = from[xx];
            }
        }
    }
    if (layout.grey) {
        float* q = out.data().data();
        for (size_t i = 0; i < out.data().size(); i += 3) q[i + 1] = q[i + 2] = q[i];
    }
    return out;
}

#endif

} // namespace rt

#endif // RTWEEKEND_ENGINE_BODIES
