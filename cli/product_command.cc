#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "zhf/io/coefficients.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/gaunt.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/product.h"

namespace zhf::cli {
namespace {

struct ProductOptions {
  std::string lhs, rhs;
  int channels = 0;
  int order = 0;
  std::string out;
};

// The vectors of a side padded with zeros to the working order.
std::vector<double> padded(const std::vector<double>& v, int order) {
  std::vector<double> out(static_cast<size_t>(order) * order, 0.0);
  std::copy(v.begin(), v.end(), out.begin());
  return out;
}

int run_product(const ProductOptions& o) {
  io::PendingFile out_file(o.out);  // refuse an unwritable output before the work
  const io::CoefficientFile f = io::read_coefficients(o.lhs, o.channels);
  const io::CoefficientFile g = io::read_coefficients(o.rhs, o.channels);
  const int max_order = runtime::kMaxGauntOrder;
  for (const auto* side : {&f, &g})
    if (side->order > max_order)
      throw io::InputError((side == &f ? o.lhs : o.rhs) + ": order " + std::to_string(side->order) + " is above " +
                           std::to_string(max_order) + ", the largest product order");
  // A one-channel side (a visibility, a grey transfer) multiplies every channel of the other.
  if (f.channels != g.channels && f.channels != 1 && g.channels != 1)
    throw io::InputError(o.rhs + ": " + std::to_string(g.channels) + " channels, where " + o.lhs + " has " +
                         std::to_string(f.channels) + " (one side may have a single channel, used for every channel of the other)");
  const int channels_out = std::max(f.channels, g.channels);
  const size_t f_vectors = f.signals.size() / f.channels, g_vectors = g.signals.size() / g.channels;
  if (f_vectors != g_vectors && f_vectors != 1 && g_vectors != 1)
    throw io::InputError(o.rhs + ": " + std::to_string(g_vectors) + " vectors, where " + o.lhs + " has " + std::to_string(f_vectors) +
                         " (one side may hold a single vector, used with every vector of the other)");
  // The product of orders a and b has order a + b - 1; h is it projected to the order asked for.
  const int order = o.order ? o.order : std::max(f.order, g.order);
  const int work = std::max({order, f.order, g.order});
  const runtime::ShProduct product(work);
  const size_t n = static_cast<size_t>(order) * order;
  std::vector<double> h(static_cast<size_t>(work) * work);
  nlohmann::ordered_json vectors = nlohmann::ordered_json::array();
  for (size_t v = 0; v < std::max(f_vectors, g_vectors); ++v) {
    nlohmann::ordered_json channels = nlohmann::ordered_json::array();
    for (int c = 0; c < channels_out; ++c) {
      const std::vector<double> a = padded(f.signals[(f_vectors == 1 ? 0 : v) * f.channels + (f.channels == 1 ? 0 : c)], work);
      const std::vector<double> b = padded(g.signals[(g_vectors == 1 ? 0 : v) * g.channels + (g.channels == 1 ? 0 : c)], work);
      product.product(a.data(), b.data(), h.data());
      channels.push_back(std::vector<double>(h.begin(), h.begin() + n));
    }
    vectors.push_back(channels_out == 1 ? channels[0] : channels);
    io::throw_if_interrupted();
  }
  out_file.write(io::json_text(vectors));
  io::throw_if_interrupted();
  out_file.commit();
  std::printf("multiplied %s (orders %d and %d, projected to %d, %s) into %s\n", counted(vectors.size(), "vector pair").c_str(),
              f.order, g.order, order, counted(channels_out, "channel").c_str(), o.out.c_str());
  return kExitOk;
}

}  // namespace

void add_product_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<ProductOptions>();
  CLI::App* c = app.add_subcommand("product", "Multiply SH functions and project the product back to an order (double precision)");
  c->add_option("--lhs", o->lhs, "Coefficient vectors of f (JSON array or text; as zhf analyze reads them)")->required();
  c->add_option("--rhs", o->rhs, "Coefficient vectors of g: as many as f, or one for every f")->required();
  c->add_option("--channels", o->channels, "Channels per vector (products are taken channel by channel)")->check(CLI::Range(1, io::kMaxChannels));
  c->add_option("--order", o->order, "Order of the result h = P_N(f g) (default: the larger input order)")
      ->check(CLI::Range(1, runtime::kMaxGauntOrder));
  c->add_option("--out", o->out, "Write the products here (JSON)")->required();
  c->callback([o, &action] { action = [o] { return run_product(*o); }; });
}

}  // namespace zhf::cli
