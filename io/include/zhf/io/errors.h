// Error kinds the CLI maps to its documented exit codes (docs/usage.md). Messages are one line
// and name the file, field or option at fault.
#pragma once

#include <stdexcept>
#include <string>

#include "zhf/runtime/errors.h"

namespace zhf::io {

// A file the user gave us is missing, unreadable or malformed (exit 3): the runtime's one input
// error, so a table refused by the runtime is refused the same way by every command.
using InputError = runtime::InputError;
using runtime::excerpt;

// An output could not be written (exit 4).
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace zhf::io
