// Numeric options are taken as text and read here, exactly: the whole text must be the number,
// in range and finite; integers never wrap. Each error is a UsageError naming the option.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace zhf::cli {

long long integer_option(const std::string& option, const std::string& text, long long lo, long long hi);
std::uint64_t seed_option(const std::string& option, const std::string& text);
double number_option(const std::string& option, const std::string& text, double lo, double hi);
// "2..8", "3,5,8" or "4", every order in [lo, hi], none twice.
std::vector<int> orders_option(const std::string& option, const std::string& text, int lo, int hi);

// One rule per concept across the commands (docs/usage.md): --out is the file a command writes,
// --order N a band limit (bands 0..N-1), --count a number of things, --threads and --quiet on
// every long command. An earlier spelling stays working, out of the help: it writes the same
// variable, and giving both spellings is a usage error.
struct OldSpelling {
  std::string name;
  const CLI::Option* old;
  const CLI::Option* current;
  std::string current_name;
};
std::vector<OldSpelling>& old_spellings();

template <class T>
CLI::Option* keep_old_spelling(CLI::App* command, CLI::Option* current, const std::string& old_name, T& target) {
  CLI::Option* old = command->add_option(old_name, target, "old spelling of " + current->get_name())->group("");
  old_spellings().push_back({old_name, old, current, current->get_name()});
  return old;
}
// Throws UsageError when an option was given in both spellings (after parsing).
void check_old_spellings();

// --threads T (0..runtime::kMaxThreads, 0: all cores; a result never depends on it) and its
// reading; --quiet and --verbose, the progress line's flags (progress.h).
CLI::Option* add_threads_option(CLI::App* command, std::string& threads);
int threads_option(const std::string& threads);
void add_progress_flags(CLI::App* command, bool& quiet, bool& verbose);

// "1 vector", "2 vectors".
inline std::string counted(std::size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace zhf::cli
