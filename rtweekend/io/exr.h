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
//   decode_exr(bytes, name)        the linear RGB pixels of an EXR file's first part, as float:
//                                  R, G and B channels of any pixel type (half, float, uint), or a
//                                  lone Y channel (luminance) copied to all three. Other channels
//                                  (alpha, depth, ...) are ignored. The image is the data window,
//                                  whatever its origin.
//
// Why OpenEXR and not tinyexr: it is the reference implementation, maintained by the Academy
// Software Foundation, fuzzed continuously (OSS-Fuzz), and Debian ships it with a CMake config
// (OpenEXR::OpenEXR). Its C API (OpenEXRCore) reads a header with per-file size limits and
// without allocating for the pixels, so a claimed size beyond max_image_pixels is refused before
// anything is allocated for it; its C++ API then decodes every pixel type, compression and tiled
// layout into float.
//
// The library is optional: CMake defines RTWEEKEND_HAVE_OPENEXR=1 on the rtweekend target when it
// finds it. Without that define this header still compiles, and both functions throw
// scene_error("... EXR support was not built: install libopenexr-dev ..."), so programs that never
// see an EXR file need nothing more.
//
// Errors are scene_error: "cannot write 'NAME': ..." and "cannot read 'NAME': EXR ...".

#include "../engine/image.h"
#include "../scene_error.h"
#include "input_limits.h"

#include <string>

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/openexr.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#endif

namespace rt {

#if defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR
inline constexpr bool exr_supported = true;
#else
inline constexpr bool exr_supported = false;
#endif

inline const char* exr_not_built_text() {
    return "EXR support was not built: install libopenexr-dev and reconfigure with CMake";
}

std::string encode_exr(const image& img, const std::string& name);
image decode_exr(const std::string& bytes, const std::string& name);

// --- IMPLEMENTATION -----------------------------------------------------------------------------

#if !(defined(RTWEEKEND_HAVE_OPENEXR) && RTWEEKEND_HAVE_OPENEXR)

inline std::string encode_exr(const image&, const std::string& name) {
    throw scene_error("cannot write '" + name + "': " + exr_not_built_text());
}

inline image decode_exr(const std::string&, const std::string& name) {
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

// OpenEXR's C++ input from bytes already in memory (read_file has applied its size limit).
class exr_string_istream final : public Imf::IStream {
public:
    exr_string_istream(const std::string& bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
    // Returns whether more data follows, as the interface asks; reading past the end throws,
    // which the library reports as a truncated file.
    bool read(char c[], int n) override {
        if (n < 0 || pos_ > bytes_.size() || size_t(n) > bytes_.size() - pos_)
            throw std::runtime_error("file ends early (it is truncated)");
        std::memcpy(c, bytes_.data() + pos_, size_t(n));
        pos_ += size_t(n);
        return pos_ < bytes_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override { pos_ = pos; }

private:
    const std::string& bytes_;
    uint64_t pos_ = 0;
};

// What the header check of OpenEXRCore reads from: the bytes, and the library's last message.
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

// What the header check found: the data window and whether the file has R, G, B or only Y.
struct exr_layout {
    int min_x = 0, min_y = 0, width = 0, height = 0;
    bool grey = false;
};

// Reads the header of the first part with OpenEXRCore, which allocates only for the header, and
// checks what decode_exr will need before the C++ library allocates anything for the pixels.
inline exr_layout check_exr_header(const std::string& bytes, const std::string& name) {
    auto fail = [&](const std::string& problem) -> void { throw scene_error("cannot read '" + name + "': EXR " + problem); };
    exr_core_source source{bytes, {}};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &source;
    init.read_fn = exr_core_read;
    init.size_fn = exr_core_size;
    init.error_handler_fn = exr_core_error;
    // Per-file limits (not the library's global defaults, which other code may own). The sides
    // are limited here, their product below.
    init.max_image_width = int(max_image_side);
    init.max_image_height = int(max_image_side);
    init.max_tile_width = int(max_image_side);
    init.max_tile_height = int(max_image_side);

    exr_context_t ctxt = nullptr;
    exr_result_t rv = exr_start_read(&ctxt, name.c_str(), &init);
    // The context is closed on every path out, error or not.
    struct closer {
        exr_context_t& c;
        ~closer() {
            if (c) exr_finish(&c);
        }
    } close_context{ctxt};
    auto check = [&](exr_result_t r, const char* what) {
        if (r != EXR_ERR_SUCCESS)
            fail(std::string(what) + ": " + exr_one_line(source.message.empty() ? exr_get_error_code_as_string(r) : source.message));
    };
    check(rv, "header cannot be read");

    exr_storage_t storage{};
    check(exr_get_storage(ctxt, 0, &storage), "header has no storage type");
    if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
        fail("file holds deep data (several samples a pixel), which cannot be read as an image");

    exr_attr_box2i_t dw{};
    check(exr_get_data_window(ctxt, 0, &dw), "header has no data window");
    // 64-bit arithmetic: a hostile window's corners can be anywhere in int32.
    const int64_t w = int64_t(dw.max.x) - int64_t(dw.min.x) + 1, h = int64_t(dw.max.y) - int64_t(dw.min.y) + 1;
    if (w <= 0 || h <= 0)
        fail("data window " + std::to_string(dw.min.x) + "," + std::to_string(dw.min.y) + " .. " + std::to_string(dw.max.x) +
             "," + std::to_string(dw.max.y) + " is empty");
    try {
        check_image_size(uint64_t(w), uint64_t(h), "EXR image");
    } catch (const scene_error& e) {
        throw scene_error("cannot read '" + name + "': " + e.what());
    }

    const exr_attr_chlist_t* channels = nullptr;
    check(exr_get_channels(ctxt, 0, &channels), "header has no channel list");
    bool r = false, g = false, b = false, y = false;
    for (int i = 0; channels && i < channels->num_channels; ++i) {
        const exr_attr_chlist_entry_t& c = channels->entries[i];
        const std::string channel(c.name.str ? c.name.str : "", c.name.str ? size_t(c.name.length) : 0);
        const bool wanted = channel == "R" || channel == "G" || channel == "B" || channel == "Y";
        if (wanted && (c.x_sampling != 1 || c.y_sampling != 1))
            fail("channel " + channel + " is subsampled, which is not supported");
        r |= channel == "R", g |= channel == "G", b |= channel == "B", y |= channel == "Y";
    }
    if (!(r && g && b) && !y) fail("file has neither R, G and B channels nor a Y (luminance) channel");
    return {dw.min.x, dw.min.y, int(w), int(h), !(r && g && b)};
}

} // namespace detail

inline std::string encode_exr(const image& img, const std::string& name) {
    if (img.empty()) throw scene_error("cannot write '" + name + "': the image is empty");
    try {
        Imf::Header header(img.width(), img.height(), 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                           Imf::ZIP_COMPRESSION);
        for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        detail::exr_string_ostream out(name);
        {
            Imf::OutputFile file(out, header);
        // The framebuffer is interleaved RGB floats, rows top to bottom: EXR's y grows downwards
        // too, so the slices point straight at it.
            // (The library only reads through this pointer; Slice takes it non-const.)
            auto* base = const_cast<char*>(reinterpret_cast<const char*>(img.data().data()));
            const size_t x_stride = 3 * sizeof(float), y_stride = x_stride * size_t(img.width());
            Imf::FrameBuffer fb;
            fb.insert("R", Imf::Slice(Imf::FLOAT, base, x_stride, y_stride));
            fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), x_stride, y_stride));
            fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), x_stride, y_stride));
            file.setFrameBuffer(fb);
            file.writePixels(img.height());
        } // the file's destructor writes the table of chunk offsets, so the bytes are complete after it
        return std::move(out.bytes());
    } catch (const scene_error&) {
        throw;
    } catch (const std::exception& e) {
        throw scene_error("cannot write '" + name + "': EXR " + detail::exr_one_line(e.what()));
    }
}

