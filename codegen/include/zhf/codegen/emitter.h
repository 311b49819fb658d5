// One emitter interface, one backend per language. Every backend prints the same Module
// (kernels.h) with the shared C-family printer and its own small LanguageConfig; see
// codegen/README.md for adding one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "zhf/codegen/kernels.h"

namespace zhf::codegen {

enum class Precision { kFloat, kDouble };

struct EmitOptions {
  Precision precision = Precision::kFloat;  // shaders; C++ kernels are templates on T
  std::string command;                      // recorded in the banner
  std::string table_path;                   // where the lobe table came from, for the derivation comment
};

struct FunctionCount {
  std::string name;
  OpCount ops;
};

struct EmittedFile {
  std::string file_name;  // relative to the language's output directory
  std::string text;
  std::vector<FunctionCount> counts;
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string language() const = 0;  // "cpp", "hlsl", "glsl"
  virtual EmittedFile emit(const Module& module, const EmitOptions& options) const = 0;
};

// "cpp", "hlsl" or "glsl"; nullptr otherwise.
std::unique_ptr<Backend> make_backend(const std::string& language);
std::vector<std::string> backend_languages();

}  // namespace zhf::codegen
