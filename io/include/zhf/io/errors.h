// Error kinds the CLI maps to its documented exit codes. Messages are one line and name
// the file, field or option at fault.
#pragma once

#include <stdexcept>
#include <string>

namespace zhf::io {

// A file the user gave us is missing, unreadable or malformed (exit 3).
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An output could not be written (exit 4).
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace zhf::io
