// The WebAssembly module's C API (zhf_web.h) over zhf::dispatch: the checks of every argument, the
// conventions at the edge, and a rotator per order and type kept for the module's lifetime.
#include "zhf/web/zhf_web.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "zhf/dispatch/checks.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/conventions.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/rotation.h"
#include "zhf/web/limits.h"

namespace zhf::web {
namespace {

std::string last_error;

// A refused argument: the call returns 1 and zhf_web_error() gives the message.
struct Refused {
  std::string message;
};

void check_order(int order) {
  if (order < 1 || order > runtime::kMaxZxzxzOrder)
    throw Refused{"order: " + std::to_string(order) + " is outside 1.." + std::to_string(runtime::kMaxZxzxzOrder)};
}

const runtime::Convention& convention_at(int index) {
  if (index < 0 || index >= int(runtime::conventions().size()))
    throw Refused{"convention: " + std::to_string(index) + " is not a convention's index"};
  return runtime::conventions()[std::size_t(index)];
}

// The rotation given in the convention's axes, as zhf rotates the convention's coefficients.
runtime::Matrix3 rotation_in_zhf_terms(const runtime::Convention& convention, const double* rotation) {
  runtime::Matrix3 r;
  for (int i = 0; i < 9; ++i) r[i] = rotation[i];
  const runtime::RotationCheck check = runtime::validate_rotation(r.data());
  if (!check.ok) throw Refused{"rotation: " + check.message};
  return convention.rotation_in_zhf_terms(r);
}

template <class T>
void check_finite(const T* values, std::size_t count, const char* name) {
  if (dispatch::all_finite(values, count)) return;
  std::size_t i = 0;
  while (std::isfinite(double(values[i]))) ++i;
  throw Refused{std::string(name) + "[" + std::to_string(i) + "]: not a finite number"};
}

// count * per values, or refused when that overflows the module's memory.
std::size_t values_of(std::size_t count, std::size_t per) {
  if (per != 0 && count > (std::size_t(-1) / sizeof(double)) / per) throw Refused{"count: " + std::to_string(count) + " is too large"};
  return count * per;
}

// The order's rotator of type T, made on first use.
template <class T>
const dispatch::Rotator<T>& rotator(int order) {
  static std::vector<std::optional<dispatch::Rotator<T>>> made(runtime::kMaxZxzxzOrder + 1);
  std::optional<dispatch::Rotator<T>>& r = made[std::size_t(order)];
  if (!r) r = dispatch::Rotator<T>::make(order);
  return *r;
}

// in, or a copy of it where out is the same memory (the dispatch calls read and write apart).
template <class T>
const T* apart_from(const T* in, const T* out, std::size_t values, std::vector<T>& copy) {
  if (in != out) return in;
  copy.assign(in, in + values);
  return copy.data();
}

template <class T>
void rotate(int order, int convention, const double* rotation, std::size_t count, const T* in, T* out) {
  check_order(order);
  const runtime::Matrix3 q = rotation_in_zhf_terms(convention_at(convention), rotation);
  const std::size_t values = values_of(count, std::size_t(order) * order);
  check_finite(in, values, "coefficients");
  T r[9];
  for (int i = 0; i < 9; ++i) r[i] = T(q[i]);
  std::vector<T> copy;
  rotator<T>(order).transform_shared(count, r, apart_from(in, out, values, copy), out, 1);
}

template <class T>
void rotate_each(int order, int convention, std::size_t count, const T* rotations, const T* in, T* out) {
  check_order(order);
  const runtime::Convention& c = convention_at(convention);
  const std::size_t values = values_of(count, std::size_t(order) * order);
  check_finite(in, values, "coefficients");
  std::vector<T> turned(values_of(count, 9));
  for (std::size_t v = 0; v < count; ++v) {
    const T* r = rotations + 9 * v;
    if (!runtime::rotation_accepted(r)) {
      throw Refused{"rotations[" + std::to_string(v) + "]: " + runtime::validate_rotation(r).message};
    }
    runtime::Matrix3 m;
    for (int i = 0; i < 9; ++i) m[i] = r[i];
    const runtime::Matrix3 q = c.rotation_in_zhf_terms(m);
    for (int i = 0; i < 9; ++i) turned[9 * v + i] = T(q[i]);
  }
  std::vector<T> copy;
  rotator<T>(order).rotate_batch(count, turned.data(), apart_from(in, out, values, copy), out, 1);
}

void rotate_splats(int degree, int convention, const double* rotation, std::size_t count, const float* in, float* out) {
  if (degree < 0 || degree > kMaxSplatDegree)
    throw Refused{"degree: " + std::to_string(degree) + " is outside 0.." + std::to_string(kMaxSplatDegree)};
  const runtime::Matrix3 q = rotation_in_zhf_terms(convention_at(convention), rotation);
  const int order = degree + 1;
  const std::size_t values = values_of(count, 3 * std::size_t(order) * order);
  check_finite(in, values, "splats");
  if (degree == 0) {
    if (in != out) std::memmove(out, in, values * sizeof(float));
    return;
  }
  float r[9];
  for (int i = 0; i < 9; ++i) r[i] = float(q[i]);
  rotator<float>(order).apply_splats(r, count, in, out, 1);
}

// Runs a call: 0, or 1 with its message kept for zhf_web_error.
template <class Call>
int run(Call&& call) {
  try {
    call();
    last_error.clear();
    return 0;
  } catch (const Refused& refused) {
    last_error = refused.message;
  } catch (const std::bad_alloc&) {
    last_error = "out of memory";
  } catch (const std::exception& e) {
    last_error = e.what();
  }
  return 1;
}

}  // namespace
}  // namespace zhf::web

