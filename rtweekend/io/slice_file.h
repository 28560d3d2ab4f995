#pragma once
// Sample slices: a render of samples [A, B) of every pixel, kept exactly, so that slices rendered
// anywhere (other machines, other days) merge into the image the whole render would have made,
// bit for bit (render/fixed_point.h: the sums are integers, and integer addition does not care in
// which order or grouping the slices come).
//
//   render scene.txt --spp 64 --samples 0:32 -o a.pfm      (apps/render.cpp)
//   render scene.txt --spp 64 --samples 32:64 -o b.pfm
//   merge a.pfm b.pfm -o scene.png                         (apps/merge.cpp: the bytes of
//                                                           `render scene.txt --spp 64 -o scene.png`)
//
// In code: sample_slice s = read_slice(path); slice_merger m; m.add(std::move(s), path); ...
// merged_render r = m.result(false); write_image(out, mean_image(r.sums)).
//
// The file is a valid PFM of the slice's own mean (any viewer shows it; read_image reads it as
// that image), followed by a trailer that PFM readers do not read:
//
//   PF\n<w> <h>\n-1.0\n<raster: float RGB, little-endian, rows bottom to top>
//   \nrtweekend-slice 1\n                  the magic line (image_read.h: slice_trailer_magic) and version
//   width <w>\nheight <h>\n                 the same as the PFM header's
//   samples_per_pixel <n>\n                 the whole render's spp (the sampler's plan depends on it)
//   first_sample <a>\nend_sample <b>\n      this slice: samples [a, b) of every pixel, 0 <= a < b <= n
//   seed <s>\nsampler <name>\n
//   settings <text>\n                       the other settings that decide a sample (e.g. "max_depth 4,
//                                           estimator nee"), compared as text
//   scene <16 hex digits>\n                 scene_fingerprint() of the files the scene was read from
//   rays <r>\nnonfinite <n>\nsaturated <n>\n  the slice's statistics
//   sums <bytes>\n<bytes>                   w * h * 3 int64 sums, little-endian, rows top to bottom,
//                                           RGB, in units of 2^-32 (fixed_point.h)
//   \nchecksum <16 hex digits>\n            FNV-1a (64 bit) of every byte of the file before this line
//
// Reading refuses, with one line naming the file: a file that is not a PFM with this trailer, a
// version it does not know, a field missing, out of order or malformed, sizes that disagree with
// the header, a sums block of the wrong length, a checksum that does not match (truncated or
// damaged files), and sums beyond what (b - a) samples can add up to. Merging refuses slices of
// different renders (size, spp, seed, sampler, settings or scene: the message names the field and
// both files), overlapping ranges (both files named), and gaps in [0, spp) unless asked to allow
// them, when each pixel is the mean of the samples the slices hold (a render of fewer samples,
// not the whole render).

#include "../render/fixed_point.h"
#include "../image/image.h"
#include "../core/scene_error.h"
#include "../core/file.h"
#include "../image/image_read.h"
#include "../image/image_write.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace rt {

// What a slice belongs to: two slices merge only when all of this is equal.
struct slice_render {
    int width = 0, height = 0;
    int samples_per_pixel = 0; // the whole render's
    uint64_t seed = 0;
    std::string sampler;  // sampler_name()
    std::string settings; // every other setting that decides a sample's value, as text (one line)
    std::string scene;    // scene_fingerprint() of the scene's files
};

struct sample_slice {
    slice_render render;
    int first_sample = 0, end_sample = 0; // samples [first, end) of every pixel
    uint64_t rays = 0, nonfinite = 0, saturated = 0;
    std::vector<int64_t> sums; // width * height * 3, rows top to bottom (fixed_point.h)
};

// The file's bytes: the PFM of the slice's mean, then the trailer. Throws scene_error for a slice
// that is not consistent (sizes, range, a line break in a text field).
std::string encode_slice(const sample_slice& slice);
// The slice a file holds; `name` goes in messages. Throws scene_error (one line).
sample_slice decode_slice(const std::string& bytes, const std::string& name);
sample_slice read_slice(const std::string& path);
void write_slice(const std::string& path, const sample_slice& slice); // atomically

