// zhf splat through the real binary: random 3DGS scenes of SH degree 0..3, binary and ASCII,
// transformed by rotations and reflections with scale and translation. The oracle: the colour
// (3DGS's own basis formula) seen from R d after equals the colour seen from d before; positions,
// orientations and log-scales as stated; every other column, the comments and the types as
// they were. Malformed files are refused with exit 3 and nothing written. .splat and compressed
// .ply files: each field as the published layout says (decoded here independently), read back
// exactly as written, within the format's step of the scene, transformed as their .ply is.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include "sh_bases.h"
#include "spz_layout.h"
#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/io/ply.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
using namespace std::string_literals;
using runtime::Matrix3;

constexpr double kFloatStorage = tolerance::kSplatFloatStorage;

struct Scene {
  int degree = 3;
  std::vector<std::string> names;  // float properties, then "custom" (int)
  std::vector<std::vector<double>> rows;
};

Scene random_scene(int degree, int splats, std::mt19937_64& rng) {
  sh::Normal<> normal;
  Scene s;
  s.degree = degree;
  s.names = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  const int rest = 3 * ((degree + 1) * (degree + 1) - 1);
  for (int i = 0; i < rest; ++i) s.names.push_back("f_rest_" + std::to_string(i));
  for (const char* n : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) s.names.push_back(n);
  for (int k = 0; k < splats; ++k) {
    std::vector<double> row;
    for (std::size_t i = 0; i < s.names.size(); ++i) row.push_back(double(float(normal(rng))));
    row.push_back(double(k * 7 - 1000));  // custom
    s.rows.push_back(row);
  }
  return s;
}

std::string header_text(const Scene& s, bool ascii) {
  std::string h = std::string("ply\nformat ") + (ascii ? "ascii" : "binary_little_endian") + " 1.0\ncomment made by the zhf test\n";
  h += "element vertex " + std::to_string(s.rows.size()) + "\n";
  for (const std::string& n : s.names) h += "property float " + n + "\n";
  h += "property int custom\nend_header\n";
  return h;
}

void write_scene(const Scene& s, const std::string& path, bool ascii) {
  std::ofstream out(path, std::ios::binary);
  out << header_text(s, ascii);
  for (const auto& row : s.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (ascii) {
        char text[40];
        std::snprintf(text, sizeof text, i + 1 == row.size() ? "%.0f" : "%.9g", row[i]);
        out << (i ? " " : "") << text;
      } else if (i + 1 == row.size()) {
        const std::int32_t v = std::int32_t(row[i]);
        out.write(reinterpret_cast<const char*>(&v), 4);
      } else {
        const float v = float(row[i]);
        out.write(reinterpret_cast<const char*>(&v), 4);
      }
    }
    if (ascii) out << "\n";
  }
}

// The output's header text and rows, read with zhf's PLY header reader.
Scene read_scene(const std::string& path, const Scene& like, std::string& header) {
  std::ifstream in(path, std::ios::binary);
  const io::ply::Header h = io::ply::read_header(in, path);
  header = h.text;
  Scene s = like;
  for (auto& row : s.rows) {
    if (h.format == io::ply::Format::kAscii) {
      for (double& x : row) in >> x;
    } else {
      std::vector<unsigned char> record(h.record_bytes);
      in.read(reinterpret_cast<char*>(record.data()), std::streamsize(record.size()));
      // A converted file has the 3DGS record's columns only: `like`'s extra ones read as 0.
      for (std::size_t i = 0; i < row.size(); ++i) row[i] = i < h.properties.size() ? io::ply::read_binary(record.data(), h.properties[i]) : 0;
    }
  }
  return s;
}

int index_of(const Scene& s, const std::string& name) {
  for (std::size_t i = 0; i < s.names.size(); ++i)
    if (s.names[i] == name) return int(i);
  return -1;
}

// Channel c's colour from direction d (3DGS's eval_sh, without the +0.5 and clamp).
double colour(const Scene& s, const std::vector<double>& row, int c, const std::array<double, 3>& d) {
  const std::vector<double> b = test::gaussian_splatting_basis(d[0], d[1], d[2]);
  const int per = (s.degree + 1) * (s.degree + 1) - 1;
  double sum = b[0] * row[index_of(s, "f_dc_" + std::to_string(c))];
  for (int j = 0; j < per; ++j) sum += b[1 + j] * row[index_of(s, "f_rest_" + std::to_string(c * per + j))];
  return sum;
}

Matrix3 quaternion_matrix(const std::vector<double>& row, const Scene& s) {
  Matrix3 q;
  runtime::rotation_from_quaternion(row[index_of(s, "rot_0")], row[index_of(s, "rot_1")], row[index_of(s, "rot_2")],
                                    row[index_of(s, "rot_3")], q);
  return q;
}

// `content` written to `in` and given to zhf splat: refused with exit 3 and one line holding
// `message`, and `out` not written.
void expect_refused(const std::string& in, const std::string& content, const std::string& out, const std::string& options,
                    const std::string& message) {
  test::write_text(in, content);
  const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out + "' " + options + " --quiet");
  EXPECT_EQ(run.exit_code, 3) << message << ": " << run.err;
  EXPECT_NE(run.err.find(message), std::string::npos) << message << ": " << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(fs::exists(out)) << message;
}

// A turn, scale and shift for comparing one scene's transforms from two files.
const std::string kTurn = "--zyz '0.3 0.5 0.7' --scale 2 --translate '1 2 3'";

// zhf splat on two inputs, each with its options, both written as .ply: the same records to
// float storage (the last column, `like`'s "custom", is not in a converted record).
void expect_alike(const std::string& a_in, const std::string& a_options, const std::string& b_in, const std::string& b_options,
                  const Scene& like, const fs::path& dir) {
  const std::string a_out = (dir / "alike_a.ply").string(), b_out = (dir / "alike_b.ply").string();
  ASSERT_EQ(test::run_zhf("splat --in '" + a_in + "' --out '" + a_out + "' " + a_options + " --quiet").exit_code, 0) << a_in;
  ASSERT_EQ(test::run_zhf("splat --in '" + b_in + "' --out '" + b_out + "' " + b_options + " --quiet").exit_code, 0) << b_in;
  std::string header;
  const Scene a = read_scene(a_out, like, header), b = read_scene(b_out, like, header);
  for (std::size_t k = 0; k < a.rows.size(); ++k)
    for (std::size_t i = 0; i + 1 < a.rows[k].size(); ++i)
      ASSERT_NEAR(a.rows[k][i], b.rows[k][i], kFloatStorage * (1 + std::abs(b.rows[k][i]))) << a_in << ": splat " << k << ", " << like.names[i];
}

struct Case {
  std::string options;
  Matrix3 r;
  double scale;
  std::array<double, 3> t;
};

TEST(Splat, TransformsEveryPartOfTheSceneAsStated) {
  const test::TempDir dir;
  std::mt19937_64 rng(21);
  const Matrix3 turn = runtime::rotation_from_zyz(0.4, 1.1, -2.3);
  Matrix3 mirror_turn = turn;
  for (int i = 0; i < 3; ++i) mirror_turn[3 * i] = -mirror_turn[3 * i];  // R diag(-1, 1, 1): det -1
  char mirror_text[256];
  std::snprintf(mirror_text, sizeof mirror_text, "--matrix '%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g'", mirror_turn[0],
                mirror_turn[1], mirror_turn[2], mirror_turn[3], mirror_turn[4], mirror_turn[5], mirror_turn[6], mirror_turn[7],
                mirror_turn[8]);
  const std::vector<Case> cases = {
      {"--zyz '0.4 1.1 -2.3' --scale 2.5 --translate '1 -2 0.5'", turn, 2.5, {1, -2, 0.5}},
      {mirror_text, mirror_turn, 1, {0, 0, 0}},
  };
  for (int degree = 0; degree <= 3; ++degree)
    for (bool ascii : {false, true})
      for (const Case& c : cases) {
        const std::string what = "degree " + std::to_string(degree) + (ascii ? ", ascii, " : ", binary, ") + c.options;
        const Scene in = random_scene(degree, 300, rng);
        const std::string in_path = (dir / "in.ply").string(), out_path = (dir / "out.ply").string();
        write_scene(in, in_path, ascii);
        const test::RunResult run = test::run_zhf("splat --in '" + in_path + "' --out '" + out_path + "' --quiet " + c.options);
        ASSERT_EQ(run.exit_code, 0) << what << ": " << run.err;
        std::string header;
        const Scene out = read_scene(out_path, in, header);
        EXPECT_EQ(header, header_text(in, ascii)) << what;
        const double det = c.r[0] * (c.r[4] * c.r[8] - c.r[5] * c.r[7]) - c.r[1] * (c.r[3] * c.r[8] - c.r[5] * c.r[6]) +
                           c.r[2] * (c.r[3] * c.r[7] - c.r[4] * c.r[6]);
        for (std::size_t k = 0; k < in.rows.size(); ++k) {
          const auto& a = in.rows[k];
          const auto& b = out.rows[k];
          const std::string at = what + ", splat " + std::to_string(k);
          EXPECT_EQ(b.back(), a.back()) << at << ": the int column changed";
          EXPECT_EQ(float(b[index_of(in, "opacity")]), float(a[index_of(in, "opacity")])) << at;
          for (int i = 0; i < 3; ++i) {
            double p = c.t[i];
            for (int j = 0; j < 3; ++j) p += c.scale * c.r[3 * i + j] * a[index_of(in, std::string(1, "xyz"[j]))];
            EXPECT_NEAR(b[index_of(in, std::string(1, "xyz"[i]))], p, kFloatStorage * 20) << at << ", position " << i;
            EXPECT_NEAR(b[index_of(in, "scale_" + std::to_string(i))], a[index_of(in, "scale_" + std::to_string(i))] + std::log(c.scale),
                        kFloatStorage * 10)
                << at;
          }
          // Orientation: R Q, or R Q diag(1, 1, -1) for a reflection (a rotation either way).
          const Matrix3 q_in = quaternion_matrix(a, in), q_out = quaternion_matrix(b, in);
          Matrix3 expected = runtime::multiply(c.r, q_in);
          if (det < 0)
            for (int i = 0; i < 3; ++i) expected[3 * i + 2] = -expected[3 * i + 2];
          for (int i = 0; i < 9; ++i) EXPECT_NEAR(q_out[i], expected[i], kFloatStorage * 20) << at << ", orientation " << i;
          // The colour seen from R d after is the colour seen from d before.
          for (int trial = 0; trial < 3; ++trial) {
            const Eigen::Vector3d e = sh::random_direction(rng);
            const std::array<double, 3> d{e[0], e[1], e[2]};
            std::array<double, 3> rd{};
            for (int i = 0; i < 3; ++i) rd[i] = c.r[3 * i] * d[0] + c.r[3 * i + 1] * d[1] + c.r[3 * i + 2] * d[2];
            for (int ch = 0; ch < 3; ++ch)
              EXPECT_NEAR(colour(out, b, ch, rd), colour(in, a, ch, d), kFloatStorage * 40) << at << ", channel " << ch;
          }
        }
      }
}

