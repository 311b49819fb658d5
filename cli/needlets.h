// zhf needlets, shared by the files of its subcommands: the options, their parsing, and each
// subcommand's run function; needlets_command.cc registers them.
#pragma once

#include <string>

#include "zhf/codegen/backend.h"
#include "zhf/codegen/needlet_lut.h"
#include "zhf/frames/needlets.h"

namespace zhf::cli {

struct NeedletOptions {
  std::string dilation = "2", order, lmax, sizes = "64,256,1024,4096,16384";
  bool gauss = false;
  std::string size = "1024", interpolation = "linear", lang, langs = "cpp,glsl,hlsl,wgsl", prefix = "zhf_needlets", compiler;
  std::string set = "0", binding = "0";
  std::string out, data;
  std::string cut = "10", margin = "4";
  std::string window = "standard", mexican_order = "1", level;
  std::string healpix, mask, iterations = "3", in, nside, ordering = "ring";
  std::string scene = "sphere", transfer = "diffuse", image, side = "16", kept = "16,64,256,1024", csv, shading_csv;
  std::string threads = "0";
  bool quiet = false, verbose = false;
};

inline constexpr const char* kNeedletCoefficientsFormat = "zhf-needlet-coefficients-1";

// The top band L of a needlet command's signals, in [lo, hi]: --order N means bands 0..N-1 (as in
// every command), the old --lmax L bands 0..L.
int top_band(const NeedletOptions& o, int lo, int hi);
double dilation_option(const std::string& text);
// Each level on the smallest shipped design exact for it, or on Gauss product nodes.
frames::NeedletFrame needlet_frame(double dilation, int lmax, bool gauss);
codegen::NeedletLutOptions lut_options(const NeedletOptions& o, const std::string& command);
// A language the needlet evaluators are emitted in, refused naming option.
codegen::Language language_option(const std::string& option, const std::string& name);

// needlets_emit_commands.cc
int run_needlet_emit(const NeedletOptions& o, const std::string& command);
int run_needlet_verify(const NeedletOptions& o);
// needlets_frame_commands.cc
int run_needlet_window(const NeedletOptions& o);
int run_needlet_tables(const NeedletOptions& o);
int run_needlet_profile(const NeedletOptions& o);
int run_needlet_mask(const NeedletOptions& o);
// needlets_map_commands.cc
int run_needlet_analyze(const NeedletOptions& o);
int run_needlet_synthesize(const NeedletOptions& o);
// needlets_prt_command.cc
int run_needlet_prt(const NeedletOptions& o);

}  // namespace zhf::cli