// FNV-1a, 64 bit: a checksum and fingerprint (not a cryptographic hash: it detects damage and
// mix-ups, not forgery).
uint64_t fnv1a64(const char* data, size_t size, uint64_t hash = 0xcbf29ce484222325ULL);
std::string hex64(uint64_t v);

// 16 hex digits identifying the contents of `files` (each read whole, up to the input limit), in
// order: the same scene read on another machine, from another path, gives the same fingerprint.
std::string scene_fingerprint(const std::vector<std::string>& files);

// The sums of a set of slices of one render, and what they cover.
struct merged_render {
    slice_render render;
    pixel_sums sums;                          // counts: the samples each pixel holds
    std::vector<std::pair<int, int>> gaps;    // sample ranges [a, b) no slice holds
    uint64_t rays = 0, nonfinite = 0, saturated = 0;
    int slices = 0;
};

// Adds slices one at a time (a file's sums can be dropped once added, so a merge of many large
// slices needs the memory of two).
class slice_merger {
  public:
    // Throws scene_error if `slice` belongs to another render than the slices before it, or
    // overlaps one of them; `name` (its file) goes in messages.
    void add(const sample_slice& slice, const std::string& name);
    // The merged sums. Throws scene_error when no slice was added, or when [0, spp) has gaps and
    // allow_gaps is false.
    merged_render result(bool allow_gaps) const;

  private:
    struct range {
        int first, end;
        std::string name;
    };
    merged_render merged_;
    std::vector<range> ranges_;
    std::string first_name_;
};

// --- IMPLEMENTATION -----------------------------------------------------------------------------

inline uint64_t fnv1a64(const char* data, size_t size, uint64_t hash) {
    for (size_t i = 0; i < size; ++i) {
        hash ^= static_cast<unsigned char>(data[i]);
        hash *= 0x100000001b3ULL;
    }
    return hash;
}

inline std::string hex64(uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

inline std::string scene_fingerprint(const std::vector<std::string>& files) {
    uint64_t hash = fnv1a64(nullptr, 0);
    for (const std::string& path : files) {
        const std::string bytes = read_file(path, "scene file");
        // The length first, so that moving bytes from one file to the next changes the hash.
        const std::string length = std::to_string(bytes.size()) + ":";
        hash = fnv1a64(length.data(), length.size(), hash);
        hash = fnv1a64(bytes.data(), bytes.size(), hash);
    }
    return hex64(hash);
}

namespace detail {

inline constexpr int slice_version = 1;

// Whether a text field is printable: no control characters (line breaks, carriage returns, NUL,
// ...), which the writer refuses and the reader refuses in turn.
inline bool slice_text_printable(const std::string& value) {
    for (char c : value) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f) return false;
    }
    return true;
}

// A text field must stay on its line, and print as it is in messages.
inline void check_slice_text(const std::string& field, const std::string& value) {
    if (!slice_text_printable(value))
        throw scene_error("slice " + field + " '" + token_text(value) + "' must be printable text on one line");
}

// Reads the trailer's "key value\n" lines in their fixed order.
struct slice_reader {
    const std::string& bytes;
    const std::string& name;
    size_t pos;

    [[noreturn]] void fail(const std::string& problem) const {
        throw scene_error("cannot read slice '" + name + "': " + problem);
    }

    // The value of the next line, which must be `key value`.
    std::string field(const char* key) {
        const size_t key_size = std::strlen(key);
        if (bytes.compare(pos, key_size, key) != 0 || pos + key_size >= bytes.size() || bytes[pos + key_size] != ' ')
            fail(std::string("the trailer has no '") + key + "' line where it belongs (truncated or damaged)");
        const size_t start = pos + key_size + 1;
        const size_t end = bytes.find('\n', start);
        if (end == std::string::npos) fail(std::string("the '") + key + "' line is cut short (truncated file)");
        // A field of a few numbers or words: a line longer than this is garbage.
        if (end - start > 4096) fail(std::string("the '") + key + "' line is too long");
        pos = end + 1;
        std::string value = bytes.substr(start, end - start);
        if (!slice_text_printable(value))
            fail(std::string("the '") + key + "' line holds a control character ('" + token_text(value) + "')");
        return value;
    }