TEST(Splat, TheIdentityRewritesABinaryFileByteForByte) {
  const test::TempDir dir;
  std::mt19937_64 rng(22);
  const std::string in = (dir / "in.ply").string(), out = (dir / "out.ply").string();
  write_scene(random_scene(3, 70000, rng), in, false);  // more than one chunk
  const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out + "' --identity --quiet --threads 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(test::read_text(in), test::read_text(out));
  // A plain conversion needs no --identity; --identity beside a rotation would drop it: refused,
  // nothing written.
  const std::string plain = (dir / "plain.ply").string();
  const test::RunResult conversion = test::run_zhf("splat --in '" + in + "' --out '" + plain + "' --quiet");
  ASSERT_EQ(conversion.exit_code, 0) << conversion.err;
  EXPECT_EQ(test::read_text(in), test::read_text(plain));
  const std::string dropped = (dir / "dropped.ply").string();
  const test::RunResult both = test::run_zhf("splat --in '" + in + "' --out '" + dropped + "' --identity --zyz '0 1 0' --quiet");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("--identity: a rotation is given too"), std::string::npos) << both.err;
  EXPECT_FALSE(std::filesystem::exists(dropped));
  EXPECT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + dropped + "' --repair --quiet").exit_code, 2);  // a word about no rotation
}

TEST(Splat, MalformedScenesAreRefusedAndNothingIsWritten) {
  const test::TempDir dir;
  std::mt19937_64 rng(23);
  const std::string good = (dir / "good.ply").string();
  write_scene(random_scene(1, 5, rng), good, false);
  const std::string text = test::read_text(good);
  const std::size_t data = text.find("end_header\n") + 11;
  std::string nan_scene = text;
  const float nan = NAN;
  std::memcpy(&nan_scene[data + 8], &nan, 4);  // z of splat 0
  std::string ascii_nan = header_text(random_scene(1, 1, rng), true);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {text.substr(0, text.size() - 3), "truncated"},
      {text + "x", "bytes after the last splat"},
      {std::string(text).replace(text.find("binary_little_endian"), 20, "binary_big_endian"), "big-endian PLY is not supported"},
      {std::string(text).replace(text.find("binary_little_endian"), 20, "binary_weird_endian"), "unknown format"},
      {std::string(text).replace(text.find("property float f_rest_8\n"), 24, ""), "8 f_rest properties"},
      {nan_scene, "splat 0: property z is nan"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2\n",
       "splat 0: 2 numbers, the header has 3 properties"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 nan\n",
       "splat 0: property z: 'nan' is not finite"},
      {"ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n",
       "truncated"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty uchar x\nproperty float y\nproperty float z\nend_header\n1 2 3\n",
       "property x is not float or double"},
      {"PLY\n", "not a PLY file"},
      {"ply\nformat ascii 1.0\nelement vertex 99999999999\n", "is not a count up to 2^31"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar int vertex_indices\nend_header\n", "list properties"},
  };
  for (const auto& [content, message] : cases)
    expect_refused((dir / "bad.ply").string(), content, (dir / "out.ply").string(), "--zyz '1 2 3'", message);
  for (const auto& [options, message] : std::vector<std::pair<std::string, std::string>>{
           {"--zyz '1 2 3' --scale 0", "--scale"},
           {"--zyz '1 2 3' --scale '1 2 3'", "--scale"},
           {"--zyz '1 2 3' --translate '1 2'", "--translate: expected 3 numbers, found 2"},
           {"--zyz '1 2 3' --convention nope", "--convention: 'nope' is not one of"},
           {"--repair", "give exactly one of --matrix"},  // a word about a rotation, without one
           {"--identity --axis-angle '0 0 1 1'", "--identity: a rotation is given too"},
       }) {
    const test::RunResult run = test::run_zhf("splat --in '" + good + "' --out '" + (dir / "out.ply").string() + "' " + options);
    EXPECT_EQ(run.exit_code, 2) << options << ": " << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << options << ": " << run.err;
  }
}


// antimatter15's .splat, 32 bytes a splat: position and linear scale as float32, colour and
// alpha and the quaternion as bytes (the formulas written out here, independently of zhf).
struct SplatRecord {
  float position[3], scale[3];
  unsigned char rgba[4], rot[4];
};
static_assert(sizeof(SplatRecord) == 32, "the .splat record");

std::vector<SplatRecord> read_splats(const std::string& path) {
  const std::string bytes = test::read_text(path);
  std::vector<SplatRecord> out(bytes.size() / 32);
  std::memcpy(out.data(), bytes.data(), out.size() * 32);
  return out;
}

int expected_byte(double x) { return int(std::clamp(std::nearbyint(x), 0.0, 255.0)); }

TEST(Splat, SplatFilesHoldThePublishedBytesAndReadBackExactly) {
  const test::TempDir dir;
  std::mt19937_64 rng(31);
  Scene scene = random_scene(3, 70000, rng);  // more than one chunk
  const std::string in = (dir / "in.ply").string(), splat = (dir / "out.splat").string(), back = (dir / "back.ply").string();
  write_scene(scene, in, false);
  test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + splat + "' --identity --quiet --threads 2");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Lossy, and said so: the SH above degree 0, and colours beyond 0..255 (N(0, 1) f_dc reaches them).
  EXPECT_NE(run.err.find("keeps SH degree 0 only; degrees 1..3 were dropped"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("values beyond the .splat format's range were written as its nearest"), std::string::npos) << run.err;
  const std::vector<SplatRecord> records = read_splats(splat);
  ASSERT_EQ(records.size(), scene.rows.size());
  const double c0 = runtime::kInvSqrt4Pi;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const std::vector<double>& row = scene.rows[k];
    const SplatRecord& r = records[k];
    const std::string at = "splat " + std::to_string(k);
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(r.position[i], float(row[index_of(scene, "xyz"s.substr(i, 1))])) << at;
      ASSERT_EQ(r.scale[i], float(std::exp(row[index_of(scene, "scale_" + std::to_string(i))]))) << at;
      ASSERT_EQ(r.rgba[i], expected_byte(255 * (0.5 + c0 * row[index_of(scene, "f_dc_" + std::to_string(i))]))) << at;
    }
    ASSERT_EQ(r.rgba[3], expected_byte(255 / (1 + std::exp(-row[index_of(scene, "opacity")])))) << at;
    double norm = 0;
    for (int i = 0; i < 4; ++i) norm += row[index_of(scene, "rot_" + std::to_string(i))] * row[index_of(scene, "rot_" + std::to_string(i))];
    for (int i = 0; i < 4; ++i)
      ASSERT_EQ(r.rot[i], expected_byte(128 * row[index_of(scene, "rot_" + std::to_string(i))] / std::sqrt(norm) + 128)) << at;
  }
  // Read back: exactly the quantised values (the colour and alpha decoded, the quaternion as stored).
  run = test::run_zhf("splat --in '" + splat + "' --out '" + back + "' --identity --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream file(back, std::ios::binary);
  const io::ply::Header h = io::ply::read_header(file, back);
  ASSERT_EQ(h.vertices, records.size());
  std::vector<unsigned char> record(h.record_bytes);
  for (std::size_t k = 0; k < records.size(); ++k) {
    file.read(reinterpret_cast<char*>(record.data()), std::streamsize(record.size()));
    const SplatRecord& r = records[k];
    auto value = [&](const char* name) { return io::ply::read_binary(record.data(), h.properties[h.find(name)]); };
    const std::string at = "splat " + std::to_string(k);
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(value(("xyz"s.substr(i, 1)).c_str()), r.position[i]) << at;
      ASSERT_EQ(value(("scale_" + std::to_string(i)).c_str()), float(std::log(double(r.scale[i])))) << at;
      ASSERT_EQ(value(("f_dc_" + std::to_string(i)).c_str()), float((r.rgba[i] / 255.0 - 0.5) / c0)) << at;
      ASSERT_EQ(value(("n" + "xyz"s.substr(i, 1)).c_str()), 0.0) << at;
    }
    ASSERT_EQ(value("opacity"), float(test::opacity_of_alpha(r.rgba[3] / 255.0))) << at;
    for (int i = 0; i < 4; ++i) ASSERT_EQ(value(("rot_" + std::to_string(i)).c_str()), (r.rot[i] - 128.0) / 128) << at;
  }
  EXPECT_EQ(h.find("f_rest_0"), -1);
}

// The alpha rule (docs/formats.md) at its two ends: opacities of -30 and 30 store alpha bytes 0
// and 255 (in a .glb floats within 1e-13 of 0 and 1); every format reads them back as
// splat-transform does, -13.8 and 13.8, and a .splat written from those holds 0 and 255 again.
TEST(Splat, AlphaZeroAnd255ReadAsSplatTransformReadsThem) {
  const test::TempDir dir;
  std::mt19937_64 rng(71);
  Scene scene = random_scene(1, 64, rng);
  const int opacity = index_of(scene, "opacity");
  for (std::size_t k = 0; k < scene.rows.size(); ++k) scene.rows[k][opacity] = k % 2 ? 30 : -30;
  const std::string in = (dir / "in.ply").string();
  write_scene(scene, in, false);
  for (const std::string format : {"splat", "compressed.ply", "spz", "glb"}) {
    const std::string mid = (dir / ("mid." + format)).string(), back = (dir / ("back_" + format + ".ply")).string();
    const std::string order = format == "compressed.ply" ? " --keep-order" : "";  // else Morton's
    test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + mid + "' --identity --quiet" + order);
    ASSERT_EQ(run.exit_code, 0) << format << ": " << run.err;
    run = test::run_zhf("splat --in '" + mid + "' --out '" + back + "' --identity --quiet");
    ASSERT_EQ(run.exit_code, 0) << format << ": " << run.err;
    // By name: the columns differ (a .splat holds no SH).
    std::ifstream back_file(back, std::ios::binary);
    const io::ply::Header h = io::ply::read_header(back_file, back);
    const auto column = std::find_if(h.properties.begin(), h.properties.end(), [](const io::ply::Property& p) { return p.name == "opacity"; });
    ASSERT_NE(column, h.properties.end()) << format;
    std::vector<unsigned char> record(h.record_bytes);
    for (std::size_t k = 0; k < scene.rows.size(); ++k) {
      ASSERT_TRUE(back_file.read(reinterpret_cast<char*>(record.data()), std::streamsize(record.size()))) << format << ", splat " << k;
      ASSERT_EQ(io::ply::read_binary(record.data(), *column), float(test::opacity_of_alpha(k % 2 ? 1.0 : 0.0))) << format << ", splat " << k;
    }
    if (format != "splat") continue;
    const std::string again = (dir / "again.splat").string();
    run = test::run_zhf("splat --in '" + back + "' --out '" + again + "' --identity --quiet");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::vector<SplatRecord> records = read_splats(again);
    for (std::size_t k = 0; k < records.size(); ++k) ASSERT_EQ(int(records[k].rgba[3]), k % 2 ? 255 : 0) << "splat " << k;
  }
}

