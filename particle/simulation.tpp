// Implementation of Simulation<M> (included from simulation.hpp).

namespace twinflow::particle {

template <class M>
Simulation<M>::Simulation(const M& model, const ParticleParameters& p)
    : Store(p, ParticleKind{model.rc, model.cv, M::has_energy}), model_(model),
      wall_friction_(model.friction), wall_heat_(model.heat) {
  has_external_ = p.has_walls();
  for (int d = 0; d < D; ++d) has_external_ |= p.gravity[d] != 0;
  has_external_ |= p.poiseuille_force != 0;
  wall_friction_.w = Weight(p.wall_range, p.dissipation.exponent);
  if constexpr (M::Heat::active) wall_heat_.w = Weight(p.wall_range, p.heat_weight.exponent);
  if (p.has_wall_model(WallModel::HalfSpace)) half_space_ = make_half_space_wall(p);
  dt_ = p.dt;
  sqrt_dt_ = std::sqrt(dt_);
  inv_sqrt_dt_ = 1 / sqrt_dt_;
  update_neighbours(true);
  prepare();
}

template <class M> void Simulation<M>::prepare() {
  if (p_.integrator == Integrator::EcVerlet)
    conservative_pass(true);
  else if (p_.integrator == Integrator::Shardlow)
    conservative_pass(false);
  else
    potential_pass();
}

template <class M>
typename Simulation<M>::PairForce
Simulation<M>::pair_force(const PairNoise& noise, std::size_t i, std::size_t j, const double* dx,
                          double r2, const std::array<std::vector<double>, D>& v) const {
  PairForce pf;
  const double r = std::sqrt(r2), inv_r = 1 / r;
  double th_i = 1, th_j = 1;
  if constexpr (M::has_energy) th_i = theta(i), th_j = theta(j);
  if constexpr (M::Conservative::active)
    if (r < model_.conservative.rc)
      model_.conservative.eval(r, th_i, th_j, pf.conservative, pf.phi);
  double xi, zeta;
  noise.pair(state_.id[i], state_.id[j], xi, zeta);
  const auto& fr = model_.friction;
  if (r < fr.w.rc) {
    double wd, wr, ev = 0;
    fr.w.eval(r, wd, wr);
    for (int d = 0; d < D; ++d) ev += dx[d] * (v[d][i] - v[d][j]);
    ev *= inv_r;
    const double big_theta = fr.harmonic(th_i, th_j);
    // Noise amplitude at the pre-point, so the friction carries 003:(18)'s drift correction
    // (a no-op for constant sigma). F^D + F^R along e_ij (docs/theory.md; 002:(3)).
    const double gamma = fr.ito_gamma(th_i, th_j);
    pf.dissipative_random = -gamma * wd * ev + fr.sigma_of(big_theta) * wr * xi * inv_sqrt_dt_;
  }
  if constexpr (M::Heat::active) {
    if (r < model_.heat.w.rc) {
      double rate, amplitude;
      heat_terms(model_.heat, r, th_i, th_j, rate, amplitude);
      pf.heat = rate + amplitude * zeta * inv_sqrt_dt_; // q_ij, docs/theory.md
    }
  }
  return pf;
}

// zeroed: the step's first kick already set f, q and the potentials to 0 while it read them (one
// pass less over memory, and no serial fill), and no sort has reused f's storage since.
template <class M>
void Simulation<M>::conservative_pass(bool with_velocity_terms, bool zeroed, bool external) {
  if (!zeroed) {
    const long n = static_cast<long>(state_.size());
    const bool heat_rates = !carried_.q.empty();
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) {
      for (int d = 0; d < D; ++d) carried_.f[d][i] = 0;
      if (heat_rates) carried_.q[i] = 0;
      carried_.potential[i] = 0;
    }
  }
  const PairNoise noise = pair_noise();
  auto& c = carried_;
  auto& x = state_.x;
  if (with_velocity_terms) {
    if constexpr (D == 2)
      halo({&x[0], &x[1], &state_.v[0], &state_.v[1], &state_.u, &c.f[0], &c.f[1], &c.q,
            &c.potential},
           {&c.f[0], &c.f[1], &c.q, &c.potential});
    else
      halo({&x[0], &x[1], &x[2], &state_.v[0], &state_.v[1], &state_.v[2], &state_.u, &c.f[0],
            &c.f[1], &c.f[2], &c.q, &c.potential},
           {&c.f[0], &c.f[1], &c.f[2], &c.q, &c.potential});
    force_blocks(noise);
  } else {
    if constexpr (D == 2)
      halo({&x[0], &x[1], &state_.u, &c.f[0], &c.f[1], &c.potential},
           {&c.f[0], &c.f[1], &c.potential});
    else
      halo({&x[0], &x[1], &x[2], &state_.u, &c.f[0], &c.f[1], &c.f[2], &c.potential},
           {&c.f[0], &c.f[1], &c.f[2], &c.potential});
    conservative_blocks();
  }
  if (has_external_ && external) external_forces();
  if (with_velocity_terms && p_.has_walls()) wall_forces(state_.v, carried_.f, 1);
}

