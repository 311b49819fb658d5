// Tests of the compiled library (zhf::dispatch) on every instruction-set path this CPU runs.
#pragma once

#include <string>
#include <vector>

#include "zhf/dispatch/isa.h"

namespace zhf::test {

// Calls check(path name) with each path forced in turn, fastest first; the fastest is in force
// again afterwards, also when check stops early.
template <class Check>
void on_every_dispatch_path(Check&& check) {
  const std::vector<dispatch::Isa> isas = dispatch::supported_isas();
  struct Restore {
    dispatch::Isa fastest;
    ~Restore() { dispatch::use_isa(dispatch::isa_name(fastest)); }
  } restore{isas.front()};
  for (dispatch::Isa isa : isas) {
    dispatch::use_isa(dispatch::isa_name(isa));
    check(std::string(dispatch::isa_name(isa)));
  }
}

}  // namespace zhf::test