// --info reads the scene whole and writes nothing: its count, degree and the box of its positions
// (computed here from the rows), for a .ply and for the same scene as a .spz (its axes and records
// too); with an output or a transform it is refused in one line.
TEST(Splat, InfoSaysWhatTheSceneHoldsAndWritesNothing) {
  const test::TempDir dir;
  std::mt19937_64 rng(73);
  const Scene scene = random_scene(2, 3000, rng);
  const std::string in = (dir / "in.ply").string(), spz = (dir / "in.spz").string();
  write_scene(scene, in, false);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + spz + "' --quiet").exit_code, 0);
  std::array<double, 3> low{1e300, 1e300, 1e300}, high{-1e300, -1e300, -1e300};
  for (const auto& row : scene.rows)
    for (int i = 0; i < 3; ++i) {
      low[i] = std::min(low[i], row[i]);
      high[i] = std::max(high[i], row[i]);
    }
  char bounds[200];
  std::snprintf(bounds, sizeof bounds, "bounds in the .ply's axes: x %.6g .. %.6g, y %.6g .. %.6g, z %.6g .. %.6g", low[0], high[0], low[1],
                high[1], low[2], high[2]);
  test::RunResult run = test::run_zhf("splat --in '" + in + "' --info");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find(".ply, 3000 splats, SH degree 2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(bounds), std::string::npos) << run.out << "\nexpected " << bounds;
  run = test::run_zhf("splat --in '" + spz + "' --info");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find(".spz, 3000 splats, SH degree 2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("extension records: 0"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("antialiased: no"), std::string::npos) << run.out;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.string()), fs::directory_iterator()), 2) << "--info wrote something";
  for (const std::string& args : {" --info --out '" + (dir / "x.ply").string() + "'", std::string(" --info --zyz '1 2 3'")}) {
    run = test::run_zhf("splat --in '" + in + "'" + args);
    EXPECT_EQ(run.exit_code, 2) << args << ": " << run.err;
    EXPECT_EQ(test::line_count(run.err), 1) << run.err;
    EXPECT_NE(run.err.find("--info"), std::string::npos) << run.err;
  }
}

// Every conversion keeps a field or names it on stderr in one line: a .ply's extra properties
// (here `custom`, and `confidence`), its comments, ASCII and doubles where the canonical record
// writes a .ply, and normals that are not all 0 where the output has none. A scene with nothing
// to lose converts without a word.
TEST(Splat, ConversionsNameWhatTheyDoNotKeep) {
  const test::TempDir dir;
  std::mt19937_64 rng(91);
  Scene scene = random_scene(2, 50, rng);
  const std::string in = (dir / "in.ply").string(), ascii = (dir / "ascii.ply").string();
  write_scene(scene, in, false);
  write_scene(scene, ascii, true);
  auto note = [&](const std::string& from, const std::string& to, const std::string& options) {
    const test::RunResult run = test::run_zhf("splat --in '" + from + "' --out '" + (dir / to).string() + "' --quiet " + options);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const std::size_t at = run.err.find(": not kept from ");
    if (at == std::string::npos) return std::string();
    EXPECT_EQ(run.err.find(": not kept from ", at + 1), std::string::npos) << "one line: " << run.err;
    const std::size_t begin = run.err.find(": ", at + 16) + 2;
    return run.err.substr(begin, run.err.find('\n', begin) + 1 - begin);
  };
  EXPECT_EQ(note(in, "cut.ply", "--sh-degree 1"), "property custom; 1 comment line\n");
  EXPECT_EQ(note(ascii, "cut_ascii.ply", "--sh-degree 1"), "property custom; 1 comment line; ASCII (written binary)\n");
  EXPECT_EQ(note(in, "out.spz", ""), "property custom; normals (nx, ny, nz; not all 0)\n");
  EXPECT_EQ(note(in, "same.ply", "--zyz '0.1 0.2 0.3'"), "") << "a .ply turned in place keeps everything";
  // Doubles and a second extra property; the scene's own record (normals 0) into .spz says nothing.
  std::string text = test::read_text(in);
  const std::string header = text.substr(0, text.find("end_header\n"));
  std::string doubled = header;
  for (const char* name : {"x", "y", "z"}) {
    const std::string from = std::string("property float ") + name + "\n";
    doubled.replace(doubled.find(from), from.size(), std::string("property double ") + name + "\n");
  }
  doubled += "property float confidence\nend_header\n";
  const std::size_t record = 4 * (scene.names.size() + 1);
  for (std::size_t k = 0; k < scene.rows.size(); ++k) {
    const std::string row = text.substr(header.size() + 11 + k * record, record);
    for (int i = 0; i < 3; ++i) {
      float f;
      std::memcpy(&f, row.data() + 4 * i, 4);
      const double d = f;
      doubled.append(reinterpret_cast<const char*>(&d), 8);
    }
    doubled += row.substr(12) + std::string(4, '\0');
  }
  const std::string wide = (dir / "wide.ply").string();
  test::write_text(wide, doubled);
  EXPECT_EQ(note(wide, "cut_wide.ply", "--sh-degree 0"), "properties custom, confidence; 1 comment line; double precision (written as float)\n");
  const std::string plain = (dir / "plain.ply").string();
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + plain + "' --quiet --sh-degree 2").exit_code, 0);
  std::string zeroed = test::read_text(plain);
  const std::size_t body = zeroed.find("end_header\n") + 11, width = 4 * (9 + 24 + 8);
  for (std::size_t k = 0; k < scene.rows.size(); ++k) std::memset(&zeroed[body + k * width + 12], 0, 12);
  test::write_text(plain, zeroed);
  EXPECT_EQ(note(plain, "plain.spz", ""), "") << "the canonical record with normals 0";
}

// The filters against a verdict computed here for each splat, in this order: a NaN or infinite
// value, then the box (where the transform puts the splat, 2 R p + t), then sigmoid(opacity)
// below the bound. The kept splats come out in the input's order, where the transform puts them.
TEST(Splat, FiltersKeepTheSplatsTheTestComputes) {
  const test::TempDir dir;
  std::mt19937_64 rng(73);
  Scene scene = random_scene(1, 3000, rng);
  const int x = index_of(scene, "x"), opacity = index_of(scene, "opacity");
  for (std::size_t k = 0; k < scene.rows.size(); k += 97) scene.rows[k][index_of(scene, "f_rest_4")] = std::nan("");
  for (std::size_t k = 5; k < scene.rows.size(); k += 101) scene.rows[k][index_of(scene, "scale_1")] = HUGE_VAL;
  const std::string in = (dir / "in.ply").string(), out = (dir / "out.ply").string();
  write_scene(scene, in, false);
  const Matrix3 r = runtime::rotation_from_zyz(0.3, 0.5, 0.7);
  const double t[3] = {0.5, 0, -0.25}, low[3] = {-2, -1.5, -3}, high[3] = {2, 2.5, 1}, least = 0.3;
  std::uint64_t nonfinite = 0, outside = 0, transparent = 0;
  std::vector<std::array<double, 4>> expected;  // x, y, z after, opacity
  for (const std::vector<double>& row : scene.rows) {
    if (!std::all_of(row.begin(), row.end(), [](double v) { return std::isfinite(v); })) {
      ++nonfinite;
      continue;
    }
    double p[3];
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
      p[i] = 2 * (r[3 * i] * row[x] + r[3 * i + 1] * row[x + 1] + r[3 * i + 2] * row[x + 2]) + t[i];
      inside = inside && p[i] >= low[i] && p[i] <= high[i];
    }
    if (!inside) ++outside;
    else if (1 / (1 + std::exp(-row[opacity])) < least) ++transparent;
    else expected.push_back({p[0], p[1], p[2], row[opacity]});
  }
  ASSERT_GT(nonfinite, 0u);
  ASSERT_GT(outside, 0u);
  ASSERT_GT(transparent, 0u);
  ASSERT_GT(expected.size(), 100u);
  const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out +
                                            "' --zyz '0.3 0.5 0.7' --scale 2 --translate '0.5 0 -0.25' --crop-box '-2 -1.5 -3 2 2.5 1' "
                                            "--min-opacity 0.3 --drop-nonfinite --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string line = "wrote " + std::to_string(expected.size()) + " of 3000 splats; left out " + std::to_string(nonfinite) +
                           " with a NaN or infinite value, " + std::to_string(outside) + " outside the crop, " +
                           std::to_string(transparent) + " below --min-opacity\n";
  EXPECT_NE(run.err.find(line), std::string::npos) << run.err << "expected " << line;
  std::ifstream file(out, std::ios::binary);
  const io::ply::Header h = io::ply::read_header(file, out);
  ASSERT_EQ(h.vertices, expected.size());
  auto column = [&](const std::string& name) {
    return *std::find_if(h.properties.begin(), h.properties.end(), [&](const io::ply::Property& p) { return p.name == name; });
  };
  const io::ply::Property columns[4] = {column("x"), column("y"), column("z"), column("opacity")};
  std::vector<unsigned char> record(h.record_bytes);
  for (std::size_t k = 0; k < expected.size(); ++k) {
    ASSERT_TRUE(file.read(reinterpret_cast<char*>(record.data()), std::streamsize(record.size()))) << "splat " << k;
    for (int i = 0; i < 3; ++i)
      ASSERT_NEAR(io::ply::read_binary(record.data(), columns[i]), expected[k][i], kFloatStorage * std::max(1.0, std::abs(expected[k][i])))
          << "splat " << k << ", " << "xyz"[i];
    ASSERT_EQ(io::ply::read_binary(record.data(), columns[3]), float(expected[k][3])) << "splat " << k << ", opacity";
  }
  // A sphere, into .splat (32 bytes a splat), without a transform: the count computed here.
  const std::string splat = (dir / "ball.splat").string();
  std::size_t within = 0;
  for (const std::vector<double>& row : scene.rows) {
    const double d[3] = {row[x] - 0.5, row[x + 1], row[x + 2] + 1};
    within += std::all_of(row.begin(), row.end(), [](double v) { return std::isfinite(v); }) && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= 1.5 * 1.5;
  }
  const test::RunResult ball = test::run_zhf("splat --in '" + in + "' --out '" + splat + "' --crop-sphere '0.5 0 -1 1.5' --drop-nonfinite --quiet");
  ASSERT_EQ(ball.exit_code, 0) << ball.err;
  EXPECT_EQ(fs::file_size(splat), 32 * within);
  EXPECT_NE(ball.err.find("wrote " + std::to_string(within) + " of 3000 splats"), std::string::npos) << ball.err;
}

