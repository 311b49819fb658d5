// The native side of benchmarks/web_splats.mjs: zhf::dispatch's apply_splats, the call the WebAssembly
// module makes, on one thread, in place, over SPLATS splats of each SH degree 1..4 (3 (degree + 1)^2
// floats each, the values the script uses), best of RUNS: alone, and after the check of every
// value (dispatch::all_finite), as the module, the CLI and the Python module check their input
// before they change anything. One line per degree:
//   degree D ns_per_splat X checked_ns_per_splat Y isa I
//   zhf_web_splats_native [splats=1000000] [runs=7]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "zhf/dispatch/checks.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/rotation.h"

int main(int argc, char** argv) {
  const std::size_t splats = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int runs = argc > 2 ? std::atoi(argv[2]) : 7;
  // The script's rotation: the quaternion (w, x, y, z) below, as its JavaScript writes it.
  zhf::runtime::Matrix3 r;
  zhf::runtime::rotation_from_quaternion(0.8775825619, 0.1369787253, 0.2054680880, 0.4109361759, r);
  float q[9];
  for (int i = 0; i < 9; ++i) q[i] = float(r[i]);
  for (int degree = 1; degree <= 4; ++degree) {
    const std::size_t per = 3 * std::size_t(degree + 1) * std::size_t(degree + 1);
    std::vector<float> values(per * splats);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = float(std::sin(double(i % 65536)));
    const auto rotator = zhf::dispatch::Rotator<float>::make(degree + 1);
    double best = 1e30, checked = 1e30;
    for (int run = 0; run < runs; ++run) {
      auto start = std::chrono::steady_clock::now();
      rotator.apply_splats(q, splats, values.data(), values.data(), 1);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      start = std::chrono::steady_clock::now();
      if (!zhf::dispatch::all_finite(values.data(), values.size())) return 1;
      rotator.apply_splats(q, splats, values.data(), values.data(), 1);
      checked = std::min(checked, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::printf("degree %d ns_per_splat %.3f checked_ns_per_splat %.3f isa %s\n", degree, best * 1e9 / double(splats),
                checked * 1e9 / double(splats), zhf::dispatch::isa_name(rotator.isa()));
  }
  return 0;
}
