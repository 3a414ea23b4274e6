// Simulation<M> on several MPI ranks (included from simulation.hpp; decomposition.hpp): each rank
// owns a slab of cell planes and keeps a ghost copy of the upper rank's first plane. Particles
// move to the rank of their sort cell at every list rebuild; the pair passes exchange the ghost
// plane between their two phases (CellGrid::for_each_row), so every particle sees its pairs in
// the one-process order and every result is the one-process result, bit for bit.

namespace twinflow::particle {

template <class M> int Simulation<M>::owner_of(std::size_t i) const {
  const double key =
      x_listed_[D - 1].empty() ? state_.x[D - 1][i] : static_cast<double>(x_listed_[D - 1][i]);
  return slabs_.owner(grid_.global_plane(key));
}

template <class M> void Simulation<M>::resize_local(std::size_t n) {
  const auto fit = [n](auto& a) { resize_with_margin(a, n); };
  for (int d = 0; d < D; ++d) {
    fit(state_.x[d]), fit(state_.v[d]), fit(carried_.f[d]);
    if (!x_listed_[d].empty()) fit(x_listed_[d]);
  }
  if (!state_.u.empty()) fit(state_.u);
  fit(state_.id);
  if (!carried_.q.empty() || p_.integrator != Integrator::Shardlow) fit(carried_.q);
  fit(carried_.potential);
}

template <class M> void Simulation<M>::keep_owned() {
  std::size_t kept = 0;
  auto move = [](auto& a, std::size_t from, std::size_t to) {
    if (!a.empty()) a[to] = a[from];
  };
  for (std::size_t i = 0; i < owned_; ++i) {
    if (owner_of(i) != slabs_.rank) continue;
    for (int d = 0; d < D; ++d) {
      move(state_.x[d], i, kept), move(state_.v[d], i, kept), move(x_listed_[d], i, kept);
      move(carried_.f[d], i, kept);
    }
    move(state_.u, i, kept), move(state_.id, i, kept);
    move(carried_.q, i, kept), move(carried_.potential, i, kept);
    ++kept;
  }
  owned_ = kept;
  resize_local(kept);
}

// Each particle to the rank of its sort cell (any rank: a list kept past its bound may have let
// a particle cross more than one slab). Order does not matter: the sort follows.
template <class M> void Simulation<M>::migrate() {
  const int ranks = slabs_.ranks;
  const int fields = 2 * D + (state_.u.empty() ? 0 : 1) + 1; // x, v, u, id
  std::vector<std::vector<double>> out(static_cast<std::size_t>(ranks));
  std::size_t kept = 0;
  for (std::size_t i = 0; i < owned_; ++i) {
    const int r = owner_of(i);
    if (r == slabs_.rank) {
      for (int d = 0; d < D; ++d)
        state_.x[d][kept] = state_.x[d][i], state_.v[d][kept] = state_.v[d][i];
      if (!state_.u.empty()) state_.u[kept] = state_.u[i];
      state_.id[kept] = state_.id[i];
      ++kept;
      continue;
    }
    auto& o = out[static_cast<std::size_t>(r)];
    for (int d = 0; d < D; ++d) o.push_back(state_.x[d][i]), o.push_back(state_.v[d][i]);
    if (!state_.u.empty()) o.push_back(state_.u[i]);
    o.push_back(static_cast<double>(state_.id[i])); // exact: ids < 2^32
  }
  std::vector<int> send_counts(static_cast<std::size_t>(ranks)), receive_counts(send_counts.size());
  std::vector<int> send_offsets(send_counts.size() + 1, 0), receive_offsets(send_offsets);
  std::vector<double> send;
  for (int r = 0; r < ranks; ++r) {
    send_counts[r] = static_cast<int>(out[r].size());
    send_offsets[r + 1] = send_offsets[r] + send_counts[r];
    send.insert(send.end(), out[r].begin(), out[r].end());
  }
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, slabs_.comm);
  for (int r = 0; r < ranks; ++r) receive_offsets[r + 1] = receive_offsets[r] + receive_counts[r];
  std::vector<double> received(static_cast<std::size_t>(receive_offsets.back()));
  MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), MPI_DOUBLE, received.data(),
                receive_counts.data(), receive_offsets.data(), MPI_DOUBLE, slabs_.comm);
  const std::size_t arrived = received.size() / static_cast<std::size_t>(fields);
  owned_ = kept + arrived;
  x_listed_ = {}; // recomputed from the positions by the caller
  resize_local(owned_);
  for (std::size_t k = 0; k < arrived; ++k) {
    const double* p = received.data() + k * static_cast<std::size_t>(fields);
    const std::size_t i = kept + k;
    for (int d = 0; d < D; ++d) state_.x[d][i] = *p++, state_.v[d][i] = *p++;
    if (!state_.u.empty()) state_.u[i] = *p++;
    state_.id[i] = static_cast<std::uint32_t>(*p);
  }
}