// Two scenes merged: a .ply of SH degree 1, and a .spz of degree 3 in x right, y up, z back
// (--spz-axes rub: turned into the .ply's axes on reading), turned, scaled, shifted and cropped as
// one. The degree-1 scene's count, order, positions and colours, and the zeros in the bands it
// lacks, are computed here; the .spz's splats follow, each as zhf splat converts that file alone.
TEST(Splat, MergedScenesAreEachTransformedAndKeptInOrder) {
  const test::TempDir dir;
  std::mt19937_64 rng(75);
  const Scene a = random_scene(1, 300, rng), b = random_scene(3, 200, rng);
  const std::string a_in = (dir / "a.ply").string(), b_ply = (dir / "b.ply").string(), b_in = (dir / "b.spz").string();
  const std::string out = (dir / "merged.ply").string(), b_alone = (dir / "b_alone.ply").string();
  write_scene(a, a_in, false);
  write_scene(b, b_ply, false);
  ASSERT_EQ(test::run_zhf("splat --in '" + b_ply + "' --out '" + b_in + "' --spz-axes rub --quiet").exit_code, 0);
  const std::string transform = " --zyz '0.3 0.5 0.7' --scale 2 --translate '0.5 0 -0.25' --crop-sphere '0 0 0 3' --spz-axes rub";
  const Matrix3 r = runtime::rotation_from_zyz(0.3, 0.5, 0.7);
  const double t[3] = {0.5, 0, -0.25}, radius = 3;
  std::vector<std::pair<std::size_t, std::array<double, 3>>> kept_a;  // a's row, its position after
  const int x = index_of(a, "x");
  for (std::size_t k = 0; k < a.rows.size(); ++k) {
    const std::vector<double>& row = a.rows[k];
    std::array<double, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = 2 * (r[3 * i] * row[x] + r[3 * i + 1] * row[x + 1] + r[3 * i + 2] * row[x + 2]) + t[i];
    if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= radius * radius) kept_a.push_back({k, p});
  }
  const test::RunResult alone = test::run_zhf("splat --in '" + b_in + "' --out '" + b_alone + "'" + transform + " --quiet");
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  std::ifstream alone_file(b_alone, std::ios::binary);
  const std::size_t kept_b = io::ply::read_header(alone_file, b_alone).vertices;
  ASSERT_GT(kept_a.size(), 20u);
  ASSERT_GT(kept_b, 20u);
  ASSERT_LT(kept_a.size() + kept_b, 400u);
  const std::size_t kept = kept_a.size() + kept_b;
  const test::RunResult run = test::run_zhf("splat --in '" + a_in + "' --in '" + b_in + "' --out '" + out + "'" + transform);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("merged 2 scenes"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("wrote " + std::to_string(kept) + " of 500 splats; left out " + std::to_string(500 - kept) + " outside the crop\n"),
            std::string::npos)
      << run.err;
  Scene like = b;  // the output: degree 3, the canonical columns (b's, without its int column)
  like.rows.assign(kept, b.rows[0]);
  std::string header;
  const Scene merged = read_scene(out, like, header);
  ASSERT_NE(header.find("element vertex " + std::to_string(kept) + "\n"), std::string::npos) << header;
  ASSERT_NE(header.find("property float f_rest_44\n"), std::string::npos) << header;
  for (std::size_t k = 0; k < kept_a.size(); ++k) {
    const std::vector<double>& in = a.rows[kept_a[k].first];
    const std::vector<double>& got = merged.rows[k];
    const std::string at = "merged splat " + std::to_string(k) + " (a.ply splat " + std::to_string(kept_a[k].first) + ")";
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[index_of(like, std::string(1, "xyz"[i]))], kept_a[k].second[i], kFloatStorage * 20) << at << ", position " << i;
    for (int ch = 0; ch < 3; ++ch)
      for (int j = 3; j < 15; ++j)  // bands 2 and 3 of each channel
        EXPECT_EQ(got[index_of(like, "f_rest_" + std::to_string(ch * 15 + j))], 0) << at << ", channel " << ch << ", coefficient " << j + 1;
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::Vector3d v = sh::random_direction(rng);
      const std::array<double, 3> d{v[0], v[1], v[2]};
      std::array<double, 3> rd{};
      for (int i = 0; i < 3; ++i) rd[i] = r[3 * i] * d[0] + r[3 * i + 1] * d[1] + r[3 * i + 2] * d[2];
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(colour(like, got, ch, rd), colour(a, in, ch, d), kFloatStorage * 40) << at << ", channel " << ch;
    }
  }
  Scene b_like = like;
  b_like.rows.assign(kept_b, b.rows[0]);
  const Scene b_rows = read_scene(b_alone, b_like, header);
  for (std::size_t k = 0; k < kept_b; ++k)
    for (std::size_t i = 0; i + 1 < like.names.size() + 1; ++i)
      ASSERT_EQ(merged.rows[kept_a.size() + k][i], b_rows.rows[k][i]) << "merged splat " << kept_a.size() + k << " (b.spz's " << k << "th kept), " << like.names[i];
}

// Merging refused: an unbundled SOG output, too many inputs, a missing one; one line, nothing written.
TEST(Splat, BadMergesAreRefusedAndNothingIsWritten) {
  const test::TempDir dir;
  std::mt19937_64 rng(76);
  const std::string in = (dir / "in.ply").string(), out = (dir / "out.ply").string();
  write_scene(random_scene(0, 20, rng), in, false);
  std::string many;
  for (int i = 0; i <= 64; ++i) many += " --in '" + in + "'";
  const struct {
    std::string options, named;
    int exit_code;
  } bad[] = {
      {"--in '" + in + "' --in '" + in + "' --out '" + (dir / "meta.json").string() + "'", "meta.json", 3},
      {many + " --out '" + out + "'", "--in", 2},
      {"--in '" + in + "' --in '" + (dir / "missing.ply").string() + "' --out '" + out + "'", "missing.ply", 3},
  };
  for (const auto& c : bad) {
    const test::RunResult run = test::run_zhf("splat " + c.options + " --quiet");
    EXPECT_EQ(run.exit_code, c.exit_code) << c.options << ": " << run.err;
    EXPECT_EQ(test::line_count(run.err), 1) << c.options << ": " << run.err;
    EXPECT_NE(run.err.find(c.named), std::string::npos) << c.options << ": " << run.err;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.string()), fs::directory_iterator()), 1) << "something was written";
}

// Bad filter options: one line naming the option, exit 2; a NaN without --drop-nonfinite and a
// filtered .sog, exit 3; nothing written.
TEST(Splat, BadFiltersAreRefusedAndNothingIsWritten) {
  const test::TempDir dir;
  std::mt19937_64 rng(74);
  Scene scene = random_scene(0, 20, rng);
  scene.rows[7][index_of(scene, "y")] = std::nan("");
  const std::string in = (dir / "in.ply").string(), out = (dir / "out.ply").string();
  write_scene(scene, in, false);
  const struct {
    std::string options, named;
    int exit_code;
  } bad[] = {
      {"--crop-box '1 2 3'", "--crop-box", 2},
      {"--crop-box '0 0 0 -1 1 1' --drop-nonfinite", "--crop-box", 2},
      {"--crop-box '0 0 0 nan 1 1' --drop-nonfinite", "--crop-box", 2},
      {"--crop-sphere '0 0 0 -1' --drop-nonfinite", "--crop-sphere", 2},
      {"--crop-sphere '0 0 0'", "--crop-sphere", 2},
      {"--min-opacity 1.5 --drop-nonfinite", "--min-opacity", 2},
      {"--min-opacity x", "--min-opacity", 2},
      {"--min-opacity 0.5", "property y", 3},
  };
  for (const auto& b : bad) {
    const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out + "' " + b.options);
    EXPECT_EQ(run.exit_code, b.exit_code) << b.options << ": " << run.err;
    EXPECT_EQ(test::line_count(run.err), 1) << b.options << ": " << run.err;
    EXPECT_NE(run.err.find(b.named), std::string::npos) << b.options << ": " << run.err;
    EXPECT_FALSE(fs::exists(out)) << b.options;
  }
  const test::RunResult info = test::run_zhf("splat --in '" + in + "' --info --min-opacity 0.5");
  EXPECT_EQ(info.exit_code, 2) << info.err;
  EXPECT_NE(info.err.find("--info"), std::string::npos) << info.err;
  const test::RunResult seed = test::run_zhf("splat --in '" + in + "' --out '" + (dir / "x.sog").string() + "' --seed -1 --drop-nonfinite");
  EXPECT_EQ(seed.exit_code, 2) << seed.err;
  EXPECT_NE(seed.err.find("--seed"), std::string::npos) << seed.err;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.string()), fs::directory_iterator()), 1) << "something was written";
}

TEST(Splat, TransformingASplatFileMatchesTransformingItsPly) {
  const test::TempDir dir;
  std::mt19937_64 rng(32);
  const std::string in = (dir / "in.ply").string(), splat = (dir / "in.splat").string();
  write_scene(random_scene(0, 3000, rng), in, false);
  const std::string turn = " --zyz '0.3 0.5 0.7' --scale 2 --translate '1 2 3' --quiet";
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + splat + "' --identity --quiet").exit_code, 0);
  // .splat in, .splat out (by the extension) against .ply transformed, then converted.
  ASSERT_EQ(test::run_zhf("splat --in '" + splat + "' --out '" + (dir / "a.splat").string() + "'" + turn).exit_code, 0);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + (dir / "b.ply").string() + "'" + turn).exit_code, 0);
  ASSERT_EQ(test::run_zhf("splat --in '" + (dir / "b.ply").string() + "' --out '" + (dir / "b.bin").string() + "' --format splat --identity --quiet")
                .exit_code,
            0);
  const std::vector<SplatRecord> a = read_splats((dir / "a.splat").string()), b = read_splats((dir / "b.bin").string());
  ASSERT_EQ(a.size(), 3000u);
  ASSERT_EQ(b.size(), a.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(a[k].position[i], b[k].position[i]) << "splat " << k;  // float positions rotate the same
      EXPECT_NEAR(a[k].scale[i], b[k].scale[i], 1e-6 * b[k].scale[i]) << "splat " << k;
    }
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(a[k].rgba[i], b[k].rgba[i]) << "splat " << k;  // degree 0: rotation leaves colour alone
      // The quaternion: rotated from its bytes, or from the float it came from: a step at most.
      EXPECT_LE(std::abs(int(a[k].rot[i]) - int(b[k].rot[i])), 1) << "splat " << k << ", rot " << i;
    }
  }
}

