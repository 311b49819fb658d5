// zhf splat through the real binary: random 3DGS scenes of SH degree 0..3, binary and ASCII,
// transformed by rotations and reflections with scale and translation. The oracle: the colour
// (3DGS's own basis formula) seen from R d after equals the colour seen from d before; positions,
// orientations and log-scales as stated; every other column, the comments and the types as
// they were. Malformed files are refused with exit 3 and nothing written.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sh_bases.h"
#include "test_support.h"
#include "zhf/io/ply.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;
using runtime::Matrix3;

// Float32 storage: each value is rounded to float once on the way in and once on the way out.
constexpr double kFloatStorage = 4 * runtime::tolerance::kFloatEpsilon;

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
      for (std::size_t i = 0; i < row.size(); ++i) row[i] = io::ply::read_binary(record.data(), h.properties[i]);
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
  for (const auto& [content, message] : cases) {
    const std::string in = (dir / "bad.ply").string(), out = (dir / "out.ply").string();
    test::write_text(in, content);
    const test::RunResult run = test::run_zhf("splat --in '" + in + "' --out '" + out + "' --zyz '1 2 3' --quiet");
    EXPECT_EQ(run.exit_code, 3) << message << ": " << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << message << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(out)) << message;
  }
  for (const auto& [options, message] : std::vector<std::pair<std::string, std::string>>{
           {"--zyz '1 2 3' --scale 0", "--scale"},
           {"--zyz '1 2 3' --scale '1 2 3'", "--scale"},
           {"--zyz '1 2 3' --translate '1 2'", "--translate: expected 3 numbers, found 2"},
           {"--zyz '1 2 3' --convention nope", "--convention: 'nope' is not one of"},
           {"", "give exactly one of --matrix"},
       }) {
    const test::RunResult run = test::run_zhf("splat --in '" + good + "' --out '" + (dir / "out.ply").string() + "' " + options);
    EXPECT_EQ(run.exit_code, 2) << options << ": " << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << options << ": " << run.err;
  }
}

}  // namespace
}  // namespace zhf
