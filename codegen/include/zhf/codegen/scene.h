// A scene spec: the SH signals a renderer rotates, and so the only kernels it needs.
//
//   {
//     "format": "zhf-scene-1",
//     "targets": ["glsl"],            // any of cpp, hlsl, glsl, wgsl
//     "precision": "float",           // float or double (shaders; C++ kernels are templates)
//     "lobe_stage": "auto",           // auto, float, double-rotation or double: where float
//                                     // kernels run the lobe stage (runtime/lobe_stage.h); optional
//     "method": "auto",               // auto, zhf, zxzxz or quadratic: how rotations rotate each band >= 2
//                                     // (kernels.h; zhf emit --method); optional
//     "signals": [
//       {"name": "lighting", "order": 3, "channels": 3, "variants": ["standard"]},
//       {"name": "transfer", "order": 5, "channels": 1, "variants": ["signal-tailored"],
//        "zero_bands": [1, 3]}
//     ]
//   }
//
// variants: standard, signal-tailored, batch (C++, one channel plane per call), dense-matrix
// (build once, apply many), zonal (the signal is zonal: N^2 work, no lobes), sh-eval,
// lobe-multiplies, products (product_orderN and square_orderN: SH products of signals of the
// order, single channel), shading (shade_orderN: the signal rotated and integrated against a
// transfer vector; shade_lobes_orderN too with lobe-multiplies). zero_bands: bands known to be zero; their outputs are 0 and cost nothing.
// Signals of the same order share one file per language and must agree on zero_bands.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/codegen/backend.h"
#include "zhf/io/json.h"
#include "zhf/runtime/limits.h"

namespace zhf::codegen {

struct SceneSignal {
  std::string name;
  int order = 0;
  int channels = 1;
  std::vector<std::string> variants;
  std::vector<int> zero_bands;
};

struct Scene {
  std::vector<Language> targets;
  Precision precision = Precision::kFloat;
  std::optional<runtime::LobeStage> lobe_stage;  // none: auto
  std::optional<BandMethod> method;              // none: auto
  std::vector<SceneSignal> signals;

  std::vector<int> orders() const;                   // sorted, unique
  std::map<int, ModuleOptions> module_options() const;  // per order: exactly what the signals need
  nlohmann::ordered_json to_json() const;
};

inline constexpr const char* kSceneFormat = "zhf-scene-1";

// Throws io::InputError naming the file and field, e.g. "scene.json: signals[1].channels: must
// be 1, 3 or 4 (got 2)".
Scene parse_scene(const io::json::Json& root, const std::string& source);
Scene read_scene(const std::string& path);

}  // namespace zhf::codegen