    uint64_t number(const char* key, uint64_t max) {
        const std::string text = field(key);
        uint64_t v = 0;
        if (text.empty() || text.size() > 20) fail(std::string(key) + " '" + token_text(text) + "' is not a number");
        for (char c : text) {
            if (c < '0' || c > '9') fail(std::string(key) + " '" + token_text(text) + "' is not a number");
            const uint64_t digit = uint64_t(c - '0');
            if (v > (max - digit) / 10) fail(std::string(key) + " " + text + " is larger than " + std::to_string(max));
            v = v * 10 + digit;
        }
        return v;
    }
};

inline std::string slice_range_text(int first, int end) {
    return "samples " + std::to_string(first) + " to " + std::to_string(end - 1);
}

} // namespace detail

inline std::string encode_slice(const sample_slice& s) {
    const slice_render& r = s.render;
    if (r.width < 1 || r.height < 1) throw scene_error("slice has no pixels");
    check_render_size(uint64_t(r.width), uint64_t(r.height), "slice");
    if (!(0 <= s.first_sample && s.first_sample < s.end_sample && s.end_sample <= r.samples_per_pixel))
        throw scene_error("slice range [" + std::to_string(s.first_sample) + ", " + std::to_string(s.end_sample) +
                          ") is not a non-empty part of [0, " + std::to_string(r.samples_per_pixel) + ")");
    const size_t pixels = size_t(r.width) * size_t(r.height);
    if (s.sums.size() != pixels * 3) throw scene_error("slice sums do not match its size");
    detail::check_slice_text("sampler", r.sampler);
    detail::check_slice_text("settings", r.settings);
    detail::check_slice_text("scene", r.scene);

    // The PFM part: the slice's own mean, so that the file is an image of the slice.
    pixel_sums own(r.width, r.height);
    own.rgb = s.sums;
    std::fill(own.counts.begin(), own.counts.end(), s.end_sample - s.first_sample);
    std::string out = encode_pfm(mean_image(own));

    out += slice_trailer_magic;
    out += std::to_string(detail::slice_version) + "\n";
    auto line = [&](const char* key, const std::string& value) { out += std::string(key) + " " + value + "\n"; };
    line("width", std::to_string(r.width));
    line("height", std::to_string(r.height));
    line("samples_per_pixel", std::to_string(r.samples_per_pixel));
    line("first_sample", std::to_string(s.first_sample));
    line("end_sample", std::to_string(s.end_sample));
    line("seed", std::to_string(r.seed));
    line("sampler", r.sampler);
    line("settings", r.settings);
    line("scene", r.scene);
    line("rays", std::to_string(s.rays));
    line("nonfinite", std::to_string(s.nonfinite));
    line("saturated", std::to_string(s.saturated));
    line("sums", std::to_string(s.sums.size() * 8));
    const size_t at = out.size();
    out.resize(at + s.sums.size() * 8);
    for (size_t i = 0; i < s.sums.size(); ++i) {
        const uint64_t v = static_cast<uint64_t>(s.sums[i]);
        for (int b = 0; b < 8; ++b) out[at + i * 8 + size_t(b)] = static_cast<char>((v >> (8 * b)) & 0xff);
    }
    const uint64_t checksum = fnv1a64(out.data(), out.size());
    out += "\nchecksum " + hex64(checksum) + "\n";
    return out;
}

