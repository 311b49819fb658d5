// Between the kernel builder (kernels.cc) and the cost model (cost_model.cc): the builder counts
// the kernels the model compares, and the model picks the methods the builder uses.
#pragma once

#include <string>
#include <vector>

#include "zhf/codegen/kernels.h"
#include "zhf/sh/reference_rotation.h"

namespace zhf::codegen {

// The operations of rotate_orderN (one channel) with each band >= 2 rotated by methods[l], built
// as build_module builds it.
OpCount rotation_op_count(const Module& module, const ModuleOptions& options, const std::vector<BandMethod>& methods,
                          const sh::BandMatrices& quarter_turn);
// The lobe-set-dependent part of rotate_orderN with every band by lobes (lobe_dependent_multiplies).
OpCount lobe_dependent_op_count(const runtime::LobeTable& table);

// The assignment of methods to the bands of module's order whose rotate_orderN has the fewest
// operations; reason says what was compared.
std::vector<BandMethod> cheapest_band_methods(const Module& module, const ModuleOptions& options,
                                              const sh::BandMatrices& quarter_turn, std::string& reason);

}  // namespace zhf::codegen
