#include "zhf/codegen/expr.h"
#include "zhf/tolerances/tolerances.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace zhf::codegen {

std::size_t Graph::KeyHash::operator()(const Key& k) const {
  std::uint64_t bits = 0;
  const double value = k.value == 0 ? 0.0 : k.value;  // -0 == +0 as keys: one hash
  std::memcpy(&bits, &value, sizeof bits);
  auto mix = [](std::uint64_t x) {  // splitmix64's finaliser
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  };
  std::uint64_t h = mix(bits);
  h = mix(h ^ (std::uint64_t(std::uint32_t(k.a)) << 32 | std::uint32_t(k.b)));
  h = mix(h ^ (std::uint64_t(std::uint32_t(k.c)) << 32 | std::uint32_t(k.op) << 1 | std::uint32_t(k.wide)));
  h = mix(h ^ (std::uint64_t(std::uint32_t(k.param)) << 32 | std::uint32_t(k.element)));
  return static_cast<std::size_t>(h);
}

int Graph::intern(const Node& n) {
  Node node = n;
  node.wide = wide_;
  const Key key{static_cast<int>(node.op), node.a, node.b, node.c, node.value, node.param, node.element, node.wide};
  auto it = index_.find(key);
  if (it != index_.end()) return it->second;
  nodes_.push_back(node);
  index_.emplace(key, size() - 1);
  return size() - 1;
}

int Graph::binary(Op op, int a, int b) {
  Node n;
  n.op = op;
  n.a = a;
  n.b = b;
  n.lanes = std::max(nodes_[a].lanes, nodes_[b].lanes);
  return intern(n);
}

int Graph::input(int param, int element, int lanes) {
  Node n;
  n.op = Op::kInput;
  n.param = param;
  n.element = element;
  n.lanes = lanes;
  const int raw = intern(n);
  const bool negated = std::find(negated_.begin(), negated_.end(), std::make_pair(param, element)) != negated_.end();
  return negated ? neg(raw) : raw;
}

void Graph::negate_inputs(int param, const std::vector<int>& elements) {
  for (int e : elements) negated_.push_back({param, e});
}

int Graph::constant(double value) {
  Node n;
  n.op = Op::kConst;
  n.value = value == 0 ? 0.0 : value;  // one zero, not two
  return intern(n);
}

int Graph::neg(int a) {
  const Node& x = nodes_[a];
  if (x.op == Op::kConst) return constant(-x.value);
  if (x.op == Op::kNeg) return x.a;
  if (x.op == Op::kSub) return sub(x.b, x.a);
  if (x.op == Op::kMul && nodes_[x.a].op == Op::kConst) return mul(constant(-nodes_[x.a].value), x.b);
  Node n;
  n.op = Op::kNeg;
  n.a = a;
  n.lanes = x.lanes;
  return intern(n);
}

int Graph::add(int a, int b) {
  if (is_const(a, 0)) return b;
  if (is_const(b, 0)) return a;
  if (nodes_[a].op == Op::kConst && nodes_[b].op == Op::kConst) return constant(nodes_[a].value + nodes_[b].value);
  if (nodes_[b].op == Op::kNeg) return sub(a, nodes_[b].a);
  if (nodes_[a].op == Op::kNeg) return sub(b, nodes_[a].a);
  if (a > b) std::swap(a, b);  // commutative: one canonical order for sharing
  return binary(Op::kAdd, a, b);
}

int Graph::sub(int a, int b) {
  if (is_const(b, 0)) return a;
  if (is_const(a, 0)) return neg(b);
  if (a == b) return constant(0);
  if (nodes_[a].op == Op::kConst && nodes_[b].op == Op::kConst) return constant(nodes_[a].value - nodes_[b].value);
  if (nodes_[b].op == Op::kNeg) return add(a, nodes_[b].a);
  return binary(Op::kSub, a, b);
}

