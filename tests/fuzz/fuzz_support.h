#pragma once
// What the libFuzzer harnesses share: the input as a string, a scratch directory of this process
// for loaders that read files, splitting an input in two, and the oracle for refused input.
//
//   fuzz::bytes(data, size)          the input as a std::string (NUL bytes kept)
//   fuzz::scratch()                  a directory of this process only (under $TMPDIR, else
//                                    /dev/shm, else /tmp), made at first use, removed at exit
//   fuzz::empty_scratch()            removes everything inside it (each input starts clean)
//   fuzz::put(name, bytes)           writes a file inside it, returns its path
//   fuzz::split(input, separator)    {before, after, found}: the input cut at the first separator
//   fuzz::refused(error)             the oracle for an input a loader refuses: the scene_error's
//                                    message must be one non-empty line without NUL bytes (what
//                                    the apps print after "app: error: "); otherwise it aborts,
//                                    and libFuzzer reports the input as a crash. With
//                                    RTWEEKEND_FUZZ_VERBOSE=1 in the environment it also prints
//                                    the message (to see what a harness makes of a given input)
//
// Any exception other than rt::scene_error escapes the harness: libFuzzer reports it as a crash
// (uncaught exception), because a loader must turn every problem into one clear scene_error.

#include <rtweekend/core/scene_error.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace fuzz {

inline std::string bytes(const uint8_t* data, size_t size) {
    return std::string(reinterpret_cast<const char*>(data), size);
}

namespace detail {

inline std::filesystem::path make_scratch() {
    namespace fs = std::filesystem;
    fs::path base;
    std::error_code ec;
    if (const char* tmp = std::getenv("TMPDIR"); tmp && *tmp && fs::is_directory(tmp, ec)) base = tmp;
    else if (fs::is_directory("/dev/shm", ec)) base = "/dev/shm";
    else base = "/tmp";
    fs::path dir = base / ("rtweekend_fuzz_" + std::to_string(::getpid()));
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    return dir;
}

inline void remove_scratch();

} // namespace detail

// The scratch directory (see the top); made once, then only read. Never destroyed, so that the
// exit handler that removes the directory can still name it.
inline const std::filesystem::path& scratch() {
    static const std::filesystem::path* const dir = [] {
        auto* d = new std::filesystem::path(detail::make_scratch());
        std::atexit(detail::remove_scratch);
        return d;
    }();
    return *dir;
}

inline void detail::remove_scratch() {
    std::error_code ec;
    std::filesystem::remove_all(scratch(), ec);
}

inline void empty_scratch() {
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(scratch(), ec)) {
        std::error_code ignored;
        std::filesystem::remove_all(entry.path(), ignored);
    }
}

inline std::string put(const std::string& name, const std::string& contents) {
    const std::string path = (scratch() / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(contents.data(), std::streamsize(contents.size()));
    out.close();
    if (!out) {
        std::fprintf(stderr, "fuzz: cannot write the scratch file %s\n", path.c_str());
        std::abort();
    }
    return path;
}

struct halves {
    std::string before, after;
    bool found = false;
};

inline halves split(const std::string& input, const std::string& separator) {
    const size_t at = input.find(separator);
    if (at == std::string::npos) return {input, "", false};
    return {input.substr(0, at), input.substr(at + separator.size()), true};
}

// A message the program prints (an error or a warning) must be one line: not empty, no line
// break, no NUL byte; aborts (a finding) otherwise.
inline void check_one_line(const std::string& message) {
    const char* problem = message.empty()                            ? "is empty"
                          : message.find('\n') != std::string::npos ? "spans more than one line"
                          : message.find('\0') != std::string::npos ? "holds a NUL byte"
                                                                     : nullptr;
    if (!problem) return;
    std::fprintf(stderr, "fuzz: the message %s: '%s'\n", problem, message.c_str());
    std::abort();
}

inline void refused(const rt::scene_error& e) {
    const std::string message = e.what();
    check_one_line(message);
    if (const char* verbose = std::getenv("RTWEEKEND_FUZZ_VERBOSE"); verbose && *verbose == '1')
        std::fprintf(stderr, "fuzz: refused: %s\n", message.c_str());
}

} // namespace fuzz
