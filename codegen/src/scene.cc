#include "zhf/codegen/scene.h"

#include <algorithm>
#include <set>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"

namespace zhf::codegen {
namespace {

const std::vector<std::string> kVariants = {"standard", "signal-tailored", "batch", "dense-matrix",
                                            "zonal",    "sh-eval",         "lobe-multiplies"};

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw io::InputError(source_ + ": " + field + ": " + what);
  }
  const nlohmann::json& member(const nlohmann::json& object, const std::string& key, const std::string& field) const {
    if (!object.contains(key)) fail(field, "missing");
    return object.at(key);
  }
  int integer(const nlohmann::json& v, const std::string& field, int lo, int hi) const {
    if (!v.is_number_integer()) fail(field, "must be an integer");
    const auto x = v.get<long long>();
    if (x < lo || x > hi)
      fail(field, "must be " + std::to_string(lo) + ".." + std::to_string(hi) + " (got " + std::to_string(x) + ")");
    return static_cast<int>(x);
  }
  std::string text(const nlohmann::json& v, const std::string& field) const {
    if (!v.is_string()) fail(field, "must be a string");
    return v.get<std::string>();
  }
  std::string one_of(const nlohmann::json& v, const std::string& field, const std::vector<std::string>& allowed) const {
    const std::string s = text(v, field);
    if (std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(field, "'" + s + "' is not one of " + list);
    }
    return s;
  }
  const nlohmann::json& array(const nlohmann::json& v, const std::string& field, bool non_empty) const {
    if (!v.is_array()) fail(field, "must be an array");
    if (non_empty && v.empty()) fail(field, "must not be empty");
    return v;
  }

 private:
  std::string source_;
};

}  // namespace

std::vector<int> Scene::orders() const {
  std::set<int> s;
  for (const SceneSignal& signal : signals) s.insert(signal.order);
  return {s.begin(), s.end()};
}

std::map<int, ModuleOptions> Scene::module_options() const {
  std::map<int, ModuleOptions> out;
  for (const SceneSignal& signal : signals) {
    if (!out.count(signal.order)) {
      ModuleOptions none;
      none.sh_eval = none.lobe_multiplies = none.batch = false;
      none.standard_channels.clear();
      none.tailored_channels.clear();
      none.zero_bands = signal.zero_bands;
      none.lobe_precision = lobe_precision;
      out[signal.order] = none;
    }
    ModuleOptions& m = out[signal.order];
    auto add = [](std::vector<int>& list, int channels) {
      if (std::find(list.begin(), list.end(), channels) == list.end()) list.push_back(channels);
    };
    for (const std::string& v : signal.variants) {
      if (v == "standard") add(m.standard_channels, signal.channels);
      if (v == "signal-tailored") add(m.tailored_channels, signal.channels);
      if (v == "batch") m.batch = true;
      if (v == "dense-matrix") add(m.dense_channels, signal.channels);
      if (v == "zonal") add(m.zonal_channels, signal.channels);
      if (v == "sh-eval") m.sh_eval = true;
      if (v == "lobe-multiplies") m.lobe_multiplies = true;
    }
  }
  return out;
}

nlohmann::ordered_json Scene::to_json() const {
  nlohmann::ordered_json j;
  j["format"] = kSceneFormat;
  j["targets"] = targets;
  j["precision"] = precision == Precision::kDouble ? "double" : "float";
  j["lobe_precision"] = lobe_precision_name(lobe_precision);
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const SceneSignal& s : signals)
    list.push_back({{"name", s.name}, {"order", s.order}, {"channels", s.channels}, {"variants", s.variants},
                    {"zero_bands", s.zero_bands}});
  j["signals"] = list;
  return j;
}

