// Numbers typed by people (text coefficient files, rotations, option values), read exactly: the
// whole token must be one decimal or exponent-form number (an optional leading + or -), finite;
// no hex, no "nan" or "inf", no trailing characters. Below a double's range is zero.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace zhf::io {

// The number, or the reason it is none ("is not a number", "is beyond the range of a double",
// "is not finite") to follow a quoted excerpt of the token.
struct ParsedNumber {
  std::optional<double> value;
  std::string problem;
};
ParsedNumber parse_number(std::string_view token);

}  // namespace zhf::io
