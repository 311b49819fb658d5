// zhf needlets: the needlet frame's windows, kernel look-up tables, localisation experiments, and
// the emitted evaluators with their verification (frames/needlets.h, codegen/needlet_lut.h). The
// subcommands run in needlets_*_command(s).cc; this file registers them.
#include <memory>
#include <string>

#include "commands.h"
#include "needlets.h"
#include "options.h"
#include "zhf/codegen/limits.h"
#include "zhf/frames/limits.h"
#include "zhf/healpix/limits.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::cli {
namespace {

const std::string kDilationHelp = "Dilation B, in [" + runtime::format_number(frames::kMinDilation) + ", " +
                                  runtime::format_number(frames::kMaxDilation) + "] (default 2)";
const std::string kTableSizeRange = std::to_string(frames::kMinNeedletTableSize) + ".." + std::to_string(frames::kMaxNeedletTableSize);
const std::string kTableSizeHelp = "Entries per kernel table, " + kTableSizeRange + " (default 1024)";

// --order N (bands 0..N-1, N up to max_top_band + 1) and its old spelling --lmax L (bands 0..L).
void add_band_limit(CLI::App* command, NeedletOptions& o, int max_top_band) {
  CLI::Option* order = command->add_option("--order", o.order, "Bands 0..N-1, N in 1.." + std::to_string(max_top_band + 1));
  CLI::Option* lmax = command->add_option("--lmax", o.lmax, "old spelling: the top band, --order minus 1")->group("");
  old_spellings().push_back({"--lmax", lmax, order, "--order (minus 1)"});
}

}  // namespace

