#pragma once
// course_json: a CENG795 scene in the course's JSON form (the Fall 2025-26 edition) turned into the
// XML document it translates, so that one reader (io/xml_scene.h) reads both. The translation is
// mechanical (shared/formats/ceng795-later.md, section 15):
//
//   {"Scene": {"MaxRecursionDepth": "6",                    <Scene><MaxRecursionDepth>6</...>
//     "Cameras": {"Camera": [{"_id": "1", ...}, ...]},      <Cameras><Camera id="1">...</Camera>...
//     "Objects": {"Mesh": {"_id": "1",                      <Objects><Mesh id="1">
//        "Faces": {"_data": "1 2 3", "_plyFile": "a.ply"}}}  <Faces plyFile="a.ply">1 2 3</Faces>
//
// a key holding an object is an element; its keys starting with '_' are attributes ("_data" is the
// element's text); a key holding a string (or a number or a boolean, which the course's files do
// not use but a hand-written file might) is an element with that text; a key holding an array is
// that element once per entry. Keys keep their order (nlohmann::ordered_json), so cameras, lights
// and objects come in the file's order, as in the XML.
//
// Parsed by nlohmann/json (Debian's nlohmann-json3-dev). Only the engine's bodies include this
// file (io/xml_scene.h's implementation).
//
// Errors: scene_error "PATH:LINE: malformed JSON: ..." (nlohmann's reason, the line counted here),
// "PATH: the JSON scene must be an object holding \"Scene\"", an array inside an array, an
// attribute holding an object or array, or nesting deeper than 64 levels (no course file is
// deeper than 6).

#include "../core/scene_error.h"
#include "../core/text_lines.h"

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include <string>

namespace rt {
namespace detail {

class course_json_translator {
  public:
    course_json_translator(const std::string& text, const std::string& path) : text_(text), path_(path) {}

    // Fills `doc` with the <Scene> element the JSON text translates. Throws scene_error.
    void translate(pugi::xml_document& doc) const {
        nlohmann::ordered_json root;
        try {
            root = nlohmann::ordered_json::parse(text_);
        } catch (const nlohmann::json::parse_error& e) {
            // nlohmann's message starts "[json.exception.parse_error.101] parse error at line L,
            // column C: "; the line is counted here, and the rest kept.
            const size_t at = e.byte == 0 ? 0 : std::min<size_t>(e.byte - 1, text_.size());
            const size_t line = text_.empty() ? 1 : line_index(text_).line_of(std::min(at, text_.size() - 1));
            throw scene_error(one_line(path_ + ":" + std::to_string(line) + ": malformed JSON: " + reason_of(e)));
        } catch (const nlohmann::json::exception& e) {
            // Any other of nlohmann's refusals (a number beyond a double: out_of_range.406), which
            // carries no position.
            throw scene_error(one_line(path_ + ": malformed JSON: " + reason_of(e)));
        }
        if (!root.is_object() || !root.contains("Scene") || !root["Scene"].is_object())
            fail("the JSON scene must be an object holding \"Scene\": {...}");
        if (root.size() != 1) fail("the JSON scene holds more than \"Scene\" at its top");
        element(doc, "Scene", root["Scene"], 1);
    }

  private:
    static constexpr int max_depth = 64;
    const std::string& text_;
    const std::string& path_;

    [[noreturn]] void fail(const std::string& problem) const { throw scene_error(one_line(path_ + ": " + problem)); }

    // nlohmann's message without its "[json.exception.KIND.N] ... : " prefix, at most 160
    // characters (it quotes the token it stopped at, which a file may make as long as it likes).
    static std::string reason_of(const nlohmann::json::exception& e) {
        std::string reason = e.what();
        if (size_t colon = reason.find(": "); colon != std::string::npos && reason.compare(0, 1, "[") == 0)
            reason = reason.substr(colon + 2);
        else if (size_t bracket = reason.find("] "); bracket != std::string::npos && reason.compare(0, 1, "[") == 0)
            reason = reason.substr(bracket + 2);
        constexpr size_t max_reason = 160;
        if (reason.size() > max_reason) reason = reason.substr(0, max_reason) + "... (" + std::to_string(reason.size()) + " characters)";
        return reason;
    }

    std::string scalar_text(const nlohmann::ordered_json& v) const {
        if (v.is_null()) return "";
        if (!v.is_string()) return v.dump(); // a number or boolean, as JSON writes it
        std::string s = v.get<std::string>();
        // XML text cannot hold one, and pugixml would end the value there.
        if (s.find('\0') != std::string::npos) fail("a value holds a NUL character (\\u0000)");
        return s;
    }

    // Appends to `parent` the element(s) `key` holds.
    void element(pugi::xml_node parent, const std::string& key, const nlohmann::ordered_json& value, int depth) const {
        if (depth > max_depth) fail("the JSON scene is nested more than " + std::to_string(max_depth) + " levels deep");
        if (key.empty()) fail("a key is empty: it names no element");
        if (value.is_array()) {
            for (const auto& entry : value) {
                if (entry.is_array()) fail("\"" + token_text(key) + "\" holds an array inside an array");
                element(parent, key, entry, depth + 1);
            }
            return;
        }
        pugi::xml_node el = parent.append_child(key.c_str());
        if (!value.is_object()) {
            const std::string text = scalar_text(value);
            if (!text.empty()) el.append_child(pugi::node_pcdata).set_value(text.c_str());
            return;
        }
        for (const auto& [k, v] : value.items()) {
            if (k.empty() || k[0] != '_') {
                element(el, k, v, depth + 1);
                continue;
            }
            if (k.size() == 1) fail("a key \"_\" of \"" + token_text(key) + "\" names no attribute");
            if (v.is_object() || v.is_array())
                fail("\"" + token_text(k) + "\" of \"" + token_text(key) + "\" is an attribute and must hold text");
            if (k == "_data") {
                const std::string text = scalar_text(v);
                if (!text.empty()) el.append_child(pugi::node_pcdata).set_value(text.c_str());
            } else {
                el.append_attribute(k.substr(1).c_str()).set_value(scalar_text(v).c_str());
            }
        }
    }
};

} // namespace detail
} // namespace rt
