// PlayCanvas's SOG, built here from its layout (meta.json and lossless WebP images, libwebp linked
// into this test) and read by zhf splat: every field as the layout says. A SOG turned into a SOG:
// positions and orientations per splat within the 16-bit and 8-bit steps, the SH palette turned
// once against the double reference, labels, scales and colours carried byte for byte. Hostile
// SOGs are refused in one line with nothing written.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <webp/encode.h>
#include <zlib.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/io/ply.h"
#include "zhf/runtime/rotation.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;

constexpr int kBands = 2, kCoefficients = 8, kPalette = 100;
// A turned quaternion's matrix entries: its components are 8-bit (steps of sqrt(2) / 255 before
// the largest is rebuilt), so an entry moves by a few steps at most.
const double kQuaternionEntry = 4 * 2 / 255.0;
// A log-scale codebook entry plus log s, rounded to float twice (codebook, .ply), values below 8.
constexpr double kShiftedLogScale = 16 * tolerance::kSplatFloatStorage;
// A codebook level, or an alpha byte's value, read back through the .ply's float (values below 8).
constexpr double kReadBackLevel = 16 * tolerance::kSplatFloatStorage;

// A SOG's content, made here: n splats, kPalette palette entries, codebooks of 256.
struct Built {
  int n = 0, width = 0, height = 0;
  std::vector<double> scales, colours, sh;
  std::array<double, 3> mins{}, maxs{};
  std::vector<std::array<unsigned char, 4>> low, high, quats, scale_bytes, sh0, labels;
  std::vector<std::array<unsigned char, 4>> centroids;  // 64 K x rows
  nlohmann::json meta;
};

std::string webp(const std::vector<std::array<unsigned char, 4>>& texels, int width, int height) {
  std::vector<unsigned char> rgba(std::size_t(width) * height * 4, 255);
  for (std::size_t i = 0; i < std::min(texels.size(), rgba.size() / 4); ++i) std::memcpy(&rgba[4 * i], texels[i].data(), 4);
  std::uint8_t* out = nullptr;
  const std::size_t size = WebPEncodeLosslessRGBA(rgba.data(), width, height, width * 4, &out);
  std::string bytes(reinterpret_cast<const char*>(out), size);
  WebPFree(out);
  return bytes;
}

Built build(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto byte = [&] { return static_cast<unsigned char>(rng() >> 56); };
  Built b;
  b.n = n;
  b.width = int(std::ceil(std::sqrt(double(n)) / 4)) * 4;
  b.height = int((n + b.width * 4 - 1) / (b.width * 4)) * 4;
  for (int k = 0; k < 256; ++k) {
    b.scales.push_back(double(float(-8 + 10.0 * k / 255)));
    b.colours.push_back(double(float(-2 + 4.0 * k / 255)));
    b.sh.push_back(double(float(-0.9 + 1.8 * k / 255)));
  }
  b.mins = {-3, -2, -4};
  b.maxs = {3, 2.5, 1};
  for (int i = 0; i < n; ++i) {
    b.low.push_back({byte(), byte(), byte(), 255});
    b.high.push_back({byte(), byte(), byte(), 255});
    b.quats.push_back({byte(), byte(), byte(), static_cast<unsigned char>(252 + (rng() >> 62))});
    b.scale_bytes.push_back({byte(), byte(), byte(), 255});
    b.sh0.push_back({byte(), byte(), byte(), static_cast<unsigned char>(1 + (rng() >> 57) % 254)});
    const int label = int(rng() % kPalette);
    b.labels.push_back({static_cast<unsigned char>(label & 0xff), static_cast<unsigned char>(label >> 8), 0, 255});
  }
  b.centroids.assign(64 * kCoefficients * ((kPalette + 63) / 64), {0, 0, 0, 255});
  for (int e = 0; e < kPalette; ++e)
    for (int j = 0; j < kCoefficients; ++j) b.centroids[(e / 64) * 64 * kCoefficients + (e % 64) * kCoefficients + j] = {byte(), byte(), byte(), 255};
  b.meta = {{"version", 2},
            {"asset", {{"generator", "zhf test"}}},
            {"count", n},
            {"means", {{"mins", b.mins}, {"maxs", b.maxs}, {"files", {"means_l.webp", "means_u.webp"}}}},
            {"scales", {{"codebook", b.scales}, {"files", {"scales.webp"}}}},
            {"quats", {{"files", {"quats.webp"}}}},
            {"sh0", {{"codebook", b.colours}, {"files", {"sh0.webp"}}}},
            {"shN", {{"count", kPalette}, {"bands", kBands}, {"codebook", b.sh}, {"files", {"shN_centroids.webp", "shN_labels.webp"}}}}};
  return b;
}

