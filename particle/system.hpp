#pragma once
// Particle state (structure of arrays) and the one neighbour loop: linked cells, re-sorted by
// (cell, id) every step so that the pair order, and hence every result, depends only on the
// positions and ids, not on storage order or thread count.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace twinflow::particle {

template <int D> struct State {
  std::array<std::vector<double>, D> x, v;
  std::vector<double> u;         // internal energies; empty for isothermal DPD
  std::vector<std::uint32_t> id; // survives sorting
  std::array<double, D> box{};
  std::size_t size() const { return id.size(); }
};

// Extra per-particle arrays an integrator keeps across steps (forces, potentials); they are
// permuted together with the state.
template <int D> struct Carried {
  std::array<std::vector<double>, D> f; // force on each particle
  std::vector<double> q;                // heat rate (ec-verlet)
  std::vector<double> potential;        // per-particle share of pair potentials
};

template <int D> class CellGrid {
public:
  // Cell side >= rc. In a periodic direction the cell count is a multiple of 3 (cells of one of
  // the 27 / 9 colours then touch disjoint particles, also across the wrap), or 1 when the box
  // holds fewer than 3 cutoffs. A direction with walls has no wrap and no minimum image.
  CellGrid(const std::array<double, D>& box, double rc,
           std::array<bool, D> periodic = all_periodic())
      : box_(box), periodic_(periodic) {
    for (int d = 0; d < D; ++d) {
      int n = static_cast<int>(std::floor(box[d] / rc));
      if (periodic[d]) n = n >= 3 ? 3 * (n / 3) : 1;
      n_[d] = std::max(n, 1);
      inv_side_[d] = n_[d] / box[d];
      inv_box_[d] = periodic[d] ? 1.0 / box[d] : 0.0; // 0: nearbyint(0) = 0, no image shift
    }
    total_ = 1;
    for (int d = 0; d < D; ++d) total_ *= n_[d];
    start_.assign(total_ + 1, 0);
    build_stencil();
  }
  static std::array<bool, D> all_periodic() {
    std::array<bool, D> p;
    p.fill(true);
    return p;
  }

  int cells() const { return total_; }
  const std::array<int, D>& counts() const { return n_; }
  std::size_t begin(int c) const { return start_[c]; }
  std::size_t end(int c) const { return start_[c + 1]; }
  double side(int d) const { return box_[d] / n_[d]; }

  int cell_of(const double* pos) const {
    int c = 0;
    for (int d = D - 1; d >= 0; --d) {
      int k = static_cast<int>(pos[d] * inv_side_[d]);
      k = std::min(std::max(k, 0), n_[d] - 1);
      c = c * n_[d] + k;
    }
    return c;
  }

  // Wraps positions into the box and sorts every per-particle array by (cell, id).
  void sort(State<D>& s, Carried<D>& carried);

  // Minimum-image separation x_i - x_j.
  void separation(const State<D>& s, std::size_t i, std::size_t j, double* dx) const {
    for (int d = 0; d < D; ++d) {
      double r = s.x[d][i] - s.x[d][j];
      r -= box_[d] * std::nearbyint(r * inv_box_[d]);
      dx[d] = r;
    }
  }

  // Calls fn(i, j, dx, r2) once for every pair closer than rc (dx = x_i - x_j). Colours run in
  // turn, the cells of one colour in parallel: the pairs a cell visits touch only its 3^D block,
  // so no two threads write the same particle and each particle sees its pairs in one fixed
  // order, whatever the thread count.
  template <class PairFn> void for_each_pair(const State<D>& s, double rc, PairFn&& fn) const {
    const double rc2 = rc * rc;
    const int colours = static_cast<int>(colour_cells_.size());
    for (int colour = 0; colour < colours; ++colour) {
      const auto& list = colour_cells_[colour];
      const long count = static_cast<long>(list.size());
#pragma omp parallel for schedule(static)
      for (long k = 0; k < count; ++k) visit_cell(s, list[k], rc2, fn);
    }
  }

  // The same pairs, one thread, in the same order (reference for tests and for serial passes).
  template <class PairFn>
  void for_each_pair_serial(const State<D>& s, double rc, PairFn&& fn) const {
    const double rc2 = rc * rc;
    for (const auto& list : colour_cells_)
      for (const int c : list) visit_cell(s, c, rc2, fn);
  }

private:
  template <class PairFn> void visit_cell(const State<D>& s, int c, double rc2, PairFn& fn) const {
    std::array<int, D> idx;
    int rem = c;
    for (int d = 0; d < D; ++d) {
      idx[d] = rem % n_[d];
      rem /= n_[d];
    }
    double dx[D];
    for (const auto& offset : stencil_) {
      int nb = 0;
      bool outside = false;
      for (int d = D - 1; d >= 0; --d) {
        const int k = idx[d] + offset[d];
        outside |= !periodic_[d] && (k < 0 || k >= n_[d]);
        nb = nb * n_[d] + (k + n_[d]) % n_[d];
      }
      if (outside) continue;
      const bool same = nb == c;
      for (std::size_t i = start_[c]; i < start_[c + 1]; ++i) {
        for (std::size_t j = same ? i + 1 : start_[nb]; j < start_[nb + 1]; ++j) {
          double r2 = 0;
          for (int d = 0; d < D; ++d) {
            double r = s.x[d][i] - s.x[d][j];
            r -= box_[d] * std::nearbyint(r * inv_box_[d]);
            dx[d] = r;
            r2 += r * r;
          }
          if (r2 < rc2) fn(i, j, dx, r2);
        }
      }
    }
  }

  void build_stencil();

  std::array<double, D> box_, inv_side_, inv_box_;
  std::array<bool, D> periodic_;
  std::array<int, D> n_;
  int total_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::array<int, D>> stencil_; // half shell: each neighbour pair of cells once
  std::vector<std::vector<int>> colour_cells_;
  std::vector<int> cell_, order_;
  std::vector<double> scratch_;
};

} // namespace twinflow::particle