// The upper rank's first plane, as its sort left it, after the owned particles: positions,
// velocities, energies, ids and the sort keys. Its cells are the grid's ghost plane.
template <class M> void Simulation<M>::build_ghosts() {
  const bool listed = !x_listed_[0].empty();
  std::vector<std::vector<double>*> fields;
  for (int d = 0; d < D; ++d) fields.push_back(&state_.x[d]), fields.push_back(&state_.v[d]);
  if (!state_.u.empty()) fields.push_back(&state_.u);
  first_plane_count_ = grid_.end(grid_.cells_per_plane() - 1);
  long mine = static_cast<long>(first_plane_count_), theirs = 0;
  MPI_Sendrecv(&mine, 1, MPI_LONG, slabs_.lower, 10, &theirs, 1, MPI_LONG, slabs_.upper, 10,
               slabs_.comm, MPI_STATUS_IGNORE);
  ghost_count_ = static_cast<std::size_t>(theirs);
  resize_local(owned_ + ghost_count_);
  std::vector<ArraySpan> send, receive;
  const std::size_t m = first_plane_count_, g = ghost_count_, o = owned_;
  for (auto* f : fields) send.emplace_back(f->data(), m), receive.emplace_back(f->data() + o, g);
  send.emplace_back(state_.id.data(), m), receive.emplace_back(state_.id.data() + o, g);
  if (listed)
    for (int d = 0; d < D; ++d)
      send.emplace_back(x_listed_[d].data(), m), receive.emplace_back(x_listed_[d].data() + o, g);
  sendrecv_spans(send, slabs_.lower, receive, slabs_.upper, 11, slabs_.comm);
  if (listed)
    grid_.set_ghost_cells(x_listed_, owned_, ghost_count_);
  else
    grid_.set_ghost_cells(state_.x, owned_, ghost_count_);
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

// list_still_complete on a slab: every rank's far movers go to every rank, and each checks them
// against the particles it owns. A pair is checked by the owner of its partner: the same pairs
// as one process checks, so the same answer.
template <class M> bool Simulation<M>::slab_list_still_complete(double largest, std::size_t moved) {
  const std::size_t n = static_cast<std::size_t>(p_.particle_count());
  if (moved > 8 + n / 256 || model_.rc + 2 * std::sqrt(largest) >= 2 * grid_.smallest_side())
    return false;
  const double half_skin2 = 0.25 * skin_ * skin_;
  const std::size_t fields = 2 * D + 1; // x, listed x, id
  std::vector<double> mine;
  for (std::size_t i = 0; i < owned_; ++i) {
    if (displacement2(i) < half_skin2) continue;
    for (int d = 0; d < D; ++d) mine.push_back(state_.x[d][i]);
    for (int d = 0; d < D; ++d) mine.push_back(x_listed_[d][i]);
    mine.push_back(state_.id[i]);
  }
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(slabs_.ranks)), offsets(counts.size() + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, slabs_.comm);
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<double> far(static_cast<std::size_t>(offsets.back()));
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, far.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, slabs_.comm);
  const double rc2 = model_.rc * model_.rc;
  const double listed2 = list_cutoff_ * list_cutoff_ * (1 - 1e-9); // as list_still_complete
  const long movers = static_cast<long>(far.size() / fields);
  int missing = 0;
