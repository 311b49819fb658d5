// zhf needlets emit and verify: the needlet evaluators as source, and their check against the CPU
// mirror and the exact expansion.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "needlets.h"
#include "options.h"
#include "progress.h"
#include "zhf/frames/limits.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/data_root.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/verify/needlets.h"

namespace zhf::cli {

int run_needlet_emit(const NeedletOptions& o, const std::string& command) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = top_band(o, 1, frames::kMaxNeedletFrameBand);
  const codegen::NeedletLutOptions lut = lut_options(o, command);
  const codegen::Language language = language_option("--lang", o.lang);
  // The evaluator and its data are one result: both are written, or neither.
  io::PendingFiles outputs;
  io::PendingFile& out = outputs.add(o.out);
  io::PendingFile* data = o.data.empty() ? nullptr : &outputs.add(o.data);
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  const codegen::EmittedFile file = codegen::emit_needlet_lut(frame, language, lut);
  out.write(file.text);
  if (data) {
    const std::vector<float> values = codegen::needlet_lut_data(frame, lut.table_size);
    std::string bytes(values.size() * sizeof(float), '\0');
    for (std::size_t i = 0; i < values.size(); ++i) {  // little-endian float32, whatever the host
      std::uint32_t word;
      std::memcpy(&word, &values[i], sizeof word);
      for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<char>((word >> (8 * b)) & 0xff);
    }
    data->write(bytes);
  }
  outputs.commit();
  std::printf("%s: %s, %d multiplies and %d adds per evaluation\n", o.out.c_str(), file.functions[0].name.c_str(),
              file.functions[0].ops.multiplies, file.functions[0].ops.adds);
  return kExitOk;
}
int run_needlet_verify(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = top_band(o, 1, frames::kMaxNeedletFrameBand);
  const codegen::NeedletLutOptions lut = lut_options(o, "zhf needlets verify");
  verify::NeedletLutVerify v;
  v.languages.clear();
  for (std::size_t start = 0; start <= o.langs.size();) {
    const std::size_t comma = std::min(o.langs.find(',', start), o.langs.size());
    const codegen::Language language = language_option("--langs", o.langs.substr(start, comma - start));
    if (std::find(v.languages.begin(), v.languages.end(), language) != v.languages.end())
      throw UsageError("--langs: '" + o.langs.substr(start, comma - start) + "' is listed twice");
    v.languages.push_back(language);
    start = comma + 1;
  }
  v.compiler = o.compiler;
  v.naga_wasm = pipeline::data_root().naga_wasm();
  Progress progress("needlets verify", o.quiet, o.verbose);
  v.checkpoint = [&progress](std::size_t done, std::size_t languages) {
    io::throw_if_interrupted();
    progress.update(double(done), double(languages), "languages compiled and run");
  };
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  const std::vector<verify::NeedletLutResult> results = verify::verify_needlet_lut(frame, lut, v);
  io::throw_if_interrupted();
  progress.done();
  std::printf("needlet frame B = %g, bands 0..%d, %d coefficients; %d-entry tables, %s\n", dilation, lmax, frame.size(), lut.table_size,
              o.interpolation.c_str());
  std::printf("%-6s %14s %14s  %s\n", "lang", "vs mirror", "table error", "result");
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  bool pass = true, no_device = false;
  for (const verify::NeedletLutResult& r : results) {
    std::printf("%-6s %14.3e %14.3e  %s\n", r.language.c_str(), r.vs_mirror, r.table_error,
                r.pass ? "pass" : ("FAIL" + (r.error.empty() ? "" : ": " + r.error)).c_str());
    pass = pass && r.pass;
    no_device = no_device || r.error.rfind("no Vulkan device", 0) == 0;
    rows.push_back({{"language", r.language}, {"vs_mirror", r.vs_mirror}, {"table_error", r.table_error}, {"pass", r.pass},
                    {"error", r.error}});
  }
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-needlet-verify-1"},
                                                    {"B", dilation},
                                                    {"lmax", lmax},
                                                    {"size", lut.table_size},
                                                    {"interpolation", o.interpolation},
                                                    {"tolerance", zhf::tolerance::kNeedletLutFloat},
                                                    {"results", rows}}));
    out->commit();
  }
  return pass ? kExitOk : no_device ? kExitNoDevice : kExitFailure;
}

}  // namespace zhf::cli