// The SOG's files beside its meta.json in `dir`; returns meta.json's path.
std::string write_unbundled(const Built& b, const fs::path& dir, const nlohmann::json& meta) {
  fs::create_directories(dir);
  test::write_text((dir / "means_l.webp").string(), webp(b.low, b.width, b.height));
  test::write_text((dir / "means_u.webp").string(), webp(b.high, b.width, b.height));
  test::write_text((dir / "quats.webp").string(), webp(b.quats, b.width, b.height));
  test::write_text((dir / "scales.webp").string(), webp(b.scale_bytes, b.width, b.height));
  test::write_text((dir / "sh0.webp").string(), webp(b.sh0, b.width, b.height));
  test::write_text((dir / "shN_labels.webp").string(), webp(b.labels, b.width, b.height));
  test::write_text((dir / "shN_centroids.webp").string(), webp(b.centroids, 64 * kCoefficients, (kPalette + 63) / 64));
  test::write_text((dir / "meta.json").string(), meta.dump());
  return (dir / "meta.json").string();
}

double inverse_log(double v) { return std::copysign(std::exp(std::abs(v)) - 1, v); }

struct Ply {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  int index(const std::string& name) const { return int(std::find(names.begin(), names.end(), name) - names.begin()); }
};

Ply read_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const io::ply::Header h = io::ply::read_header(in, path);
  Ply p;
  for (const auto& property : h.properties) p.names.push_back(property.name);
  std::vector<unsigned char> record(h.record_bytes);
  for (std::uint64_t k = 0; k < h.vertices; ++k) {
    in.read(reinterpret_cast<char*>(record.data()), std::streamsize(record.size()));
    std::vector<double> row;
    for (const auto& property : h.properties) row.push_back(io::ply::read_binary(record.data(), property));
    p.rows.push_back(row);
  }
  return p;
}

