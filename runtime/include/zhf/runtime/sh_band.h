// Band-l real SH at a unit direction for the run-time (JSON table) path. Written for the
// runtime alone (it may depend only on the standard library); tests hold it to zhf's
// reference evaluation for every band.
#pragma once

#include <cmath>
#include <vector>

namespace zhf::runtime {

// out[m + l] = y_l^m(v), m = -l..l, v unit. Uses the sin^m-free Legendre recurrence in z and
// Re/Im (x + i y)^m, as the generated code does, with the constants tabulated once per band.
template <class T>
class BandEvaluator {
 public:
  explicit BandEvaluator(int l) : l_(l), diag_(l + 1), a_(l + 1), b_(l + 1) {
    // Q_m^m(z) for m = 0..l, then Q_l^m from Q_m^m by the three-term recurrence.
    double q = 0.28209479177387814347;  // 1 / sqrt(4 pi)
    for (int m = 0; m <= l; ++m) {
      if (m > 0) q *= std::sqrt((2.0 * m + 1) / (2.0 * m));
      diag_[m] = q * (m == 0 ? 1.0 : std::sqrt(2.0));
    }
    for (int n = 0; n <= l; ++n) {
      a_[n].resize(n + 1);
      b_[n].resize(n + 1);
      for (int m = 0; m + 2 <= n; ++m) {
        a_[n][m] = std::sqrt((4.0 * n * n - 1) / (double(n) * n - double(m) * m));
        b_[n][m] = std::sqrt((double(n - 1) * (n - 1) - double(m) * m) / (4.0 * (n - 1) * (n - 1) - 1));
      }
    }
  }

  int band() const { return l_; }

  void operator()(const T v[3], T* out) const {
    T c = 1, s = 0;
    for (int m = 0; m <= l_; ++m) {
      if (m > 0) {
        const T c_next = v[0] * c - v[1] * s;
        s = v[0] * s + v[1] * c;
        c = c_next;
      }
      T q_prev = 0, q = T(diag_[m]);
      if (m < l_) {
        q_prev = q;
        q = T(std::sqrt(2.0 * m + 3)) * v[2] * q;
        for (int n = m + 2; n <= l_; ++n) {
          const T next = T(a_[n][m]) * (v[2] * q - T(b_[n][m]) * q_prev);
          q_prev = q;
          q = next;
        }
      }
      if (m == 0) {
        out[l_] = q;
      } else {
        out[l_ + m] = q * c;
        out[l_ - m] = q * s;
      }
    }
  }

 private:
  int l_;
  std::vector<double> diag_;
  std::vector<std::vector<double>> a_, b_;
};

}  // namespace zhf::runtime
