// One backend per language, all behind one interface: each prints the same Module (kernels.h)
// with the shared C-family printer and its own small LanguageConfig. The languages are listed
// once, in languages.def.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "zhf/codegen/kernels.h"

namespace zhf::codegen {

enum class Language {
#define ZHF_LANGUAGE(Enum, id, name) Enum,
#include "zhf/codegen/languages.def"
#undef ZHF_LANGUAGE
};

const std::vector<Language>& all_languages();
const char* language_name(Language language);
// False for a name no backend has.
bool parse_language(const std::string& name, Language& language);

// Shaders are emitted in float or double; C++ kernels are templates on the scalar type.
enum class Precision { kFloat, kDouble };

struct EmitOptions {
  Precision precision = Precision::kFloat;
  std::string command;     // recorded in the banner
  std::string table_path;  // where the lobe table came from, for the derivation comment
};

struct EmittedFunction {
  std::string name;
  KernelKind kind = KernelKind::kRotate;
  int channels = 1;
  OpCount ops;  // as printed (a vector operation counts once)
};

struct EmittedFile {
  std::string file_name;  // relative to the language's output directory
  std::string text;
  std::vector<EmittedFunction> functions;
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual Language language() const = 0;
  // False where the language has no double type: its files print every node in float and run
  // their lobe stage in float, whatever the module's.
  virtual bool has_double() const { return true; }
  // Prints a module; a backend refuses (std::invalid_argument) a module kind it has no layout for.
  virtual EmittedFile emit(const Module& module, const EmitOptions& options) const = 0;
};

#define ZHF_LANGUAGE(Enum, id, name) std::unique_ptr<Backend> make_##id##_backend();
#include "zhf/codegen/languages.def"
#undef ZHF_LANGUAGE

std::unique_ptr<Backend> make_backend(Language language);

}  // namespace zhf::codegen
