// Writing lobe tables (the format and the reader: runtime/lobe_table.h). What is written always
// reads back: the table is validated first.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "zhf/runtime/lobe_table.h"

namespace zhf::io {

// The table as JSON: fields in the documented order, structural zeros as the integer 0,
// provenance keys in alphabetical order (the same command gives the same bytes).
nlohmann::ordered_json lobe_table_json(const runtime::LobeTable& table);

// Validates (InputError naming `source` if the table does not hold together) and returns the
// file's text.
std::string lobe_table_text(const runtime::LobeTable& table, const std::string& source);

}  // namespace zhf::io