using zhf::web::run;

extern "C" {

const char* zhf_web_isa(void) { return zhf::dispatch::isa_name(zhf::dispatch::active_isa()); }
const char* zhf_web_error(void) { return zhf::web::last_error.c_str(); }
int zhf_web_max_order(void) { return zhf::runtime::kMaxZxzxzOrder; }
int zhf_web_max_splat_degree(void) { return zhf::web::kMaxSplatDegree; }
int zhf_web_convention_count(void) { return int(zhf::runtime::conventions().size()); }
const char* zhf_web_convention_name(int index) {
  static std::vector<std::string> names;
  if (names.empty())
    for (const zhf::runtime::Convention& c : zhf::runtime::conventions()) names.emplace_back(c.name);
  return index >= 0 && index < int(names.size()) ? names[std::size_t(index)].c_str() : "";
}

int zhf_web_rotation_from_quaternion(const double* q, double* out) {
  return run([&] {
    zhf::runtime::Matrix3 r;
    if (!zhf::runtime::rotation_from_quaternion(q[0], q[1], q[2], q[3], r))
      throw zhf::web::Refused{"quaternion: zero or not finite"};
    for (int i = 0; i < 9; ++i) out[i] = r[i];
  });
}

int zhf_web_rotation_in_zhf_terms(int convention, const double* rotation, double* out) {
  return run([&] {
    const zhf::runtime::Matrix3 q = zhf::web::rotation_in_zhf_terms(zhf::web::convention_at(convention), rotation);
    for (int i = 0; i < 9; ++i) out[i] = q[i];
  });
}

int zhf_web_rotate_f32(int order, int convention, const double* rotation, size_t count, const float* in, float* out) {
  return run([&] { zhf::web::rotate(order, convention, rotation, count, in, out); });
}
int zhf_web_rotate_f64(int order, int convention, const double* rotation, size_t count, const double* in, double* out) {
  return run([&] { zhf::web::rotate(order, convention, rotation, count, in, out); });
}
int zhf_web_rotate_each_f32(int order, int convention, size_t count, const float* rotations, const float* in, float* out) {
  return run([&] { zhf::web::rotate_each(order, convention, count, rotations, in, out); });
}
int zhf_web_rotate_each_f64(int order, int convention, size_t count, const double* rotations, const double* in, double* out) {
  return run([&] { zhf::web::rotate_each(order, convention, count, rotations, in, out); });
}
int zhf_web_rotate_splats_f32(int degree, int convention, const double* rotation, size_t count, const float* in, float* out) {
  return run([&] { zhf::web::rotate_splats(degree, convention, rotation, count, in, out); });
}

void* zhf_web_alloc(size_t bytes) { return std::aligned_alloc(16, (bytes + 15) / 16 * 16); }
void zhf_web_free(void* pointer) { std::free(pointer); }

}  // extern "C"