template <class M> void Simulation<M>::potential_pass() {
  std::fill(carried_.potential.begin(), carried_.potential.end(), 0.0);
  if constexpr (M::Conservative::active) {
    const auto& c = model_.conservative;
    auto& pot = carried_.potential;
    auto& x = state_.x;
    if constexpr (D == 2)
      halo({&x[0], &x[1], &state_.u, &pot}, {&pot});
    else
      halo({&x[0], &x[1], &x[2], &state_.u, &pot}, {&pot});
    grid_.for_each_pair(state_, c.rc, [&](std::size_t i, std::size_t j, const double*, double r2) {
      double th_i = 1, th_j = 1, fc, phi;
      if constexpr (M::has_energy) th_i = theta(i), th_j = theta(j);
      c.eval(std::sqrt(r2), th_i, th_j, fc, phi);
      pot[i] += 0.5 * phi;
      pot[j] += 0.5 * phi;
    });
  }
  if (has_external_) { // potentials only: forces are not used by the Euler step's energy pass
    for (int d = 0; d < D; ++d) std::fill(carried_.f[d].begin(), carried_.f[d].end(), 0.0);
    external_forces();
  }
}

template <class M> void Simulation<M>::step() {
  switch (p_.integrator) {
  case Integrator::EcVerlet:
    step_ec_verlet();
    break;
  case Integrator::Euler:
    step_euler();
    break;
  case Integrator::Shardlow:
    step_shardlow();
    break;
  }
  if (slabs_.active() && p_.wall_diffuse) share_emissions();
  if (!emissions_.empty())
    emit_from_walls();
  else
    tally_.end_pass(); // as emit_from_walls: every rank counts the same passes
  if (!p_.heat_slabs.empty()) apply_heat_slabs();
}

// 002 section III.B: every step the hot slab's particles share +power dt, the cold slab's
// -power dt; the total energy is unchanged.
template <class M> void Simulation<M>::apply_heat_slabs() {
  if constexpr (M::has_energy) {
    for (const auto& slab : p_.heat_slabs) {
      slab_members_.clear();
      const auto& x = state_.x[slab.direction];
      for (std::size_t i = 0; i < owned_; ++i)
        if (x[i] >= slab.lower && x[i] < slab.upper) slab_members_.push_back(i);
      unsigned long members = slab_members_.size(); // on several ranks: all ranks' members
      if (slabs_.active())
        MPI_Allreduce(MPI_IN_PLACE, &members, 1, MPI_UNSIGNED_LONG, MPI_SUM, slabs_.comm);
      if (members == 0)
        throw InstabilityError("heat slab [" + std::to_string(slab.lower) + ", " +
                               std::to_string(slab.upper) + ") is empty at step " +
                               std::to_string(step_) + ": widen it");
      const double share = slab.power * dt_ / members;
      for (const std::size_t i : slab_members_) {
        state_.u[i] += share;
        if (!(state_.u[i] > 0))
          throw InstabilityError(
              "the cold heat slab took more energy than particle " + std::to_string(state_.id[i]) +
              " had at step " + std::to_string(step_) + " (u = " + std::to_string(state_.u[i]) +
              "): the case is too stiff for this dt and power; lower the time step or the "
              "power, or widen the cold slab so that more particles share the loss");
      }
    }
  }
}

// 002 Appendix A: velocity-Verlet; each particle's kinetic and potential changes are taken from
// its own internal energy, so the total energy is conserved to round-off for every force.
template <class M> void Simulation<M>::step_ec_verlet() {
  ++step_;
  const std::size_t n = owned_;
  const double half = 0.5 * dt_ / model_.mass, m2 = 0.5 * model_.mass;
  auto& v = state_.v;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    double k_old = 0, k_half = 0;
    for (int d = 0; d < D; ++d) {
      k_old += v[d][i] * v[d][i];
      v[d][i] += half * carried_.f[d][i]; // 002:(A1)
      carried_.f[d][i] = 0;
      k_half += v[d][i] * v[d][i];
      state_.x[d][i] += v[d][i] * dt_; // 002:(A3)
    }
    if constexpr (M::has_energy) // 002:(A2); + P_i(t) is the first half of (A5)'s -[P(t+dt) - P(t)]
      state_.u[i] += 0.5 * dt_ * carried_.q[i] - m2 * (k_half - k_old) + carried_.potential[i];
    carried_.q[i] = 0, carried_.potential[i] = 0;
  }
  if (p_.has_walls()) reflect_at_walls();
  const bool sorted = update_neighbours(false);
  conservative_pass(true, !sorted); // F, q, P at t + dt from r(t+dt), v(t+dt/2), u(t+dt/2)
  bool bad = false;                 // a non-finite velocity or non-positive energy (check_energies)