TEST(Splat, MalformedSplatFilesAreRefusedAndNothingIsWritten) {
  const test::TempDir dir;
  SplatRecord good{{1, 2, 3}, {0.5f, 0.25f, 1}, {10, 20, 30, 200}, {255, 128, 128, 128}};
  auto bytes = [](std::vector<SplatRecord> records) {
    std::string s(records.size() * 32, '\0');
    std::memcpy(s.data(), records.data(), s.size());
    return s;
  };
  auto with = [&](auto change) {
    SplatRecord r = good;
    change(r);
    return bytes({good, r});
  };
  std::mt19937_64 rng(33);
  Scene no_opacity = random_scene(1, 2, rng);
  const std::string no_opacity_path = (dir / "no_opacity.ply").string();
  {
    std::string text = header_text(no_opacity, false);
    text.replace(text.find("property float opacity\n"), 23, "property float alpha\n");
    test::write_text(no_opacity_path, text + std::string(2 * (no_opacity.names.size() + 1) * 4, '\0'));
  }
  Scene zero_turn = random_scene(0, 2, rng);
  for (const char* q : {"rot_0", "rot_1", "rot_2", "rot_3"}) zero_turn.rows[1][index_of(zero_turn, q)] = 0;
  const std::string zero_turn_path = (dir / "zero_turn.ply").string(), ascii_path = (dir / "ascii.ply").string();
  write_scene(zero_turn, zero_turn_path, false);
  write_scene(zero_turn, ascii_path, true);
  const std::string plain_ascii_path = (dir / "plain_ascii.ply").string();
  write_scene(random_scene(0, 2, rng), plain_ascii_path, true);
  struct Bad {
    std::string in, content, message;  // content empty: `in` exists already
  };
  const std::vector<Bad> cases = {
      {"short.splat", bytes({good}).substr(0, 31), "31 bytes: not a whole number of 32-byte splats"},
      {"long.splat", bytes({good}) + "x", "33 bytes: not a whole number of 32-byte splats"},
      {"nan.splat", with([](SplatRecord& r) { r.position[1] = NAN; }), "splat 1: y is nan"},
      {"inf.splat", with([](SplatRecord& r) { r.position[2] = -INFINITY; }), "splat 1: z is -inf"},
      {"inf_scale.splat", with([](SplatRecord& r) { r.scale[0] = INFINITY; }), "splat 1: scale_0 is inf"},
      {"zero_scale.splat", with([](SplatRecord& r) { r.scale[1] = 0; }), "splat 1: scale_1 is 0, not above 0"},
      {"negative_scale.splat", with([](SplatRecord& r) { r.scale[2] = -1; }), "splat 1: scale_2 is -1, not above 0"},
      {"zero_turn.splat", with([](SplatRecord& r) { std::fill(r.rot, r.rot + 4, 128); }), "splat 1: rotation bytes all 128"},
      {"missing.splat", "", "cannot open"},
      {"dir.splat", "", "not a regular file"},
      {"no_opacity.ply", "", "no property opacity: converting to another format needs it"},
      {"zero_turn.ply", "", "splat 1: rot_0..3 are all zero"},
      {"ascii.ply", "", "splat 1: rot_0..3 are all zero"},
      {"ascii_short.ply", header_text(zero_turn, true) + "1 2 3\n", "splat 0: 3 numbers, the header has"},
      {"ascii_trailing.ply", test::read_text(plain_ascii_path) + "7\n", "data after the last splat"},
  };
  fs::create_directory(dir / "dir.splat");
  for (const Bad& bad : cases) {
    const std::string in = (dir / bad.in).string();
    if (!bad.content.empty()) test::write_text(in, bad.content);
    const bool to_splat = bad.in.size() > 4 && bad.in.substr(bad.in.size() - 4) == ".ply";
    const std::string out = (dir / (to_splat ? "out.splat" : "out.ply")).string();
    const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out + "' --zyz '1 2 3' --quiet");
    EXPECT_EQ(run.exit_code, 3) << bad.message << ": " << run.err;
    EXPECT_NE(run.err.find(bad.message), std::string::npos) << bad.message << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(out)) << bad.message;
  }
  // A FIFO has no size to count 32-byte records by.
  const test::RunResult fifo = test::run_zhf("splat --in /dev/stdin --in-format splat --out '" + (dir / "o.ply").string() + "' --identity");
  EXPECT_EQ(fifo.exit_code, 3) << fifo.err;
  EXPECT_NE(fifo.err.find("not a regular file"), std::string::npos) << fifo.err;
  const test::RunResult format = test::run_zhf("splat --in '" + zero_turn_path + "' --out x --format gltf --identity");
  EXPECT_EQ(format.exit_code, 2) << format.err;
  EXPECT_NE(format.err.find("--format: 'gltf' is not ply, compressed-ply, splat, spz, glb or sog"), std::string::npos) << format.err;
}

// A quaternion read back: rot_0..3 exactly the decoded q (w x y z, in float), the same rotation
// as the original's within `tolerance` of |cos| of their angle.
void expect_quaternion(const Scene& scene, const std::vector<double>& row, const std::vector<double>& original, const double q[4],
                       double tolerance, const std::string& at) {
  double dot = 0, norm = 0;
  for (int i = 0; i < 4; ++i) {
    const double o = original[index_of(scene, "rot_" + std::to_string(i))];
    ASSERT_EQ(row[index_of(scene, "rot_" + std::to_string(i))], float(q[i])) << at;
    dot += q[i] * o;
    norm += o * o;
  }
  ASSERT_GT(std::abs(dot) / std::sqrt(norm), 1 - tolerance) << at;
}

// PlayCanvas's compressed .ply, decoded here from its layout: elements chunk (18 floats: position,
// log-scale and colour bounds), vertex (4 packed uint32) and sh (uint8).
struct Compressed {
  std::vector<std::array<float, 18>> chunks;
  std::vector<std::array<std::uint32_t, 4>> packed;
  std::vector<std::vector<unsigned char>> sh;
};

Compressed read_compressed(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const io::ply::Header h = io::ply::read_header_elements(in, path);
  Compressed c;
  for (const io::ply::Element& e : h.elements)
    for (std::uint64_t row = 0; row < e.count; ++row) {
      std::vector<unsigned char> bytes(e.record_bytes);
      in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
      if (e.name == "chunk") std::memcpy(c.chunks.emplace_back().data(), bytes.data(), 72);
      if (e.name == "vertex") std::memcpy(c.packed.emplace_back().data(), bytes.data(), 16);
      if (e.name == "sh") c.sh.push_back(bytes);
    }
  return c;
}

double unorm(std::uint32_t word, int shift, int bits) { return double((word >> shift) & ((1u << bits) - 1)) / ((1u << bits) - 1); }

TEST(Splat, CompressedPlyHoldsTheLayoutAndReadsBackExactly) {
  const test::TempDir dir;
  std::mt19937_64 rng(34);
  Scene scene = random_scene(3, 70000, rng);
  for (auto& row : scene.rows) {  // SH within the format's [-4, 4]
    for (int i = 0; i < 45; ++i) row[index_of(scene, "f_rest_" + std::to_string(i))] *= 0.5;
  }
  const std::string in = (dir / "in.ply").string(), packed = (dir / "out.compressed.ply").string(), back = (dir / "back.ply").string();
  write_scene(scene, in, false);
  test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + packed + "' --identity --keep-order");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Nothing beyond the format's range; the note names what the format does not hold.
  EXPECT_EQ(test::line_count(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(": not kept from "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(": property custom; normals (nx, ny, nz; not all 0)\n"), std::string::npos) << run.err;
  // The error the format added, per SH band, reported: SH to half a step of 8 / 256.
  double error[4] = {-1, -1, -1, -1};
  const std::size_t report = run.out.find("largest per SH band:");
  ASSERT_NE(report, std::string::npos) << run.out;
  ASSERT_EQ(std::sscanf(run.out.c_str() + report, "largest per SH band: 0: %lf 1: %lf 2: %lf 3: %lf", &error[0], &error[1], &error[2], &error[3]), 4)
      << run.out;
  for (int band = 1; band < 4; ++band) {
    EXPECT_GT(error[band], 0) << band;
    EXPECT_LE(error[band], 1.0 / 64 + 1e-12) << band;
  }
  const Compressed c = read_compressed(packed);
  ASSERT_EQ(c.chunks.size(), (scene.rows.size() + 255) / 256);
  ASSERT_EQ(c.packed.size(), scene.rows.size());
  ASSERT_EQ(c.sh.size(), scene.rows.size());
  // Read back against the layout decoded here.
  run = test::run_zhf("splat --in '" + packed + "' --out '" + back + "' --identity --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::string header;
  const Scene got = read_scene(back, scene, header);
  const double c0 = runtime::kInvSqrt4Pi;
  for (std::size_t k = 0; k < scene.rows.size(); ++k) {
    const std::array<float, 18>& b = c.chunks[k / 256];
    const std::array<std::uint32_t, 4>& w = c.packed[k];
    const std::vector<double>& row = got.rows[k];
    const std::vector<double>& original = scene.rows[k];
    const std::string at = "splat " + std::to_string(k);
    const int shifts[3] = {21, 11, 0}, bits[3] = {11, 10, 11};
    auto lerp = [](double lo, double hi, double t) { return lo * (1 - t) + hi * t; };
    for (int i = 0; i < 3; ++i) {
      const std::string axis = "xyz"s.substr(i, 1), n = std::to_string(i);
      const double x = lerp(b[i], b[3 + i], unorm(w[0], shifts[i], bits[i]));
      ASSERT_EQ(row[index_of(scene, axis)], float(x)) << at;
      // Within half a step of the chunk's range (and the float rounding of its bounds).
      const double step = (double(b[3 + i]) - b[i]) / ((1 << bits[i]) - 1);
      ASSERT_LE(std::abs(x - original[index_of(scene, axis)]), 0.5 * step + 1e-6 * std::abs(x) + 1e-30) << at;
      ASSERT_EQ(row[index_of(scene, "scale_" + n)], float(lerp(b[6 + i], b[9 + i], unorm(w[2], shifts[i], bits[i])))) << at;
      const double colour = lerp(b[12 + i], b[15 + i], unorm(w[3], 24 - 8 * i, 8));
      ASSERT_EQ(row[index_of(scene, "f_dc_" + n)], float((colour - 0.5) / c0)) << at;
    }
    ASSERT_EQ(row[index_of(scene, "opacity")], float(test::opacity_of_alpha(unorm(w[3], 0, 8)))) << at;
    // The quaternion: three of 10 bits, the largest (named by the top 2) from the unit norm; the
    // same rotation as the original, within a step.
    const int largest = int(w[1] >> 30);
    double q[4], norm = 0;
    for (int i = 0, j = 0; i < 4; ++i) {
      if (i == largest) continue;
      q[i] = (unorm(w[1], 20 - 10 * j++, 10) - 0.5) * std::sqrt(2.0);
      norm += q[i] * q[i];
    }
    q[largest] = std::sqrt(std::max(0.0, 1 - norm));
    expect_quaternion(scene, row, original, q, 1e-4, at);
    for (int i = 0; i < 45; ++i) {
      const unsigned char v = c.sh[k][i];
      const double value = v == 0 ? -4.0 : v == 255 ? 4.0 : 8 * ((v + 0.5) / 256 - 0.5);
      ASSERT_EQ(row[index_of(scene, "f_rest_" + std::to_string(i))], float(value)) << at;
      ASSERT_LE(std::abs(value - original[index_of(scene, "f_rest_" + std::to_string(i))]), 1.0 / 64 + 1e-12) << at << ", f_rest " << i;
    }
  }
  // Named plain .ply, the file is known by its header.
  fs::copy_file(packed, dir / "plain.ply");
  run = test::run_zhf("splat --in '" + (dir / "plain.ply").string() + "' --out '" + (dir / "plain_back.ply").string() + "' --identity --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(test::read_text((dir / "plain_back.ply").string()), test::read_text(back));
  // Transformed straight from the compressed file, as its decoded .ply is.
  expect_alike(packed, kTurn, back, kTurn, scene, dir);
}

// By default the splats are written in Morton order: the same splats (known by their SH bytes,
// which do not depend on the chunk), each within half a step of its chunk's range, and chunks far
// smaller than in the input's random order.
TEST(Splat, CompressedPlyIsWrittenInMortonOrder) {
  const test::TempDir dir;
  std::mt19937_64 rng(37);
  Scene scene = random_scene(3, 20000, rng);
  for (auto& row : scene.rows)
    for (int i = 0; i < 45; ++i) row[index_of(scene, "f_rest_" + std::to_string(i))] *= 0.5;
  const std::string in = (dir / "in.ply").string(), kept = (dir / "kept.compressed.ply").string(), sorted = (dir / "sorted.compressed.ply").string();
  write_scene(scene, in, false);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + kept + "' --quiet --keep-order").exit_code, 0);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + sorted + "' --quiet").exit_code, 0);
  const Compressed a = read_compressed(kept), b = read_compressed(sorted);
  ASSERT_EQ(b.packed.size(), scene.rows.size());
  std::map<std::vector<unsigned char>, std::size_t> input_of;
  for (std::size_t k = 0; k < a.sh.size(); ++k) input_of[a.sh[k]] = k;
  ASSERT_EQ(input_of.size(), scene.rows.size()) << "SH bytes name each splat";
  std::set<std::size_t> seen;
  double kept_extent = 0, sorted_extent = 0, sorted_worst = 0;
  for (std::size_t k = 0; k < b.sh.size(); ++k) {
    const auto found = input_of.find(b.sh[k]);
    ASSERT_NE(found, input_of.end()) << "splat " << k << " is not one of the input's";
    seen.insert(found->second);
    const std::array<float, 18>& bounds = b.chunks[k / 256];
    for (int i = 0; i < 3; ++i) {
      const double t = unorm(b.packed[k][0], i == 0 ? 21 : i == 1 ? 11 : 0, i == 1 ? 10 : 11);
      const double x = bounds[i] * (1 - t) + bounds[3 + i] * t, original = scene.rows[found->second][i];
      const double step = (double(bounds[3 + i]) - bounds[i]) / ((1 << (i == 1 ? 10 : 11)) - 1);
      ASSERT_LE(std::abs(x - original), 0.5 * step + 1e-6 * std::abs(x) + 1e-30) << "splat " << k;
      sorted_worst = std::max(sorted_worst, std::abs(x - original));
    }
  }
  EXPECT_EQ(seen.size(), scene.rows.size());
  for (const auto& c : a.chunks) kept_extent += (c[3] - c[0]) + (c[4] - c[1]) + (c[5] - c[2]);
  for (const auto& c : b.chunks) sorted_extent += (c[3] - c[0]) + (c[4] - c[1]) + (c[5] - c[2]);
  EXPECT_LT(sorted_extent, kept_extent / 2) << "chunk extents summed: Morton " << sorted_extent << ", input order " << kept_extent;
}

