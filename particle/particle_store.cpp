// ParticleStore<D> (particle_store.hpp): compiled here once per dimension.
#define TWINFLOW_PARTICLE_STORE_UNIT
#include "particle/particle_store.hpp"

#include <cmath>
#include <sstream>

#include "particle/archive.hpp"
#include "particle/pair_terms.hpp"

namespace twinflow::particle {

template <int D>
ParticleStore<D>::ParticleStore(const ParticleParameters& p, const ParticleKind& kind)
    : p_(p), kind_(kind), grid_(
                              [&] {
                                std::array<double, D> box;
                                for (int d = 0; d < D; ++d) box[d] = p.box[d];
                                return box;
                              }(),
                              kind.rc + list_skin(p),
                              [&] {
                                std::array<bool, D> periodic;
                                for (int d = 0; d < D; ++d) periodic[d] = !p.walls[d].present;
                                return periodic;
                              }()) {
  skin_ = list_skin(p);
  list_cutoff_ = kind.rc + skin_;
  // Several MPI ranks: each keeps the particles of its slab's planes.
  slabs_ = Slabs::split(grid_.counts()[D - 1], !p.walls[D - 1].present, D == 2 ? "y" : "z");
  place_particles();
  owned_ = state_.id.size();
  for (int d = 0; d < D; ++d) carried_.f[d].assign(owned_, 0.0);
  if (p_.integrator != Integrator::Shardlow) carried_.q.assign(owned_, 0.0); // heat rates
  carried_.potential.assign(owned_, 0.0);
  if (slabs_.active()) {
    tally_.start_logging();
    grid_.restrict_to_slab(slabs_.begin(), slabs_.end() - slabs_.begin(),
                           slabs_.upper != MPI_PROC_NULL);
    halo_.store = this;
    grid_.set_phase_hook(&halo_);
    if (listed_key()) list_positions();
  }
}

template <int D> ParticleStore<D>::~ParticleStore() = default;

template <int D> void ParticleStore<D>::place_particles() {
  const ParticleParameters& p = p_;
  const std::size_t n = static_cast<std::size_t>(p.particle_count());
  // Positions uniform, velocities Maxwell at T: counter-based, so independent of threads and
  // ranks. Two passes over the ids, so that no rank ever holds all N: the first sums the
  // velocities (the same sum in the same order on every rank), the second keeps a rank's own.
  const PairNoise initial(p.seed, 0, PairNoise::Initial);
  const double vscale = std::sqrt(p.temperature / p.mass);
  auto make = [&](std::size_t i, double* x, double* v) {
    for (int d = 0; d < D; ++d) {
      double g1, g2;
      initial.particle_gaussians(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(d), g1,
                                 g2);
      // Gaussian -> uniform through the normal CDF of g1: exact and cheap enough at start-up.
      x[d] = p.box[d] * 0.5 * std::erfc(-g1 / std::sqrt(2.0));
      v[d] = p.initial_velocities == InitialVelocities::Maxwell ? vscale * g2 : 0.0;
      if (d == 1 && p.shear_perturbation != 0) // the shear relaxation scene's initial mode
        v[1] += p.shear_perturbation * vscale * std::sin(2 * M_PI * x[0] / p.box[0]);
    }
  };
  std::array<double, D> mean{};
  double x[D], v[D];
  for (std::size_t i = 0; i < n; ++i) {
    make(i, x, v);
    for (int d = 0; d < D; ++d) mean[d] += v[d] / n;
  }
  const double share =
      slabs_.active() ? double(slabs_.end() - slabs_.begin()) / grid_.counts()[D - 1] : 1.0;
  const auto expected = static_cast<std::size_t>(1.05 * share * n + 64); // a slab's count varies
  for (int d = 0; d < D; ++d) {
    state_.box[d] = p.box[d];
    state_.x[d].reserve(expected), state_.v[d].reserve(expected);
  }
  state_.id.reserve(expected);
  if (kind_.has_energy) state_.u.reserve(expected);
  // 000:(3.21): <u> = (c_v + k) T in equilibrium (k = 1); seed 002 starts at theta_i = T
  const double u0 = p.initial_internal_energy == InitialInternalEnergy::Equilibrium
                        ? (kind_.cv + 1) * p.temperature
                        : kind_.cv * p.temperature;
  for (std::size_t i = 0; i < n; ++i) {
    make(i, x, v);
    double u = u0;
    if (p.temperature_perturbation != 0) // the thermal relaxation scene's initial mode
      u *= 1 + p.temperature_perturbation * std::sin(2 * M_PI * x[0] / p.box[0]);
    if (slabs_.active()) {
      for (int d = 0; d < D; ++d) x[d] = grid_.wrapped(x[d], d);
      // the plane as the sort will take it: of the listed (float) position when there is a list
      const double key =
          listed_key() ? static_cast<double>(static_cast<float>(x[D - 1])) : x[D - 1];
      if (slabs_.owner(grid_.global_plane(key)) != slabs_.rank) continue;
    }
    for (int d = 0; d < D; ++d) state_.x[d].push_back(x[d]), state_.v[d].push_back(v[d] - mean[d]);
    state_.id.push_back(static_cast<std::uint32_t>(i));
    if (kind_.has_energy) state_.u.push_back(u);
  }
}

template <int D> void ParticleStore<D>::save_particles(SaveArchive& a) {
  if (slabs_.active()) { // one file: the particles gathered in one-process order
    GatheredParticles<D> g;
    gather(g);
    archive_arrays(a, g.state, g.carried, g.x_listed);
    return;
  }
  archive_arrays(a, state_, carried_, x_listed_);
}

template <int D> void ParticleStore<D>::load_particles(LoadArchive& a) {
  archive_arrays(a, state_, carried_, x_listed_);
  const bool heat_rates = p_.integrator != Integrator::Shardlow;
  if (carried_.q.size() != (heat_rates ? state_.id.size() : 0) ||
      state_.x[0].size() != state_.id.size())
    throw std::invalid_argument("checkpoint: particle arrays of different lengths");
  // Stored in (cell, id) order of the positions the pair list was built from: the sort
  // rebuilds the cell index only, and the list is the one the run had.
  const bool listed = !x_listed_[0].empty();
  owned_ = state_.size();
  if (slabs_.active()) keep_owned();
  grid_.sort(state_, carried_, listed ? &x_listed_ : nullptr);
  if (slabs_.active()) build_ghosts();
  if (listed) grid_.build_pairs(x_listed_, list_cutoff_);
}

template <int D>
template <class A>
void ParticleStore<D>::archive_arrays(A& a, State<D>& s, Carried<D>& c,
                                      typename CellGrid<D>::ListedPositions& l) {
  std::array<double, 6> energy_in = wall_energy_in(), momentum_in = wall_momentum_in();
  std::array<double, 12> heat_moves = wall_heat_moves();
  long crossings = wall_crossings();
  a("x", s.x), a("v", s.v), a("u", s.u), a("id", s.id);
  a("force", c.f), a("heat_rate", c.q), a("potential", c.potential);
  a("step", step_), a("wall_energy_in", energy_in), a("wall_crossings", crossings);
  a("wall_momentum_in", momentum_in), a("wall_heat_moves", heat_moves), a("x_listed", l);
  if constexpr (A::loading) {
    for (int k = 0; k < 6; ++k)
      tally_.sums()[k] = energy_in[k], tally_.sums()[6 + k] = momentum_in[k];
    for (int k = 0; k < 12; ++k) tally_.sums()[12 + k] = heat_moves[k];
    tally_.set_counted(slabs_.root() ? crossings : 0);
  }
}

template <int D> void ParticleStore<D>::list_positions() {
  const std::size_t n = state_.size();
  for (int d = 0; d < D; ++d) {
    x_listed_[d].resize(n);
    for (std::size_t i = 0; i < n; ++i) x_listed_[d][i] = static_cast<float>(state_.x[d][i]);
  }
}

template <int D> void ParticleStore<D>::fail(std::size_t i, const char* where) const {
  std::ostringstream s;
  s << "unstable at step " << step_ << " (" << where << "): particle " << state_.id[i] << " x = (";
  for (int d = 0; d < D; ++d) s << (d ? ", " : "") << state_.x[d][i];
  s << ") v = (";
  for (int d = 0; d < D; ++d) s << (d ? ", " : "") << state_.v[d][i];
  s << ")";
  if (kind_.has_energy) {
    s << " u = " << state_.u[i] << " theta = " << theta(i) << "; neighbours' theta:";
    for (std::size_t j = 0; j < state_.size(); ++j) { // brute force: only on failure
      if (j == i) continue;
      double dx[D], r2 = 0;
      grid_.separation(state_, i, j, dx);
      for (int d = 0; d < D; ++d) r2 += dx[d] * dx[d];
      if (r2 < kind_.rc * kind_.rc) s << " " << theta(j);
    }
  }
  s << ". " << stability_hint(p_);
  throw InstabilityError(s.str());
}

template <int D> int ParticleStore<D>::owner_of(std::size_t i) const {
  const double key =
      x_listed_[D - 1].empty() ? state_.x[D - 1][i] : static_cast<double>(x_listed_[D - 1][i]);
  return slabs_.owner(grid_.global_plane(key));
}

template <int D> void ParticleStore<D>::resize_local(std::size_t n) {
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

template <int D> void ParticleStore<D>::keep_owned() {
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
template <int D> void ParticleStore<D>::migrate() {
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
template <int D> void ParticleStore<D>::build_ghosts() {
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

// list_still_complete on a slab: every rank's far movers go to every rank, and each checks them
// against the particles it owns. A pair is checked by the owner of its partner: the same pairs
// as one process checks, so the same answer.
template <int D>
bool ParticleStore<D>::slab_list_still_complete(double largest, std::size_t moved) {
  if (!movers_checkable(largest, moved, static_cast<std::size_t>(p_.particle_count())))
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
  const double rc2 = kind_.rc * kind_.rc;
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

template <int D>
void ParticleStore<D>::halo(std::initializer_list<std::vector<double>*> forward,
                            std::initializer_list<std::vector<double>*> back) {
  halo_.forward_fields.clear(), halo_.back_fields.clear();
  for (auto* f : forward)
    if (!f->empty()) halo_.forward_fields.push_back(f);
  for (auto* f : back)
    if (!f->empty()) halo_.back_fields.push_back(f);
}

// The upper rank's first plane, as its even phase left it, into this rank's ghost plane.
template <int D> void ParticleStore<D>::Halo::forward() {
  const std::size_t m = store->first_plane_count_, g = store->ghost_count_, o = store->owned_;
  std::vector<ArraySpan> send, receive;
  for (auto* f : forward_fields)
    send.emplace_back(f->data(), m), receive.emplace_back(f->data() + o, g);
  sendrecv_spans(send, store->slabs_.lower, receive, store->slabs_.upper, 20, store->slabs_.comm);
}

// The ghost plane's updates back to its owner, whose first plane they are (none below a wall:
// no rank holds them as ghosts, and nothing arrives from MPI_PROC_NULL).
template <int D> void ParticleStore<D>::Halo::back() {
  const std::size_t m = store->first_plane_count_, g = store->ghost_count_, o = store->owned_;
  std::vector<ArraySpan> send, receive;
  for (auto* f : back_fields)
    send.emplace_back(f->data() + o, g), receive.emplace_back(f->data(), m);
  sendrecv_spans(send, store->slabs_.upper, receive, store->slabs_.lower, 21, store->slabs_.comm);
}

template <int D> void ParticleStore<D>::share_emissions() {
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

template <int D> void ParticleStore<D>::gather(GatheredParticles<D>& out) {
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

template class ParticleStore<2>;
template class ParticleStore<3>;

} // namespace twinflow::particle