#pragma omp parallel for schedule(static) reduction(|| : bad)
  for (std::size_t i = 0; i < owned_; ++i) {
    double k_half = 0, k_new = 0;
    for (int d = 0; d < D; ++d) {
      k_half += v[d][i] * v[d][i];
      v[d][i] += half * carried_.f[d][i]; // 002:(A4)
      k_new += v[d][i] * v[d][i];
    }
    if constexpr (M::has_energy) { // 002:(A5)
      state_.u[i] += 0.5 * dt_ * carried_.q[i] - m2 * (k_new - k_half) - carried_.potential[i];
      bad = bad || !(state_.u[i] > 0) || !std::isfinite(state_.u[i]);
    }
    bad = bad || !std::isfinite(k_new);
  }
  if (bad) check_energies("ec-verlet step");
  // The walls' heat, split off the step (their friction's work stays in the particles' internal
  // energies, as every force's does here).
  if (p_.has_walls()) wall_heat_pass();
}

// Explicit first-order update: 001 eqs. (1)-(2) (isothermal); 000:(2.23)-(2.25) / 003:(15)-(17)
// for DPDE, with the dissipative+random work split equally and exactly: du_i += -1/2 dp_ij.(vbar_i
// - vbar_j).
// Euler's impulses dp and heat rates q of every pair at the current state (001:(2)).
template <class M> void Simulation<M>::euler_impulses(const PairNoise& noise) {
  auto& v = state_.v;
  auto& x = state_.x;
  auto& dp = carried_.f;
  auto& q = carried_.q;
  for (int d = 0; d < D; ++d) std::fill(dp[d].begin(), dp[d].end(), 0.0);
  std::fill(q.begin(), q.end(), 0.0);
  if constexpr (D == 2)
    halo({&x[0], &x[1], &v[0], &v[1], &state_.u, &dp[0], &dp[1], &q}, {&dp[0], &dp[1], &q});
  else
    halo({&x[0], &x[1], &x[2], &v[0], &v[1], &v[2], &state_.u, &dp[0], &dp[1], &dp[2], &q},
         {&dp[0], &dp[1], &dp[2], &q});
  grid_.for_each_pair(
      state_, model_.rc, [&](std::size_t i, std::size_t j, const double* dx, double r2) {
        const PairForce pf = pair_force(noise, i, j, dx, r2, v);
        const double scale = (pf.conservative + pf.dissipative_random) * dt_ / std::sqrt(r2);
        for (int d = 0; d < D; ++d) {
          dp[d][i] += scale * dx[d];
          dp[d][j] -= scale * dx[d];
        }
        q[i] += pf.heat;
        q[j] -= pf.heat;
      });
}

// The internal energies' increments du (in carried_.q) after the velocity update: the heat, less
// each pair's dissipative work split evenly (a second pass over the same pairs and noise), or
// 002 Appendix A's offset.
template <class M> void Simulation<M>::euler_energy_increments(const PairNoise& noise) {
  const std::size_t n = owned_;
  auto& v = state_.v;
  auto& x = state_.x;
  std::vector<double>& du = carried_.q; // heat rates become the energy increments
  for (std::size_t i = 0; i < n; ++i) du[i] *= dt_;
  if (p_.energy_offset) {
    for (std::size_t i = 0; i < n; ++i) { // 002 Appendix A offset: -dK_i
      double k_old = 0, k_new = 0;
      for (int d = 0; d < D; ++d) k_old += v_old_[d][i] * v_old_[d][i], k_new += v[d][i] * v[d][i];
      du[i] -= 0.5 * model_.mass * (k_new - k_old);
    }
    return;
  }
  // Counter-based noise: recomputed, not stored.
  if constexpr (D == 2)
    halo({&x[0], &x[1], &v[0], &v[1], &v_old_[0], &v_old_[1], &state_.u, &du}, {&du});
  else
    halo({&x[0], &x[1], &x[2], &v[0], &v[1], &v[2], &v_old_[0], &v_old_[1], &v_old_[2], &state_.u,
          &du},
         {&du});
  grid_.for_each_pair(
      state_, model_.rc, [&](std::size_t i, std::size_t j, const double* dx, double r2) {
        const PairForce pf = pair_force(noise, i, j, dx, r2, v_old_);
        const double inv_r = 1 / std::sqrt(r2);
        double rel = 0; // e_ij . (vbar_i - vbar_j)
        for (int d = 0; d < D; ++d)
          rel += dx[d] * inv_r * 0.5 * (v_old_[d][i] + v[d][i] - v_old_[d][j] - v[d][j]);
        const double work = pf.dissipative_random * dt_ * rel; // dK of the pair, docs/theory.md
        du[i] -= 0.5 * work;
        du[j] -= 0.5 * work;
      });
  if (p_.has_walls()) wall_work_split(du);
}

