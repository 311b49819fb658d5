// The run-time rotation of any order up to kMaxTableOrder from a lobe table (Rotator::from_table).
//
// Band l of f is sum_d z_{l,d} y_l(R w_d) with z_l = A_l^T f_l. The lobes are taken Pack<double>
// (4) at a time: each group of lobes is rotated, z of every band that uses one of them is formed
// as whole packs (a dense column product: a SIMD A_l^T beats a sparse scalar one at these sizes),
// and one Legendre recurrence (sh_eval.h) over all bands evaluates the SH at those lobes and
// accumulates y_l^m(R w_d) z_{l,d} lane-wise. With lobe sharing a lobe is evaluated once for all
// the bands that use it, not once per band. Lane sums come at the end.
//
// Convention: as Rotator (coefficients of f(R^T w)). Precision: the lobe stage runs in double
// with R first projected onto the rotations, since A_l amplifies the lobe stage's rounding by
// its condition number (205 at order 32: a float stage would give ~4e-4); the error is then the
// rounding of R and of the output, tested within tolerance::float_rotation(order, k, true).
// Cost: (2N-1) N^2 recurrence steps and sum_l (2l+1)^2 multiply-adds for A^T, 4 lanes at a time;
// no heap allocation per call; stack use 40 KB per channel.
#pragma once

#include <algorithm>
#include <vector>

#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/pack.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::runtime {

template <class T>
class TableRotation {
 public:
  using P = Pack<double>;
  static constexpr int kLanes = P::kLanes;

  TableRotation() : legendre_(0) {}

  // The table's shape must have been checked (validate_lobe_table): bands l = 2..order-1 in order,
  // lobe positions in range.
  explicit TableRotation(const LobeTable& table) : order_(table.order), legendre_(table.order) {
    const int lobes = static_cast<int>(table.lobes.size());
    const int packs = (lobes + kLanes - 1) / kLanes;
    for (int p = 0; p < packs; ++p) {
      double xyz[3][kLanes];
      for (int lane = 0; lane < kLanes; ++lane) {
        const int lobe = std::min(p * kLanes + lane, lobes - 1);  // padding: a copy, weighted 0
        for (int k = 0; k < 3; ++k) xyz[k][lane] = table.lobes[lobe].xyz[k];
      }
      lobes_.push_back({P::load(xyz[0]), P::load(xyz[1]), P::load(xyz[2])});
    }
    pack_bands_.resize(packs);
    for (const TableBand& band : table.bands) {
      const int size = band_size(band.l);
      for (int p = 0; p < packs; ++p) {
        // Column lane of this pack holds A_l[.][d] for the band's lobe d at that position.
        std::vector<double> rows(size * kLanes, 0.0);
        bool used = false;
        for (int d = 0; d < size; ++d) {
          const int lobe = band.lobes[d];
          if (lobe / kLanes != p) continue;
          used = true;
          for (int m = 0; m < size; ++m) rows[m * kLanes + lobe % kLanes] = band.inverse(m, d);
        }
        if (!used) continue;
        pack_bands_[p].push_back({band.l, static_cast<int>(inverse_rows_.size())});
        for (int m = 0; m < size; ++m) inverse_rows_.push_back(P::load(&rows[m * kLanes]));
      }
    }
  }

  int order() const { return order_; }

  // out[c N^2 + i] for channels c < channels (1..3), from in laid out the same way.
  void rotate(const T r[9], const T* in, T* out, int channels) const {
    switch (channels) {
      case 1: return run<1>(r, in, out);
      case 2: return run<2>(r, in, out);
      default: return run<3>(r, in, out);
    }
  }

 private:
  struct LobePack {
    P x, y, z;
  };
  struct PackBand {
    int l;
    int rows;  // position of its 2l+1 rows of A_l^T lanes in inverse_rows_
  };

  template <int C>
  void run(const T r[9], const T* in, T* out) const {
    const int n = order_ * order_;
    double q[9];
    polar_step(r, q);
    double f_wide[C][kMaxTableOrder * kMaxTableOrder];
    for (int c = 0; c < C; ++c)
      for (int i = 0; i < n; ++i) f_wide[c][i] = double(in[c * n + i]);
    P acc[C][kMaxTableOrder * kMaxTableOrder];
    for (int c = 0; c < C; ++c)
      for (int i = 0; i < n; ++i) acc[c][i] = P(0.0);
    for (std::size_t p = 0; p < lobes_.size(); ++p) {
      const LobePack& w = lobes_[p];
      // R w_d: row k of R dotted with w_d.
      const P x = P(q[0]) * w.x + P(q[1]) * w.y + P(q[2]) * w.z;
      const P y = P(q[3]) * w.x + P(q[4]) * w.y + P(q[5]) * w.z;
      const P z = P(q[6]) * w.x + P(q[7]) * w.y + P(q[8]) * w.z;
      // z_{l,d} for the lobes of this pack, in lanes; zero for bands that use none of them.
      // Accumulating the zeros costs less than branching on them.
      P weight[C][kMaxTableOrder];
      for (int c = 0; c < C; ++c)
        for (int l = 0; l < order_; ++l) weight[c][l] = P(0.0);
      for (const PackBand& b : pack_bands_[p]) {
        const P* rows = &inverse_rows_[b.rows];
        for (int c = 0; c < C; ++c) {
          // Four partial sums: one would be a chain of dependent multiply-adds.
          const double* f = &f_wide[c][b.l * b.l];
          const int size = band_size(b.l);
          P sum[4] = {P(0.0), P(0.0), P(0.0), P(0.0)};
          int m = 0;
          for (; m + 4 <= size; m += 4)
            for (int k = 0; k < 4; ++k) sum[k] += P(f[m + k]) * rows[m + k];
          for (; m < size; ++m) sum[m % 4] += P(f[m]) * rows[m];
          weight[c][b.l] = (sum[0] + sum[1]) + (sum[2] + sum[3]);
        }
      }
      for_each_legendre<P>(order_, x, y, z, legendre_, [&](int l, int m, const P& q_lm, const P& cos_m, const P& sin_m) {
        if (m == 0) {
          for (int c = 0; c < C; ++c) acc[c][index(l, 0)] += q_lm * weight[c][l];
        } else {
          const P qc = q_lm * cos_m, qs = q_lm * sin_m;
          for (int c = 0; c < C; ++c) {
            acc[c][index(l, m)] += qc * weight[c][l];
            acc[c][index(l, -m)] += qs * weight[c][l];
          }
        }
      });
    }
    for (int c = 0; c < C; ++c) {
      const T* f = in + c * n;
      T* g = out + c * n;
      g[0] = f[0];
      if (order_ > 1) rotate_band1(r, f + 1, g + 1);
      double sums[kMaxTableOrder * kMaxTableOrder];
      P::sums(acc[c], n, sums);
      for (int l = 2; l < order_; ++l)
        for (int m = -l; m <= l; ++m) g[index(l, m)] = T(sums[index(l, m)] * (m == 0 ? 1.0 : kSqrt2));
    }
  }

  int order_ = 0;
  TabulatedLegendreCoefficients legendre_;
  std::vector<LobePack> lobes_;
  std::vector<std::vector<PackBand>> pack_bands_;  // per lobe pack, the bands using it
  std::vector<P> inverse_rows_;
};

}  // namespace zhf::runtime
