#pragma once
// Lines of a text file and their numbers, for readers whose messages say "file:LINE: problem".
//
//   text_lines lines(text);
//   for (std::string_view line; lines.next(line);)   // without its '\n' (a '\r' before it stays)
//       ... lines.number() ...                         // 1 for the first line
//   lines.offset()                                     // where the next line starts
//
//   line_index index(text);                            // for parsers that report byte offsets
//   index.line_of(offset)                              // 1-based line holding that byte
//
//   one_line(message)                                  // control characters (a line break in a
//                                                      // quoted value) shown as \x0a: a message
//                                                      // stays one line

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace rt {

class text_lines {
  public:
    explicit text_lines(std::string_view text) : text_(text) {}

    // The next line, false when the text is used up.
    bool next(std::string_view& line) {
        if (next_ >= text_.size()) return false;
        size_t end = text_.find('\n', next_);
        if (end == std::string_view::npos) end = text_.size();
        line = text_.substr(next_, end - next_);
        next_ = std::min(end + 1, text_.size());
        ++number_;
        return true;
    }

    size_t number() const { return number_; }
    size_t offset() const { return next_; }

  private:
    std::string_view text_;
    size_t next_ = 0, number_ = 0;
};

class line_index {
  public:
    explicit line_index(std::string_view text) {
        for (size_t i = 0; i < text.size(); ++i)
            if (text[i] == '\n') newlines_.push_back(i);
    }

    size_t line_of(size_t offset) const {
        return size_t(std::lower_bound(newlines_.begin(), newlines_.end(), offset) - newlines_.begin()) + 1;
    }

  private:
    std::vector<size_t> newlines_; // offsets of the '\n' characters
};

// The message with each control character but the tab (line breaks above all) written as \xNN.
inline std::string one_line(const std::string& message) {
    static const char digits[] = "0123456789abcdef";
    std::string out;
    out.reserve(message.size());
    for (char c : message) {
        const unsigned char u = static_cast<unsigned char>(c);
        if ((u < 0x20 && c != '\t') || u == 0x7f) {
            out += "\\x";
            out += digits[u >> 4];
            out += digits[u & 15];
        } else {
            out += c;
        }
    }
    return out;
}

} // namespace rt