// The canonical values the layout gives for splat i, as double.
std::vector<double> expected(const Built& b, int i, const Ply& like) {
  std::vector<double> v(like.names.size(), 0);
  for (int a = 0; a < 3; ++a) {
    const double t = (b.low[i][a] | (b.high[i][a] << 8)) / 65535.0;
    v[like.index(std::string(1, "xyz"[a]))] = inverse_log(b.mins[a] + (b.maxs[a] - b.mins[a]) * t);
    v[like.index("scale_" + std::to_string(a))] = b.scales[b.scale_bytes[i][a]];
    v[like.index("f_dc_" + std::to_string(a))] = b.colours[b.sh0[i][a]];
  }
  v[like.index("opacity")] = test::opacity_of_alpha(b.sh0[i][3] / 255.0);
  const int stored[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  const int largest = b.quats[i][3] - 252;
  double q[4], squares = 0;
  for (int k = 0; k < 3; ++k) {
    q[stored[largest][k]] = (b.quats[i][k] / 255.0 * 2 - 1) / std::sqrt(2.0);
    squares += q[stored[largest][k]] * q[stored[largest][k]];
  }
  q[largest] = std::sqrt(std::max(0.0, 1 - squares));
  for (int k = 0; k < 4; ++k) v[like.index("rot_" + std::to_string(k))] = q[k];
  const int entry = b.labels[i][0] | (b.labels[i][1] << 8);
  for (int ch = 0; ch < 3; ++ch)
    for (int j = 0; j < kCoefficients; ++j)
      v[like.index("f_rest_" + std::to_string(ch * kCoefficients + j))] = b.sh[b.centroids[(entry / 64) * 64 * kCoefficients + (entry % 64) * kCoefficients + j][ch]];
  return v;
}

TEST(Sog, EveryFieldReadsAsTheLayoutSays) {
  const test::TempDir dir;
  const Built b = build(1000, 3);
  const std::string meta = write_unbundled(b, dir / "scene", b.meta), out = (dir / "out.ply").string();
  const test::RunResult run = test::run_zhf("splat --in '" + meta + "' --out '" + out + "' --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Ply p = read_ply(out);
  ASSERT_EQ(p.rows.size(), 1000u);
  ASSERT_EQ(p.names.size(), std::size_t(9 + 3 * kCoefficients + 8));
  for (int i = 0; i < b.n; ++i) {
    const std::vector<double> e = expected(b, i, p);
    for (std::size_t k = 0; k < e.size(); ++k) ASSERT_EQ(p.rows[i][k], float(e[k])) << "splat " << i << ", " << p.names[k];
  }
}

// tests/data/uniform.sog, as splat-transform 3.7 wrote it (crosscheck/uniform_sog.sh; entries
// stored, and deflated in uniform_deflated.sog): 200 000 equal splats at the corners of a unit
// square, whose images of a few dozen bytes each decode to 448 x 448 texels. Every splat reads as
// the scene crosscheck/uniform_sog.py wrote: the codebooks hold its few distinct values exactly,
// the alpha byte is 255 sigmoid(2) truncated (224, not 225: its writer stores into a Uint8Array)
// and the quaternion's small components are within the format's step, sqrt(2) / 255, of 0.
TEST(Sog, SplatTransformsUniformSceneReadsAsWritten) {
  const test::TempDir dir;
  const std::string out = (dir / "uniform.ply").string();
  const test::RunResult run = test::run_zhf("splat --in '" + test::data_path("uniform.sog") + "' --out '" + out + "' --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Ply p = read_ply(out);
  ASSERT_EQ(p.rows.size(), 200000u);
  const double alpha = std::floor(255 / (1 + std::exp(-2.0))) / 255, quaternion_step = std::sqrt(2.0) / 255;
  std::array<int, 4> corners{};
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const std::vector<double>& r = p.rows[i];
    auto at = [&](const std::string& name) { return r[p.index(name)]; };
    const double x = at("x"), y = at("y");
    ASSERT_TRUE((x == 0 || std::abs(x - 1) <= tolerance::kSplatFloatStorage) && (y == 0 || std::abs(y - 1) <= tolerance::kSplatFloatStorage))
        << "splat " << i << ": (" << x << ", " << y << ")";
    ++corners[(x > 0.5) + 2 * (y > 0.5)];
    ASSERT_NEAR(at("z"), 1, tolerance::kSplatFloatStorage) << "splat " << i;
    const double dc[3] = {0.5, -0.25, 0.75};
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(at("f_dc_" + std::to_string(a)), float(dc[a])) << "splat " << i << ", f_dc_" << a;
      ASSERT_EQ(at("scale_" + std::to_string(a)), -3) << "splat " << i << ", scale_" << a;
    }
    for (int j = 0; j < 45; ++j)
      ASSERT_EQ(at("f_rest_" + std::to_string(j)), float(0.25 * (j % 2 ? -1 : 1) / (1 + j / 15))) << "splat " << i << ", f_rest_" << j;
    ASSERT_EQ(at("opacity"), float(test::opacity_of_alpha(alpha))) << "splat " << i;
    ASSERT_NEAR(at("rot_0"), 1, quaternion_step * quaternion_step) << "splat " << i;
    for (int k = 1; k < 4; ++k) ASSERT_LE(std::abs(at("rot_" + std::to_string(k))), quaternion_step) << "splat " << i << ", rot_" << k;
  }
  EXPECT_EQ(corners, (std::array<int, 4>{50000, 50000, 50000, 50000}));
  // The same archive with its entries deflated (Python's zipfile): the same scene.
  const std::string deflated = (dir / "deflated.ply").string();
  const test::RunResult again = test::run_zhf("splat --in '" + test::data_path("uniform_deflated.sog") + "' --out '" + deflated + "' --quiet");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(test::read_text(deflated), test::read_text(out));
}

// Turned .sog to .sog: read back, each splat where the turn puts it (within the format's steps),
// its SH from the palette turned once as the double reference turns it.
TEST(Sog, ATurnedSogMovesSplatsAndTurnsThePaletteOnce) {
  const test::TempDir dir;
  const Built b = build(2000, 5);
  const std::string meta = write_unbundled(b, dir / "scene", b.meta), turned = (dir / "turned.sog").string();
  const std::string before = (dir / "before.ply").string(), after = (dir / "after.ply").string();
  const test::RunResult run = test::run_zhf("splat --in '" + meta + "' --out '" + turned + "' --zyz '0.3 0.5 0.7' --scale 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("palette of 100 entries turned once"), std::string::npos) << run.out;
  ASSERT_EQ(test::run_zhf("splat --in '" + meta + "' --out '" + before + "' --quiet").exit_code, 0);
  ASSERT_EQ(test::run_zhf("splat --in '" + turned + "' --out '" + after + "' --quiet").exit_code, 0);
  const Ply x = read_ply(before), y = read_ply(after);
  const runtime::Matrix3 r = runtime::rotation_from_zyz(0.3, 0.5, 0.7);
  // 16 bits of sign(p) ln(|p| + 1): a step of (max - min) / 65535 in that, times (|p| + 1) in p.
  const sh::BandMatrices bands = sh::ivanic_ruedenberg(sh::to_eigen(r), kBands + 1);
  // The new SH codebook, from meta.json, the archive's first entry (stored: 30-byte header, name).
  const std::string sog = test::read_text(turned);
  std::uint32_t meta_bytes;
  std::memcpy(&meta_bytes, sog.data() + 18, 4);
  ASSERT_EQ(sog.substr(30, 9), "meta.json");
  const nlohmann::json written = nlohmann::json::parse(sog.substr(39, meta_bytes));
  const std::vector<double> levels = written["shN"]["codebook"].get<std::vector<double>>();
  ASSERT_EQ(levels.size(), 256u);
  auto nearest_distance = [&](double v) {
    double best = INFINITY;
    for (double level : levels) best = std::min(best, std::abs(level - v));
    return best;
  };
  for (int i = 0; i < b.n; ++i) {
    for (int a = 0; a < 3; ++a) {
      double p = 0;
      for (int k = 0; k < 3; ++k) p += 2 * r[3 * a + k] * x.rows[i][x.index(std::string(1, "xyz"[k]))];
      // A 16-bit step of sign(p) ln(|p| + 1) between the written bounds, in p: times e^|v| = |p| + 1.
      const double step = (written["means"]["maxs"][a].get<double>() - written["means"]["mins"][a].get<double>()) / 65535 * (std::abs(p) + 1);
      ASSERT_NEAR(y.rows[i][y.index(std::string(1, "xyz"[a]))], p, step) << "splat " << i << ", axis " << a;
      ASSERT_NEAR(y.rows[i][y.index("scale_" + std::to_string(a))], x.rows[i][x.index("scale_" + std::to_string(a))] + std::log(2.0), kShiftedLogScale);
      ASSERT_EQ(y.rows[i][y.index("f_dc_" + std::to_string(a))], x.rows[i][x.index("f_dc_" + std::to_string(a))]);
    }
    ASSERT_EQ(y.rows[i][y.index("opacity")], x.rows[i][x.index("opacity")]);
    // Orientation R Q, up to sign and the 8-bit steps of the smallest three.
    runtime::Matrix3 q_in, q_out;
    auto q_of = [](const Ply& p, int i, runtime::Matrix3& m) {
      runtime::rotation_from_quaternion(p.rows[i][p.index("rot_0")], p.rows[i][p.index("rot_1")], p.rows[i][p.index("rot_2")],
                                        p.rows[i][p.index("rot_3")], m);
    };
    q_of(x, i, q_in);
    q_of(y, i, q_out);
    const runtime::Matrix3 turned_q = runtime::multiply(r, q_in);
    for (int k = 0; k < 9; ++k) ASSERT_NEAR(q_out[k], turned_q[k], kQuaternionEntry) << "splat " << i;
    // SH: 3DGS's coefficients carry (-1)^m against zhf's basis.
    for (int ch = 0; ch < 3; ++ch) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(9);
      for (int j = 0; j < kCoefficients; ++j) {
        const int l = j < 3 ? 1 : 2, m = j + 1 - l * (l + 1);
        f[1 + j] = (m % 2 ? -1 : 1) * x.rows[i][x.index("f_rest_" + std::to_string(ch * kCoefficients + j))];
      }
      const Eigen::VectorXd g = sh::apply_band_matrices(bands, f);
      for (int j = 0; j < kCoefficients; ++j) {
        const int l = j < 3 ? 1 : 2, m = j + 1 - l * (l + 1);
        const double reference = (m % 2 ? -1 : 1) * g[1 + j];
        ASSERT_LE(std::abs(y.rows[i][y.index("f_rest_" + std::to_string(ch * kCoefficients + j))] - reference), nearest_distance(reference) + 1e-7)
            << "splat " << i << ", channel " << ch << ", coefficient " << j << ": not the codebook's nearest level to the reference";
      }
    }
  }
  // Labels, scales and colours carried as stored.
  const std::string labels_in = test::read_text((dir / "scene" / "shN_labels.webp").string());
  EXPECT_NE(sog.find(labels_in), std::string::npos) << "the labels image, byte for byte";
  EXPECT_NE(sog.find(test::read_text((dir / "scene" / "sh0.webp").string())), std::string::npos);
}

// A binary .ply of the canonical record, SH degree `degree`, n splats of random values (positions
// spread over a few units, opacities over the logit range, unit-ish quaternions).
Ply write_random_ply(const std::string& path, int degree, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * double(rng() >> 11) / 9007199254740992.0; };
  Ply p;
  p.names = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  const int rest = 3 * ((degree + 1) * (degree + 1) - 1);
  for (int k = 0; k < rest; ++k) p.names.push_back("f_rest_" + std::to_string(k));
  for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) p.names.push_back(name);
  std::string text = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) + "\n";
  for (const std::string& name : p.names) text += "property float " + name + "\n";
  text += "end_header\n";
  for (int i = 0; i < n; ++i) {
    std::vector<double> row;
    for (const std::string& name : p.names) {
      double v = name.rfind("f_rest", 0) == 0 ? uniform(-0.5, 0.5) : name.rfind("f_dc", 0) == 0 ? uniform(-2, 2)
                 : name == "opacity"                                                   ? uniform(-6, 6)
                 : name.rfind("scale", 0) == 0                                         ? uniform(-7, -1)
                 : name.rfind("rot", 0) == 0                                           ? uniform(-1, 1)
                 : name[0] == 'n'                                                      ? 0
                                                                                       : uniform(-4, 4);
      v = double(float(v));
      row.push_back(v);
      const float f = float(v);
      text.append(reinterpret_cast<const char*>(&f), 4);
    }
    p.rows.push_back(row);
  }
  test::write_text(path, text);
  return p;
}

