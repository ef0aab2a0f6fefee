// Reading JSON field by field: json_fields.hpp.
#include "formats/json_fields.hpp"

#include <algorithm>
#include <climits>
#include <cmath>

#include "isolux/error.hpp"

namespace isolux {

json parse_json(std::string_view text, std::string_view source) {
    try {
        return json::parse(text);
    } catch (const json::parse_error& e) {
        throw Error(std::string(source) + ": malformed JSON at byte " + std::to_string(e.byte));
    } catch (const json::exception& e) {
        // e.g. a number beyond the range of a double (out_of_range 406)
        throw Error(std::string(source) + ": malformed JSON (" + e.what() + ")");
    }
}

long long Fields::integer(const char* k, long long lo, long long hi) const {
    const json& v = obj[k];
    if (!v.is_number_integer()) fail(k, "must be an integer, got " + std::string(v.type_name()));
    long long x = v.is_number_unsigned() ? (long long)std::min<unsigned long long>(v.get<unsigned long long>(), (unsigned long long)LLONG_MAX) : v.get<long long>();
    if (x < lo || x > hi)
        fail(k, "= " + std::to_string(x) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return x;
}

double Fields::real(const char* k) const {
    const json& v = obj[k];
    if (!v.is_number()) fail(k, "must be a number, got " + std::string(v.type_name()));
    double x = v.get<double>();
    if (!std::isfinite(x)) fail(k, "must be finite");
    return x;
}

std::string Fields::text(const char* k) const {
    const json& v = obj[k];
    if (!v.is_string()) fail(k, "must be a string, got " + std::string(v.type_name()));
    return v.get<std::string>();
}

bool Fields::boolean(const char* k) const {
    const json& v = obj[k];
    if (!v.is_boolean()) fail(k, "must be true or false, got " + std::string(v.type_name()));
    return v.get<bool>();
}

void Fields::warn_unknown(std::initializer_list<const char*> known, std::vector<std::string>* warnings) const {
    if (!warnings) return;
    std::vector<std::string> unknown;
    for (auto it = obj.begin(); it != obj.end(); ++it) {  // nlohmann's object is a std::map: ordered
        bool ok = false;
        for (const char* k : known) ok = ok || it.key() == k;
        if (!ok) unknown.push_back(it.key());
    }
    report_unknown(where, unknown, warnings);
}

void Fields::report_unknown(const std::string& where, const std::vector<std::string>& unknown,
                            std::vector<std::string>* warnings) {
    constexpr std::size_t named = 10;
    for (std::size_t i = 0; i < unknown.size() && i < named; ++i)
        warnings->push_back(where + ": unknown field \"" + unknown[i] + "\" ignored");
    if (unknown.size() > named)
        warnings->push_back(where + ": and " + std::to_string(unknown.size() - named) + " more unknown fields ignored");
}

void check_object(const json& j, const std::string& where) {
    if (!j.is_object()) throw Error(where + ": must be a JSON object, got " + std::string(j.type_name()));
}

void check_schema(const Fields& f, std::vector<std::string>* warnings, int newest) {
    if (!f.has("schema_version")) {
        if (warnings) warnings->push_back(f.where + ": no schema_version; reading as version 1");
        return;
    }
    long long v = f.integer("schema_version", 1, 1000000);
    if (v > newest)
        f.fail("schema_version", "= " + std::to_string(v) + " is newer than this isolux reads (" +
                                     std::to_string(newest) + ")");
}

Params params_from(const Fields& f) {
    Params p;
    for (const ParamInfo& info : param_table()) {
        const char* k = info.name;
        if (!f.has(k)) continue;
        double v = 0;
        switch (info.type) {
            case ParamType::integer: v = double(f.integer(k, (long long)info.min, (long long)info.max)); break;
            case ParamType::real: v = f.real(k); break;
            case ParamType::choice: v = parse_param(info, f.text(k), f.where); break;
            case ParamType::boolean: v = f.boolean(k) ? 1 : 0; break;
        }
        check_param(info, v, f.where);
        info.set(p, v);
    }
    return p;
}

json params_json(const Params& p) {
    json j = json::object();
    for (const ParamInfo& info : param_table()) {
        const double v = info.get(p);
        switch (info.type) {
            case ParamType::integer: j[info.name] = (long long)v; break;
            case ParamType::real: j[info.name] = v; break;
            case ParamType::choice: j[info.name] = format_param(info, v); break;
            case ParamType::boolean: j[info.name] = v != 0; break;
        }
    }
    return j;
}

void warn_unknown_params(const Fields& f, std::initializer_list<const char*> extra, std::vector<std::string>* warnings) {
    if (!warnings) return;
    std::vector<std::string> unknown;
    for (auto it = f.obj.begin(); it != f.obj.end(); ++it) {  // nlohmann's object is a std::map: ordered
        bool known = find_param(it.key()) != nullptr;
        for (const char* k : extra) known = known || it.key() == k;
        if (!known) unknown.push_back(it.key());
    }
    Fields::report_unknown(f.where, unknown, warnings);
}

}  // namespace isolux
