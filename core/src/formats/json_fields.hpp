// Inside core: reading JSON files field by field, so that every error names
// the file and the field (presets, scenes and tileset manifests share it).
#pragma once
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "isolux/error.hpp"
#include "isolux/params.hpp"
#include "isolux/scene_file.hpp"

namespace isolux {

using nlohmann::json;

// Parses `text`; throws Error naming `source` and the byte where it fails.
json parse_json(std::string_view text, std::string_view source);

// `j` as a file's text, indented, ending in a newline. A string that is not
// UTF-8 (a Latin-1 file name, a light's name from a TMX) is written with
// U+FFFD in place of its bad bytes: a save never fails on a name.
inline std::string file_text(const json& j) {
    return j.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

// Field access that names the file and the field in every error.
struct Fields {
    const json& obj;
    std::string where;  // "file.json" or "file.json: sprites[2] (\"oak\")"

    [[noreturn]] void fail(const std::string& field, const std::string& what) const {
        throw Error(where + ": " + field + " " + what);
    }
    bool has(const char* k) const { return obj.contains(k) && !obj[k].is_null(); }

    long long integer(const char* k, long long lo, long long hi) const;
    double real(const char* k) const;  // finite
    std::string text(const char* k) const;
    bool boolean(const char* k) const;
    // Warns about every field not in `known`.
    void warn_unknown(std::initializer_list<const char*> known, std::vector<std::string>* warnings) const;
    // The first few unknown fields by name, then how many more: a file with
    // 200000 of them gives 11 lines, not 200000.
    static void report_unknown(const std::string& where, const std::vector<std::string>& unknown,
                               std::vector<std::string>* warnings);
};

// Throws Error naming `where` unless `j` is an object.
void check_object(const json& j, const std::string& where);

// A missing schema_version reads as 1 (with a warning); a newer one than
// `newest` is refused.
void check_schema(const Fields& f, std::vector<std::string>* warnings, int newest = schema_version);

// Every parameter the object holds, by the table; the rest at their defaults.
Params params_from(const Fields& f);
json params_json(const Params& p);

// Warns about every field of a preset object that is neither a parameter nor
// one of `extra`.
void warn_unknown_params(const Fields& f, std::initializer_list<const char*> extra, std::vector<std::string>* warnings);

}  // namespace isolux