// meta.json of a bundled .sog zhf wrote: the archive's first entry, stored (30-byte header, its name).
nlohmann::json written_meta(const std::string& sog) {
  std::uint32_t bytes;
  std::memcpy(&bytes, sog.data() + 18, 4);
  EXPECT_EQ(sog.substr(30, 9), "meta.json");
  return nlohmann::json::parse(sog.substr(39, bytes));
}

double nearest_level_distance(const std::vector<double>& levels, double v) {
  double best = INFINITY;
  for (double level : levels) best = std::min(best, std::abs(level - v));
  return best;
}

// A .ply written as a .sog (fewer splats than a palette holds: each its own entry) and read back:
// every position within its 16-bit step, every scale, colour and SH value the nearest level of its
// codebook in meta.json, opacity the nearest byte, orientations within their 8-bit steps.
TEST(Sog, APlyWrittenAsSogKeepsEachFieldToItsNearestStep) {
  const test::TempDir dir;
  const std::string in = (dir / "in.ply").string(), sog = (dir / "out.sog").string(), back = (dir / "back.ply").string();
  const Ply x = write_random_ply(in, 3, 3000, 11);
  const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + sog + "' --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_EQ(test::run_zhf("splat --in '" + sog + "' --out '" + back + "' --quiet").exit_code, 0);
  const nlohmann::json meta = written_meta(test::read_text(sog));
  EXPECT_EQ(meta["count"], 3000);
  EXPECT_EQ(meta["shN"]["bands"], 3);
  EXPECT_EQ(meta["shN"]["count"], 3000);
  const std::vector<double> scales = meta["scales"]["codebook"], colours = meta["sh0"]["codebook"], sh = meta["shN"]["codebook"];
  const Ply y = read_ply(back);
  ASSERT_EQ(y.rows.size(), 3000u);
  for (std::size_t i = 0; i < y.rows.size(); ++i) {
    const std::string at = "splat " + std::to_string(i);
    for (int a = 0; a < 3; ++a) {
      const std::string axis(1, "xyz"[a]), index = std::to_string(a);
      const double p = x.rows[i][x.index(axis)];
      const double step = (meta["means"]["maxs"][a].get<double>() - meta["means"]["mins"][a].get<double>()) / 65535 * (std::abs(p) + 1);
      ASSERT_NEAR(y.rows[i][y.index(axis)], p, step) << at << ", " << axis;
      const double s = x.rows[i][x.index("scale_" + index)], c = x.rows[i][x.index("f_dc_" + index)];
      ASSERT_NEAR(std::abs(y.rows[i][y.index("scale_" + index)] - s), nearest_level_distance(scales, s), kReadBackLevel) << at << ", scale_" << a;
      ASSERT_NEAR(std::abs(y.rows[i][y.index("f_dc_" + index)] - c), nearest_level_distance(colours, c), kReadBackLevel) << at << ", f_dc_" << a;
    }
    const double alpha = 1 / (1 + std::exp(-x.rows[i][x.index("opacity")]));
    ASSERT_NEAR(1 / (1 + std::exp(-y.rows[i][y.index("opacity")])), std::nearbyint(255 * alpha) / 255, kReadBackLevel) << at << ", opacity";
    for (int k = 0; k < 45; ++k) {
      const double v = x.rows[i][x.index("f_rest_" + std::to_string(k))];
      ASSERT_NEAR(std::abs(y.rows[i][y.index("f_rest_" + std::to_string(k))] - v), nearest_level_distance(sh, v), kReadBackLevel) << at << ", f_rest_" << k;
    }
    runtime::Matrix3 q_in, q_out;
    runtime::rotation_from_quaternion(x.rows[i][x.index("rot_0")], x.rows[i][x.index("rot_1")], x.rows[i][x.index("rot_2")], x.rows[i][x.index("rot_3")], q_in);
    runtime::rotation_from_quaternion(y.rows[i][y.index("rot_0")], y.rows[i][y.index("rot_1")], y.rows[i][y.index("rot_2")], y.rows[i][y.index("rot_3")], q_out);
    for (int k = 0; k < 9; ++k) ASSERT_NEAR(q_out[k], q_in[k], kQuaternionEntry) << at << ", orientation " << k;
  }
  // No splats (WebP holds no empty image): refused in one line, nothing written.
  const std::string empty = (dir / "empty.ply").string(), empty_sog = (dir / "empty.sog").string();
  write_random_ply(empty, 1, 0, 1);
  const test::RunResult none = test::run_zhf("splat --in '" + empty + "' --out '" + empty_sog + "' --quiet");
  EXPECT_EQ(none.exit_code, 3) << none.err;
  EXPECT_EQ(test::line_count(none.err), 1) << none.err;
  EXPECT_NE(none.err.find("empty.sog: no splats to write"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(empty_sog));
}

// More splats than a palette holds: the palette is fitted (k-means), the same bytes on one thread
// and on two, other bytes with another seed; it fills its 65 536 entries, and the SH read back are
// far nearer the input than the input's own spread.
TEST(Sog, AFittedPaletteIsTheSameOnAnyThreadCount) {
  const test::TempDir dir;
  const int n = 70000;
  const std::string in = (dir / "in.ply").string(), one = (dir / "one.sog").string(), two = (dir / "two.sog").string();
  const std::string other = (dir / "other.sog").string(), back = (dir / "back.ply").string();
  const Ply x = write_random_ply(in, 1, n, 12);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + one + "' --threads 1 --quiet").exit_code, 0);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + two + "' --threads 2 --quiet").exit_code, 0);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + other + "' --seed 2 --quiet").exit_code, 0);
  const std::string bytes = test::read_text(one);
  EXPECT_TRUE(bytes == test::read_text(two)) << "one thread and two wrote different files";
  EXPECT_FALSE(bytes == test::read_text(other)) << "--seed 2 changed nothing";
  EXPECT_EQ(written_meta(bytes)["shN"]["count"], 65536);
  ASSERT_EQ(test::run_zhf("splat --in '" + one + "' --out '" + back + "' --quiet").exit_code, 0);
  const Ply y = read_ply(back);
  ASSERT_EQ(y.rows.size(), std::size_t(n));
  double error = 0, spread = 0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 9; ++k) {
      const double v = x.rows[i][x.index("f_rest_" + std::to_string(k))];
      error += std::pow(y.rows[i][y.index("f_rest_" + std::to_string(k))] - v, 2);
      spread += v * v;
    }
  EXPECT_LT(std::sqrt(error / spread), 0.1) << "the palette's relative RMS error";
  // Over twice the palette: the first level is fitted on a sample; still the same on any thread count.
  const std::string big = (dir / "big.ply").string(), big_one = (dir / "big_one.sog").string(), big_two = (dir / "big_two.sog").string();
  write_random_ply(big, 1, 140000, 13);
  ASSERT_EQ(test::run_zhf("splat --in '" + big + "' --out '" + big_one + "' --threads 1 --quiet").exit_code, 0);
  ASSERT_EQ(test::run_zhf("splat --in '" + big + "' --out '" + big_two + "' --threads 2 --quiet").exit_code, 0);
  const std::string big_bytes = test::read_text(big_one);
  EXPECT_TRUE(big_bytes == test::read_text(big_two)) << "one thread and two wrote different files (140 000 splats)";
  EXPECT_EQ(written_meta(big_bytes)["shN"]["count"], 65536);
}

