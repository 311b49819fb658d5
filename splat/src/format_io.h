// What the format readers and writers share: the canonical record's layout, opening and sizing
// input, messages, and quantising with the clamps counted.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "zhf/splat/limits.h"

namespace zhf::splat {

// Where each field sits in the canonical record of one SH degree (scene_io.h).
struct Canonical {
  explicit Canonical(int degree) : rest(3 * ((degree + 1) * (degree + 1) - 1)) {}
  int rest;  // f_rest values
  static constexpr int kPosition = 0, kNormal = 3, kDc = 6, kRest = 9;
  int opacity() const { return kRest + rest; }
  int scale() const { return kRest + rest + 1; }
  int rotation() const { return kRest + rest + 4; }
  int size() const { return kRest + rest + 8; }
  // The SH band of f_rest value k of a channel: k + 1 = l (l + 1) + m, so l = floor(sqrt(k + 1)).
  static int band(int k) {
    int l = 1;
    while ((l + 1) * (l + 1) <= k + 1) ++l;
    return l;
  }
};

// The file opened for reading, or io::InputError.
std::ifstream open_input(const std::string& path);
// The size of a regular file, or io::InputError saying why a stream without one cannot be read.
std::uint64_t regular_file_size(const std::string& path, const char* why);
// "<path>: splat <k>: <field>", the start of a message about one value.
std::string where(const std::string& path, std::uint64_t splat, const std::string& field);

// Float32 of a double, the nearest finite float when it is beyond the range (counted).
float clamped_float(double value, std::uint64_t& clamped);
// round(x) into 0..max, counting values outside.
std::uint32_t clamped_round(double x, std::uint32_t max, std::uint64_t& clamped);

// Little-endian float32 and uint32, on a little-endian host as the .ply path (x86-64, AArch64).
inline void put_float(unsigned char* at, float value) { std::memcpy(at, &value, sizeof value); }
inline float get_float(const unsigned char* at) {
  float value;
  std::memcpy(&value, at, sizeof value);
  return value;
}
inline void put_uint32(unsigned char* at, std::uint32_t value) { std::memcpy(at, &value, sizeof value); }
inline std::uint32_t get_uint32(const unsigned char* at) {
  std::uint32_t value;
  std::memcpy(&value, at, sizeof value);
  return value;
}

// The sign a half turn about an axis gives each f_rest coefficient k of a channel (band l, order
// m, k + 1 = l (l + 1) + m): the frame changes at the formats' edges.
enum class Axis { kX, kZ };
const std::array<double, kMaxRestPerChannel>& half_turn_signs(Axis axis);

// The logistic function and its inverse (3DGS stores opacity as a logit).
double sigmoid(double x);
double logit(double p);
// The .ply's opacity (a logit) of an alpha stored in 0..1. Alpha 0 and 1 (bytes 0 and 255) have
// no logit: an alpha within kAlphaMargin of either reads as that far from it, as splat-transform
// reads them, so the two tools' conversions agree, the logit stays finite (-13.8 and 13.8) and
// writes back as the same byte.
double opacity_of_alpha(double alpha);

}  // namespace zhf::splat