Scene parse_scene(const nlohmann::json& j, const std::string& source) {
  const Reader r(source);
  if (!j.is_object()) r.fail("(top level)", "must be a JSON object");
  const std::string format = r.text(r.member(j, "format", "format"), "format");
  if (format != kSceneFormat) r.fail("format", "'" + format + "' is not " + kSceneFormat);
  for (const auto& [key, value] : j.items())
    if (key != "format" && key != "targets" && key != "precision" && key != "lobe_precision" && key != "signals")
      r.fail(key, "unknown field");
  Scene scene;
  const nlohmann::json& targets = r.array(r.member(j, "targets", "targets"), "targets", true);
  for (size_t i = 0; i < targets.size(); ++i) {
    const std::string field = "targets[" + std::to_string(i) + "]";
    const std::string t = r.one_of(targets[i], field, backend_languages());
    if (std::find(scene.targets.begin(), scene.targets.end(), t) != scene.targets.end()) r.fail(field, "'" + t + "' listed twice");
    scene.targets.push_back(t);
  }
  if (j.contains("precision")) {
    const std::string p = r.text(j["precision"], "precision");
    if (p == "half") r.fail("precision", "half is not supported yet (float or double)");
    scene.precision = r.one_of(j["precision"], "precision", {"float", "double"}) == "double" ? Precision::kDouble : Precision::kFloat;
  }
  if (j.contains("lobe_precision"))
    parse_lobe_precision(r.one_of(j["lobe_precision"], "lobe_precision", {"auto", "float", "double"}), scene.lobe_precision);
  const nlohmann::json& signals = r.array(r.member(j, "signals", "signals"), "signals", true);
  std::map<int, std::string> first_of_order;
  for (size_t i = 0; i < signals.size(); ++i) {
    const std::string at = "signals[" + std::to_string(i) + "]";
    const nlohmann::json& s = signals[i];
    if (!s.is_object()) r.fail(at, "must be an object");
    for (const auto& [key, value] : s.items())
      if (key != "name" && key != "order" && key != "channels" && key != "variants" && key != "zero_bands")
        r.fail(at + "." + key, "unknown field");
    SceneSignal signal;
    signal.name = s.contains("name") ? r.text(s["name"], at + ".name") : "signal" + std::to_string(i);
    signal.order = r.integer(r.member(s, "order", at + ".order"), at + ".order", 2, kMaxSceneOrder);
    if (s.contains("channels")) {
      signal.channels = r.integer(s["channels"], at + ".channels", 1, 4);
      if (signal.channels == 2) r.fail(at + ".channels", "must be 1, 3 or 4 (got 2)");
    }
    const nlohmann::json& variants = r.array(r.member(s, "variants", at + ".variants"), at + ".variants", true);
    for (size_t k = 0; k < variants.size(); ++k)
      signal.variants.push_back(r.one_of(variants[k], at + ".variants[" + std::to_string(k) + "]", kVariants));
    if (s.contains("zero_bands")) {
      const nlohmann::json& bands = r.array(s["zero_bands"], at + ".zero_bands", false);
      for (size_t k = 0; k < bands.size(); ++k)
        signal.zero_bands.push_back(r.integer(bands[k], at + ".zero_bands[" + std::to_string(k) + "]", 0, signal.order - 1));
      std::sort(signal.zero_bands.begin(), signal.zero_bands.end());
      if (std::adjacent_find(signal.zero_bands.begin(), signal.zero_bands.end()) != signal.zero_bands.end())
        r.fail(at + ".zero_bands", "lists a band twice");
      if (static_cast<int>(signal.zero_bands.size()) == signal.order) r.fail(at + ".zero_bands", "every band is zero");
    }
    const auto previous = first_of_order.find(signal.order);
    if (previous != first_of_order.end()) {
      for (const SceneSignal& other : scene.signals)
        if (other.order == signal.order && other.zero_bands != signal.zero_bands)
          r.fail(at + ".zero_bands", "differ from signal '" + previous->second + "' of the same order (one kernel file per order)");
    } else {
      first_of_order[signal.order] = signal.name;
    }
    scene.signals.push_back(signal);
  }
  return scene;
}

Scene read_scene(const std::string& path) { return parse_scene(io::read_json_file(path), path); }

}  // namespace zhf::codegen