TEST(Sog, HostileSogsAreRefusedInOneLine) {
  const test::TempDir dir;
  const Built b = build(300, 7);
  const std::string out = (dir / "out.ply").string();
  auto refused = [&](const std::string& what, const std::string& meta_path, const std::string& message) {
    const test::RunResult run = test::run_zhf("splat --in '" + meta_path + "' --out '" + out + "' --quiet");
    EXPECT_EQ(run.exit_code, 3) << what << ": " << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << what << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << what << ": " << run.err;
    EXPECT_FALSE(fs::exists(out)) << what;
  };
  int case_number = 0;
  auto scene = [&](const nlohmann::json& meta) { return write_unbundled(b, dir / ("s" + std::to_string(case_number++)), meta); };
  nlohmann::json lie = b.meta;
  lie["count"] = 5000;
  refused("a count the images cannot hold", scene(lie), "texels; meta.json's count needs");
  lie["count"] = 200000000;
  refused("a count past the decoded cap", scene(lie), "meta.json: 200000000 splats decode to");
  lie = b.meta;
  lie["shN"]["codebook"].erase(0);
  refused("a short codebook", scene(lie), "shN.codebook: expected 256 entries, found 255");
  lie = b.meta;
  lie["version"] = 1;
  refused("version 1", scene(lie), "SOG version 1; zhf reads version 2");
  lie = b.meta;
  lie["sh0"]["files"] = {"../sh0.webp"};
  refused("a path in a file name", scene(lie), "sh0.files[0]: '../sh0.webp' is not a plain file name");
  lie = b.meta;
  lie["shN"]["count"] = 70;  // the same centroid rows; labels reach 99
  refused("labels past the palette", scene(lie), "palette entry");
  lie = b.meta;
  lie["means"]["maxs"][0] = 1000;
  refused("a log-position past float", scene(lie), "means.maxs[0]: beyond the log-position");
  const std::string bad_webp = scene(b.meta);
  test::write_text((fs::path(bad_webp).parent_path() / "quats.webp").string(), "RIFF....WEBPVP8L garbage");
  refused("a bad WebP", bad_webp, "quats.webp: not a WebP image zhf can decode");
  const std::string small = scene(b.meta);
  test::write_text((fs::path(small).parent_path() / "scales.webp").string(), webp(b.scale_bytes, b.width, b.height / 2));
  refused("an image of the wrong size", small,
          "scales.webp: " + std::to_string(b.width) + " x " + std::to_string(b.height / 2) + " texels; meta.json's count needs " +
              std::to_string(b.width) + " x " + std::to_string(b.height));
  // A lossless WebP whose header claims 16000 x 16000 texels (its 14-bit sizes after the
  // signature byte) in a few hundred bytes: refused by its size before anything is allocated.
  const std::string huge = scene(b.meta);
  std::string claim = webp(b.quats, b.width, b.height);
  ASSERT_EQ(claim.substr(12, 4), "VP8L");
  std::uint32_t bits;
  std::memcpy(&bits, claim.data() + 21, 4);
  bits = (bits & ~((1u << 28) - 1)) | 15999u | (15999u << 14);
  std::memcpy(claim.data() + 21, &bits, 4);
  test::write_text((fs::path(huge).parent_path() / "quats.webp").string(), claim);
  refused("a WebP claiming more texels than meta.json's count", huge,
          "quats.webp: 16000 x 16000 texels; meta.json's count needs " + std::to_string(b.width) + " x " + std::to_string(b.height));
  Built tagged = b;
  tagged.quats[7][3] = 17;
  refused("a quaternion tag outside 252..255", write_unbundled(tagged, dir / "tag", b.meta), "splat 7: quats: tag 17 is not 252..255");
  // A bundled .sog whose entry is damaged: its CRC.
  const std::string meta = scene(b.meta), sog = (dir / "good.sog").string(), turned = (dir / "turned.sog").string();
  ASSERT_EQ(test::run_zhf("splat --in '" + meta + "' --out '" + sog + "' --quiet").exit_code, 0);
  std::string bytes = test::read_text(sog);
  const std::size_t at = bytes.find("RIFF", bytes.size() / 2);
  ASSERT_NE(at, std::string::npos);
  bytes[at + 40] = char(bytes[at + 40] ^ 0x5a);
  test::write_text((dir / "damaged.sog").string(), bytes);
  refused("a damaged entry", (dir / "damaged.sog").string(), "CRC mismatch");
  test::write_text((dir / "cut.sog").string(), bytes.substr(0, bytes.size() - 30));
  refused("a truncated archive", (dir / "cut.sog").string(), "cut.sog");
  // zhf writes bundled SOGs only: an output named meta.json is refused in one line, nothing written.
  const std::string ply = (dir / "in.ply").string(), into = (dir / "unbundled" / "meta.json").string();
  ASSERT_EQ(test::run_zhf("splat --in '" + meta + "' --out '" + ply + "' --quiet").exit_code, 0);
  fs::create_directories(dir / "unbundled");
  const test::RunResult run = test::run_zhf("splat --in '" + ply + "' --out '" + into + "' --quiet");
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_NE(run.err.find("name the output .sog"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(into));
}

}  // namespace
}  // namespace zhf
