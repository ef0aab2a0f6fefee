// isolux: the one error type for bad user data (files, fields, sizes).
// Programmer errors (broken preconditions) assert instead.
#pragma once
#include <stdexcept>
#include <string>
#include <string_view>

namespace isolux {

// `text` with its control characters written as \xNN: C0 (newlines and
// escapes included), DEL, and C1 (as UTF-8, U+0080 to U+009F). A name read
// from a file then cannot move the cursor, clear the screen or set the
// clipboard when a message holding it is printed, and a message stays one line.
inline std::string printable(std::string_view text) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    out.reserve(text.size());
    auto escape = [&](unsigned char c) {
        out += "\\x";
        out += hex[c >> 4];
        out += hex[c & 15];
    };
    for (std::size_t i = 0; i < text.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c == 0x7f) {
            escape(c);
        } else if (c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                   static_cast<unsigned char>(text[i + 1]) <= 0x9f) {
            escape(static_cast<unsigned char>(text[++i]));  // U+0080..U+009F: C1 controls
        } else {
            out += char(c);
        }
    }
    return out;
}

// A problem with user input. what() is one line that names the file and the
// entry or field at fault, ready to print as is (control characters in it,
// from a file or a name, are escaped: printable).
struct Error : std::runtime_error {
    explicit Error(const std::string& what) : std::runtime_error(printable(what)) {}
    explicit Error(const char* what) : std::runtime_error(printable(what)) {}
};

// Work stopped because the user asked (TraceControl::cancel): not a failure.
struct Cancelled : Error {
    Cancelled() : Error("cancelled") {}
};

}  // namespace isolux
