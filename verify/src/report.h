// Comparing a runner's outputs with the reference, and the tolerances that apply.
#pragma once

#include <string>
#include <vector>

#include "inputs.h"
#include "zhf/runtime/lobe_stage.h"
#include "zhf/verify/verify.h"

namespace zhf::verify {

// What a file's tolerances depend on besides the order.
struct Conditioning {
  double worst_condition = 1;
  runtime::LobeStage lobe_stage = runtime::LobeStage::kFloat;
};

// One function's results against the reference (and, for shaders, against the C++ float kernel).
FunctionResult compare(const Inputs& in, const Conditioning& conditioning, const Mode& mode, const std::vector<double>& got,
                       const std::vector<double>& expected, const std::string& language, const std::string& precision,
                       const std::vector<double>* cpp_float);

}  // namespace zhf::verify
