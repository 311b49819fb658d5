// WGSL: the wrapper in WGSL, turned into SPIR-V by naga (naga-wasm under Node; shader_runner.cc).
#include "shader_runner.h"

namespace zhf::verify {

std::unique_ptr<Runner> make_wgsl_runner() { return make_shader_runner(wgsl_dialect()); }

}  // namespace zhf::verify
