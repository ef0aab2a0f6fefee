// isolux: the one error type for bad user data (files, fields, sizes).
// Programmer errors (broken preconditions) assert instead.
#pragma once
#include <stdexcept>
#include <string>

namespace isolux {

// A problem with user input. what() is one line that names the file and the
// entry or field at fault, ready to print as is.
struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Work stopped because the user asked (TraceControl::cancel): not a failure.
struct Cancelled : Error {
    Cancelled() : Error("cancelled") {}
};

}  // namespace isolux