void add_needlets_command(CLI::App& app, Action& action, const std::string& command_line) {
  CLI::App* nc = app.add_subcommand("needlets", "Spherical needlets: windows, kernel tables, tabulated rotation, analysis and synthesis of HEALPix maps");
  nc->require_subcommand(1);
  auto w = std::make_shared<NeedletOptions>();
  CLI::App* wc = nc->add_subcommand("window", "The windows b(l / B^j), every non-zero one for bands 0..lmax, their frame bounds and (--level) localisation");
  wc->add_option("--B", w->dilation, kDilationHelp);
  wc->add_option("--window", w->window, "standard (the C-infinity bump), spline (cubic B-spline step) or mexican (x^(2p) exp(-x^2)); default standard");
  wc->add_option("--mexican-order", w->mexican_order, "p of the Mexican window, 1.." + std::to_string(frames::kMaxMexicanOrder) + " (default 1)");
  wc->add_option("--level", w->level, "Also print level J's kernel energy outside caps of radius k / B^J, k = 1, 2, 4, 8 (J in 0.." +
                     std::to_string(frames::kMaxLocalisationLevel) + ")");
  add_band_limit(wc, *w, frames::kMaxNeedletBand);
  keep_old_spelling(wc, wc->add_option("--out", w->out, "Write the windows here: {\"B\", \"lmax\", \"b\": [[j, l, value], ...]}"), "--json", w->out);
  wc->callback([w, &action] { action = [w] { return run_needlet_window(*w); }; });
  auto an = std::make_shared<NeedletOptions>();
  CLI::App* ac = nc->add_subcommand("analyze", "Needlet coefficients of a HEALPix map, optionally masked");
  ac->add_option("--healpix", an->healpix, "The map (FITS, RING or NESTED; healpy's layout)");
  ac->add_option("--mask", an->mask, "A mask of the same Nside, values in [0, 1], multiplied into the map (UNSEEN pixels need 0)");
  ac->add_option("--iterations", an->iterations, "Jacobi steps of the map's SH projection, 0.." + std::to_string(healpix::kMaxHealpixIterations) + " (default 3)");
  ac->add_option("--B", an->dilation, kDilationHelp);
  add_band_limit(ac, *an, frames::kMaxNeedletFrameBand);
  ac->add_flag("--gauss", an->gauss, "Gauss product cubatures instead of the shipped designs");
  ac->add_option("--out", an->out, std::string("Write the coefficients here (") + kNeedletCoefficientsFormat + ")");
  ac->callback([an, &action] { action = [an] { return run_needlet_analyze(*an); }; });
  auto sy = std::make_shared<NeedletOptions>();
  CLI::App* sc = nc->add_subcommand("synthesize", "A HEALPix map from needlet coefficients (zhf needlets analyze's file)");
  sc->add_option("--in", sy->in, std::string("The coefficients (") + kNeedletCoefficientsFormat + ")");
  keep_old_spelling(sc, sc->add_option("--out", sy->out, "Write the map here (FITS, double values)"), "--healpix-out", sy->out);
  sc->add_option("--nside", sy->nside, "The map's Nside, 1.." + std::to_string(healpix::kMaxHealpixNside));
  sc->add_option("--ordering", sy->ordering, "ring (default) or nested");
  sc->callback([sy, &action] { action = [sy] { return run_needlet_synthesize(*sy); }; });
  auto pr_t = std::make_shared<NeedletOptions>();
  CLI::App* rc = nc->add_subcommand("prt", "Shadowed transfer shaded with SH and with needlets at equal coefficient counts, against the exact integral");
  rc->add_option("--scene", pr_t->scene, "sphere (default; one sphere over the ground), corner (two walls), spheres (three) or open (the ground alone)");
  rc->add_option("--transfer", pr_t->transfer, "diffuse (default) or glossy (Phong lobe, exponent 20)");
  keep_old_spelling(rc, rc->add_option("--image", pr_t->image, "A Radiance .hdr equirectangular sky (row 0 at +z, phi from +x towards +y; default: an analytic sun and sky)"), "--sky", pr_t->image);
  rc->add_option("--side", pr_t->side, "Vertices per side of the ground grid, 1.." + std::to_string(frames::kMaxPrtSide) + " (default 16)");
  rc->add_option("--kept", pr_t->kept, "Coefficient counts K per vertex, e.g. 16,64,256,1024 (the default)");
  rc->add_option("--B", pr_t->dilation, kDilationHelp);
  add_band_limit(rc, *pr_t, frames::kMaxProjectionOrder - 1);
  rc->add_option("--size", pr_t->size, kTableSizeHelp + " (the tabulated rotation of the sky)");
  rc->add_flag("--gauss", pr_t->gauss, "Gauss product cubatures instead of the shipped designs");
  rc->add_option("--out", pr_t->out, "Write the report here (zhf-needlet-prt-1)");
  rc->add_option("--shading-csv", pr_t->shading_csv, "Write each vertex's shading here (x, y, exact, then SH, needlets and SH's best K per K): the images");
  add_threads_option(rc, pr_t->threads);
  add_progress_flags(rc, pr_t->quiet, pr_t->verbose);
  rc->add_option("--csv", pr_t->csv, "Write the error table here (K, SH rms, SH worst, needlet rms, needlet worst, both skies' least values, SH's best-K rms and worst, bytes per vertex of each)");
  rc->callback([pr_t, &action] { action = [pr_t] { return run_needlet_prt(*pr_t); }; });
  auto t = std::make_shared<NeedletOptions>();
  CLI::App* tc = nc->add_subcommand("tables", "The needlet frame of bands 0..lmax: levels, kernel look-up error and tabulated rotation error per table size");
  tc->add_option("--B", t->dilation, kDilationHelp);
  add_band_limit(tc, *t, frames::kMaxNeedletFrameBand);
  tc->add_option("--sizes", t->sizes, "Table sizes, e.g. 64,256,1024 (" + kTableSizeRange + "; default 64,256,1024,4096,16384)");
  tc->add_flag("--gauss", t->gauss, "Gauss product cubatures at every level instead of the shipped designs");
  keep_old_spelling(tc, tc->add_option("--out", t->out, "Write the tables here (zhf-needlet-tables-1)"), "--json", t->out);
  add_progress_flags(tc, t->quiet, t->verbose);
  tc->callback([t, &action] { action = [t] { return run_needlet_tables(*t); }; });
  auto pr = std::make_shared<NeedletOptions>();
  CLI::App* pc = nc->add_subcommand("profile", "One level's needlet against the SH delta of its top band: energy and side lobes outside caps");
  pc->add_option("--B", pr->dilation, kDilationHelp);
  keep_old_spelling(pc, pc->add_option("--level", pr->level, "Level, 0.." + std::to_string(frames::kMaxProfileLevel) + " (default 1)"), "--j", pr->level);
  keep_old_spelling(pc, pc->add_option("--out", pr->out, "Write both profiles against theta here as CSV (degrees, each divided by its peak)"), "--csv", pr->out);
  pc->callback([pr, &action] { action = [pr] { return run_needlet_profile(*pr); }; });
  auto mk = std::make_shared<NeedletOptions>();
  CLI::App* mc = nc->add_subcommand("mask", "A signal cut around the equator: which SH and needlet coefficients the cut disturbs");
  mc->add_option("--B", mk->dilation, kDilationHelp);
  add_band_limit(mc, *mk, frames::kMaxNeedletFrameBand);
  mc->add_option("--cut", mk->cut, "Half-width of the cut band in degrees of latitude, " + runtime::format_number(frames::kMinMaskCut) + ".." +
                                      runtime::format_number(frames::kMaxMaskCut) + " (default 10)");
  mc->add_option("--margin", mk->margin, "Beyond the cut by this many half-wavelengths of the top band (pi / lmax of a level, pi / L for SH), 0.." +
                                            runtime::format_number(frames::kMaxMaskMargin) + " (default 4)");
  mc->add_flag("--gauss", mk->gauss, "Gauss product cubatures instead of the shipped designs");
  mc->callback([mk, &action] { action = [mk] { return run_needlet_mask(*mk); }; });
  auto e = std::make_shared<NeedletOptions>();
  CLI::App* ec = nc->add_subcommand("emit", "Emit a needlet expansion's evaluator (kernel look-up tables) as C++, GLSL, HLSL or WGSL");
  ec->add_option("--B", e->dilation, kDilationHelp);
  add_band_limit(ec, *e, frames::kMaxNeedletFrameBand);
  ec->add_option("--size", e->size, kTableSizeHelp);
  ec->add_option("--interpolation", e->interpolation, "linear (default) or quadratic");
  ec->add_option("--lang", e->lang, "cpp, glsl, hlsl or wgsl")->required();
  ec->add_option("--prefix", e->prefix, "Prefix of every emitted name (default zhf_needlets)");
  ec->add_option("--set", e->set, "Shaders' data buffer: descriptor set / WGSL group, 0.." + std::to_string(codegen::kMaxStorageSet) + " (default 0)");
  ec->add_option("--binding", e->binding, "Shaders' data buffer: binding, 0.." + std::to_string(codegen::kMaxStorageBinding) + " (default 0)");
  ec->add_flag("--gauss", e->gauss, "Gauss product cubatures instead of the shipped designs");
  ec->add_option("--out", e->out, "The file to write")->required();
  ec->add_option("--data", e->data, "Also write the nodes, scales and tables as little-endian float32 (the shaders' storage buffer)");
  ec->callback([e, &action, command_line] { action = [e, command_line] { return run_needlet_emit(*e, command_line); }; });
  auto v = std::make_shared<NeedletOptions>();
  CLI::App* vc = nc->add_subcommand("verify", "Compile and run the emitted needlet evaluators against their CPU mirror and the exact expansion");
  vc->add_option("--B", v->dilation, kDilationHelp);
  add_band_limit(vc, *v, frames::kMaxNeedletFrameBand);
  vc->add_option("--size", v->size, kTableSizeHelp);
  vc->add_option("--interpolation", v->interpolation, "linear (default) or quadratic");
  vc->add_option("--langs", v->langs, "Languages, e.g. cpp,glsl (default cpp,glsl,hlsl,wgsl)");
  vc->add_option("--compiler", v->compiler, "C++ compiler and leading arguments (default $CXX, else c++)");
  vc->add_flag("--gauss", v->gauss, "Gauss product cubatures instead of the shipped designs");
  keep_old_spelling(vc, vc->add_option("--out", v->out, "Write the results here (zhf-needlet-verify-1)"), "--json", v->out);
  add_progress_flags(vc, v->quiet, v->verbose);
  vc->callback([v, &action] { action = [v] { return run_needlet_verify(*v); }; });
}

}  // namespace zhf::cli