inline sample_slice decode_slice(const std::string& bytes, const std::string& name) {
    if (bytes.size() < 2 || bytes.compare(0, 2, "PF") != 0)
        throw scene_error("cannot read slice '" + name + "': not a slice file (a slice is a PFM file, 'PF', with a trailer)");
    // The PFM part: its header checked, truncation and sizes refused, as for any PFM.
    const detail::pfm_layout layout = detail::read_pfm_layout(bytes, name);
    detail::slice_reader in{bytes, name, layout.raster_end};
    const std::string magic = slice_trailer_magic;
    if (bytes.compare(in.pos, magic.size(), magic) != 0)
        in.fail("a PFM image without a slice trailer (written by render without --samples?)");
    in.pos += magic.size();
    const size_t version_end = bytes.find('\n', in.pos);
    if (version_end == std::string::npos || version_end - in.pos > 16) in.fail("the magic line is cut short");
    const std::string version = bytes.substr(in.pos, version_end - in.pos);
    if (version != std::to_string(detail::slice_version))
        in.fail("slice format version '" + token_text(version) + "' is not supported (this program reads version " +
                std::to_string(detail::slice_version) + ")");
    in.pos = version_end + 1;

    // The checksum line ends the file: find it first, so that a damaged file fails with that.
    const std::string tail = "\nchecksum ";
    const size_t tail_size = tail.size() + 16 + 1;
    if (bytes.size() < in.pos + tail_size || bytes.compare(bytes.size() - tail_size, tail.size(), tail) != 0 ||
        bytes.back() != '\n')
        in.fail("the file does not end with its checksum line (truncated?)");
    const size_t checksum_at = bytes.size() - tail_size;
    const std::string stored = bytes.substr(checksum_at + tail.size(), 16);
    if (stored != hex64(fnv1a64(bytes.data(), checksum_at)))
        in.fail("checksum mismatch: the file is damaged (stored " + token_text(stored) + ", computed " +
                hex64(fnv1a64(bytes.data(), checksum_at)) + ")");

    sample_slice s;
    slice_render& r = s.render;
    const uint64_t w = in.number("width", max_image_side), h = in.number("height", max_image_side);
    if (w != layout.width || h != layout.height)
        in.fail("the trailer says " + std::to_string(w) + "x" + std::to_string(h) + ", the PFM header " +
                std::to_string(layout.width) + "x" + std::to_string(layout.height));
    if (w * h > max_render_pixels)
        in.fail("it is " + std::to_string(w) + "x" + std::to_string(h) + " pixels, more than the limit of " +
                std::to_string(max_render_pixels) + " (2^26) pixels for a render");
    if (layout.channels != 3) in.fail("a slice's PFM holds colour ('PF'), not grey");
    r.width = int(w);
    r.height = int(h);
    r.samples_per_pixel = int(in.number("samples_per_pixel", uint64_t(INT32_MAX)));
    s.first_sample = int(in.number("first_sample", uint64_t(INT32_MAX)));
    s.end_sample = int(in.number("end_sample", uint64_t(INT32_MAX)));
    if (!(s.first_sample < s.end_sample && s.end_sample <= r.samples_per_pixel))
        in.fail("its range [" + std::to_string(s.first_sample) + ", " + std::to_string(s.end_sample) +
                ") is not a non-empty part of [0, " + std::to_string(r.samples_per_pixel) + ")");
    r.seed = in.number("seed", UINT64_MAX);
    r.sampler = in.field("sampler");
    r.settings = in.field("settings");
    r.scene = in.field("scene");
    s.rays = in.number("rays", UINT64_MAX);
    s.nonfinite = in.number("nonfinite", UINT64_MAX);
    s.saturated = in.number("saturated", UINT64_MAX);
    const uint64_t pixels = w * h;
    const uint64_t sum_bytes = in.number("sums", UINT64_MAX);
    if (sum_bytes != pixels * 24)
        in.fail("its sums hold " + std::to_string(sum_bytes) + " bytes, a " + std::to_string(w) + "x" +
                std::to_string(h) + " slice has " + std::to_string(pixels * 24));
    if (checksum_at - in.pos != sum_bytes)
        in.fail("its sums are " + std::to_string(checksum_at - in.pos) + " bytes long, not " + std::to_string(sum_bytes));

    // Every sum within what (end - first) samples can add up to: a merge of slices of one render
    // then cannot overflow (fixed_point.h).
    const int64_t bound = sample_limit(r.samples_per_pixel) * int64_t(s.end_sample - s.first_sample);
    s.sums.resize(size_t(pixels) * 3);
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + in.pos);
    for (size_t i = 0; i < s.sums.size(); ++i) {
        uint64_t v = 0;
        for (int k = 7; k >= 0; --k) v = (v << 8) | b[i * 8 + size_t(k)];
        const int64_t x = static_cast<int64_t>(v);
        if (x > bound || x < -bound)
            in.fail("sum " + std::to_string(i) + " is beyond what " + std::to_string(s.end_sample - s.first_sample) +
                    " samples can add up to");
        s.sums[i] = x;
    }

    // The PFM part is the slice's own mean, as the writer makes it: an image edited after the
    // checksum was recomputed would be merged from the sums and shown by compare from the image.
    pixel_sums own(r.width, r.height);
    own.rgb = s.sums;
    std::fill(own.counts.begin(), own.counts.end(), s.end_sample - s.first_sample);
    const image expected = mean_image(own);
    const image stored_image = detail::decode_pfm(bytes.substr(0, layout.raster_end), name).pixels;
    if (stored_image.data().size() != expected.data().size() ||
        std::memcmp(stored_image.data().data(), expected.data().data(), expected.data().size() * sizeof(float)) != 0)
        in.fail("its image is not the mean of its sums (the file was edited)");
    return s;
}