inline image decode_exr(const std::string& bytes, const std::string& name) {
    const detail::exr_layout layout = detail::check_exr_header(bytes, name);
    image out(layout.width, layout.height);
    try {
        detail::exr_string_istream in(bytes, name);
        Imf::InputFile file(in);
        const Imath::Box2i dw = file.header().dataWindow();
        // The C++ library read the same header; a mismatch would mean a different part or a bug.
        if (dw.min.x != layout.min_x || dw.min.y != layout.min_y || dw.max.x - dw.min.x + 1 != layout.width ||
            dw.max.y - dw.min.y + 1 != layout.height)
            throw scene_error("cannot read '" + name + "': EXR headers disagree about the data window");
        char* base = reinterpret_cast<char*>(out.data().data());
        const size_t x_stride = 3 * sizeof(float), y_stride = x_stride * size_t(layout.width);
        Imf::FrameBuffer fb;
        // Slice::Make offsets the pointer by the window's origin, so pixel (min.x, min.y) lands at
        // the image's first pixel.
        if (layout.grey) {
            fb.insert("Y", Imf::Slice::Make(Imf::FLOAT, base, dw, x_stride, y_stride));
        } else {
            fb.insert("R", Imf::Slice::Make(Imf::FLOAT, base, dw, x_stride, y_stride));
            fb.insert("G", Imf::Slice::Make(Imf::FLOAT, base + sizeof(float), dw, x_stride, y_stride));
            fb.insert("B", Imf::Slice::Make(Imf::FLOAT, base + 2 * sizeof(float), dw, x_stride, y_stride));
        }
        file.setFrameBuffer(fb);
        // A file cut short, or with damaged chunks, throws here rather than leaving black rows.
        file.readPixels(dw.min.y, dw.max.y);
    } catch (const scene_error&) {
        throw;
    } catch (const std::exception& e) {
        throw scene_error("cannot read '" + name + "': EXR " + detail::exr_one_line(e.what()));
    }
    if (layout.grey) {
        float* p = out.data().data();
        for (size_t i = 0; i < out.data().size(); i += 3) p[i + 1] = p[i + 2] = p[i];
    }
    return out;
}

#endif

} // namespace rt
