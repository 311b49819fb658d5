#include "healpix_method.h"

#include <alm_powspec_tools.h>
#include <rotmatrix.h>

#include "zhf/healpix/alm.h"

namespace zhf::bench {

struct HealpixRotator::State {
  int order;
  mutable healpix::ComplexAlm alm;
  explicit State(int n) : order(n), alm(n - 1, n - 1) {}

  void to_complex(const double* f) const { healpix::real_to_alm(f, alm); }
  void to_real(double* f) const { healpix::alm_to_real(alm, f); }
};

HealpixRotator::HealpixRotator(int order) : state_(std::make_unique<State>(order)) {}
HealpixRotator::~HealpixRotator() = default;

void HealpixRotator::rotate(const double r[9], const double* in, double* out) const {
  state_->to_complex(in);
  rotate_alm(state_->alm, rotmatrix(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]));
  state_->to_real(out);
}

void HealpixRotator::convert_only(const double*, const double* in, double* out) const {
  state_->to_complex(in);
  state_->to_real(out);
}

}  // namespace zhf::bench