TEST(Splat, MalformedCompressedPlyIsRefusedAndNothingIsWritten) {
  const test::TempDir dir;
  std::mt19937_64 rng(35);
  const std::string in = (dir / "in.ply").string(), good = (dir / "good.compressed.ply").string();
  write_scene(random_scene(1, 300, rng), in, false);  // two chunks
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + good + "' --identity --quiet").exit_code, 0);
  const std::string text = test::read_text(good);
  const std::size_t data = text.find("end_header\n") + 11;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = text;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  std::string nan_bound = text;
  const float nan = NAN;
  std::memcpy(&nan_bound[data + 72 + 4], &nan, 4);  // chunk 1: min_y
  const std::vector<std::pair<std::string, std::string>> cases = {
      {text.substr(0, text.size() - 1), "truncated"},
      {text + "x", "bytes after the last splat"},
      {replaced("element chunk 2", "element chunk 3"), "3 chunks for 300 splats; expected 2"},
      {replaced("property uint packed_scale", "property float packed_scale"), "element vertex has no uint property packed_scale"},
      {replaced("property float max_b\n", ""), "element chunk has 17 properties, not 12 or 18"},
      {replaced("property float min_r", "property float min_red"), "element chunk has no float property min_r"},
      {replaced("property uchar f_rest_8\n", ""), "element sh has 8 properties"},
      {replaced("element sh 300", "element sh 299"), "299 sh rows for 300 splats"},
      {replaced("end_header", "element extra 0\nproperty float e\nend_header"), "an element other than chunk, vertex and sh"},
      {replaced("binary_little_endian", "ascii"), "a compressed .ply is binary little-endian"},
      {replaced("element vertex 300\n", "element vertex 300\nproperty uint packed_extra\n"), "element vertex has 5 properties"},
      {nan_bound, "chunk 1: min_y is nan"},
  };
  for (const auto& [content, message] : cases)
    expect_refused((dir / "bad.compressed.ply").string(), content, (dir / "out.ply").string(), "--zyz '1 2 3'", message);
}

// gzip of bytes, and back (zlib, as a writer of .spz would).
std::string gzip(const std::string& bytes) {
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&z, uLong(bytes.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = uInt(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::string gunzip(const std::string& bytes) {
  z_stream z{};
  EXPECT_EQ(inflateInit2(&z, 16 + MAX_WBITS), Z_OK);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = uInt(bytes.size());
  std::string out;
  char buffer[1 << 16];
  int result = Z_OK;
  while (result == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buffer);
    z.avail_out = sizeof buffer;
    result = inflate(&z, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - z.avail_out);
  }
  EXPECT_EQ(result, Z_STREAM_END);
  inflateEnd(&z);
  return out;
}

std::string spz_header(std::uint32_t version, std::uint32_t splats, int degree, int fractional_bits = 12, int reserved = 0) {
  std::string h(16, '\0');
  const std::uint32_t words[3] = {0x5053474e, version, splats};
  std::memcpy(h.data(), words, 12);
  h[12] = char(degree);
  h[13] = char(fractional_bits);
  h[15] = char(reserved);
  return h;
}

// With --spz-axes rub (the format's documented axes) the file is RUB and the .ply RDF.
TEST(Splat, SpzHoldsTheLayoutInItsAxesAndReadsBackExactly) {
  const test::TempDir dir;
  std::mt19937_64 rng(36);
  Scene scene = random_scene(3, 70000, rng);
  for (auto& row : scene.rows) {  // within the format's ranges: f_dc to 3.3, SH to 1, log-scales -10..5.9
    for (int i = 0; i < 3; ++i) row[index_of(scene, "f_dc_" + std::to_string(i))] *= 0.5;
    for (int i = 0; i < 45; ++i) row[index_of(scene, "f_rest_" + std::to_string(i))] *= 0.15;
  }
  const std::string in = (dir / "in.ply").string(), spz = (dir / "out.spz").string(), back = (dir / "back.ply").string();
  write_scene(scene, in, false);
  test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + spz + "' --identity --quiet --spz-version 3 --spz-axes rub");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Nothing clamped: the one line is the note of what .spz does not keep (the extra property, normals).
  EXPECT_EQ(test::line_count(run.err), 1) << run.err;
  EXPECT_NE(run.err.find(": not kept from "), std::string::npos) << run.err;
  const std::string data = gunzip(test::read_text(spz));
  const std::size_t n = scene.rows.size();
  ASSERT_EQ(data.size(), 16 + n * (9 + 1 + 3 + 3 + 4 + 45));
  EXPECT_EQ(data.substr(0, 16), spz_header(3, std::uint32_t(n), 3));
  run = test::run_zhf("splat --in '" + spz + "' --out '" + back + "' --identity --quiet --spz-axes rub");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::string header;
  const Scene got = read_scene(back, scene, header);
  auto byte = [&](std::size_t at) { return static_cast<unsigned char>(data[at]); };
  // The file's axes are RUB, the .ply's RDF: y and z flip.
  const double flip[3] = {1, -1, -1};
  for (std::size_t k = 0; k < n; ++k) {
    const std::vector<double>& row = got.rows[k];
    const std::vector<double>& original = scene.rows[k];
    const std::string at = "splat " + std::to_string(k);
    for (int i = 0; i < 3; ++i) {
      const std::size_t p = 16 + 9 * k + 3 * i;
      std::int32_t fixed = byte(p) | (byte(p + 1) << 8) | (byte(p + 2) << 16);
      if (fixed & 0x800000) fixed -= 1 << 24;
      const double x = flip[i] * fixed / 4096.0;
      ASSERT_EQ(row[index_of(scene, "xyz"s.substr(i, 1))], float(x)) << at;
      ASSERT_LE(std::abs(x - original[index_of(scene, "xyz"s.substr(i, 1))]), 0.5 / 4096 + 1e-12) << at;
      const double colour = (byte(16 + 10 * n + 3 * k + i) / 255.0 - 0.5) / 0.15;
      ASSERT_EQ(row[index_of(scene, "f_dc_" + std::to_string(i))], float(colour)) << at;
      ASSERT_LE(std::abs(colour - original[index_of(scene, "f_dc_" + std::to_string(i))]), 0.5 / 255 / 0.15 + 1e-12) << at;
      const double scale = byte(16 + 13 * n + 3 * k + i) / 16.0 - 10;
      ASSERT_EQ(row[index_of(scene, "scale_" + std::to_string(i))], float(scale)) << at;
    }
    ASSERT_EQ(row[index_of(scene, "opacity")], float(test::opacity_of_alpha(byte(16 + 9 * n + k) / 255.0))) << at;
    std::uint32_t word;
    std::memcpy(&word, &data[16 + 16 * n + 4 * k], 4);
    const std::array<double, 4> xyzw = test::spz_smallest_three(word);
    const double wxyz[4] = {xyzw[3], xyzw[0], -xyzw[1], -xyzw[2]};
    expect_quaternion(scene, row, original, wxyz, 2e-5, at);
    // SH: coefficient-major, channel inner, each odd in (y, z) flipped; 5 bits kept in band 1, 4 above.
    for (int j = 0; j < 15; ++j) {
      const int l = j < 3 ? 1 : j < 8 ? 2 : 3, m = j + 1 - l * (l + 1);
      const double sign = (m >= 0 ? 1 : -1) * ((l + std::abs(m)) % 2 == 0 ? 1 : -1);
      for (int ch = 0; ch < 3; ++ch) {
        const double value = sign * (byte(16 + 20 * n + 45 * k + 3 * j + ch) - 128.0) / 128;
        const std::string name = "f_rest_" + std::to_string(15 * ch + j);
        ASSERT_EQ(row[index_of(scene, name)], float(value)) << at << ", " << name;
        ASSERT_LE(std::abs(value - original[index_of(scene, name)]), (l == 1 ? 4.0 : 8.0) / 128 + 0.5 / 128 + 1e-6) << at << ", " << name;
      }
    }
  }
  // Version 4 (the default): the same attributes as zstd frames, so the same values read back.
  const std::string v4 = (dir / "v4.spz").string(), v4_back = (dir / "v4_back.ply").string();
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + v4 + "' --identity --quiet --spz-axes rub").exit_code, 0);
  const std::string v4_bytes = test::read_text(v4);
  ASSERT_GE(v4_bytes.size(), 32u + 96u);
  EXPECT_EQ(v4_bytes.substr(0, 12), spz_header(4, std::uint32_t(n), 3).substr(0, 12));
  ASSERT_EQ(test::run_zhf("splat --in '" + v4 + "' --out '" + v4_back + "' --identity --quiet --spz-axes rub").exit_code, 0);
  EXPECT_EQ(test::read_text(v4_back), test::read_text(back));
  // Transformed straight from the .spz, as its decoded .ply is.
  expect_alike(spz, kTurn + " --spz-axes rub", back, kTurn, scene, dir);
}

