// Without libhealpix-cxx-dev: the suite notes that the HEALPix method was not built.
#include <stdexcept>

#include "healpix_method.h"

namespace zhf::bench {

bool healpix_available() { return false; }

struct HealpixRotator::State {};
HealpixRotator::HealpixRotator(int) { throw std::logic_error("HEALPix was not found at configure time"); }
HealpixRotator::~HealpixRotator() = default;
void HealpixRotator::rotate(const double*, const double*, double*) const {}
void HealpixRotator::convert_only(const double*, const double*, double*) const {}

}  // namespace zhf::bench
