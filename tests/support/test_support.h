// What the tests share: running the real zhf binary as a user would (no shell: the argument
// string is split by the rules below), private temp directories, an independent JSON parser
// for outputs, and where the project's data is.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/io/process.h"
#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::test {

// The published lobe table (tests/data) is a paper's, not zhf's: its lobes, snapped to exact
// candidate values, match to kPaperLobeMatch, and its condition numbers are printed to 2 decimals.
inline constexpr double kPaperLobeMatch = 1e-9;
inline constexpr double kPaperConditionRelative = 0.01;
// Other published and printed numbers: a value quoted to 10 digits; a number std::to_string wrote
// (6 decimals).
inline constexpr double kQuotedTenDigits = 1e-10;
// One formula computed by two paths that the compiler may contract into fused multiply-adds
// differently (GCC contracts by default where FMA is in the instruction set: aarch64's baseline,
// x86-64-v3): equal where there is no FMA, within a few roundings (relative) where there is.
#if defined(__FP_FAST_FMA)
inline constexpr double kContractedRelative = 1e-14;
#else
inline constexpr double kContractedRelative = 0;
#endif
inline constexpr double kSixDecimals = 1e-6;

struct RunResult {
  int exit_code = -1;
  int signal = 0;
  std::string out;
  std::string err;
};

// args split at spaces; '...' and "..." group (the quotes dropped), nothing else is special.
std::vector<std::string> split_arguments(const std::string& args);
// The binary is ZHF_BINARY, or $ZHF_TEST_BINARY when set (to run the CLI tests against another
// build). environment: NAME=value entries on top of the test's. A run that hangs (an older build
// opening a FIFO to read it, say) is stopped after kRunTimeLimitSeconds and reports SIGTERM.
constexpr double kRunTimeLimitSeconds = 300;
RunResult run_zhf(const std::string& args);
RunResult run_zhf(const std::vector<std::string>& args, const std::string& working_dir = "",
                  const std::vector<std::string>& environment = {});
std::string zhf_binary();

// zhf started and left running (to interrupt it, or two at once): stdout to /dev/null, stderr to
// stderr_path (/dev/null when empty), the environment entries NAME=value on top of the test's.
io::Process start_zhf(const std::vector<std::string>& args, const std::string& stderr_path = "",
                      const std::vector<std::string>& environment = {});
// Its exit code, or 128 + the signal that ended it, waiting at most kRunTimeLimitSeconds.
int exit_code_of(io::Process& zhf);

// A fresh private directory; remove it with remove_dir.
std::string make_temp_dir();
void remove_dir(const std::string& dir);

// A fresh private directory removed with everything in it when it leaves scope, whether the test
// passed or failed.
class TempDir {
 public:
  TempDir() : path_(make_temp_dir()) {}
  ~TempDir() { remove_dir(path_.string()); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  operator const std::filesystem::path&() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  std::string string() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// The project's files, e.g. source_path("generated/lobes/order_3.json").
std::string source_path(const std::string& relative);
// The checked-in lobe table of an order: generated/lobes/order_N.json.
std::string checked_in_table(int order);
// tests/data/<name>: test data kept in the project (the published lobe table among them).
std::string data_path(const std::string& name);

// Outputs read with nlohmann's parser: independent of zhf's own reader.
std::string read_text(const std::string& path);
nlohmann::json read_json(const std::string& path);
void write_text(const std::string& path, const std::string& text);

// Lines of text (newlines counted).
int line_count(const std::string& text);

// Two arrays of size values in buffer (resized to hold them), each starting on an
// alignment-byte boundary and the second a whole number of those after the first: the layout
// DenseRotation::planar_streams asks for, whatever the allocator's placement.
template <class T>
std::pair<T*, T*> aligned_pair(std::vector<T>& buffer, std::size_t size, std::size_t alignment) {
  const std::size_t step = alignment / sizeof(T), whole = (size + step - 1) / step * step;
  buffer.assign(2 * whole + step, T(0));
  T* const first = buffer.data() + (step - reinterpret_cast<std::uintptr_t>(buffer.data()) / sizeof(T) % step) % step;
  return {first, first + whole};
}

// Whether headless Chromium with WebGPU can run here (chromium on PATH or $ZHF_CHROMIUM, node, and
// puppeteer-core in the checkout's tools/node: scripts/setup_web.sh), and why not; and whether the
// test command demands it (ZHF_REQUIRE_BROWSER=1), so that a test fails where it would skip.
bool browser_available(std::string& why);
bool browser_required();

// The alpha rule of the splat formats (docs/formats.md), written here apart from splat/: an alpha
// within 10^-6 of 0 or 1 reads as 10^-6 from it, as splat-transform reads it.
inline double opacity_of_alpha(double alpha) {
  const double margin = 1e-6;
  const double a = alpha < margin ? margin : alpha > 1 - margin ? 1 - margin : alpha;
  return std::log(a / (1 - a));
}

// What a rotation of type T at this order is held to against the reference: double kDouble; float
// kFloatRotation at the generated orders and kRuntimeOrdersFloat above them (zxzxz).
template <class T>
double rotation_tolerance(int order) {
  if (std::is_same_v<T, double>) return runtime::tolerance::kDouble;
  return order <= runtime::kMaxGeneratedOrder ? runtime::tolerance::kFloatRotation : runtime::tolerance::kRuntimeOrdersFloat;
}

// The largest |out_i - (D(R) f)_i| over the N^2 coefficients of one rotated vector, D(R) from the
// recurrence in long double (in double its rounding reaches ~5e-7 at l = 127); at: that i.
template <class T>
double worst_against_recurrence(const double r[9], int order, const std::vector<double>& f, const T* out, int& at) {
  const auto bands = runtime::recurrence_band_matrices<long double>(r, order);
  double worst = 0;
  for (int l = 0; l < order; ++l)
    for (int i = 0; i < 2 * l + 1; ++i) {
      long double expected = 0;
      for (int j = 0; j < 2 * l + 1; ++j) expected += bands[l][i * (2 * l + 1) + j] * f[l * l + j];
      const double error = double(std::abs(out[l * l + i] - expected));
      if (error > worst) worst = error, at = l * l + i;
    }
  return worst;
}

}  // namespace zhf::test