inline sample_slice read_slice(const std::string& path) { return decode_slice(read_file(path, "slice file"), path); }

inline void write_slice(const std::string& path, const sample_slice& slice) {
    write_file_atomically(path, encode_slice(slice));
}

inline void slice_merger::add(const sample_slice& s, const std::string& name) {
    const slice_render& r = s.render;
    if (merged_.slices == 0) {
        merged_.render = r;
        merged_.sums = pixel_sums(r.width, r.height);
        first_name_ = name;
    } else {
        const slice_render& m = merged_.render;
        auto differ = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
            throw scene_error("'" + name + "' is a slice of another render than '" + first_name_ + "': " + what + " " +
                              mine + " against " + theirs);
        };
        if (r.width != m.width || r.height != m.height)
            differ("size", std::to_string(r.width) + "x" + std::to_string(r.height),
                   std::to_string(m.width) + "x" + std::to_string(m.height));
        if (r.samples_per_pixel != m.samples_per_pixel)
            differ("samples per pixel", std::to_string(r.samples_per_pixel), std::to_string(m.samples_per_pixel));
        if (r.seed != m.seed) differ("seed", std::to_string(r.seed), std::to_string(m.seed));
        if (r.sampler != m.sampler) differ("sampler", r.sampler, m.sampler);
        if (r.settings != m.settings) differ("settings", "'" + r.settings + "'", "'" + m.settings + "'");
        if (r.scene != m.scene) differ("scene (its files' contents)", r.scene, m.scene);
    }
    for (const range& other : ranges_)
        if (s.first_sample < other.end && other.first < s.end_sample)
            throw scene_error("'" + name + "' (" + detail::slice_range_text(s.first_sample, s.end_sample) + ") and '" +
                              other.name + "' (" + detail::slice_range_text(other.first, other.end) +
                              ") overlap: a sample would be counted twice");
    if (s.sums.size() != merged_.sums.rgb.size()) throw scene_error("'" + name + "': its sums do not match its size");
    for (size_t i = 0; i < s.sums.size(); ++i)
        if (!add_fixed(merged_.sums.rgb[i], s.sums[i], merged_.sums.rgb[i]))
            throw scene_error("'" + name + "': sum " + std::to_string(i) + " overflows (a damaged slice)");
    for (int32_t& n : merged_.sums.counts) n += s.end_sample - s.first_sample;
    ranges_.push_back({s.first_sample, s.end_sample, name});
    merged_.rays += s.rays;
    merged_.nonfinite += s.nonfinite;
    merged_.saturated += s.saturated;
    ++merged_.slices;
}

inline merged_render slice_merger::result(bool allow_gaps) const {
    if (merged_.slices == 0) throw scene_error("no slices to merge");
    merged_render out = merged_;
    std::vector<range> sorted = ranges_;
    std::sort(sorted.begin(), sorted.end(), [](const range& a, const range& b) { return a.first < b.first; });
    int covered = 0;
    for (const range& r : sorted) {
        if (r.first > covered) out.gaps.push_back({covered, r.first});
        covered = r.end;
    }
    if (covered < out.render.samples_per_pixel) out.gaps.push_back({covered, out.render.samples_per_pixel});
    if (!out.gaps.empty() && !allow_gaps) {
        std::string missing;
        for (const auto& g : out.gaps)
            missing += (missing.empty() ? "" : ", ") + detail::slice_range_text(g.first, g.second);
        throw scene_error("the slices do not cover the render's " + std::to_string(out.render.samples_per_pixel) +
                          " samples per pixel: " + missing +
                          " are missing (add their slices, or --allow-gaps for the mean of the samples there are)");
    }
    return out;
}

} // namespace rt
