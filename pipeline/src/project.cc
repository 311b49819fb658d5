#include "zhf/pipeline/project.h"

#include <filesystem>

namespace zhf::pipeline {

runtime::LobeTable Project::table(int order) const {
  if (order == 2) return runtime::lobe_free_table();
  return runtime::read_lobe_table(lobes() + "/order_" + std::to_string(order) + ".json", order);
}

Project project() {
  std::error_code ec;
  const bool here = std::filesystem::is_directory("generated/lobes", ec) && !std::filesystem::is_empty("generated/lobes", ec);
  return Project{here ? "." : ZHF_SOURCE_DIR};
}

}  // namespace zhf::pipeline
