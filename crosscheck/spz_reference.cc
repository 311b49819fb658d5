// Files the reference .spz library (nianticlabs/spz) writes, and what it reads back from them,
// for tests/splat/spz_test.cc: a scene of 4 splats in the .ply's axes (RDF), written
// once per coordinate-system record 1..16 at SH degree 3 (sys_NN.spz), once at degree 4 with no
// record, converted to RUB (rub_degree4.spz), and once as version 2 (gzip, the quaternion's x y z
// in a byte each) at degree 3, values as they are (version2.spz); beside each, the library's reading of it
// into RDF as a binary .ply in the 3DGS tools' record (x y z nx ny nz f_dc_0..2 f_rest_* opacity
// scale_0..2 rot_0..3, rot w x y z, normals 0).
// Built and run by crosscheck/spz_reference.sh against a checkout of the library.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "coordinate-system-adobe.h"
#include "load-spz.h"
#include "zhf/sh/random.h"

namespace {

constexpr int kSplats = 4;

// Uniform in [a, b), from zhf's draws that every standard library makes alike.
struct Uniform {
  zhf::sh::Rng rng{7};
  float operator()(double a, double b) { return float(a + (b - a) * zhf::sh::uniform01(rng)); }
};

spz::GaussianCloud scene(int degree) {
  Uniform u;
  spz::GaussianCloud g;
  g.numPoints = kSplats;
  g.shDegree = degree;
  const int rest = ((degree + 1) * (degree + 1) - 1) * 3;
  for (int i = 0; i < kSplats; ++i) {
    for (int k = 0; k < 3; ++k) {
      g.positions.push_back(u(-3, 3));
      g.scales.push_back(u(-4, 0));
      g.colors.push_back(u(-1, 1));
    }
    float q[4], norm = 0;
    for (float& x : q) norm += (x = u(-1, 1)) * x;
    for (float x : q) g.rotations.push_back(x / std::sqrt(norm));
    g.alphas.push_back(u(-2, 2));
    for (int k = 0; k < rest; ++k) g.sh.push_back(u(-0.9, 0.9));
  }
  return g;
}

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The library's reading of `bytes` into RDF, as a .ply of float properties.
void write_reading(const std::string& path, const std::vector<std::uint8_t>& bytes, spz::CoordinateSystem to = spz::CoordinateSystem::RDF) {
  spz::UnpackOptions to_ply;
  to_ply.to = to;
  const spz::GaussianCloud g = spz::loadSpz(bytes, to_ply);
  const int dim = (g.shDegree + 1) * (g.shDegree + 1) - 1;
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << g.numPoints << "\n";
  for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"}) out << "property float " << name << "\n";
  for (int k = 0; k < 3 * dim; ++k) out << "property float f_rest_" << k << "\n";
  for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) out << "property float " << name << "\n";
  out << "end_header\n";
  for (int i = 0; i < g.numPoints; ++i) {
    std::vector<float> row(g.positions.begin() + 3 * i, g.positions.begin() + 3 * i + 3);
    row.insert(row.end(), 3, 0.0f);
    row.insert(row.end(), g.colors.begin() + 3 * i, g.colors.begin() + 3 * i + 3);
    for (int ch = 0; ch < 3; ++ch)
      for (int k = 0; k < dim; ++k) row.push_back(g.sh[3 * dim * i + 3 * k + ch]);  // the library's channel is inner
    row.push_back(g.alphas[i]);
    row.insert(row.end(), g.scales.begin() + 3 * i, g.scales.begin() + 3 * i + 3);
    row.push_back(g.rotations[4 * i + 3]);  // the library's x y z w as the .ply's w x y z
    row.insert(row.end(), g.rotations.begin() + 4 * i, g.rotations.begin() + 4 * i + 3);
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: spz_reference OUT_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  spz::PackOptions from_ply;
  from_ply.from = spz::CoordinateSystem::RDF;
  for (int system = 1; system <= 16; ++system) {
    spz::GaussianCloud g = scene(3);
    auto record = std::make_shared<spz::SpzExtensionCoordinateSystemAdobe>();
    record->coordinateSystem = spz::CoordinateSystem(system);
    g.extensions.push_back(record);
    std::vector<std::uint8_t> bytes;
    if (!spz::saveSpz(g, from_ply, &bytes)) return 1;
    char name[32];
    std::snprintf(name, sizeof name, "/sys_%02d", system);
    write_bytes(dir + name + ".spz", bytes);
    write_reading(dir + name + ".ply", bytes);
  }
  std::vector<std::uint8_t> bytes;
  if (!spz::saveSpz(scene(4), from_ply, &bytes)) return 1;
  write_bytes(dir + "/rub_degree4.spz", bytes);
  write_reading(dir + "/rub_degree4.ply", bytes);
  spz::PackOptions version2;
  version2.version = 2;
  if (!spz::saveSpz(scene(3), version2, &bytes)) return 1;
  write_bytes(dir + "/version2.spz", bytes);
  write_reading(dir + "/version2.ply", bytes, spz::CoordinateSystem::UNSPECIFIED);
  return 0;
}
