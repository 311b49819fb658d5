#include "zhf/codegen/backend.h"

namespace zhf::codegen {

const std::vector<Language>& all_languages() {
  static const std::vector<Language> languages = {
#define ZHF_LANGUAGE(Enum, id, name) Language::Enum,
#include "zhf/codegen/languages.def"
#undef ZHF_LANGUAGE
  };
  return languages;
}

const char* language_name(Language language) {
  switch (language) {
#define ZHF_LANGUAGE(Enum, id, name) \
  case Language::Enum:               \
    return name;
#include "zhf/codegen/languages.def"
#undef ZHF_LANGUAGE
  }
  return "?";
}

bool parse_language(const std::string& name, Language& language) {
  for (Language l : all_languages())
    if (name == language_name(l)) {
      language = l;
      return true;
    }
  return false;
}

std::unique_ptr<Backend> make_backend(Language language) {
  switch (language) {
#define ZHF_LANGUAGE(Enum, id, name) \
  case Language::Enum:               \
    return make_##id##_backend();
#include "zhf/codegen/languages.def"
#undef ZHF_LANGUAGE
  }
  return nullptr;
}

}  // namespace zhf::codegen
