#include "particle/system.hpp"

#include "particle/simd.hpp"

#include <omp.h>

#include <stdexcept>
#include <string>

namespace twinflow::particle {

namespace {
// A cell's candidates as columns (x[d][q]: the candidate positions, index[q]: their indices;
// r2: scratch).
struct Candidates {
  const double *x0, *x1, *x2;
  const std::uint32_t* index;
  double* r2;
};

// Appends (i, index[q]) for every candidate q in [from, to) closer to y than sqrt(rc2), in q
// order, at out_i[m], out_j[m]; returns the new end. The distance is the minimum image by
// nearbyint as in visit_cell, and the same in every version (bitwise: the same pairs). The
// AVX-512 version tests eight candidates at a time and compresses the close ones into place, the
// AVX2 one four; they write up to eight entries past the returned end (the caller's margin).
template <int D>
std::size_t append_close(const Candidates& c, const double* y, const double* box, const double* inv,
                         double rc2, std::size_t from, std::size_t to, std::uint16_t i,
                         std::uint16_t* out_i, std::uint32_t* out_j, std::size_t m) {
#ifdef TWINFLOW_AVX512
  const __m128i wide_i = _mm_set1_epi16(static_cast<short>(i));
  const __m512d limit = _mm512_set1_pd(rc2);
  auto component = [&](const double* x, int d, __mmask8 live, std::size_t q) {
    const __m512d r = _mm512_sub_pd(_mm512_set1_pd(y[d]), _mm512_maskz_loadu_pd(live, x + q));
    return minimum_image(r, box[d], inv[d]);
  };
  for (std::size_t q = from; q < to; q += 8) {
    const __mmask8 live =
        to - q >= 8 ? __mmask8(0xFF) : static_cast<__mmask8>((1u << (to - q)) - 1);
    __m512d r = component(c.x0, 0, live, q);
    __m512d sum = _mm512_mul_pd(r, r);
    r = component(c.x1, 1, live, q);
    sum = _mm512_add_pd(sum, _mm512_mul_pd(r, r));
    if constexpr (D == 3) {
      r = component(c.x2, 2, live, q);
      sum = _mm512_add_pd(sum, _mm512_mul_pd(r, r));
    }
    const __mmask8 close = _mm512_mask_cmp_pd_mask(live, sum, limit, _CMP_LT_OQ);
    const __m256i j =
        _mm256_maskz_compress_epi32(close, _mm256_maskz_loadu_epi32(live, c.index + q));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out_j + m), j);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out_i + m), wide_i);
    m += static_cast<std::size_t>(__builtin_popcount(close));
  }
  return m;
#else
#ifdef TWINFLOW_AVX2
  // Four candidates at a time, compressed by a permutation (simd.hpp); the last (to - from) % 4
  // by the portable loops below. Writes up to four entries past the end.
  const __m256d limit = _mm256_set1_pd(rc2);
  auto component = [&](const double* x, int d, std::size_t q) {
    const __m256d r = _mm256_sub_pd(_mm256_set1_pd(y[d]), _mm256_loadu_pd(x + q));
    return minimum_image(r, box[d], inv[d]);
  };
  const __m128i wide_i = _mm_set1_epi16(static_cast<short>(i));
  for (; from + 4 <= to; from += 4) {
    __m256d r = component(c.x0, 0, from);
    __m256d sum = _mm256_mul_pd(r, r);
    r = component(c.x1, 1, from);
    sum = _mm256_add_pd(sum, _mm256_mul_pd(r, r));
    if constexpr (D == 3) {
      r = component(c.x2, 2, from);
      sum = _mm256_add_pd(sum, _mm256_mul_pd(r, r));
    }
    const int close = _mm256_movemask_pd(_mm256_cmp_pd(sum, limit, _CMP_LT_OQ));
    const __m128i j =
        compress(_mm_loadu_si128(reinterpret_cast<const __m128i*>(c.index + from)), close);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out_j + m), j);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out_i + m), wide_i);
    m += static_cast<std::size_t>(__builtin_popcount(close));
  }
