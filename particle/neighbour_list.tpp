// The pair list of Simulation<M> (included from simulation.hpp): when it is rebuilt and from
// which positions.

namespace twinflow::particle {

// Verlet list: the pairs closer than rc + skin, kept while no pair closer than rc can be missing:
// while every particle is within skin/2 of where it was when they were listed, or, past that,
// while list_still_complete finds none; otherwise the particles are re-sorted and listed anew.
// The decision depends on the positions alone, so the rebuild steps are the same for any thread
// count, and a checkpoint holds the listed positions. Returns whether it re-sorted.
template <class M> bool Simulation<M>::update_neighbours(bool force) {
  if (!force && skin_ > 0 && grid_.has_pairs()) {
    const long n = static_cast<long>(owned_);
    const double half_skin2 = 0.25 * skin_ * skin_;
    double largest = 0;    // max |x_i - x_listed_i|^2, minimum image
    std::size_t moved = 0; // particles farther than skin/2
#pragma omp parallel for schedule(static) reduction(max : largest) reduction(+ : moved)
    for (long i = 0; i < n; ++i) {
      for (int d = 0; d < D; ++d) state_.x[d][i] = grid_.wrapped(state_.x[d][i], d);
      const double r2 = displacement2(i);
      largest = std::max(largest, r2);
      moved += r2 >= half_skin2;
    }
    if (slabs_.active()) {
      MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, slabs_.comm);
      unsigned long all = moved;
      MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_UNSIGNED_LONG, MPI_SUM, slabs_.comm);
      moved = all;
    }
    if (largest < half_skin2) return false;
    if (slabs_.active() ? slab_list_still_complete(largest, moved)
                        : list_still_complete(largest, moved)) {
      ++list_kept_past_bound_;
      return false;
    }
  }
  ++list_builds_;
  if (slabs_.active()) {
    rebuild_slab();
    return true;
  }
  if (skin_ == 0 || p_.integrator == Integrator::Euler) {
    grid_.sort(state_, carried_, nullptr, false);
    if (p_.integrator != Integrator::Euler) grid_.build_pairs(state_, list_cutoff_);
    return true; // euler walks the cells (for_each_pair) instead
  }
  // A Verlet list is built from the positions rounded to float, kept as the reference of the
  // displacement test: the bound holds exactly for them, and they cost half the memory.
  grid_.wrap(state_);
  list_positions();
  grid_.sort(state_, carried_, &x_listed_, false);
  list_positions(); // in the sorted order
  grid_.build_pairs(x_listed_, list_cutoff_);
  return true;
}

// A pair the list lacks was at least rc + skin apart when listed and is now closer than rc, so
// |d_i| + |d_j| > skin (d: displacement since listing): one of the two moved farther than skin/2.
// While those are few (8 + N/256), each is checked against every particle that was within two
// cells of it: a missing pair has both that and |x_i - x_j| < rc now. The global bound alone
// rebuilds when the fastest of N particles has moved skin/2, which comes sooner the larger N is
// (the largest of N Maxwell speeds grows as sqrt(ln N)); this keeps a list's life nearly
// independent of N. The limit N/256 (checking ~650 neighbours of each costs ~1 us): with N/1024
// lists lived 4.3 steps instead of 5.3 and ec-verlet ran 3% slower at N = 384000; N/128 and
// N/64 were no faster. largest: max |d_i|^2, moved: how many moved farther than skin/2.
template <class M> bool Simulation<M>::list_still_complete(double largest, std::size_t moved) {
  const std::size_t n = state_.size();
  if (!movers_checkable(largest, moved, n)) return false;
  const double half_skin2 = 0.25 * skin_ * skin_;
  const int threads = omp_get_max_threads();
  moved_far_.resize(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  { // static schedule: thread t holds the t-th range, so the lists join in storage order
    auto& mine = moved_far_[static_cast<std::size_t>(omp_get_thread_num())];
    mine.clear();
#pragma omp for schedule(static)
    for (long i = 0; i < static_cast<long>(n); ++i)
      if (displacement2(i) >= half_skin2) mine.push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<std::uint32_t> far;
  for (const auto& part : moved_far_) far.insert(far.end(), part.begin(), part.end());
  const double rc2 = model_.rc * model_.rc;
  // Listed pairs are those closer than rc + skin as the list build rounds; a margin far above
  // rounding counts a pair at the edge as missing (a rebuild, never a lost pair).
  const double listed2 = list_cutoff_ * list_cutoff_ * (1 - 1e-9);
  const long count = static_cast<long>(far.size());
  bool missing = false;
#pragma omp parallel for schedule(static) reduction(|| : missing)
  for (long k = 0; k < count; ++k) {
    const std::size_t i = far[k];
    float listed_i[D];
    for (int d = 0; d < D; ++d) listed_i[d] = x_listed_[d][i];
    grid_.for_each_near(listed_i, 2, [&](std::size_t j) {
      if (j == i) return;
      double dx[D], now2 = 0, then2 = 0;
      grid_.separation(state_, i, j, dx);
      for (int d = 0; d < D; ++d) {
        now2 += dx[d] * dx[d];
        const double l = grid_.minimum_image(
            static_cast<double>(listed_i[d]) - static_cast<double>(x_listed_[d][j]), d);
        then2 += l * l;
      }
      missing |= now2 < rc2 && then2 >= listed2;
    });
  }
  return !missing;
}

// update_neighbours' rebuild on a slab: the one-process steps (wrap, list the positions, sort by
// cell and id, list the pairs) with the migration after the listing and the ghost plane after
// the sort.
template <class M> void Simulation<M>::rebuild_slab() {
  resize_local(owned_); // the ghost copies go; build_ghosts brings them anew
  grid_.wrap(state_);
  const bool listed = listed_key();
  if (listed) list_positions();
  migrate();
  if (listed) list_positions();
  grid_.sort(state_, carried_, listed ? &x_listed_ : nullptr, false);
  if (listed) list_positions(); // in the sorted order
  resize_local(owned_);
  build_ghosts();
  if (p_.integrator == Integrator::Euler) return;
  if (listed)
    grid_.build_pairs(x_listed_, list_cutoff_);
  else
    grid_.build_pairs(state_, list_cutoff_);
}

} // namespace twinflow::particle
