#include "zhf/dispatch/rotator.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "backend.h"
#include "zhf/runtime/limits.h"

namespace zhf::dispatch {
namespace {

// The factory of each built path (ZHF_DISPATCH_PATHS), chosen by value.
template <class T, Isa... Paths>
std::unique_ptr<detail::Backend<T>> make_on(Isa isa, int order) {
  using Factory = std::unique_ptr<detail::Backend<T>> (*)(int);
  const std::pair<Isa, Factory> factories[] = {{Paths, &detail::make_backend<Paths, T>}...};
  for (const auto& [path, make] : factories)
    if (path == isa) return make(order);
  throw std::invalid_argument(std::string("zhf::dispatch: path ") + isa_name(isa) + " is not built");
}

}  // namespace

template <class T>
Rotator<T> Rotator<T>::make(int order) {
  if (order < 1 || order > runtime::kMaxZxzxzOrder)
    throw std::invalid_argument("zhf::dispatch::Rotator: order " + std::to_string(order) + " is outside 1.." +
                                std::to_string(runtime::kMaxZxzxzOrder));
  Rotator r;
  r.isa_ = active_isa();
  r.backend_ = make_on<T, ZHF_DISPATCH_PATHS>(r.isa_, order);
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