int Graph::mul(int a, int b) {
  if (nodes_[b].op == Op::kConst) std::swap(a, b);  // constants first
  if (nodes_[a].op == Op::kConst) {
    const double c = nodes_[a].value;
    if (c == 0) return constant(0);
    if (c == 1) return b;
    if (c == -1) return neg(b);
    if (nodes_[b].op == Op::kConst) return constant(c * nodes_[b].value);
    if (nodes_[b].op == Op::kNeg) return mul(constant(-c), nodes_[b].a);
    if (nodes_[b].op == Op::kMul && nodes_[nodes_[b].a].op == Op::kConst)
      return mul(constant(c * nodes_[nodes_[b].a].value), nodes_[b].b);
  } else {
    if (nodes_[a].op == Op::kNeg) return neg(mul(nodes_[a].a, b));
    if (nodes_[b].op == Op::kNeg) return neg(mul(a, nodes_[b].a));
    if (a > b) std::swap(a, b);
  }
  return binary(Op::kMul, a, b);
}

int Graph::rsqrt(int a) {
  if (nodes_[a].op == Op::kConst) return constant(1 / std::sqrt(nodes_[a].value));
  Node n;
  n.op = Op::kRsqrt;
  n.a = a;
  n.lanes = nodes_[a].lanes;
  return intern(n);
}

int Graph::select_positive(int condition, int if_positive, int otherwise) {
  if (nodes_[condition].op == Op::kConst) return nodes_[condition].value > 0 ? if_positive : otherwise;
  if (if_positive == otherwise) return otherwise;
  Node n;
  n.op = Op::kSelect;
  n.a = condition;
  n.b = if_positive;
  n.c = otherwise;
  n.lanes = std::max(nodes_[if_positive].lanes, nodes_[otherwise].lanes);
  return intern(n);
}

int Graph::linear(const std::vector<std::pair<double, int>>& terms) {
  // Groups in order of first appearance, so output is deterministic and reads like the matrix.
  std::vector<double> magnitudes;
  std::vector<std::vector<std::pair<double, int>>> groups;
  for (const auto& [c, x] : terms) {
    if (c == 0 || is_const(x, 0)) continue;
    const double m = std::abs(c);
    size_t g = 0;
    while (g < magnitudes.size() && std::abs(magnitudes[g] - m) > zhf::tolerance::kSameMagnitude * m) ++g;
    if (g == magnitudes.size()) {
      magnitudes.push_back(m);
      groups.emplace_back();
    }
    groups[g].push_back({c, x});
  }
  int total = constant(0);
  for (size_t g = 0; g < groups.size(); ++g) {
    // Lead with a positive term when there is one: c (x - y) rather than -c (y - x).
    auto& group = groups[g];
    std::stable_partition(group.begin(), group.end(), [](const auto& t) { return t.first > 0; });
    const double lead = group.front().first;
    int inner = constant(0);
    for (const auto& [c, x] : group) inner = (c > 0) == (lead > 0) ? add(inner, x) : sub(inner, x);
    total = add(total, scale(lead, inner));
  }
  return total;
}

std::vector<int> Graph::live(const std::vector<int>& outputs) const {
  std::vector<char> seen(nodes_.size(), 0);
  std::vector<int> stack(outputs.begin(), outputs.end());
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    if (i < 0 || seen[i]) continue;
    seen[i] = 1;
    stack.push_back(nodes_[i].a);
    stack.push_back(nodes_[i].b);
    stack.push_back(nodes_[i].c);
  }
  std::vector<int> order;
  for (int i = 0; i < size(); ++i)
    if (seen[i]) order.push_back(i);
  return order;
}

OpCount Graph::count(const std::vector<int>& outputs) const {
  OpCount count;
  for (int i : live(outputs)) {
    switch (nodes_[i].op) {
      case Op::kMul: ++count.multiplies; break;
      case Op::kAdd:
      case Op::kSub:
      case Op::kNeg: ++count.adds; break;
      case Op::kRsqrt:
      case Op::kSelect: ++count.others; break;
      default: break;
    }
  }
  return count;
}

}  // namespace zhf::codegen