#endif
  const double* x[3] = {c.x0, c.x1, c.x2};
  for (std::size_t q = from; q < to; ++q) { // vectorises
    double sum = 0;
    for (int d = 0; d < D; ++d) {
      double r = y[d] - x[d][q];
      r -= box[d] * std::nearbyint(r * inv[d]);
      sum += r * r;
    }
    c.r2[q] = sum;
  }
  for (std::size_t q = from; q < to; ++q) { // branch-free compaction
    out_i[m] = i;
    out_j[m] = c.index[q];
    m += c.r2[q] < rc2;
  }
  return m;
#endif
}
} // namespace

template <int D> void CellGrid<D>::build_stencil() {
  // Half shell: offsets in {-1,0,1}^D that are lexicographically >= 0, with directions of a
  // single cell collapsed to offset 0 (the neighbour is the cell itself; minimum image decides).
  std::array<int, D> o;
  const int total = D == 2 ? 9 : 27;
  for (int k = 0; k < total; ++k) {
    int rem = k;
    bool skip = false;
    for (int d = 0; d < D; ++d) {
      o[d] = rem % 3 - 1;
      rem /= 3;
      if (n_[d] == 1 && o[d] != 0) skip = true;
    }
    if (skip) continue;
    int first = 0; // first nonzero from the highest dimension decides the half
    for (int d = D - 1; d >= 0; --d)
      if (o[d] != 0) {
        first = o[d];
        break;
      }
    if (first >= 0) stencil_.push_back(o);
  }
  // Pass order (constructor): units (3D: planes z; 2D: rows y), even ones, then odd ones.
  const int units = units_, rows_per_unit = D == 2 ? 1 : n_[1];
  phase_begin_.assign(1, 0);
  unit_begin_.assign(1, 0);
  for (int parity = 0; parity < 2; ++parity) {
    for (int unit = parity; unit < units; unit += 2) {
      for (int row = unit * rows_per_unit; row < (unit + 1) * rows_per_unit; ++row)
        for (int x = 0; x < n_[0]; ++x) slot_cell_.push_back(row * n_[0] + x);
      unit_begin_.push_back(static_cast<long>(slot_cell_.size() / n_[0]));
    }
    if (unit_begin_.size() - 1 > static_cast<std::size_t>(phase_begin_.back()))
      phase_begin_.push_back(static_cast<long>(unit_begin_.size()) - 1);
  }
  row_range_.assign(slot_cell_.size() / n_[0], RowRange{});
}

