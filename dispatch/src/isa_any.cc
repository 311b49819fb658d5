// Any order on one instruction-set path (isa_unit.h): the generated orders' units (isa_order.cc),
// zxzxz beyond them.
#include "isa_unit.h"

template <>
std::unique_ptr<zhf_dispatch_api::Backend<float>> zhf_dispatch_api::make_backend<zhf::dispatch_unit::kIsa, float>(int order) {
  return zhf::dispatch_unit::any_order<float>(order);
}

template <>
std::unique_ptr<zhf_dispatch_api::Backend<double>> zhf_dispatch_api::make_backend<zhf::dispatch_unit::kIsa, double>(int order) {
  return zhf::dispatch_unit::any_order<double>(order);
}
