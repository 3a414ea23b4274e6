#pragma once
// Particle state (structure of arrays) and the one neighbour loop: linked cells, re-sorted by
// (cell, id) whenever the pair list is rebuilt, so that the pair order, and hence every result,
// depends only on the positions and ids, not on storage order or thread count.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <vector>

#include <omp.h>

namespace twinflow::particle {

template <int D> struct State {
  std::array<std::vector<double>, D> x, v;
  std::vector<double> u;         // internal energies; empty for isothermal DPD
  std::vector<std::uint32_t> id; // survives sorting
  std::array<double, D> box{};
  std::size_t size() const { return id.size(); }
};

// Extra per-particle arrays an integrator keeps across steps (forces, potentials): a step
// recomputes them after every sort, a restart restores them (CellGrid::sort).
template <int D> struct Carried {
  std::array<std::vector<double>, D> f; // force on each particle
  std::vector<double> q;                // heat rate (ec-verlet, euler; empty for shardlow)
  std::vector<double> potential;        // per-particle share of pair potentials
};

// Resizes a per-particle array, growing its capacity by a sixteenth when it must grow: resize
// alone doubles it, and counts that move a little at every rebuild (owned plus ghost particles on
// a rank) left every array at twice its size (peak heap 375 bytes per owned particle on two ranks
// against one process's 194). Owned plus ghost counts move by ~0.5% between rebuilds.
template <class Vector> void resize_with_margin(Vector& a, std::size_t n) {
  if (a.capacity() < n) a.reserve(n + n / 16);
  a.resize(n);
}

// An array whose new elements are left uninitialised: the pages a list sized with a margin
// never reaches are never touched, so they cost no memory.
template <class T> class UninitialisedArray {
public:
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  void grow(std::size_t size, std::size_t keep) { // to at least `size`, keeping [0, keep)
    if (size <= size_) return;
    if (keep == 0) data_.reset(); // the old beside the new would be the run's peak memory
    std::unique_ptr<T[]> bigger(new T[size]);
    std::copy(data_.get(), data_.get() + keep, bigger.get());
    data_ = std::move(bigger);
    size_ = size;
  }

private:
  std::unique_ptr<T[]> data_;
  std::size_t size_ = 0;
};

template <int D> class CellGrid {
public:
  // Cell side >= rc. Through its half-shell pairs a plane of cells z (3D; a row y in 2D)
  // touches only its own particles and those of the next plane, so planes of one parity touch
  // disjoint particles. The unit of parallel work is a plane (2D: a row), its rows of cells
  // along x in y order: even units run in parallel, then odd ones, as two phases would
  // (for_each_row: each odd unit after its two even neighbours, the planes still in cache; a
  // plane's particles stay in cache while its rows pass). Across the wrap this needs a
  // periodic cell count that is even and >= 4 in the last direction, >= 3 in the others, or 1
  // when the box is too small. A direction with walls has no wrap and no minimum image.
  CellGrid(const std::array<double, D>& box, double rc,
           std::array<bool, D> periodic = all_periodic())
      : box_(box), periodic_(periodic) {
    for (int d = 0; d < D; ++d) {
      int n = static_cast<int>(std::floor(box[d] / rc));
      if (periodic[d] && d == D - 1)
        n = n >= 4 ? 2 * (n / 2) : 1;
      else if (periodic[d])
        n = n >= 3 ? n : 1;
      n_[d] = std::max(n, 1);
      global_n_[d] = n_[d];
      cell_wrap_[d] = periodic[d];
      inv_side_[d] = n_[d] / box[d];
      inv_box_[d] = periodic[d] ? 1.0 / box[d] : 0.0; // 0: nearbyint(0) = 0, no image shift
    }
    total_ = 1;
    for (int d = 0; d < D; ++d) total_ *= n_[d];
    start_.assign(total_ + 1, 0);
    units_ = n_[D - 1];
    build_stencil();
  }
  // Restricts the grid to a slab of planes along the last direction (decomposition.hpp):
  // `owned` planes from global plane `first`, and with `ghost` the plane after them (the next
  // rank's first) whose particles are only ever a pair's j. Positions stay global, and so do the
  // cell sides and minimum images: the pairs, and their order, are those of the whole grid.
  void restrict_to_slab(int first, int owned, bool ghost) {
    z0_ = first;
    units_ = owned;
    n_[D - 1] = owned + (ghost ? 1 : 0);
    cell_wrap_[D - 1] = false;
    total_ = 1;
    for (int d = 0; d < D; ++d) total_ *= n_[d];
    start_.assign(total_ + 1, 0);
    stencil_.clear(), slot_cell_.clear(), unit_begin_.clear(), phase_begin_.clear();
    work_before_.clear();
    build_stencil();
  }
  // Called by the pair passes of a slab between their two phases of planes (forward: the upper
  // rank's first plane into the ghost plane) and after them (back: the ghost plane's updates to
  // its owner), on the calling thread, outside any parallel region.
  struct PhaseHook {
    virtual void forward() = 0;
    virtual void back() = 0;
  };
  void set_phase_hook(PhaseHook* hook) { hook_ = hook; }
  bool has_ghost_plane() const { return n_[D - 1] > units_; }
  int cells_per_plane() const { return total_ / n_[D - 1]; }
  // The ghost plane's particles, storage [first, first + count), already in (cell, id) order:
  // their cells from `key` (positions in storage order).
  template <class T>
  void set_ghost_cells(const std::array<std::vector<T>, D>& key, std::size_t first,
                       std::size_t count) {
    const int per_plane = cells_per_plane(), c0 = units_ * per_plane;
    for (int c = c0; c <= total_; ++c) start_[c] = first;
    for (std::size_t i = first; i < first + count; ++i) {
      double pos[D];
      for (int d = 0; d < D; ++d) pos[d] = key[d][i];
      ++start_[cell_of(pos) + 1];
    }
    for (int c = c0; c < total_; ++c) start_[c + 1] += start_[c] - first;
  }
  // The plane, in the whole box, of a position (as the sort's cells take it).
  int global_plane(double pos) const {
    const int k = static_cast<int>(pos * inv_side_[D - 1]);
    return std::min(std::max(k, 0), global_n_[D - 1] - 1);
  }
  // Calls fn(j) for the particles of this slab's own planes in the cells within `reach` cells
  // of pos's cell (pos anywhere in the box), each cell once: for_each_near on a slab.
  template <class T, class Fn> void for_each_near_in_slab(const T* pos, int reach, Fn&& fn) const {
    std::array<int, D> lo, hi, k;
    for (int d = 0; d < D; ++d) {
      const int g = global_n_[d];
      int idx = static_cast<int>(pos[d] * inv_side_[d]);
      idx = std::min(std::max(idx, 0), g - 1);
      if (periodic_[d] && 2 * reach + 1 >= g)
        lo[d] = 0, hi[d] = g - 1;
      else if (periodic_[d])
        lo[d] = idx - reach, hi[d] = idx + reach;
      else
        lo[d] = std::max(idx - reach, 0), hi[d] = std::min(idx + reach, g - 1);
    }
    k = lo;
    while (true) {
      int c = 0;
      bool inside = true;
      for (int d = D - 1; d >= 0; --d) {
        int kk = (k[d] + global_n_[d]) % global_n_[d];
        if (d == D - 1) {
          kk -= z0_;
          if (kk < 0) kk += global_n_[d];
          inside = kk < units_;
        }
        c = c * n_[d] + kk;
      }
      if (inside)
        for (std::size_t j = start_[c]; j < start_[c + 1]; ++j) fn(j);
      int d = 0;
      while (d < D && k[d] == hi[d]) k[d] = lo[d], ++d;
      if (d == D) break;
      ++k[d];
    }
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
  double side(int d) const { return box_[d] / global_n_[d]; }
  double smallest_side() const {
    double s = side(0);
    for (int d = 1; d < D; ++d) s = std::min(s, side(d));
    return s;
  }
  // Calls fn(j) for every particle of the cells within `reach` cells of pos's cell in every
  // direction, each cell once (periodic directions wrap; walls end the range).
  template <class T, class Fn> void for_each_near(const T* pos, int reach, Fn&& fn) const {
    double p[D];
    for (int d = 0; d < D; ++d) p[d] = pos[d];
    int rem = cell_of(p);
    std::array<int, D> lo, hi, k;
    for (int d = 0; d < D; ++d) {
      const int idx = rem % n_[d];
      rem /= n_[d];
      if (cell_wrap_[d] && 2 * reach + 1 >= n_[d])
        lo[d] = 0, hi[d] = n_[d] - 1;
      else if (cell_wrap_[d])
        lo[d] = idx - reach, hi[d] = idx + reach;
      else
        lo[d] = std::max(idx - reach, 0), hi[d] = std::min(idx + reach, n_[d] - 1);
    }
    k = lo;
    while (true) {
      int c = 0;
      for (int d = D - 1; d >= 0; --d) c = c * n_[d] + (k[d] + n_[d]) % n_[d];
      for (std::size_t j = start_[c]; j < start_[c + 1]; ++j) fn(j);
      int d = 0;
      while (d < D && k[d] == hi[d]) k[d] = lo[d], ++d;
      if (d == D) break;
      ++k[d];
    }
  }

  int cell_of(const double* pos) const {
    int c = 0;
    for (int d = D - 1; d >= 0; --d) {
      int k = static_cast<int>(pos[d] * inv_side_[d]);
      k = std::min(std::max(k, 0), global_n_[d] - 1);
      if (d == D - 1 &&
          n_[d] != global_n_[d]) { // a slab: its planes from z0_, the ghost plane wrapped
        k -= z0_;
        if (k < 0) k += global_n_[d];
        k = std::min(k, n_[d] - 1);
      }
      c = c * n_[d] + k;
    }
    return c;
  }

  // Wraps positions into the box and sorts the state by (cell, id), the cell of each particle
  // taken from `key` (positions in storage order) if given, else from s.x. The carried arrays
  // are sorted with it (keep_carried) or left stale: a step recomputes them after every sort
  // before it reads them, and f[0] then lends its storage to the sort (no extra array).
  template <class T> using Positions = std::array<std::vector<T>, D>;
  using ListedPositions = Positions<float>; // what a Verlet list is built from (12 bytes)
  void sort(State<D>& s, Carried<D>& carried, const ListedPositions* key = nullptr,
            bool keep_carried = true);
  // Wraps positions in periodic directions into [0, box) (keeps the storage order).
  void wrap(State<D>& s) const;
  double wrapped(double x, int d) const {
    if (!periodic_[d]) return x;
    x -= box_[d] * std::floor(x * inv_box_[d]);
    return x >= box_[d] ? 0 : x; // -tiny wraps to box exactly
  }

  // Minimum image of a difference r along d (r itself in a direction with walls).
  double minimum_image(double r, int d) const {
    return r - box_[d] * std::nearbyint(r * inv_box_[d]);
  }
  // Minimum-image separation x_i - x_j.
  void separation(const State<D>& s, std::size_t i, std::size_t j, double* dx) const {
    for (int d = 0; d < D; ++d) dx[d] = minimum_image(s.x[d][i] - s.x[d][j], d);
  }

  // Calls fn(i, j, dx, r2) once for every pair closer than rc (dx = x_i - x_j). Phases run in
  // turn, the units of one phase in parallel (see the constructor): no two threads write the
  // same particle, and every particle sees its pairs in one fixed order, whatever the thread
  // count (rows that share particles always run in the same order).
  template <class PairFn> void for_each_pair(const State<D>& s, double rc, PairFn&& fn) const {
    const double rc2 = rc * rc;
    for_each_row([&](long row) {
      for (int x = 0; x < n_[0]; ++x) visit_cell(s, slot_cell_[row * n_[0] + x], rc2, fn);
    });
  }

  // ---- The pair list: every pair closer than rc once, stored per cell (the cell of the
  // particle i), built after a sort from the positions alone, so that its content and order do
  // not depend on the thread count. sort() invalidates it. Six bytes a pair: j, and i as a
  // 16-bit offset from its segment's first particle (a row of cells is one segment unless it
  // holds more than 65536 particles).
  void build_pairs(const State<D>& s, double rc) { build_pairs(s.x, rc); }
  template <class T> void build_pairs(const Positions<T>& x, double rc);
  bool has_pairs() const { return pairs_valid_; }
  std::size_t pair_count() const;
  // Calls fn(i, j, count) with one row of cells' pairs (storage indices, three cells at a time
  // along the row, interleaved, each cell's round-robin over its particles: see build_cell and
  // interleave_cells). A row is one block so that the per-pair loops run over hundreds of pairs,
  // not a cell's ~20, and vectorise. Rows in the order of for_each_pair.
  template <class BlockFn> void for_each_pair_block(BlockFn&& fn) const {
    for_each_row([&](long row) {
      static thread_local std::vector<std::uint32_t> rows_i; // i of one segment, widened
      const RowRange& r = row_range_[row];
      const PairBuffer& b = buffers_[r.buffer];
      for (std::size_t k = r.first_segment; k < r.first_segment + r.segments; ++k) {
        const Segment& seg = b.segments[k];
        if (rows_i.size() < seg.count) rows_i.resize(seg.count + seg.count / 2);
        const std::uint16_t* offset = b.i.data() + seg.begin;
        std::uint32_t* __restrict wide = rows_i.data();
        for (std::size_t p = 0; p < seg.count; ++p) wide[p] = seg.base + offset[p];
        fn(static_cast<const std::uint32_t*>(wide), b.j.data() + seg.begin, seg.count);
      }
    });
  }
  // minimum_image's factors, for the vector loops (inv_box 0 in wall directions).
  double image_box(int d) const { return box_[d]; }
  double inv_box(int d) const { return inv_box_[d]; }

  // The same pairs, one thread, in the same order (reference for tests and for serial passes).
  template <class PairFn>
  void for_each_pair_serial(const State<D>& s, double rc, PairFn&& fn) const {
    const double rc2 = rc * rc;
    for (const int c : slot_cell_) visit_cell(s, c, rc2, fn);
  }

private:
  // fn(row) for every row of slot_cell_ (index into its rows), the rows of a unit in order. An
  // odd unit 2k + 1 runs after both even units it shares planes with (2k and 2k + 2), and that
  // is the only order that matters: each particle then sees the pairs of its even unit, then
  // those of its odd one, as if all even units ran first (the two phases of the constructor),
  // so the result is the same for any thread count. Each thread takes a block of even units
  // and follows each with the odd unit behind it (e0, e1, o0, e2, o1, ...; e_k = unit 2k, o_k =
  // unit 2k + 1): the planes it reaches stay in cache for the odd unit instead of being read
  // again after a sweep over all of them. The odd unit between two threads' blocks waits for
  // the barrier.
  template <class RowFn> void for_each_row(RowFn&& fn) const {
    const long evens = phase_begin_.size() > 1 ? phase_begin_[1] : 0;
    const long odds = phase_begin_.size() > 2 ? phase_begin_[2] - evens : 0;
    // On a slab with a ghost plane the last odd unit reaches into it: it runs after the
    // exchange that brings the upper rank's first plane as its even phase left it.
    const long late = hook_ && has_ghost_plane() && odds > 0 ? 1 : 0;
    auto unit = [&](long u) {
      for (long row = unit_begin_[u]; row < unit_begin_[u + 1]; ++row) fn(row);
    };
    auto odd = [&](long k) {
      if (k < odds - late) unit(evens + k);
    };
#pragma omp parallel
    {
      const long threads = omp_get_num_threads(), t = omp_get_thread_num();
      const long first = block_start(t, threads), last = block_start(t + 1, threads);
      for (long k = first; k < last; ++k) {
        unit(k);
        if (k > first) odd(k - 1);
      }
#pragma omp barrier
      if (last > first) odd(last - 1);
    }
    if (hook_) {
      hook_->forward();
      if (late) unit(evens + odds - 1);
      hook_->back();
    }
  }
  // The first even unit of thread t's block (for_each_row): the blocks hold equal shares of the
  // last list's pairs (a cavity's rows are not equally full: gravity stratifies it, and the
  // walls thin the rows beside them), or equal unit counts before the first list.
  long block_start(long t, long threads) const {
    const long evens = phase_begin_.size() > 1 ? phase_begin_[1] : 0;
    if (t >= threads) return evens;
    if (work_before_.size() != static_cast<std::size_t>(evens) + 1 || !(work_before_.back() > 0))
      return evens * t / threads;
    const double target = work_before_.back() * static_cast<double>(t) / threads;
    const long k = std::lower_bound(work_before_.begin(), work_before_.end(), target) -
                   work_before_.begin(); // nearer of k - 1 and k
    return k > 0 && target - work_before_[k - 1] < work_before_[k] - target ? k - 1 : k;
  }
  void balance_units(); // work_before_ from the pair list (build_pairs)
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
        outside |= !cell_wrap_[d] && (k < 0 || k >= n_[d]);
        nb = nb * n_[d] + (k + n_[d]) % n_[d];
      }
      if (outside) continue;
      const bool same = nb == c;
      for (std::size_t i = start_[c]; i < start_[c + 1]; ++i) {
        for (std::size_t j = same ? i + 1 : start_[nb]; j < start_[nb + 1]; ++j) {
          double r2 = 0;
          for (int d = 0; d < D; ++d) {
            const double r = minimum_image(s.x[d][i] - s.x[d][j], d);
            dx[d] = r;
            r2 += r * r;
          }
          if (r2 < rc2) fn(i, j, dx, r2);
        }
      }
    }
  }

  void build_stencil();
  struct Segment { // pairs [begin, begin + count) of a buffer, i = base + offset
    std::size_t begin = 0, count = 0;
    std::uint32_t base = 0;
  };
  struct PairBuffer { // one per building thread
    UninitialisedArray<std::uint16_t> i;
    UninitialisedArray<std::uint32_t> j;
    std::size_t used = 0;
    std::vector<Segment> segments;
    std::vector<std::uint32_t> cand; // scratch: candidate indices of one cell
    std::vector<double> cx[D], r2;   // scratch: their positions and distances
    std::vector<std::size_t> count;  // scratch: first pair of each particle of the cell
    std::vector<std::uint16_t> tmp_i;
    std::vector<std::uint32_t> tmp_j;
    std::vector<std::size_t> cell_begin; // scratch: first pair of each cell of a group, the end
  };
  struct RowRange { // a row's pairs: buffers_[buffer].segments[first_segment, + segments)
    std::size_t buffer = 0, first_segment = 0, segments = 0;
  };
  template <class T>
  void build_cell(const Positions<T>& x, int c, double rc2, std::uint32_t base,
                  PairBuffer& b) const;
  // The index ranges of cell c's candidates: its own particles, then each half-shell
  // neighbour's that holds any (contiguous in storage).
  struct CandidateRanges {
    std::size_t begin[D == 2 ? 5 : 14], end[D == 2 ? 5 : 14], ranges = 0, count = 0;
  };
  CandidateRanges candidate_ranges(int c) const;
  // The candidates' indices and positions into b's scratch, in the ranges' order.
  template <class T>
  void gather_candidates(const Positions<T>& x, const CandidateRanges& r, PairBuffer& b) const;
  void interleave_cells(PairBuffer& b) const;
  void round_robin(PairBuffer& b, const std::size_t* bounds, std::size_t runs) const;

  std::array<double, D> box_, inv_side_, inv_box_;
  std::array<bool, D> periodic_;  // the box wraps (positions, minimum images)
  std::array<bool, D> cell_wrap_; // the cells wrap (not a slab's last direction)
  std::array<int, D> n_;          // cells of this grid (a slab: its planes, ghost included)
  std::array<int, D> global_n_;   // cells of the whole box
  int z0_ = 0;                    // a slab's first plane in the whole box
  int units_ = 1;                 // planes whose pairs this grid lists (not a ghost plane)
  PhaseHook* hook_ = nullptr;
  int total_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::array<int, D>> stencil_; // half shell: each neighbour pair of cells once
  std::vector<int> slot_cell_;              // cells in pass order, row by row (n_[0] per row)
  std::vector<long> unit_begin_;            // first row (of slot_cell_) of each unit, and the end
  std::vector<long> phase_begin_;           // first unit of each phase, and the end
  std::vector<RowRange> row_range_;         // per row of slot_cell_
  // Pairs in even units 0..k-1 and the odd units behind them (k = 0..evens; block_start).
  std::vector<double> work_before_;
  std::vector<PairBuffer> buffers_;
  bool pairs_valid_ = false;
  std::vector<std::uint32_t> cell_; // the sort's cell of each particle, then its id scratch
  std::vector<int> order_;          // the sort's permutation: new k <- old order_[k]
};

} // namespace twinflow::particle
