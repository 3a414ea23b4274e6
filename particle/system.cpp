#include "particle/system.hpp"

namespace twinflow::particle {

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
  // Colours: cell index mod 3 in each direction with >= 3 cells.
  const int ncolours = D == 2 ? 9 : 27;
  colour_cells_.assign(ncolours, {});
  for (int c = 0; c < total_; ++c) {
    int rem = c, colour = 0, mul = 1;
    for (int d = 0; d < D; ++d) {
      colour += ((rem % n_[d]) % 3) * mul;
      rem /= n_[d];
      mul *= 3;
    }
    colour_cells_[colour].push_back(c);
  }
  colour_cells_.erase(std::remove_if(colour_cells_.begin(), colour_cells_.end(),
                                     [](const auto& l) { return l.empty(); }),
                      colour_cells_.end());
}

template <int D> void CellGrid<D>::sort(State<D>& s, Carried<D>& carried) {
  const std::size_t n = s.size();
  cell_.resize(n);
  std::fill(start_.begin(), start_.end(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    double pos[D];
    for (int d = 0; d < D; ++d) {
      double& xd = s.x[d][i];
      xd -= box_[d] * std::floor(xd * inv_box_[d]); // no-op in wall directions (inv_box_ = 0)
      if (periodic_[d] && xd >= box_[d]) xd = 0;    // -tiny wraps to box exactly
      pos[d] = xd;
    }
    cell_[i] = cell_of(pos);
    ++start_[cell_[i] + 1];
  }
  std::partial_sum(start_.begin(), start_.end(), start_.begin());
  // Counting sort by cell, then by id inside each cell (lists are short and nearly sorted).
  order_.resize(n);
  std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) order_[fill[cell_[i]]++] = static_cast<int>(i);
  for (int c = 0; c < total_; ++c) {
    const auto b = order_.begin() + start_[c], e = order_.begin() + start_[c + 1];
    for (auto it = b + (b != e); it < e; ++it) // insertion sort by id
      for (auto k = it; k > b && s.id[*(k - 1)] > s.id[*k]; --k) std::iter_swap(k - 1, k);
  }
  auto permute = [&](auto& a) {
    if (a.empty()) return;
    using T = typename std::decay_t<decltype(a)>::value_type;
    std::vector<T> tmp(n);
    for (std::size_t k = 0; k < n; ++k) tmp[k] = a[order_[k]];
    a.swap(tmp);
  };
  for (int d = 0; d < D; ++d) {
    permute(s.x[d]);
    permute(s.v[d]);
    permute(carried.f[d]);
  }
  permute(s.u);
  permute(s.id);
  permute(carried.q);
  permute(carried.potential);
}

template class CellGrid<2>;
template class CellGrid<3>;

} // namespace twinflow::particle
