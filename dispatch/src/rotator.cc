#include "zhf/dispatch/rotator.h"

#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "backend.h"
#include "zhf/dispatch/checks.h"
#include "zhf/runtime/limits.h"

namespace zhf::dispatch {
namespace {

// call(path) for the built path (ZHF_DISPATCH_PATHS) equal to isa, path an
// std::integral_constant<Isa, ...>.
template <Isa First, Isa... Rest, class Call>
auto on_path(Isa isa, const Call& call) {
  if (isa == First) return call(std::integral_constant<Isa, First>{});
  if constexpr (sizeof...(Rest) > 0) {
    return on_path<Rest...>(isa, call);
  } else {
    throw std::invalid_argument(std::string("zhf::dispatch: path ") + isa_name(isa) + " is not built");
  }
}

template <class T>
bool all_finite_active(const T* p, std::size_t count) {
  return on_path<ZHF_DISPATCH_PATHS>(active_isa(), [&](auto path) { return detail::all_finite_on<path.value, T>(p, count); });
}

}  // namespace

bool all_finite(const float* p, std::size_t count) { return all_finite_active(p, count); }
bool all_finite(const double* p, std::size_t count) { return all_finite_active(p, count); }

template <class T>
Rotator<T> Rotator<T>::make(int order, const runtime::LobeTable* table) {
  if (order < 1 || order > runtime::kMaxZxzxzOrder)
    throw std::invalid_argument("zhf::dispatch::Rotator: order " + std::to_string(order) + " is outside 1.." +
                                std::to_string(runtime::kMaxZxzxzOrder));
  Rotator r;
  r.isa_ = active_isa();
  if (!table) {
    r.backend_ = on_path<ZHF_DISPATCH_PATHS>(r.isa_, [&](auto path) { return detail::make_backend<path.value, T>(order); });
    return r;
  }
  if (table->order != order)
    throw runtime::InputError("table: order " + std::to_string(table->order) + ", but the rotation's is " + std::to_string(order));
  // Checked here, in zhf's own types: the path's units throw their own (renamed) error types.
  runtime::validate_lobe_table(*table, "table", runtime::TableCheck::kShape);
  const auto data = detail::copy_table<detail::TableData>(*table);
  r.backend_ = on_path<ZHF_DISPATCH_PATHS>(r.isa_, [&](auto path) { return detail::make_table_backend<path.value, T>(data); });
  return r;
}

template <class T>
int Rotator<T>::order() const {
  return backend_->order();
}
template <class T>
std::string Rotator<T>::path() const {
  return backend_->path();
}
template <class T>
void Rotator<T>::rotate(const T r[9], const T* in, T* out) const {
  backend_->rotate(r, in, out);
}
template <class T>
void Rotator<T>::rotate_rgb(const T r[9], const T* in, T* out) const {
  backend_->rotate_rgb(r, in, out);
}
template <class T>
void Rotator<T>::rotate_batch(std::size_t count, const T* r, const T* in, T* out, int threads) const {
  backend_->rotate_batch(count, r, in, out, threads);
}
template <class T>
void Rotator<T>::transform_each(std::size_t count, const T* q, const T* in, T* out, int threads) const {
  backend_->transform_each(count, q, in, out, threads);
}
template <class T>
void Rotator<T>::transform_shared(std::size_t count, const T q[9], const T* in, T* out, int threads) const {
  backend_->prepare(q, count)->apply(count, in, out, threads);
}
template <class T>
PreparedTransform<T> Rotator<T>::prepare(const T q[9], std::size_t count) const {
  PreparedTransform<T> p;
  p.backend_ = backend_;
  p.prepared_ = backend_->prepare(q, count);
  return p;
}
template <class T>
void PreparedTransform<T>::apply(std::size_t count, const T* in, T* out, int threads) const {
  prepared_->apply(count, in, out, threads);
}
template <class T>
std::vector<std::vector<T>> Rotator<T>::band_matrices(const T q[9]) const {
  return backend_->band_matrices(q);
}
template <class T>
void Rotator<T>::apply_splats(const T q[9], std::size_t count, const T* in, T* out, int threads) const {
  backend_->apply_splats(q, count, in, out, threads);
}
template <class T>
void Rotator<T>::apply_planar(const T q[9], std::size_t count, int channels, const T* in, T* out, int threads) const {
  backend_->apply_planar(q, count, channels, in, out, threads);
}

template class PreparedTransform<float>;
template class PreparedTransform<double>;
template class Rotator<float>;
template class Rotator<double>;

}  // namespace zhf::dispatch