template <class M> void Simulation<M>::step_euler() {
  ++step_;
  const std::size_t n = owned_;
  const PairNoise noise = pair_noise();
  auto& v = state_.v;
  euler_impulses(noise);
  auto& dp = carried_.f;
  if (has_external_) external_forces(dt_, false); // their impulses; potentials are up to date
  if (p_.has_walls()) wall_forces(v, dp, dt_);
  for (int d = 0; d < D; ++d) v_old_[d] = v[d];
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < D; ++d) v[d][i] += dp[d][i] / model_.mass; // 001:(2)
  if constexpr (M::has_energy) {
    euler_energy_increments(noise);
    for (std::size_t i = 0; i < n; ++i) state_.u[i] += carried_.q[i];
    if (p_.has_walls()) wall_heat_pass(); // split off the step, as ec-verlet's
  }
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < D; ++d) state_.x[d][i] += v_old_[d][i] * dt_; // 001:(1)
  if (p_.has_walls()) reflect_at_walls();
  if constexpr (M::has_energy)
    if (p_.energy_offset)
      for (std::size_t i = 0; i < n; ++i) state_.u[i] += carried_.potential[i];
  update_neighbours(true);
  potential_pass();
  if constexpr (M::has_energy)
    if (p_.energy_offset)
      for (std::size_t i = 0; i < owned_; ++i) state_.u[i] -= carried_.potential[i];
  check_energies("euler step");
}

// Shardlow sweep over all pairs at r(t), then velocity-Verlet for the conservative force
// (Lisal et al. 2011; LAMMPS fix shardlow + fix nve).
template <class M> void Simulation<M>::step_shardlow() {
  ++step_;
  const PairNoise noise = pair_noise();
  if constexpr (D == 2)
    halo({&state_.x[0], &state_.x[1], &state_.v[0], &state_.v[1], &state_.u},
         {&state_.v[0], &state_.v[1], &state_.u});
  else
    halo({&state_.x[0], &state_.x[1], &state_.x[2], &state_.v[0], &state_.v[1], &state_.v[2],
          &state_.u},
         {&state_.v[0], &state_.v[1], &state_.v[2], &state_.u});
  shardlow_sweep(noise); // pair_kernels.tpp
  // Velocity-Verlet for the conservative pair force, wall repulsion and gravity (if any).
  const bool kicks = M::Conservative::active || has_external_;
  const bool offset = M::has_energy && p_.energy_offset && kicks;
  const bool pooled = offset && M::Conservative::active; // share_pool says why
  ExactSum pool;
  if (pooled) pooled_.resize(owned_);
  shardlow_first_kick(kicks, offset, pooled);
  if (pooled) add_pooled(pool); // before the sort reorders the particles
  if (p_.has_walls()) reflect_at_walls();
  const bool sorted = update_neighbours(false);
  if (!kicks) return check_energies("shardlow step");
  conservative_pass(false, !sorted, false);
  if (pooled) pooled_.resize(owned_);
  shardlow_second_kick(offset, pooled);
  if (pooled) share_pool(pool);
}