template <int D>
template <class T>
void CellGrid<D>::build_pairs(const Positions<T>& x, double rc) {
  const double rc2 = rc * rc;
  for (int c = 0; c < total_; ++c)
    if (start_[c + 1] - start_[c] > 65536)
      throw std::runtime_error("a cell of the neighbour grid holds " +
                               std::to_string(start_[c + 1] - start_[c]) +
                               " particles; the pair list takes at most 65536 (density too high)");
  const std::size_t threads = static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
  if (buffers_.size() < threads) buffers_.resize(threads);
  // First guess of the pairs per thread, 10% above the uniform density's n rho V_D(rc) / 2 with
  // n the particles whose pairs this grid lists (a slab's ghost plane only ever holds a pair's
  // j), so that a buffer is allocated once instead of grown through copies (peak memory).
  double volume = units_ * side(D - 1); // of the planes whose pairs are listed
  for (int d = 0; d < D - 1; ++d) volume *= n_[d] * side(d);
  const double ball = D == 3 ? 4.18879020478639 * rc2 * rc : 3.141592653589793 * rc2;
  const double n = static_cast<double>(start_[units_ * cells_per_plane()] - start_[0]);
  const auto guess = static_cast<std::size_t>(1.1 * 0.5 * n * n / volume * ball / threads) + 4096;
  const long rows = static_cast<long>(row_range_.size()), nx = n_[0];
#pragma omp parallel
  {
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    PairBuffer& b = buffers_[t];
    b.used = 0;
    b.segments.clear();
    if (b.i.size() < guess) // a little more, so that the next lists seldom reallocate
      b.i.grow(guess + guess / 32, 0), b.j.grow(guess + guess / 32, 0);
#pragma omp for schedule(static)
    for (long row = 0; row < rows; ++row) {
      RowRange& r = row_range_[row];
      r.buffer = t;
      r.first_segment = b.segments.size();
      Segment seg{b.used, 0, static_cast<std::uint32_t>(start_[slot_cell_[row * nx]])};
      b.cell_begin.assign(1, b.used);
      for (long slot = row * nx; slot < (row + 1) * nx; ++slot) {
        const int c = slot_cell_[slot];
        if (start_[c + 1] - seg.base > 65536) { // i no longer fits 16 bits: a new segment
          interleave_cells(b);
          seg.count = b.used - seg.begin;
          if (seg.count > 0) b.segments.push_back(seg);
          seg = Segment{b.used, 0, static_cast<std::uint32_t>(start_[c])};
        }
        build_cell(x, c, rc2, seg.base, b);
        b.cell_begin.push_back(b.used);
        if (b.cell_begin.size() == 4) interleave_cells(b);
      }
      interleave_cells(b);
      seg.count = b.used - seg.begin;
      if (seg.count > 0) b.segments.push_back(seg);
      r.segments = b.segments.size() - r.first_segment;
    }
  }
  pairs_valid_ = true;
  balance_units();
}

template <int D> void CellGrid<D>::balance_units() {
  const long evens = phase_begin_.size() > 1 ? phase_begin_[1] : 0;
  const long units = static_cast<long>(unit_begin_.size()) - 1;
  auto pairs_in = [&](long u) {
    std::size_t n = 0;
    for (long row = unit_begin_[u]; row < unit_begin_[u + 1]; ++row) {
      const RowRange& r = row_range_[row];
      for (std::size_t k = r.first_segment; k < r.first_segment + r.segments; ++k)
        n += buffers_[r.buffer].segments[k].count;
    }
    return static_cast<double>(n);
  };
  work_before_.assign(static_cast<std::size_t>(evens) + 1, 0.0);
  for (long k = 0; k < evens; ++k)
    work_before_[k + 1] =
        work_before_[k] + pairs_in(k) + (evens + k < units ? pairs_in(evens + k) : 0);
}

// The pairs of up to three neighbouring cells of a row, built one cell after the other
// (b.cell_begin: each cell's first pair and the end), interleaved: the first pair of each cell,
// then the second of each, ... Together with the round-robin inside each cell (build_cell) a
// pair seldom shares a particle with the one or two before it, so the Shardlow sweep's
// sequential updates overlap in the processor instead of each waiting on the previous pair's
// chain of divisions (a pair shares a particle with the one before it 8% of the time instead of
// 27%, and the sweep takes ~14% less time: measured on the benchmark system, N = 48000).
template <int D> void CellGrid<D>::interleave_cells(PairBuffer& b) const {
  const std::size_t cells = b.cell_begin.size() - 1, end = b.cell_begin.back();
  if (cells > 1) round_robin(b, b.cell_begin.data(), cells);
  b.cell_begin.assign(1, end);
}

template <int D> std::size_t CellGrid<D>::pair_count() const {
  std::size_t n = 0;
  for (const auto& b : buffers_)
    for (const auto& seg : b.segments) n += seg.count;
  return n;
}

