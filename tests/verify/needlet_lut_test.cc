// The emitted needlet evaluators (codegen/needlet_lut.h): compiled and run in C++, GLSL, HLSL and
// WGSL (Vulkan) against their CPU mirror by verify_needlet_lut; the table error falling with the size;
// names and provenance that could break out of the source refused or escaped.
#include <stdexcept>
#include <utility>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/codegen/limits.h"
#include "zhf/codegen/needlet_lut.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/verify/needlets.h"

namespace zhf {
namespace {

TEST(NeedletLut, EveryLanguageMatchesItsMirrorAndTablesConverge) {
  const frames::NeedletFrame frame(2.0, 6);
  for (frames::Interpolation how : {frames::Interpolation::kLinear, frames::Interpolation::kQuadratic}) {
    const char* name = how == frames::Interpolation::kLinear ? "linear" : "quadratic";
    double previous = 1;
    for (int size : {64, 512}) {
      codegen::NeedletLutOptions lut;
      lut.table_size = size;
      lut.interpolation = how;
      lut.command = "needlet_lut_test";
      verify::NeedletLutVerify v;
      v.directions = 256;
      v.naga_wasm = test::source_path("tools/node/node_modules/naga-wasm");
      const std::vector<verify::NeedletLutResult> results = verify::verify_needlet_lut(frame, lut, v);
      ASSERT_EQ(results.size(), codegen::needlet_lut_languages().size());
      for (const verify::NeedletLutResult& r : results) {
        EXPECT_TRUE(r.pass) << r.language << ", " << name << ", size " << size << ": " << r.vs_mirror << " " << r.error;
        EXPECT_LE(r.vs_mirror, zhf::tolerance::kNeedletLutFloat) << r.language << ", " << name << ", size " << size;
      }
      // The table error is the mirror's, the same for every language.
      EXPECT_LT(results.front().table_error, previous) << name << ", size " << size;
      previous = results.front().table_error;
    }
    // Eight times the nodes: linear error / 64, quadratic / 512, give or take the kernel's shape.
    EXPECT_LT(previous, how == frames::Interpolation::kLinear ? 2e-3 : 2e-4) << name;
  }
}

TEST(NeedletLut, NamesAreIdentifiersAndProvenanceIsEscaped) {
  const frames::NeedletFrame frame(2.0, 3);
  codegen::NeedletLutOptions lut;
  lut.table_size = 8;
  for (const char* bad : {"", "9lives", "a;b", "gl_Position", "a__b", "x y", "a\nb", "f(x)"}) {
    lut.prefix = bad;
    std::string why;
    EXPECT_FALSE(codegen::valid_prefix(bad, why)) << bad;
    EXPECT_THROW(codegen::emit_needlet_lut(frame, codegen::Language::kGlsl, lut), std::invalid_argument) << bad;
  }
  lut.prefix = "probe_lighting";
  lut.command = "zhf needlets emit --out 'x\n#error injected' */ \\";
  for (codegen::Language language : codegen::needlet_lut_languages()) {
    const std::string text = codegen::emit_needlet_lut(frame, language, lut).text;
    EXPECT_EQ(text.find("\n#error"), std::string::npos) << codegen::language_name(language);
    EXPECT_EQ(text.find("\\\n"), std::string::npos) << codegen::language_name(language);
    EXPECT_NE(text.find(" probe_lighting_eval("), std::string::npos) << codegen::language_name(language);
  }
  // WGSL has no preprocessor: the data buffer's group and binding are printed as given, in range.
  lut.storage_set = 2;
  lut.storage_binding = 17;
  EXPECT_NE(codegen::emit_needlet_lut(frame, codegen::Language::kWgsl, lut).text.find("@group(2) @binding(17) var<storage, read> probe_lighting_data"),
            std::string::npos);
  EXPECT_NE(codegen::emit_needlet_lut(frame, codegen::Language::kGlsl, lut).text.find("#define PROBE_LIGHTING_BINDING 17\n"), std::string::npos);
  for (const auto& [set, binding] : {std::pair{-1, 0}, std::pair{codegen::kMaxStorageSet + 1, 0}, std::pair{0, -1},
                                     std::pair{0, codegen::kMaxStorageBinding + 1}}) {
    lut.storage_set = set;
    lut.storage_binding = binding;
    EXPECT_THROW(codegen::emit_needlet_lut(frame, codegen::Language::kWgsl, lut), std::invalid_argument) << set << " " << binding;
  }
  lut.storage_set = lut.storage_binding = 0;
  lut.table_size = 2;
  EXPECT_THROW(codegen::emit_needlet_lut(frame, codegen::Language::kCpp, lut), std::invalid_argument);
}

}  // namespace
}  // namespace zhf
