// A function's expression graph run without compiling it: every node rounded to T as the emitted
// C++ kernel rounds it (no contraction), wide nodes kept in double.
#pragma once

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "zhf/codegen/kernels.h"

namespace zhf::test {

using GraphInputs = std::vector<std::vector<double>>;  // per parameter

// The function's outputs, (param, element) -> value, for one-channel functions.
template <class T = double>
std::map<std::pair<int, int>, double> evaluate(const codegen::Function& f, const GraphInputs& inputs) {
  const codegen::Graph& g = f.graph;
  std::vector<double> v(g.size());
  for (int i = 0; i < g.size(); ++i) {
    const codegen::Node& n = g.node(i);
    double x = 0;
    switch (n.op) {
      case codegen::Op::kInput: x = static_cast<T>(inputs[n.param][n.element]); break;
      case codegen::Op::kConst: x = n.wide ? n.value : static_cast<T>(n.value); break;
      case codegen::Op::kAdd: x = v[n.a] + v[n.b]; break;
      case codegen::Op::kSub: x = v[n.a] - v[n.b]; break;
      case codegen::Op::kMul: x = v[n.a] * v[n.b]; break;
      case codegen::Op::kNeg: x = -v[n.a]; break;
      case codegen::Op::kRsqrt: x = 1 / std::sqrt(v[n.a]); break;
      case codegen::Op::kSelect: x = v[n.a] > 0 ? v[n.b] : v[n.c]; break;
    }
    v[i] = n.wide ? x : static_cast<T>(x);
  }
  std::map<std::pair<int, int>, double> out;
  for (const codegen::Output& o : f.outputs) out[{o.param, o.element}] = static_cast<T>(v[o.node]);
  return out;
}

}  // namespace zhf::test