template <int D> typename CellGrid<D>::CandidateRanges CellGrid<D>::candidate_ranges(int c) const {
  std::array<int, D> idx;
  int rem = c;
  for (int d = 0; d < D; ++d) {
    idx[d] = rem % n_[d];
    rem /= n_[d];
  }
  CandidateRanges r;
  r.begin[r.ranges] = start_[c], r.end[r.ranges++] = start_[c + 1];
  r.count = start_[c + 1] - start_[c];
  for (const auto& offset : stencil_) {
    int nb = 0;
    bool outside = false, zero = true;
    for (int d = D - 1; d >= 0; --d) {
      int k = idx[d] + offset[d];
      outside |= !cell_wrap_[d] && (k < 0 || k >= n_[d]);
      zero &= offset[d] == 0;
      k = k < 0 ? k + n_[d] : k >= n_[d] ? k - n_[d] : k; // wrap without a division
      nb = nb * n_[d] + k;
    }
    if (outside || zero || start_[nb] == start_[nb + 1]) continue;
    r.begin[r.ranges] = start_[nb], r.end[r.ranges++] = start_[nb + 1];
    r.count += start_[nb + 1] - start_[nb];
  }
  return r;
}

template <int D>
template <class T>
void CellGrid<D>::gather_candidates(const Positions<T>& x, const CandidateRanges& r,
                                    PairBuffer& b) const {
  const std::size_t nc = r.count;
  if (b.cand.size() < nc) {
    b.cand.resize(nc + nc / 2);
    for (int d = 0; d < D; ++d) b.cx[d].resize(nc + nc / 2);
    b.r2.resize(nc + nc / 2);
  }
  std::size_t k = 0;
  for (std::size_t range = 0; range < r.ranges; ++range)
    for (std::size_t j = r.begin[range]; j < r.end[range]; ++j, ++k) {
      b.cand[k] = static_cast<std::uint32_t>(j);
      for (int d = 0; d < D; ++d) b.cx[d][k] = x[d][j];
    }
}

// The pairs (i, j) of cell c with i in c: j later in c, or in a half-shell neighbour cell,
// appended to b. Distances as in visit_cell (minimum image by nearbyint), the test vectorised
// over candidates. Order: see the end.
template <int D>
template <class T>
void CellGrid<D>::build_cell(const Positions<T>& x, int c, double rc2, std::uint32_t base,
                             PairBuffer& b) const {
  const std::size_t first = start_[c], ni = start_[c + 1] - first;
  if (ni == 0) return;
  const CandidateRanges ranges = candidate_ranges(c);
  const std::size_t nc = ranges.count;
  gather_candidates(x, ranges, b);
  const std::size_t need = b.used + ni * nc + 8; // 8: append_close's margin
  if (b.i.size() < need) {
    const std::size_t grown = std::max(need, b.i.size() + b.i.size() / 4);
    b.i.grow(grown, b.used), b.j.grow(grown, b.used);
  }
  const Candidates cs{b.cx[0].data(), b.cx[1].data(), b.cx[D - 1].data(), b.cand.data(),
                      b.r2.data()};
  const double box[3] = {box_[0], box_[1], box_[D - 1]};
  const double inv[3] = {inv_box_[0], inv_box_[1], inv_box_[D - 1]};
  std::size_t m = b.used;
  b.count.resize(ni + 1);
  for (std::size_t p = 0; p < ni; ++p) {
    b.count[p] = m;
    const double y[3] = {cs.x0[p], cs.x1[p], cs.x2[p]};
    const auto i = static_cast<std::uint16_t>(first + p - base);
    m = append_close<D>(cs, y, box, inv, rc2, p + 1, nc, i, b.i.data(), b.j.data(), m);
  }
  b.count[ni] = m;
  // Round-robin over the cell's particles (the k-th pair of every i, then the (k+1)-th, ...):
  // a pair shares a particle with the one before it 27% of the time instead of nearly always, so
  // the sequential pair updates of the Shardlow sweep overlap in the processor instead of
  // waiting on each other; interleave_cells mixes three cells' pairs for fewer still.
  round_robin(b, b.count.data(), ni);
  b.used = m;
}

