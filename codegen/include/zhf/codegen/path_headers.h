// The C++ headers a full tree adds to its kernel files: zhf_paths.h, the fastest verified rotation
// path per order for the instruction set the header is compiled for (from the measured path
// tables), with the kernels and rotator of one order on it; and zhf_kernels.h, every generated
// order reachable at run time.
#pragma once

#include <string>
#include <vector>

#include "zhf/codegen/backend.h"
#include "zhf/codegen/path_tables.h"

namespace zhf::codegen {

// orders: the orders with kernel files (zhf_orderN.h); lanes_orders: those with lanes tables
// (zhf_lanes_orderN.h); tables: the measured path tables (read_path_tables).
EmittedFile emit_paths_header(const std::vector<int>& orders, const std::vector<int>& lanes_orders, const std::vector<PathTable>& tables,
                              const std::string& command);
EmittedFile emit_dispatch_header(const std::vector<int>& orders, const std::string& command);

}  // namespace zhf::codegen