TEST(Splat, MalformedSpzIsRefusedAndNothingIsWritten) {
  const test::TempDir dir;
  const std::string record(9 + 1 + 3 + 3 + 4, '\x40');  // one splat of degree 0, version 3
  const std::string good = spz_header(3, 2, 0) + record + record;
  std::string reordered = spz_header(3, 2, 0);
  for (std::size_t a : {9, 1, 3, 3, 4}) reordered += std::string(2 * a, '\x40');
  ASSERT_EQ(reordered.size(), good.size());
  const std::string gz = gzip(reordered);
  std::string corrupt = gz;
  corrupt[gz.size() - 6] ^= 0x55;  // the gzip trailer's CRC
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"PK\x03\x04 not gzip", "not a .spz file (neither NGSP nor a gzip stream)"},
      {spz_header(4, 2, 0), "truncated: a version 4 header is 32 bytes"},
      {gzip(std::string("NGSX") + reordered.substr(4)), "the magic is not NGSP"},
      {gzip(spz_header(1, 2, 0) + reordered.substr(16)), ".spz version 1; zhf reads versions 2, 3 and 4"},
      {gzip(spz_header(3, 2, 5) + reordered.substr(16)), "SH degree 5; .spz holds degrees 0..4"},
      {gzip(spz_header(3, 2, 0, 12, 7) + reordered.substr(16)), "the header's reserved byte is not 0"},
      {gzip(spz_header(3, 2, 0, 30) + reordered.substr(16)), "30 fractional bits; at most 23"},
      {gz.substr(0, gz.size() - 9), "truncated: the gzip stream ends early"},
      {corrupt, "gzip: "},
      {gz + "x", "bytes after the gzip stream"},
      {gzip(reordered + "y"), "decompressed bytes after the last splat"},
      {gzip(reordered.substr(0, reordered.size() - 1)), "the decompressed data ends before the last splat"},
      {gzip(spz_header(3, 2000000000, 0)), "the header claims 2000000000 splats"},
  };
  for (const auto& [content, message] : cases)
    expect_refused((dir / "bad.spz").string(), content, (dir / "out.ply").string(), "--zyz '1 2 3'", message);
  // The well-formed file reads.
  test::write_text((dir / "good.spz").string(), gz);
  const test::RunResult run = test::run_zhf("splat --in '" + (dir / "good.spz").string() + "' --out '" + (dir / "good.ply").string() + "' --identity --quiet");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  // Version 4, as zhf writes it from that file, then broken one way at a time.
  const std::string v4_path = (dir / "good4.spz").string();
  ASSERT_EQ(test::run_zhf("splat --in '" + (dir / "good.spz").string() + "' --out '" + v4_path + "' --identity --quiet").exit_code, 0);
  const std::string v4 = test::read_text(v4_path);
  auto with_byte = [&](std::size_t at, char value) {
    std::string s = v4;
    s[at] = value;
    return s;
  };
  std::uint64_t first_stream;
  std::memcpy(&first_stream, &v4[32], 8);
  const std::vector<std::pair<std::string, std::string>> v4_cases = {
      {with_byte(15, 4), "4 streams; 2 splats of SH degree 0 have 5"},
      {with_byte(14, 4), "header flags 0x00000004: zhf knows 0x1 (antialiased) and 0x2 (extension records)"},
      {with_byte(16, 40), "8 bytes between the header and the table, and no extension flag"},
      {with_byte(16, char(0xf0)), "the table of streams at byte 240 is not inside the file"},
      {with_byte(20, 1), "the header's reserved bytes are not 0"},
      {with_byte(40, 7), "stream 0 holds 7 bytes; 2 splats need 18"},
      {with_byte(32, char(first_stream + 1)), "stream"},
      {v4 + "z", "1 bytes after the last stream"},
      {with_byte(32 + 80, char(v4[32 + 80] ^ 0x3c)), "zstd: "},  // the first frame's magic
      {v4.substr(0, v4.size() - 1), "runs past the end of the file"},
  };
  for (const auto& [content, message] : v4_cases)
    expect_refused((dir / "bad4.spz").string(), content, (dir / "out4.ply").string(), "--identity", message);
}

// ---- .glb (KHR_gaussian_splatting) ----

// A .glb of a JSON text and a BIN chunk (the JSON padded with spaces, as glTF says).
std::string glb(std::string json, const std::string& bin) {
  while (json.size() % 4) json += ' ';
  auto word = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  return word(0x46546c67) + word(2) + word(std::uint32_t(12 + 8 + json.size() + 8 + bin.size())) + word(std::uint32_t(json.size())) +
         word(0x4e4f534a) + json + word(std::uint32_t(bin.size())) + word(0x004e4942) + bin;
}

// A .glb's JSON (parsed here independently) and BIN chunk.
struct Glb {
  nlohmann::json json;
  std::string text, bin;
};
Glb parse_glb(const std::string& bytes) {
  Glb g;
  std::uint32_t words[5];
  std::memcpy(words, bytes.data(), sizeof words);
  EXPECT_EQ(words[0], 0x46546c67u);
  EXPECT_EQ(words[1], 2u);
  EXPECT_EQ(words[2], bytes.size());
  EXPECT_EQ(words[4], 0x4e4f534au);
  g.text = bytes.substr(20, words[3]);
  g.json = nlohmann::json::parse(g.text);
  std::uint32_t bin[2];
  std::memcpy(bin, bytes.data() + 20 + words[3], sizeof bin);
  EXPECT_EQ(bin[1], 0x004e4942u);
  g.bin = bytes.substr(20 + words[3] + 8, bin[0]);
  return g;
}

// Element k's component i of a float attribute.
float glb_float(const Glb& g, const std::string& attribute, std::size_t k, int i) {
  const nlohmann::json& accessor = g.json["accessors"][g.json["meshes"][0]["primitives"][0]["attributes"][attribute].get<int>()];
  EXPECT_EQ(accessor["componentType"], 5126) << attribute;
  const nlohmann::json& view = g.json["bufferViews"][accessor["bufferView"].get<int>()];
  const int width = accessor["type"] == "SCALAR" ? 1 : accessor["type"] == "VEC3" ? 3 : 4;
  float value;
  std::memcpy(&value, g.bin.data() + view.value("byteOffset", 0) + accessor.value("byteOffset", 0) + 4 * (width * k + i), 4);
  return value;
}

TEST(Splat, GlbHoldsTheLayoutInGltfAxesAndReadsBackExactly) {
  const test::TempDir dir;
  std::mt19937_64 rng(37);
  const Scene scene = random_scene(3, 5000, rng);
  const std::string in = (dir / "in.ply").string(), out = (dir / "out.glb").string(), back = (dir / "back.ply").string();
  write_scene(scene, in, false);
  test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out + "' --identity --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Glb g = parse_glb(test::read_text(out));
  const std::size_t n = scene.rows.size();
  const nlohmann::json& primitive = g.json["meshes"][0]["primitives"][0];
  EXPECT_EQ(primitive["mode"], 0);
  EXPECT_EQ(primitive["extensions"]["KHR_gaussian_splatting"]["kernel"], "ellipse");
  EXPECT_EQ(primitive["attributes"].size(), 4u + 16u);
  // What the extension's Release Candidate text (Khronos glTF, April 2026) requires besides: the
  // extension used, a colour space it names, and each attribute's accessor type, float, one per splat.
  const nlohmann::json& used = g.json["extensionsUsed"];
  EXPECT_NE(std::find(used.begin(), used.end(), "KHR_gaussian_splatting"), used.end()) << used;
  const std::string space = primitive["extensions"]["KHR_gaussian_splatting"]["colorSpace"];
  EXPECT_TRUE(space == "srgb_rec709_display" || space == "lin_rec709_display") << space;
  for (const auto& [semantic, index] : primitive["attributes"].items()) {
    const nlohmann::json& accessor = g.json["accessors"][index.get<int>()];
    const std::string type = semantic == "KHR_gaussian_splatting:ROTATION" ? "VEC4" : semantic == "KHR_gaussian_splatting:OPACITY" ? "SCALAR" : "VEC3";
    EXPECT_EQ(accessor["type"], type) << semantic;
    EXPECT_EQ(accessor["componentType"], 5126) << semantic;
    EXPECT_EQ(accessor["count"], n) << semantic;
  }
  ASSERT_EQ(test::run_zhf("splat --in '" + out + "' --out '" + back + "' --identity --quiet").exit_code, 0);
  std::string header;
  const Scene got = read_scene(back, scene, header);
  // glTF's axes are the .ply's turned half a turn about z: x and y flip, SH of odd m flip.
  std::array<double, 6> bounds{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
  for (std::size_t k = 0; k < n; ++k) {
    const std::vector<double>& o = scene.rows[k];
    const std::vector<double>& row = got.rows[k];
    const std::string at = "splat " + std::to_string(k);
    auto value = [&](const std::string& name) { return o[index_of(scene, name)]; };
    for (int i = 0; i < 3; ++i) {
      const std::string axis = "xyz"s.substr(i, 1), s = std::to_string(i);
      const float position = glb_float(g, "POSITION", k, i);
      ASSERT_EQ(position, float((i < 2 ? -1 : 1) * value(axis))) << at;
      bounds[i] = std::min<double>(bounds[i], position);
      bounds[3 + i] = std::max<double>(bounds[3 + i], position);
      ASSERT_EQ(row[index_of(scene, axis)], value(axis)) << at;
      const float scale = glb_float(g, "KHR_gaussian_splatting:SCALE", k, i);
      ASSERT_EQ(scale, float(std::exp(value("scale_" + s)))) << at;
      ASSERT_EQ(row[index_of(scene, "scale_" + s)], float(std::log(double(scale)))) << at;
      ASSERT_EQ(glb_float(g, "KHR_gaussian_splatting:SH_DEGREE_0_COEF_0", k, i), float(value("f_dc_" + s))) << at;
      for (int l = 1; l <= 3; ++l)
        for (int m = -l; m <= l; ++m) {
          const std::string name = "f_rest_" + std::to_string(15 * i + l * l + l + m - 1);
          const std::string attribute = "KHR_gaussian_splatting:SH_DEGREE_" + std::to_string(l) + "_COEF_" + std::to_string(l + m);
          ASSERT_EQ(glb_float(g, attribute, k, i), float((m % 2 ? -1 : 1) * value(name))) << at << ", " << attribute;
          ASSERT_EQ(row[index_of(scene, name)], value(name)) << at << ", " << name;
        }
    }
    const float opacity = glb_float(g, "KHR_gaussian_splatting:OPACITY", k, 0);
    ASSERT_EQ(opacity, float(1 / (1 + std::exp(-value("opacity"))))) << at;
    ASSERT_TRUE(opacity >= 0 && opacity <= 1) << at << ": opacity " << opacity;  // linear, in [0, 1]
    double squared_length = 0;
    for (int i = 0; i < 4; ++i) squared_length += std::pow(double(glb_float(g, "KHR_gaussian_splatting:ROTATION", k, i)), 2);
    ASSERT_NEAR(squared_length, 1, kFloatStorage) << at << ": the rotation is a unit quaternion (each component rounded to float once)";
    ASSERT_EQ(row[index_of(scene, "opacity")], float(test::opacity_of_alpha(opacity))) << at;
    // Stored x y z w: the unit quaternion turned by the half turn k (k q = (-z, -y, x, w) as w x y z).
    const double w = value("rot_0"), x = value("rot_1"), y = value("rot_2"), z = value("rot_3");
    const double norm = std::sqrt(w * w + x * x + y * y + z * z);
    const double expected[4] = {-y / norm, x / norm, w / norm, -z / norm};
    float stored[4];
    for (int i = 0; i < 4; ++i) {
      stored[i] = glb_float(g, "KHR_gaussian_splatting:ROTATION", k, i);
      ASSERT_NEAR(stored[i], expected[i], runtime::tolerance::kFloatEpsilon) << at;
    }
    // Read back: k^-1 applied to the stored quaternion, exactly (signs and order only).
    const float wxyz[4] = {stored[2], stored[1], -stored[0], -stored[3]};
    for (int i = 0; i < 4; ++i) ASSERT_EQ(row[index_of(scene, "rot_" + std::to_string(i))], wxyz[i]) << at;
  }
  const nlohmann::json& position = g.json["accessors"][primitive["attributes"]["POSITION"].get<int>()];
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(float(position["min"][i].get<double>()), float(bounds[i]));  // nine digits: the float exactly
    EXPECT_EQ(float(position["max"][i].get<double>()), float(bounds[3 + i]));
  }
  // An ASCII .ply converts as its binary twin does.
  const std::string ascii = (dir / "ascii.ply").string(), ascii_glb = (dir / "ascii.glb").string();
  write_scene(scene, ascii, true);
  ASSERT_EQ(test::run_zhf("splat --in '" + ascii + "' --out '" + ascii_glb + "' --identity --quiet").exit_code, 0);
  EXPECT_EQ(test::read_text(ascii_glb), test::read_text(out));
  // Transformed straight from the .glb, as its decoded .ply is.
  expect_alike(out, kTurn, back, kTurn, scene, dir);
  // A node placing the mesh (a parent's translation, its own turn about z and scale) is applied
  // on reading: in the .ply's axes the translation's x and y flip, the turn about z stays.
  const double angle = 0.7;
  std::string placed = g.text;
  const std::string node = "\"nodes\":[{\"mesh\":0}]";
  ASSERT_NE(placed.find(node), std::string::npos);
  char nodes[256];
  std::snprintf(nodes, sizeof nodes, "\"nodes\":[{\"children\":[1],\"translation\":[1,2,3]},{\"mesh\":0,\"rotation\":[0,0,%.17g,%.17g],\"scale\":[2,2,2]}]",
                std::sin(angle / 2), std::cos(angle / 2));
  placed.replace(placed.find(node), node.size(), nodes);
  const std::string placed_path = (dir / "placed.glb").string();
  test::write_text(placed_path, glb(placed, g.bin));
  expect_alike(placed_path, "--identity", back, "--axis-angle '0 0 1 0.7' --scale 2 --translate '-1 -2 3'", scene, dir);
}

