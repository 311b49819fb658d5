// Any order on one instruction-set path (isa_unit.h): the generated orders through their units
// (isa_order.cc), zxzxz beyond them; and the members of the path's backend, compiled here once.
#include "isa_unit.h"
#include "zhf_kernels.h"

namespace zhf::dispatch_unit {
namespace {

// Any order: the generated orders through their own units, zxzxz elsewhere (order 1 included).
template <class T>
std::unique_ptr<api::Backend<T>> any_order(int order) {
  if (order >= runtime::kMinGeneratedOrder && order <= runtime::kMaxGeneratedOrder)
    return gen::with_order(order, [](auto n) { return api::make_generated<kIsa, decltype(n)::value, T>(); });
  return std::make_unique<IsaBackend<T>>(runtime::Rotator<T>::zxzxz(order));
}

}  // namespace
}  // namespace zhf::dispatch_unit

template <>
std::unique_ptr<zhf_dispatch_api::Backend<float>> zhf_dispatch_api::make_backend<zhf::dispatch_unit::kIsa, float>(int order) {
  return zhf::dispatch_unit::any_order<float>(order);
}

template <>
std::unique_ptr<zhf_dispatch_api::Backend<double>> zhf_dispatch_api::make_backend<zhf::dispatch_unit::kIsa, double>(int order) {
  return zhf::dispatch_unit::any_order<double>(order);
}

template <>
std::unique_ptr<zhf_dispatch_api::Backend<float>> zhf_dispatch_api::make_table_backend<zhf::dispatch_unit::kIsa, float>(const TableData& table) {
  using namespace zhf;
  return std::make_unique<dispatch_unit::IsaBackend<float>>(runtime::Rotator<float>::from_table(copy_table<runtime::LobeTable>(table)));
}

template <>
std::unique_ptr<zhf_dispatch_api::Backend<double>> zhf_dispatch_api::make_table_backend<zhf::dispatch_unit::kIsa, double>(const TableData& table) {
  using namespace zhf;
  return std::make_unique<dispatch_unit::IsaBackend<double>>(runtime::Rotator<double>::from_table(copy_table<runtime::LobeTable>(table)));
}

template <>
bool zhf_dispatch_api::all_finite_on<zhf::dispatch_unit::kIsa, float>(const float* p, std::size_t count) {
  return zhf::runtime::all_finite(p, count);
}

template <>
bool zhf_dispatch_api::all_finite_on<zhf::dispatch_unit::kIsa, double>(const double* p, std::size_t count) {
  return zhf::runtime::all_finite(p, count);
}

namespace zhf::dispatch_unit {

template <class T>
IsaPrepared<T>::IsaPrepared(const runtime::Rotator<T>& rotator, const T* q, std::size_t count)
    : transform_(rotator, q), prepared_(transform_.prepare(count)), n_(std::size_t(rotator.coefficients())) {}

template <class T>
void IsaPrepared<T>::apply(std::size_t count, const T* in, T* out, int threads) const {
  runtime::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) prepared_.apply(in + n_ * v, out + n_ * v);
  });
}

template <class T>
IsaBackend<T>::IsaBackend(runtime::Rotator<T> rotator) : rotator_(std::move(rotator)) {}
template <class T>
int IsaBackend<T>::order() const {
  return rotator_.order();
}
template <class T>
std::string IsaBackend<T>::path() const {
  return rotator_.path();
}
template <class T>
void IsaBackend<T>::rotate(const T* r, const T* in, T* out) const {
  rotator_.rotate(r, in, out);
}
template <class T>
void IsaBackend<T>::rotate_rgb(const T* r, const T* in, T* out) const {
  rotator_.rotate_rgb(r, in, out);
}
template <class T>
void IsaBackend<T>::rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads) const {
  rotator_.rotate_batch(count, r, in, out, threads);
}
template <class T>
void IsaBackend<T>::transform_each(std::size_t count, const T* q, const T* in, T* out, int threads) const {
  const std::size_t n = static_cast<std::size_t>(rotator_.coefficients());
  runtime::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
    runtime::transform_each(rotator_, end - begin, q + 9 * begin, in + n * begin, out + n * begin);
  });
}
template <class T>
std::unique_ptr<api::PreparedBackend<T>> IsaBackend<T>::prepare(const T* q, std::size_t count) const {
  return std::make_unique<IsaPrepared<T>>(rotator_, q, count);
}
template <class T>
std::vector<std::vector<T>> IsaBackend<T>::band_matrices(const T* q) const {
  return runtime::OrthogonalTransform<T>(rotator_, q).dense().bands();
}
template <class T>
void IsaBackend<T>::apply_splats(const T* q, std::size_t count, const T* in, T* out, int threads) const {
  runtime::OrthogonalTransform<T>(rotator_, q).dense().apply_splats(count, in, out, threads);
}
template <class T>
void IsaBackend<T>::apply_planar(const T* q, std::size_t count, int channels, const T* in, T* out, int threads) const {
  runtime::OrthogonalTransform<T>(rotator_, q).dense().apply_planar(count, channels, in, out, threads);
}

template class IsaBackend<float>;
template class IsaBackend<double>;

}  // namespace zhf::dispatch_unit
