#include "options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "commands.h"
#include "zhf/io/errors.h"
#include "zhf/io/numbers.h"
#include "zhf/runtime/limits.h"

namespace zhf::cli {
namespace {

std::string quoted(const std::string& text) { return "'" + io::excerpt(text) + "'"; }

}  // namespace

long long integer_option(const std::string& option, const std::string& text, long long lo, long long hi) {
  long long x = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (error == std::errc::invalid_argument || end != text.data() + text.size() || text.empty())
    throw UsageError(option + ": " + quoted(text) + " is not an integer");
  if (error == std::errc::result_out_of_range || x < lo || x > hi)
    throw UsageError(option + ": must be " + std::to_string(lo) + ".." + std::to_string(hi) + " (got " + quoted(text) + ")");
  return x;
}

std::uint64_t seed_option(const std::string& option, const std::string& text) {
  std::uint64_t x = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (error != std::errc() || end != text.data() + text.size() || text.empty())
    throw UsageError(option + ": " + quoted(text) + " is not an integer in 0..18446744073709551615");
  return x;
}

double number_option(const std::string& option, const std::string& text, double lo, double hi) {
  const io::ParsedNumber x = io::parse_number(text);
  if (!x.value) throw UsageError(option + ": " + quoted(text) + " " + x.problem);
  if (*x.value < lo || *x.value > hi)
    throw UsageError(option + ": must be in [" + runtime::format_number(lo, 6) + ", " + runtime::format_number(hi, 6) + "] (got " + quoted(text) + ")");
  return *x.value;
}

std::vector<int> orders_option(const std::string& option, const std::string& text, int lo, int hi) {
  std::vector<int> orders;
  const auto dots = text.find("..");
  if (dots != std::string::npos) {
    const int first = static_cast<int>(integer_option(option, text.substr(0, dots), lo, hi));
    const int last = static_cast<int>(integer_option(option, text.substr(dots + 2), lo, hi));
    if (first > last) throw UsageError(option + ": the range " + quoted(text) + " is empty");
    for (int n = first; n <= last; ++n) orders.push_back(n);
    return orders;
  }
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const int n = static_cast<int>(integer_option(option, text.substr(start, comma - start), lo, hi));
    if (std::find(orders.begin(), orders.end(), n) != orders.end())
      throw UsageError(option + ": " + std::to_string(n) + " is listed twice");
    orders.push_back(n);
    start = comma + 1;
  }
  return orders;
}

std::vector<OldSpelling>& old_spellings() {
  static std::vector<OldSpelling> all;
  return all;
}

CLI::Option* add_threads_option(CLI::App* command, std::string& threads) {
  return command->add_option("--threads", threads,
                             "Threads, 0.." + std::to_string(runtime::kMaxThreads) + " (0: all cores, the default); never changes the result");
}

int threads_option(const std::string& threads) {
  return static_cast<int>(integer_option("--threads", threads, 0, runtime::kMaxThreads));
}

void add_progress_flags(CLI::App* command, bool& quiet, bool& verbose) {
  command->add_flag("--quiet", quiet, "No progress line");
  command->add_flag("--verbose", verbose, "Progress lines on stderr (one a second at most) also when it is not a terminal");
}

void check_old_spellings() {
  for (const OldSpelling& s : old_spellings())
    if (s.old->count() > 0 && s.current->count() > 0)
      throw UsageError(s.name + ": the old spelling of " + s.current_name + "; give one of them");
}

}  // namespace zhf::cli