#pragma omp parallel for schedule(static) reduction(|| : missing)
  for (long k = 0; k < movers; ++k) {
    const double* m = far.data() + static_cast<std::size_t>(k) * fields;
    const auto id = static_cast<std::uint32_t>(m[2 * D]);
    float listed_i[D];
    for (int d = 0; d < D; ++d) listed_i[d] = static_cast<float>(m[D + d]);
    grid_.for_each_near_in_slab(listed_i, 2, [&](std::size_t j) {
      if (state_.id[j] == id) return;
      double now2 = 0, then2 = 0;
      for (int d = 0; d < D; ++d) {
        const double r = grid_.minimum_image(m[d] - state_.x[d][j], d);
        now2 += r * r;
        const double l = grid_.minimum_image(
            static_cast<double>(listed_i[d]) - static_cast<double>(x_listed_[d][j]), d);
        then2 += l * l;
      }
      missing = missing || (now2 < rc2 && then2 >= listed2);
    });
  }
  MPI_Allreduce(MPI_IN_PLACE, &missing, 1, MPI_INT, MPI_LOR, slabs_.comm);
  return !missing;
}

template <class M>
void Simulation<M>::halo(std::initializer_list<std::vector<double>*> forward,
                         std::initializer_list<std::vector<double>*> back) {
  halo_.forward_fields.clear(), halo_.back_fields.clear();
  for (auto* f : forward)
    if (!f->empty()) halo_.forward_fields.push_back(f);
  for (auto* f : back)
    if (!f->empty()) halo_.back_fields.push_back(f);
}

// The upper rank's first plane, as its even phase left it, into this rank's ghost plane.
template <class M> void Simulation<M>::Halo::forward() {
  const std::size_t m = sim->first_plane_count_, g = sim->ghost_count_, o = sim->owned_;
  std::vector<ArraySpan> send, receive;
  for (auto* f : forward_fields)
    send.emplace_back(f->data(), m), receive.emplace_back(f->data() + o, g);
  sendrecv_spans(send, sim->slabs_.lower, receive, sim->slabs_.upper, 20, sim->slabs_.comm);
}

// The ghost plane's updates back to its owner, whose first plane they are (none below a wall:
// no rank holds them as ghosts, and nothing arrives from MPI_PROC_NULL).
template <class M> void Simulation<M>::Halo::back() {
  const std::size_t m = sim->first_plane_count_, g = sim->ghost_count_, o = sim->owned_;
  std::vector<ArraySpan> send, receive;
  for (auto* f : back_fields)
    send.emplace_back(f->data() + o, g), receive.emplace_back(f->data(), m);
  sendrecv_spans(send, sim->slabs_.upper, receive, sim->slabs_.lower, 21, sim->slabs_.comm);
}

template <class M> void Simulation<M>::share_emissions() {
  std::vector<std::uint32_t> mine, all;
  for (const Emission& e : emissions_)
    mine.push_back(e.id), mine.push_back(static_cast<std::uint32_t>(e.wall));
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(slabs_.ranks)), offsets(counts.size() + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, slabs_.comm);
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  all.resize(static_cast<std::size_t>(offsets.back()));
  MPI_Allgatherv(mine.data(), count, MPI_UINT32_T, all.data(), counts.data(), offsets.data(),
                 MPI_UINT32_T, slabs_.comm);
  emissions_.clear();
  for (std::size_t k = 0; k + 1 < all.size(); k += 2)
    emissions_.push_back({all[k], static_cast<int>(all[k + 1]), ~0u});
}

template <class M> void Simulation<M>::gather(GatheredParticles<D>& out) {
  tally_.flush(slabs_);
  const std::size_t n = owned_;
  for (int d = 0; d < D; ++d) {
    gather_in_rank_order(slabs_, state_.x[d].data(), n, out.state.x[d]);
    gather_in_rank_order(slabs_, state_.v[d].data(), n, out.state.v[d]);
    gather_in_rank_order(slabs_, carried_.f[d].data(), n, out.carried.f[d]);
    if (!x_listed_[d].empty())
      gather_in_rank_order(slabs_, x_listed_[d].data(), n, out.x_listed[d]);
    else
      out.x_listed[d].clear();
    out.state.box[d] = state_.box[d];
  }
  if (!state_.u.empty()) gather_in_rank_order(slabs_, state_.u.data(), n, out.state.u);
  gather_in_rank_order(slabs_, state_.id.data(), n, out.state.id);
  if (!carried_.q.empty()) gather_in_rank_order(slabs_, carried_.q.data(), n, out.carried.q);
  gather_in_rank_order(slabs_, carried_.potential.data(), n, out.carried.potential);
}

} // namespace twinflow::particle
