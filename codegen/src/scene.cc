#include "zhf/codegen/scene.h"

#include <algorithm>
#include <set>
#include <string_view>

#include "zhf/codegen/limits.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/runtime/limits.h"

namespace zhf::codegen {
namespace {

// The variant names a scene may list, in the order they are documented.
const std::initializer_list<std::string_view> kVariants = {"standard", "signal-tailored", "batch", "dense-matrix",
                                                           "zonal",    "sh-eval",         "lobe-multiplies", "products",
                                                           "shading"};

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
      none.sh_eval = none.lobe_multiplies = none.batch = none.products = none.shading = false;
      none.standard_channels.clear();
      none.tailored_channels.clear();
      none.zero_bands = signal.zero_bands;
      none.lobe_stage = lobe_stage;
      none.band_method = method;
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
      if (v == "products") m.products = true;
      if (v == "shading") m.shading = true;
    }
  }
  return out;
}

nlohmann::ordered_json Scene::to_json() const {
  nlohmann::ordered_json j;
  j["format"] = kSceneFormat;
  nlohmann::ordered_json names = nlohmann::ordered_json::array();
  for (Language t : targets) names.push_back(language_name(t));
  j["targets"] = names;
  j["precision"] = precision == Precision::kDouble ? "double" : "float";
  j["lobe_stage"] = lobe_stage_choice_name(lobe_stage);
  j["method"] = band_method_choice_name(method);
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const SceneSignal& s : signals)
    list.push_back({{"name", s.name}, {"order", s.order}, {"channels", s.channels}, {"variants", s.variants},
                    {"zero_bands", s.zero_bands}});
  j["signals"] = list;
  return j;
}

Scene parse_scene(const io::json::Json& root, const std::string& source) {
  using io::json::Field;
  const Field top(root, source);
  top.allow_only({"format", "targets", "precision", "lobe_stage", "method", "signals"});
  const Field format = top.member("format");
  if (format.string() != kSceneFormat) format.fail("'" + io::excerpt(format.string()) + "' is not " + kSceneFormat);
  Scene scene;
  for (const Field& target : top.member("targets").items(1, all_languages().size())) {
    Language t = Language::kCpp;
    if (!parse_language(target.string(), t)) {
      std::string names;
      for (Language l : all_languages()) names += (names.empty() ? "" : ", ") + std::string(language_name(l));
      target.fail("'" + io::excerpt(target.string()) + "' is not one of " + names);
    }
    if (std::find(scene.targets.begin(), scene.targets.end(), t) != scene.targets.end())
      target.fail("'" + std::string(language_name(t)) + "' listed twice");
    scene.targets.push_back(t);
  }
  if (const auto precision = top.find("precision")) {
    if (precision->string() == "half") precision->fail("half is not supported yet (float or double)");
    scene.precision = precision->one_of({"float", "double"}) == "double" ? Precision::kDouble : Precision::kFloat;
    for (Language t : scene.targets)
      if (scene.precision == Precision::kDouble && !make_backend(t)->has_double())
        precision->fail(std::string("double, but target ") + language_name(t) + " has no double type");
  }
  if (const auto stage = top.find("lobe_stage")) parse_lobe_stage_choice(stage->one_of(lobe_stage_choices()), scene.lobe_stage);
  if (const auto method = top.find("method")) parse_band_method_choice(method->one_of(band_method_choices()), scene.method);
  std::map<int, std::string> first_of_order;
  const std::vector<Field> signals = top.member("signals").items(1, codegen::kMaxSceneSignals);
  for (size_t i = 0; i < signals.size(); ++i) {
    const Field& s = signals[i];
    s.allow_only({"name", "order", "channels", "variants", "zero_bands"});
    SceneSignal signal;
    signal.name = "signal" + std::to_string(i);
    if (const auto name = s.find("name")) {
      signal.name = name->string();
      if (signal.name.empty() || signal.name.size() > 64 || !runtime::is_printable_text(signal.name))
        name->fail("must be 1 to 64 printable characters");
    }
    signal.order = s.member("order").integer(runtime::kMinGeneratedOrder, codegen::kMaxEmitOrder);
    if (const auto channels = s.find("channels")) {
      signal.channels = channels->integer(1, io::kMaxChannels);
      if (signal.channels == 2) channels->fail("must be 1, 3 or 4 (got 2)");
    }
    for (const Field& variant : s.member("variants").items(1, kVariants.size())) signal.variants.push_back(variant.one_of(kVariants));
    if (const auto bands = s.find("zero_bands")) {
      for (const Field& band : bands->items(0, signal.order)) signal.zero_bands.push_back(band.integer(0, signal.order - 1));
      std::sort(signal.zero_bands.begin(), signal.zero_bands.end());
      if (std::adjacent_find(signal.zero_bands.begin(), signal.zero_bands.end()) != signal.zero_bands.end())
        bands->fail("lists a band twice");
      if (static_cast<int>(signal.zero_bands.size()) == signal.order) bands->fail("every band is zero");
    }
    const auto previous = first_of_order.find(signal.order);
    if (previous != first_of_order.end()) {
      for (const SceneSignal& other : scene.signals)
        if (other.order == signal.order && other.zero_bands != signal.zero_bands)
          throw io::InputError(source + ": " + s.where() + ".zero_bands: differ from signal '" + io::excerpt(previous->second) +
                               "' of the same order (one kernel file per order)");
    } else {
      first_of_order[signal.order] = signal.name;
    }
    scene.signals.push_back(signal);
  }
  return scene;
}

Scene read_scene(const std::string& path) {
  return parse_scene(io::json::read_file(path, codegen::kMaxSceneBytes), path);
}

}  // namespace zhf::codegen