// The runs [bounds[r], bounds[r + 1]) of b's pairs (r < runs) reordered in place: the first pair
// of each run, then the second of each, ...
template <int D>
void CellGrid<D>::round_robin(PairBuffer& b, const std::size_t* bounds, std::size_t runs) const {
  const std::size_t first = bounds[0], total = bounds[runs] - first;
  if (b.tmp_i.size() < total) b.tmp_i.resize(total + total / 2), b.tmp_j.resize(total + total / 2);
  std::uint16_t* pair_i = b.i.data();
  std::uint32_t* pair_j = b.j.data();
  std::size_t o = 0;
  for (std::size_t round = 0; o < total; ++round)
    for (std::size_t r = 0; r < runs; ++r)
      if (bounds[r] + round < bounds[r + 1]) {
        b.tmp_i[o] = pair_i[bounds[r] + round];
        b.tmp_j[o++] = pair_j[bounds[r] + round];
      }
  std::copy(b.tmp_i.begin(), b.tmp_i.begin() + total, pair_i + first);
  std::copy(b.tmp_j.begin(), b.tmp_j.begin() + total, pair_j + first);
}

template <int D> void CellGrid<D>::wrap(State<D>& s) const {
  const long count = static_cast<long>(s.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < count; ++i)
    for (int d = 0; d < D; ++d) s.x[d][i] = wrapped(s.x[d][i], d);
}

template <int D>
void CellGrid<D>::sort(State<D>& s, Carried<D>& carried, const ListedPositions* key,
                       bool keep_carried) {
  const std::size_t n = s.size();
  pairs_valid_ = false;
  resize_with_margin(cell_, n);
  std::fill(start_.begin(), start_.end(), 0);
  const long count = static_cast<long>(n);
  wrap(s);
  for (long i = 0; i < count; ++i) {
    double pos[D];
    for (int d = 0; d < D; ++d) pos[d] = key ? (*key)[d][i] : s.x[d][i];
    cell_[i] = static_cast<std::uint32_t>(cell_of(pos));
  }
  for (std::size_t i = 0; i < n; ++i) ++start_[cell_[i] + 1];
  std::partial_sum(start_.begin(), start_.end(), start_.begin());
  // Counting sort by cell, then by id inside each cell (lists are short and nearly sorted).
  resize_with_margin(order_, n);
  std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) order_[fill[cell_[i]]++] = static_cast<int>(i);
  for (int c = 0; c < total_; ++c) {
    const auto b = order_.begin() + start_[c], e = order_.begin() + start_[c + 1];
    for (auto it = b + (b != e); it < e; ++it) // insertion sort by id
      for (auto k = it; k > b && s.id[*(k - 1)] > s.id[*k]; --k) std::iter_swap(k - 1, k);
  }
  // Through a scratch array, swapped in: f[0]'s storage when the carried arrays are left stale
  // (then no extra array: peak memory), else a temporary. Serial on purpose: on a shared
  // machine every extra barrier can cost a scheduler time slice.
  std::vector<double> temporary;
  std::vector<double>& scratch = keep_carried ? temporary : carried.f[0];
  auto permute = [&](auto& a, auto& tmp) {
    if (a.empty()) return;
    tmp.resize(n);
    for (long k = 0; k < count; ++k) tmp[k] = a[order_[k]];
    a.swap(tmp);
  };
  for (int d = 0; d < D; ++d) permute(s.x[d], scratch), permute(s.v[d], scratch);
  permute(s.u, scratch);
  permute(s.id, cell_); // the cells are no longer needed
  if (keep_carried) {
    for (int d = 0; d < D; ++d) permute(carried.f[d], scratch);
    permute(carried.q, scratch), permute(carried.potential, scratch);
  }
}

template class CellGrid<2>;
template class CellGrid<3>;
template void CellGrid<2>::build_pairs(const Positions<double>&, double);
template void CellGrid<3>::build_pairs(const Positions<double>&, double);
template void CellGrid<2>::build_pairs(const Positions<float>&, double);
template void CellGrid<3>::build_pairs(const Positions<float>&, double);

} // namespace twinflow::particle
