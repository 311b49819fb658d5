// Numeric options are taken as text and read here, exactly: the whole text must be the number,
// in range and finite; integers never wrap. Each error is a UsageError naming the option.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace zhf::cli {

long long integer_option(const std::string& option, const std::string& text, long long lo, long long hi);
std::uint64_t seed_option(const std::string& option, const std::string& text);
double number_option(const std::string& option, const std::string& text, double lo, double hi);
// "2..8", "3,5,8" or "4", every order in [lo, hi], none twice.
std::vector<int> orders_option(const std::string& option, const std::string& text, int lo, int hi);

}  // namespace zhf::cli
