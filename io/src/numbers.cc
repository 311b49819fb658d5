#include "zhf/io/numbers.h"

#include <charconv>
#include <cmath>

namespace zhf::io {

ParsedNumber parse_number(std::string_view token) {
  std::string_view digits = token;
  if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
  if (digits.empty() || digits[0] == '+') return {std::nullopt, "is not a number"};
  double x = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), x, std::chars_format::general);
  if (end != digits.data() + digits.size() || error == std::errc::invalid_argument) return {std::nullopt, "is not a number"};
  if (error == std::errc::result_out_of_range) {
    const auto e = digits.find_first_of("eE");
    if (e != std::string_view::npos && e + 1 < digits.size() && digits[e + 1] == '-') return {digits[0] == '-' ? -0.0 : 0.0, ""};
    return {std::nullopt, "is beyond the range of a double"};
  }
  if (!std::isfinite(x)) return {std::nullopt, "is not finite"};
  return {x, ""};
}

}  // namespace zhf::io