TEST(Splat, MalformedGlbIsRefusedAndNothingIsWritten) {
  const test::TempDir dir;
  std::mt19937_64 rng(38);
  const std::string in = (dir / "in.ply").string(), good_path = (dir / "good.glb").string();
  write_scene(random_scene(1, 2, rng), in, false);
  ASSERT_EQ(test::run_zhf("splat --in '" + in + "' --out '" + good_path + "' --identity --quiet").exit_code, 0);
  const std::string good = test::read_text(good_path);
  const Glb g = parse_glb(good);
  auto edited = [&](const std::string& from, const std::string& to) {
    std::string text = g.text;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return glb(text, g.bin);
  };
  auto with_float = [&](std::size_t at, float value) {  // in the BIN chunk
    std::string bin = g.bin;
    std::memcpy(&bin[at], &value, 4);
    return glb(g.text, bin);
  };
  auto with_word = [&](std::size_t at, std::uint32_t value) {
    std::string s = good;
    std::memcpy(&s[at], &value, 4);
    return s;
  };
  // Regions of two splats: POSITION at 0, ROTATION at 24, SCALE at 56, OPACITY at 80.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"PK\x03\x04 not a glb at all", "not a .glb"},
      {with_word(4, 1), ".glb version 1"},
      {good + "pad", "the header says"},
      {with_word(12, 0x7fffff00u), "JSON chunk of"},
      {with_word(12, 0x10000u), "the JSON chunk runs past the end of the file"},
      {edited("{\"asset\"", "[\"asset\""), "not valid JSON"},
      {edited("\"extensions\":{\"KHR_gaussian_splatting\"", "\"extras\":{\"KHR_gaussian_splatting\""), "no mesh primitive with KHR_gaussian_splatting"},
      {edited("\"mode\":0", "\"mode\":4"), "mode is not POINTS"},
      {edited("\"KHR_gaussian_splatting:SCALE\"", "\"_SCALE\""), "no KHR_gaussian_splatting:SCALE"},
      {edited("\"KHR_gaussian_splatting:SH_DEGREE_1_COEF_2\"", "\"KHR_gaussian_splatting:SH_DEGREE_1_COEF_9\""), "not an attribute of a degree-1 scene"},
      {edited("\"count\":2,\"type\":\"VEC4\"", "\"count\":1,\"type\":\"VEC4\""), "for POSITION"},
      {edited("\"byteOffset\":0,\"byteLength\":24", "\"byteOffset\":0,\"byteLength\":20"), "run past the end of their buffer view"},
      {edited("\"buffers\":[{", "\"buffers\":[{\"uri\":\"scene.bin\","), "external buffers are not read"},
      {edited("\"extensionsUsed\"", "\"extensionsRequired\":[\"EXT_meshopt_compression\"],\"extensionsUsed\""), "requires EXT_meshopt_compression"},
      {edited("\"type\":\"VEC4\"", "\"type\":\"VEC4\",\"sparse\":{}"), "sparse accessors are not read"},
      {edited("\"type\":\"VEC4\"", "\"type\":\"VEC3\""), "must be VEC4"},
      {edited("\"kernel\":\"ellipse\"", "\"kernel\":\"box\""), "the \"ellipse\" kernel"},
      {edited("\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"scale\":[1,2,1]}]"), "scales unevenly"},
      {edited("\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"children\":[0]}]"), "cycle"},
      {with_float(4, NAN), "splat 0: POSITION is nan"},
      {with_float(56 + 12 + 8, -1), "splat 1: KHR_gaussian_splatting:SCALE is -1, below 0"},
      {with_float(80, 1.5f), "splat 0: KHR_gaussian_splatting:OPACITY is 1.5, outside [0, 1]"},
      {[&] {
         std::string bin = g.bin;
         std::memset(&bin[24], 0, 16);
         return glb(g.text, bin);
       }(),
       "splat 0: KHR_gaussian_splatting:ROTATION is a zero quaternion"},
      {good.substr(0, good.size() - 4), "the header says"},
  };
  for (const auto& [content, message] : cases)
    expect_refused((dir / "bad.glb").string(), content, (dir / "out.ply").string(), "--zyz '1 2 3'", message);
  // glTF accessors are never empty: a scene without splats is refused as a .glb.
  expect_refused((dir / "empty.ply").string(), header_text(random_scene(0, 0, rng), false), (dir / "out.glb").string(), "--identity",
                 "a .glb holds at least one splat");
}

TEST(Splat, GlbQuantisedAttributesAndInterleavedViewsRead) {
  // Two splats as another writer may store them: position and colour interleaved (stride 24),
  // rotation as signed shorts, scale as plain bytes, opacity as normalized bytes (stride 4 each).
  const float interleaved[12] = {1, 2, 3, 0.125f, 0.25f, 0.5f, -4, 5, 0.5f, -0.5f, 0, 0.75f};
  const std::int16_t rotation[8] = {0, 0, 0, 32767, 32767, 0, 0, 0};
  const unsigned char scale[8] = {1, 2, 3, 0, 4, 5, 6, 0}, opacity[8] = {51, 0, 0, 0, 204, 0, 0, 0};
  std::string bin(reinterpret_cast<const char*>(interleaved), sizeof interleaved);
  bin.append(reinterpret_cast<const char*>(rotation), sizeof rotation);
  bin.append(reinterpret_cast<const char*>(scale), sizeof scale);
  bin.append(reinterpret_cast<const char*>(opacity), sizeof opacity);
  const std::string json =
      R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_gaussian_splatting"],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"mode":0,"attributes":{"POSITION":0,"KHR_gaussian_splatting:SH_DEGREE_0_COEF_0":1,)"
      R"("KHR_gaussian_splatting:ROTATION":2,"KHR_gaussian_splatting:SCALE":3,"KHR_gaussian_splatting:OPACITY":4},)"
      R"("extensions":{"KHR_gaussian_splatting":{"kernel":"ellipse","colorSpace":"lin_rec709_display"}}}]}],)"
      R"("buffers":[{"byteLength":80}],"bufferViews":[{"buffer":0,"byteLength":48,"byteStride":24},)"
      R"({"buffer":0,"byteOffset":48,"byteLength":16},{"buffer":0,"byteOffset":64,"byteLength":8,"byteStride":4},)"
      R"({"buffer":0,"byteOffset":72,"byteLength":8,"byteStride":4}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"},)"
      R"({"bufferView":0,"byteOffset":12,"componentType":5126,"count":2,"type":"VEC3"},)"
      R"({"bufferView":1,"componentType":5122,"normalized":true,"count":2,"type":"VEC4"},)"
      R"({"bufferView":2,"componentType":5121,"count":2,"type":"VEC3"},)"
      R"({"bufferView":3,"componentType":5121,"normalized":true,"count":2,"type":"SCALAR"}]})";
  const test::TempDir dir;
  const std::string in = (dir / "in.glb").string(), out = (dir / "out.ply").string();
  test::write_text(in, glb(json, bin));
  const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out + "' --identity --quiet");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::mt19937_64 rng(39);
  Scene like = random_scene(0, 2, rng);
  std::string header;
  const Scene got = read_scene(out, like, header);
  auto logit = [](double p) { return float(std::log(p / (1 - p))); };
  const std::vector<std::vector<float>> expected = {
      // x y z nx ny nz f_dc_0..2 opacity scale_0..2 rot_0..3 (w x y z, turned back by k^-1)
      {-1, -2, 3, 0, 0, 0, 0.125f, 0.25f, 0.5f, logit(51 / 255.0), 0, float(std::log(2.0)), float(std::log(3.0)), 0, 0, 0, -1},
      {4, -5, 0.5f, 0, 0, 0, -0.5f, 0, 0.75f, logit(204 / 255.0), float(std::log(4.0)), float(std::log(5.0)), float(std::log(6.0)), 0, 0, -1, 0}};
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t i = 0; i < expected[k].size(); ++i)
      EXPECT_EQ(got.rows[k][i], expected[k][i]) << "splat " << k << ", " << like.names[i];
}

}  // namespace
}  // namespace zhf
