// The one expression model every backend prints: a DAG of scalar (or channel-vector) additions,
// subtractions, negations and multiplications over inputs and constants, with reciprocal square
// roots and sign selections for the few kernels that normalise (the zxzxz Euler stage). Construction folds
// constants and signs and shares identical subexpressions, so the three languages get the
// same algorithm and the same operation counts by construction.
#pragma once

#include <cstddef>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace zhf::codegen {

enum class Op {
  kInput, kConst, kAdd, kSub, kMul, kNeg,
  kRsqrt,   // 1 / sqrt(a)
  kSelect,  // a > 0 ? b : c
};

struct Node {
  Op op = Op::kConst;
  int a = -1, b = -1, c = -1;  // operands
  double value = 0;     // kConst
  int param = -1;       // kInput: parameter and element
  int element = -1;
  int lanes = 1;        // channels: 1 scalar, 3 (RGB) or 4 (RGBA) per value
  bool wide = false;    // computed in the wide type (double for float kernels)
};

struct OpCount {
  int multiplies = 0;
  int adds = 0;  // additions, subtractions and negations
  int others = 0;  // reciprocal square roots and selections
};

class Graph {
 public:
  int input(int param, int element, int lanes = 1);
  // Those inputs are read negated from now on: input(param, element) gives -x. How a kernel
  // takes its arguments in another sign convention (ModuleOptions::condon_shortley); the
  // simplifier folds the negations into the adds and constants that use them.
  void negate_inputs(int param, const std::vector<int>& elements);
  int constant(double value);
  int add(int a, int b);
  int sub(int a, int b);
  int mul(int a, int b);
  int neg(int a);
  int scale(double c, int a) { return mul(constant(c), a); }
  int rsqrt(int a);
  int select_positive(int condition, int if_positive, int otherwise);

  // Nodes created while wide is set are computed in the wide type; printers convert where a
  // node's operand or output has the other width.
  void set_wide(bool wide) { wide_ = wide; }
  bool wide() const { return wide_; }

  // sum_i c_i x_i with terms of equal |c| (to 1e-12 relative) sharing one multiply:
  // c (x_1 - x_2 + ...). Terms with c = 0 are dropped.
  int linear(const std::vector<std::pair<double, int>>& terms);

  const Node& node(int i) const { return nodes_[i]; }
  int size() const { return static_cast<int>(nodes_.size()); }
  bool is_const(int i, double value) const { return nodes_[i].op == Op::kConst && nodes_[i].value == value; }

  // Operations needed for the given outputs (each shared node counted once).
  OpCount count(const std::vector<int>& outputs) const;
  // Nodes reachable from outputs, in creation (= dependency) order.
  std::vector<int> live(const std::vector<int>& outputs) const;

 private:
  int intern(const Node& n);
  int binary(Op op, int a, int b);
  std::vector<Node> nodes_;
  std::vector<std::pair<int, int>> negated_;  // (param, element)
  // Each node's identity (Node without lanes, which follow from the operands), for sharing.
  struct Key {
    int op, a, b, c;
    double value;
    int param, element;
    bool wide;
    bool operator==(const Key& o) const {
      return op == o.op && a == o.a && b == o.b && c == o.c && value == o.value && param == o.param &&
             element == o.element && wide == o.wide;
    }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const;
  };
  std::unordered_map<Key, int, KeyHash> index_;
  bool wide_ = false;
};

}  // namespace zhf::codegen
