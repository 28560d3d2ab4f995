#pragma once
// Whole files in and out, with one error line naming the path when something goes wrong.
//
//   std::string read_file(path, what)        the file's bytes; `what` ("OBJ file") goes in messages:
//                                            "PATH: cannot open OBJ file: No such file or directory".
//                                            Only a regular file is read (a directory, a device such
//                                            as /dev/zero, a FIFO or a socket is refused before it is
//                                            opened), and only up to max_input_file_bytes: a reader
//                                            never allocates more than that for one file
//   write_file_atomically(path, contents)    writes a temporary file beside `path`, then renames it
//                                            over `path`: a reader never sees half a file
//   check_writable(path)                     throws now if write_file_atomically(path, ...) could not
//                                            succeed later (no such directory, no permission, a
//                                            directory in the way), so a long job can refuse before it
//                                            starts rather than after
//   lowercase_extension(path)                ".png" for "out/A.PNG"; "" when the name has none
//
// All throw scene_error.

#include "engine_linkage.h"
#include "scene_error.h"
#include "input_limits.h"

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>

namespace rt {

RTWEEKEND_ENGINE_FUNCTION std::string read_file(const std::string& path, const std::string& what,
                                                uint64_t max_bytes = max_input_file_bytes);
RTWEEKEND_ENGINE_FUNCTION void write_file_atomically(const std::string& path, const std::string& contents);
RTWEEKEND_ENGINE_FUNCTION void check_writable(const std::string& path);
RTWEEKEND_ENGINE_FUNCTION std::string lowercase_extension(const std::string& path);

// --- IMPLEMENTATION -----------------------------------------------------------------------------
// Left out of a program that links the engine (core/engine_linkage.h).
#if RTWEEKEND_ENGINE_BODIES

namespace detail {

// A name for a temporary file beside `path`, unique to this thread and moment.
inline std::string temporary_name(const std::string& path) {
    std::ostringstream name;
    name << path << ".tmp-" << std::hex
         << (std::hash<std::thread::id>{}(std::this_thread::get_id()) ^
             uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()));
    return name.str();
}

inline std::string errno_text(int saved_errno) { return std::strerror(saved_errno ? saved_errno : EIO); }

inline std::string file_kind_text(std::filesystem::file_type type) {
    using std::filesystem::file_type;
    switch (type) {
    case file_type::character: return "it is a character device";
    case file_type::block: return "it is a block device";
    case file_type::fifo: return "it is a FIFO (named pipe)";
    case file_type::socket: return "it is a socket";
    default: return "it is a special file";
    }
}

} // namespace detail

RTWEEKEND_ENGINE_FUNCTION std::string read_file(const std::string& path, const std::string& what,
                                                uint64_t max_bytes) {
    namespace fs = std::filesystem;
    // The kind of file first: opening a FIFO would block, and reading /dev/zero or a directory
    // never ends or fails late with a vague message. A missing file falls through to fopen, whose
    // errno names the problem.
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!ec && fs::exists(st)) {
        if (fs::is_directory(st)) throw scene_error(path + ": cannot open " + what + ": it is a directory");
        if (!fs::is_regular_file(st))
            throw scene_error(path + ": cannot read " + what + ": " + detail::file_kind_text(st.type()) +
                              ", not a regular file");
        const uintmax_t size = fs::file_size(path, ec);
        if (!ec && size > max_bytes)
            throw scene_error(path + ": " + what + " is " + std::to_string(size) + " bytes, more than the limit of " +
                              byte_limit_text(max_bytes));
    }
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw scene_error(path + ": cannot open " + what + ": " + detail::errno_text(errno));
    std::string bytes;
    char buffer[1 << 16];
    size_t n;
    bool too_long = false;
    // The size was checked above, but a file can grow while it is read: the limit holds here too.
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) {
        if (n > max_bytes - bytes.size()) {
            too_long = true;
            break;
        }
        bytes.append(buffer, n);
    }
    bool failed = std::ferror(f) != 0;
    int saved_errno = errno;
    std::fclose(f);
    if (too_long) throw scene_error(path + ": " + what + " is larger than the limit of " + byte_limit_text(max_bytes));
    if (failed) throw scene_error(path + ": read error: " + detail::errno_text(saved_errno));
    return bytes;
}

RTWEEKEND_ENGINE_FUNCTION void write_file_atomically(const std::string& path, const std::string& contents) {
    std::string tmp = detail::temporary_name(path);
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw scene_error("cannot write '" + path + "': " + detail::errno_text(errno));
    bool ok = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
    int saved_errno = errno;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) {
        std::remove(tmp.c_str());
        throw scene_error("cannot write '" + path + "': " + detail::errno_text(saved_errno));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        saved_errno = errno;
        std::remove(tmp.c_str());
        throw scene_error("cannot write '" + path + "': " + detail::errno_text(saved_errno));
    }
}

RTWEEKEND_ENGINE_FUNCTION void check_writable(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw scene_error("cannot write '" + path + "': it is a directory");
    // Create and remove a file beside the target: the same test the atomic write will face.
    std::string probe = detail::temporary_name(path);
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    if (!f) throw scene_error("cannot write '" + path + "': " + detail::errno_text(errno));
    std::fclose(f);
    std::remove(probe.c_str());
}

RTWEEKEND_ENGINE_FUNCTION std::string lowercase_extension(const std::string& path) {
    auto slash = path.find_last_of("/\\");
    auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext;
}

#endif // RTWEEKEND_ENGINE_BODIES

} // namespace rt