// The walls' sweep, the first half kick and the drift. Each particle's walls, kick and checks
// touch it alone, so each half is one parallel region: at N ~ 1600 a region's start costs as
// much as a wall's work (docs/performance.md).
template <class M> void Simulation<M>::shardlow_first_kick(bool kicks, bool offset, bool pooled) {
  const double half = 0.5 * dt_ / model_.mass, m2 = 0.5 * model_.mass;
  auto& v = state_.v;
  const bool walls = p_.has_walls();
  const PairNoise wall_noise(p_.seed, static_cast<std::uint64_t>(step_), PairNoise::Wall);
  for_particles_tallied([&](std::size_t i, TallyTerms& tally) {
    if (walls) wall_sweep_particle(wall_noise, i, tally);
    double k_old = 0, k_half = 0;
    for (int d = 0; d < D; ++d) {
      k_old += v[d][i] * v[d][i];
      if (kicks) v[d][i] += half * carried_.f[d][i], carried_.f[d][i] = 0;
      k_half += v[d][i] * v[d][i];
      state_.x[d][i] += v[d][i] * dt_;
    }
    // -(dK_i + dP_i), 002 Appendix A
    if (offset) book_offset(i, carried_.potential[i] - m2 * (k_half - k_old), pooled);
    if (kicks) carried_.potential[i] = 0;
  });
  if (walls) tally_.end_pass(); // the walls' pass (OrderedTally)
}

// The external forces and the second half kick.
template <class M> void Simulation<M>::shardlow_second_kick(bool offset, bool pooled) {
  const double half = 0.5 * dt_ / model_.mass, m2 = 0.5 * model_.mass;
  auto& v = state_.v;
  for_particles_tallied([&](std::size_t i, TallyTerms& tally) {
    if (has_external_) external_force(i, 1, true, tally);
    double k_half = 0, k_new = 0;
    for (int d = 0; d < D; ++d) {
      k_half += v[d][i] * v[d][i];
      v[d][i] += half * carried_.f[d][i];
      k_new += v[d][i] * v[d][i];
    }
    // -(dK_i + dP_i), 002 Appendix A
    if (offset) book_offset(i, -(carried_.potential[i] + m2 * (k_new - k_half)), pooled);
    if (!pooled && bad_particle(i)) fail(i, "shardlow step");
  });
  if (has_external_) tally_.end_pass(); // external_forces' pass (OrderedTally)
}

// Particle i's -(dK_i + dP_i) of a kick: into its u, or kept for the pool.
template <class M> void Simulation<M>::book_offset(std::size_t i, double change, bool pooled) {
  if constexpr (M::has_energy) {
    if (pooled)
      pooled_[i] = change;
    else
      state_.u[i] += change;
  }
}

// Adds this rank's pooled changes in the pool (the same bits in any order).
template <class M> void Simulation<M>::add_pooled(ExactSum& pool) const {
  for (std::size_t i = 0; i < owned_; ++i) pool.add(pooled_[i]);
}

// The pooled change of K + P, every rank's, shared evenly among all particles. A pair force moves
// mechanical energy between particles (1/2 F_ij . (v_i + v_j) each step): taken from each
// particle's own u, that flow would be carried by the internal energies instead, and a walled
// fluid settles ~7% above its walls (docs/theory.md, "The particle model"). One-body forces'
// changes stay with their particle.
template <class M> void Simulation<M>::share_pool(ExactSum& pool) {
  if constexpr (M::has_energy) {
    add_pooled(pool);
    pool.add_over_ranks(slabs_);
    const double share = pool.value() / static_cast<double>(p_.particle_count());
    for (std::size_t i = 0; i < owned_; ++i) {
      state_.u[i] += share;
      if (bad_particle(i)) fail(i, "shardlow step");
    }
  }
}

// This rank's particles (all of them on one process).
template <class M> double Simulation<M>::kinetic_energy() const {
  return kinetic_energy_of(state_, owned_, model_.mass);
}

template <class M> double Simulation<M>::internal_energy() const {
  return sum_of(state_.u, owned_);
}

template <class M> double Simulation<M>::potential_energy() const {
  return sum_of(carried_.potential, owned_);
}

// A non-finite velocity or a non-positive internal energy.
template <class M> bool Simulation<M>::bad_particle(std::size_t i) const {
  double s = 0;
  for (int d = 0; d < D; ++d) s += state_.v[d][i];
  if constexpr (M::has_energy)
    if (!(state_.u[i] > 0) || !std::isfinite(state_.u[i])) return true;
  return !std::isfinite(s);
}

template <class M> void Simulation<M>::check_energies(const char* where) const {
  const long n = static_cast<long>(owned_);
  bool bad = false;
#pragma omp parallel for schedule(static) reduction(|| : bad)
  for (long i = 0; i < n; ++i) bad = bad || bad_particle(static_cast<std::size_t>(i));
  if (!bad) return;
  for (long i = 0; i < n; ++i) // the first bad particle, in storage order
    if (bad_particle(static_cast<std::size_t>(i))) fail(static_cast<std::size_t>(i), where);
}

} // namespace twinflow::particle
