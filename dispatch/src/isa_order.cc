// One generated order (ZHF_DISPATCH_ORDER, its kernels in ZHF_DISPATCH_ORDER_HEADER) on one
// instruction-set path (isa_unit.h): only that order's kernels are parsed here.
#include "isa_unit.h"
#include ZHF_DISPATCH_ORDER_HEADER

template <>
std::unique_ptr<zhf_dispatch_api::Backend<float>> zhf_dispatch_api::make_generated<zhf::dispatch_unit::kIsa, ZHF_DISPATCH_ORDER, float>() {
  return zhf::dispatch_unit::generated<ZHF_DISPATCH_ORDER, float>();
}

template <>
std::unique_ptr<zhf_dispatch_api::Backend<double>> zhf_dispatch_api::make_generated<zhf::dispatch_unit::kIsa, ZHF_DISPATCH_ORDER, double>() {
  return zhf::dispatch_unit::generated<ZHF_DISPATCH_ORDER, double>();
}
