// Walls and the other external fields of Simulation<M> (included from simulation.hpp). A wall
// is seed 000's (one partner of infinite mass and heat capacity at the nearest point) or a
// half-space of wall material (wall_weights.hpp); either way each pair term keeps its
// fluctuation-dissipation relation with the wall's temperature in Theta, energy that crosses a
// wall is counted in wall_energy_in_, and nothing crosses the plane (reflect_at_walls).

namespace twinflow::particle {

// Contiguous chunks, one per thread; each thread's terms are replayed in chunk order after the
// loop. An exception (a failed particle) is rethrown after it, the first chunk's first.
template <class M> template <class Body> void Simulation<M>::for_particles_tallied(Body body) {
  const std::size_t n = owned_;
  const int threads = omp_get_max_threads();
  if (threads == 1 || n < 2) {
    TallyTerms terms(tally_);
    for (std::size_t i = 0; i < n; ++i) body(i, terms);
    terms.replay_into(tally_);
    return;
  }
  tally_logs_.resize(static_cast<std::size_t>(threads));
  std::vector<TallyTerms> terms;
  for (auto& log : tally_logs_) log.clear(), terms.emplace_back(log);
  std::vector<std::exception_ptr> failed(tally_logs_.size());
  int team = 1;
#pragma omp parallel num_threads(threads)
  {
#pragma omp single
    team = omp_get_num_threads();
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t size = static_cast<std::size_t>(team);
    try {
      for (std::size_t i = n * t / size; i < n * (t + 1) / size; ++i) body(i, terms[t]);
    } catch (...) {
      failed[t] = std::current_exception();
    }
  }
  for (const auto& e : failed)
    if (e) std::rethrow_exception(e);
  for (int t = 0; t < team; ++t) terms[static_cast<std::size_t>(t)].replay_into(tally_);
}

template <class M> double Simulation<M>::wall_range(int d, int side) const {
  return p_.walls[d].model[side] == WallModel::Seed000 ? p_.wall_range : half_space_.range;
}

template <class M> double Simulation<M>::wall_temperature(int d, int side, double th_i) const {
  if constexpr (!M::has_energy) return p_.temperature;
  const WallPair& wall = p_.walls[d];
  return wall.thermal[side] ? wall.temperature[side] : th_i; // adiabatic: the particle alone
}

template <class M>
typename Simulation<M>::WallCoupling Simulation<M>::wall_coupling(int d, int side, double h) const {
  WallCoupling c;
  if (p_.walls[d].model[side] == WallModel::Seed000) { // the pair weights at distance h
    wall_friction_.w.eval(h, c.normal, c.sqrt_normal);
    c.tangent = c.normal, c.sqrt_tangent = c.sqrt_normal;
    if constexpr (M::Heat::active) wall_heat_.w.eval(h, c.heat, c.sqrt_heat);
    return c;
  }
  c.half_space = true;
  c.normal = half_space_.friction_normal(h), c.sqrt_normal = std::sqrt(c.normal);
  c.tangent = half_space_.friction_tangent(h), c.sqrt_tangent = std::sqrt(c.tangent);
  if constexpr (M::Heat::active) {
    c.heat = p_.walls[d].conduction[side] * half_space_.heat(h);
    c.sqrt_heat = std::sqrt(c.heat);
  }
  return c;
}

// The wall's heat rate into particle i (rate and noise amplitude; heat into i), q of docs/theory.md
// with theta_j = T_w.
template <class M>
void Simulation<M>::wall_heat(const WallCoupling& c, double th_i, double th_wall, double& rate,
                              double& amplitude) const {
  rate = 0, amplitude = 0;
  if constexpr (M::Heat::active) {
    if (c.half_space)
      wall_heat_.eval_wall(c.heat, c.sqrt_heat, th_i, th_wall, rate, amplitude);
    else
      wall_heat_.eval_w(c.heat, c.sqrt_heat, th_i, th_wall, rate, amplitude);
  }
}

template <class M>
double Simulation<M>::wall_gamma(const WallCoupling& c, double th_i, double th_wall) const {
  return c.half_space ? wall_friction_.wall_ito_gamma(th_i, th_wall)
                      : wall_friction_.ito_gamma(th_i, th_wall);
}

// Wall repulsion along the inward normal and its potential: seed 000's a_w (1 - h/range) with
// a_w range/2 (1 - h/range)^2 (the pair force of docs/theory.md against one wall particle), or the
// fluid's own conservative force integrated over the wall material; gravity m g with potential
// -m g.x; the reverse Poiseuille force. Forces times `scale` into carried f (ec-verlet and
// shardlow: forces; euler: impulses); potentials into carried potential if `potentials`.
template <class M> void Simulation<M>::external_forces(double scale, bool potentials) {
  for_particles_tallied(
      [&](std::size_t i, TallyTerms& tally) { external_force(i, scale, potentials, tally); });
  tally_.end_pass(); // on several ranks its terms replay in this place (OrderedTally)
}

// Particle i's share of external_forces (every direction: one parallel region for all).
template <class M>
void Simulation<M>::external_force(std::size_t i, double scale, bool potentials,
                                   TallyTerms& tally) {
  if (p_.poiseuille_force != 0) // no potential: its work heats the fluid
    carried_.f[0][i] += state_.x[1][i] < 0.5 * p_.box[1] ? scale * p_.poiseuille_force
                                                         : -(scale * p_.poiseuille_force);
  for (int d = 0; d < D; ++d) {
    const double x = state_.x[d][i], mg = model_.mass * p_.gravity[d];
    if (mg != 0) {
      carried_.f[d][i] += scale * mg;
      if (potentials) carried_.potential[i] -= mg * x;
    }
    if (!p_.walls[d].present) continue;
    for (int side = 0; side < 2; ++side) {
      const double h = side ? p_.box[d] - x : x;
      if (h >= wall_range(d, side)) continue;
      double a = p_.wall_a0, force = 0, potential = 0;
      if (p_.walls[d].model[side] == WallModel::Seed000) {
        const double c = 1 - h * (1 / p_.wall_range); // as before: bit for bit
        force = a * c, potential = 0.5 * a * p_.wall_range * c * c;
      } else if constexpr (M::Conservative::active) {
        double th_i = 1;
        if constexpr (M::has_energy) th_i = theta(i);
        a = model_.conservative.strength(th_i, wall_temperature(d, side, th_i));
        force = a * half_space_.repulsion(h), potential = a * half_space_.repulsion_potential(h);
      } else {
        continue; // an ideal fluid's wall material does not repel
      }
      carried_.f[d][i] += scale * (side ? -force : force);
      tally.add(6 + 2 * d + side, force * dt_); // this force acts for one step
      if (potentials) carried_.potential[i] += potential;
    }
  }
}

// S1 against a wall for one velocity component v (along the wall's normal or, no-slip, a
// tangent): as for a pair, with the wall's infinite mass (reduced mass m) and zero velocity; `w`
// the friction weight of that component. Returns the kinetic energy change.
template <class M>
double Simulation<M>::wall_s1(double& v, double w, double sqrt_w, double gamma, double th_i,
                              double th_wall, double xi) const {
  const auto& fr = wall_friction_;
  const double m = model_.mass;
  const double kick = fr.sigma_of(fr.harmonic(th_i, th_wall)) * sqrt_w * xi * sqrt_dt_;
  const double v0 = v;
  const double v1 = v0 + 0.5 * (-gamma * w * v0 * dt_ + kick) / m; // explicit half
  v = (v1 + 0.5 * kick / m) / (1 + 0.5 * gamma * w * dt_ / m);     // implicit half
  return 0.5 * m * (v * v - v0 * v0);
}

// Shardlow: the walls' dissipative, random and heat terms on particle i, every wall in range (its
// terms touch it alone; the caller's loop runs over the threads: for_particles_tallied).
template <class M>
void Simulation<M>::wall_sweep_particle(const PairNoise& noise, std::size_t i, TallyTerms& tally) {
  for (int d = 0; d < D; ++d)
    if (p_.walls[d].present)
      for (int side = 0; side < 2; ++side) wall_sweep_one(noise, i, d, side, tally);
}

// One wall's terms on particle i (wall_sweep_particle).
template <class M>
void Simulation<M>::wall_sweep_one(const PairNoise& noise, std::size_t i, int d, int side,
                                   TallyTerms& tally) {
  const WallPair& wall = p_.walls[d];
  const double h = side ? p_.box[d] - state_.x[d][i] : state_.x[d][i];
  if (h >= wall_range(d, side)) return;
  const int index = 2 * d + side;
  double g[4];
  noise.particle_gaussians(state_.id[i], 2 * index, g[0], g[1]);
  noise.particle_gaussians(state_.id[i], 2 * index + 1, g[2], g[3]);
  const bool thermal = wall.thermal[side];
  const WallCoupling c = wall_coupling(d, side, h);
  double th_i = p_.temperature;
  if constexpr (M::has_energy) th_i = theta(i);
  const double th_wall = wall_temperature(d, side, th_i);
  if (thermal && c.heat > 0) {
    tally.add(index, exchange_wall_heat(noise, i, index, c, th_wall, g[3], tally));
    th_i = theta(i);
  }
  if (!(c.normal > 0)) return;
  const double gamma = wall_gamma(c, th_i, th_wall);
  const double v_normal = state_.v[d][i];
  double dk = wall_s1(state_.v[d][i], c.normal, c.sqrt_normal, gamma, th_i, th_wall, g[0]);
  tally.add(6 + index, (side ? -1 : 1) * model_.mass * (state_.v[d][i] - v_normal));
  if (wall.no_slip) {
    int k = 1;
    for (int t = 0; t < D; ++t)
      if (t != d)
        dk += wall_s1(state_.v[t][i], c.tangent, c.sqrt_tangent, gamma, th_i, th_wall, g[k++]);
  }
  if constexpr (M::has_energy) {
    // Thermal wall: it keeps half the work (docs/theory.md); adiabatic: the particle all of it.
    const double to_particle = thermal ? 0.5 * dk : dk;
    state_.u[i] -= to_particle;
    tally.add(index, dk - to_particle);
  }
}

// The wall's heat into particle i over one step (index: the wall, 2 d + side; g: its Gaussian),
// Metropolis-adjusted: the explicit step of docs/theory.md's q with theta_j = T_w is proposed and
// accepted with the probability that keeps, exactly, the law u^{c_v} exp(-u/T_w) (k = 1;
// 000:(2.4)) of a particle in equilibrium with the wall (detailed balance of the proposal's
// Gaussians both ways). A step that would leave u <= 0, or is rejected, exchanges nothing: a
// strong wall cannot drive an internal energy negative. Returns the heat that entered.
template <class M>
double Simulation<M>::exchange_wall_heat(const PairNoise& noise, std::size_t i, int index,
                                         const WallCoupling& c, double th_wall, double g,
                                         TallyTerms& tally) {
  if constexpr (!M::Heat::active) {
    return 0;
  } else {
    const double cv = model_.cv, u0 = state_.u[i];
    double rate0, amplitude0;
    wall_heat(c, u0 / cv, th_wall, rate0, amplitude0);
    const double u1 = u0 + rate0 * dt_ + amplitude0 * g * sqrt_dt_;
    tally.add(12 + index, 1); // a move proposed (the acceptance rate: walls' diagnostic)
    if (!(u1 > 0)) return 0;
    double rate1, amplitude1;
    wall_heat(c, u1 / cv, th_wall, rate1, amplitude1);
    // log of [P(u1) q(u0 | u1)] / [P(u0) q(u1 | u0)], q the Gaussian proposals
    const double back = u0 - u1 - rate1 * dt_, forth = u1 - u0 - rate0 * dt_;
    const double log_ratio = cv * std::log(u1 / u0) - (u1 - u0) / th_wall -
                             back * back / (2 * amplitude1 * amplitude1 * dt_) +
                             forth * forth / (2 * amplitude0 * amplitude0 * dt_) -
                             std::log(amplitude1 / amplitude0);
    if (log_ratio < 0) {
      double g1, g2; // the acceptance's uniform, from its own counter
      noise.particle_gaussians(state_.id[i], 12 + index, g1, g2);
      if (!(0.5 * std::erfc(-g1 / std::sqrt(2.0)) < std::exp(log_ratio))) return 0;
    }
    state_.u[i] = u1;
    tally.add(18 + index, 1); // and accepted
    return u1 - u0;
  }
}

// ec-verlet and euler: every thermal wall's heat exchange, one step, particle by particle.
template <class M> void Simulation<M>::wall_heat_pass() {
  if constexpr (M::Heat::active) {
    const PairNoise noise(p_.seed, static_cast<std::uint64_t>(step_), PairNoise::Wall);
    for_particles_tallied([&](std::size_t i, TallyTerms& tally) {
      for (int d = 0; d < D; ++d) {
        const WallPair& wall = p_.walls[d];
        if (!wall.present) continue;
        for (int side = 0; side < 2; ++side) {
          const double h = side ? p_.box[d] - state_.x[d][i] : state_.x[d][i];
          if (!wall.thermal[side] || h >= wall_range(d, side)) continue;
          const WallCoupling c = wall_coupling(d, side, h);
          if (!(c.heat > 0)) continue;
          const int index = 2 * d + side;
          double g[2];
          noise.particle_gaussians(state_.id[i], 2 * index + 1, g[0], g[1]);
          tally.add(index,
                    exchange_wall_heat(noise, i, index, c, wall.temperature[side], g[1], tally));
        }
      }
    });
  }
  tally_.end_pass(); // on several ranks its terms replay in this place (OrderedTally)
}

// ec-verlet and euler: the walls' friction and random force on every particle within range, at
// velocities `v`, into forces f (times `scale`: 1 for forces, dt for impulses); the impulses
// along the inward normals are counted for the walls' pressure.
template <class M>
void Simulation<M>::wall_forces(const std::array<std::vector<double>, D>& v,
                                std::array<std::vector<double>, D>& f, double scale) {
  const PairNoise noise(p_.seed, static_cast<std::uint64_t>(step_), PairNoise::Wall);
  for_particles_tallied([&](std::size_t i, TallyTerms& tally) {
    for (int d = 0; d < D; ++d) {
      if (!p_.walls[d].present) continue;
      for (int side = 0; side < 2; ++side) {
        double force[D];
        if (!wall_force(noise, v, i, d, side, force)) continue;
        for (int t = 0; t < D; ++t) f[t][i] += scale * force[t];
        tally.add(6 + 2 * d + side, (side ? -1 : 1) * force[d] * dt_);
      }
    }
  });
  tally_.end_pass(); // on several ranks its terms replay in this place (OrderedTally)
}

// One wall's friction and random force on particle i at velocities `v` (the same noise numbers
// as wall_sweep_one's); false when i is out of its range.
template <class M>
bool Simulation<M>::wall_force(const PairNoise& noise, const std::array<std::vector<double>, D>& v,
                               std::size_t i, int d, int side, double* force) const {
  const double h = side ? p_.box[d] - state_.x[d][i] : state_.x[d][i];
  if (h >= wall_range(d, side)) return false;
  const int index = 2 * d + side;
  double g[4];
  noise.particle_gaussians(state_.id[i], 2 * index, g[0], g[1]);
  noise.particle_gaussians(state_.id[i], 2 * index + 1, g[2], g[3]);
  const WallCoupling c = wall_coupling(d, side, h);
  double th_i = p_.temperature;
  if constexpr (M::has_energy) th_i = theta(i);
  const double th_wall = wall_temperature(d, side, th_i);
  const auto& fr = wall_friction_;
  const double gamma = wall_gamma(c, th_i, th_wall);
  const double sigma = fr.sigma_of(fr.harmonic(th_i, th_wall)) * inv_sqrt_dt_;
  // F = -gamma G v + sigma sqrt(G) xi / sqrt(dt) per component (G: the component's weight)
  force[d] = -gamma * c.normal * v[d][i] + sigma * c.sqrt_normal * g[0];
  int k = 1;
  for (int t = 0; t < D; ++t)
    if (t != d)
      force[t] = p_.walls[d].no_slip
                     ? -gamma * c.tangent * v[t][i] + sigma * c.sqrt_tangent * g[k++]
                     : 0.0;
  return true;
}

// Euler without the energy offset: the wall's work on particle i, dK_w = dp_w . vbar, is shared
// as seed 000 shares a pair's: half to the particle, half kept by a thermal wall (counted as
// energy in); an adiabatic wall gives the particle all of it. Recomputes the step's wall forces
// at the old velocities (the same noise).
template <class M> void Simulation<M>::wall_work_split(std::vector<double>& du) {
  if constexpr (M::has_energy) {
    const PairNoise noise(p_.seed, static_cast<std::uint64_t>(step_), PairNoise::Wall);
    for_particles_tallied([&](std::size_t i, TallyTerms& tally) {
      for (int d = 0; d < D; ++d) {
        if (!p_.walls[d].present) continue;
        for (int side = 0; side < 2; ++side) {
          double force[D];
          if (!wall_force(noise, v_old_, i, d, side, force)) continue;
          double work = 0;
          for (int t = 0; t < D; ++t)
            work += force[t] * dt_ * 0.5 * (v_old_[t][i] + state_.v[t][i]);
          const double to_particle = p_.walls[d].thermal[side] ? 0.5 * work : work;
          du[i] -= to_particle;
          tally.add(2 * d + side, work - to_particle);
        }
      }
    });
  }
  tally_.end_pass(); // on several ranks its terms replay in this place (OrderedTally)
}

// Nothing crosses a wall: a particle past the plane is put back by specular reflection
// (free-slip) or bounce-back (no-slip). Kinetic energy is unchanged either way.
template <class M> void Simulation<M>::reflect_at_walls() {
  for (int d = 0; d < D; ++d) {
    const WallPair& wall = p_.walls[d];
    if (!wall.present) continue;
    const double length = p_.box[d];
    auto& x = state_.x[d];
    for (std::size_t i = 0; i < owned_; ++i) {
      if (x[i] >= 0 && x[i] <= length) continue;
      const int side = x[i] < 0 ? 0 : 1;
      x[i] = x[i] < 0 ? -x[i] : 2 * length - x[i];
      tally_.count(1);
      if (x[i] < 0 || x[i] > length) fail(i, "a particle moved more than a box length in one step");
      if (diffuse_wall(d, side)) { // re-emitted at the end of the step (emit_from_walls)
        emissions_.push_back({state_.id[i], 2 * d + side, static_cast<std::uint32_t>(i)});
        continue;
      }
      tally_.add(6 + 2 * d + side, 2 * model_.mass * std::fabs(state_.v[d][i]));
      if (wall.no_slip)
        for (int t = 0; t < D; ++t) state_.v[t][i] = -state_.v[t][i];
      else
        state_.v[d][i] = -state_.v[d][i];
    }
  }
  tally_.end_pass(); // on several ranks its terms replay in this place (OrderedTally)
}

template <class M> bool Simulation<M>::diffuse_wall(int d, int side) const {
  if constexpr (!M::has_energy) return false;
  const WallPair& wall = p_.walls[d];
  return p_.wall_diffuse && wall.thermal[side] && wall.model[side] == WallModel::HalfSpace;
}

// The particles that reached a diffuse wall during this step, re-emitted now that their internal
// energies hold no carried potential (ec-verlet and the offsets add P_i(t) mid-step), in storage
// order (each particle's walls in order), so that the order and the result are those of any
// thread count.
template <class M> void Simulation<M>::emit_from_walls() {
  const PairNoise noise(p_.seed, static_cast<std::uint64_t>(step_), PairNoise::Wall);
  bool in_place = !slabs_.active(); // each still where it was reflected (no sort since)
  for (const Emission& e : emissions_)
    in_place = in_place && e.index < owned_ && state_.id[e.index] == e.id;
  if (in_place) { // no search over all particles
    std::sort(emissions_.begin(), emissions_.end(), [](const Emission& a, const Emission& b) {
      return a.index < b.index || (a.index == b.index && a.wall < b.wall);
    });
    for (const Emission& e : emissions_) emit_from_wall(noise, e.index, e.wall / 2, e.wall % 2);
  } else { // re-sorted since, or ids from other ranks: find them by id
    std::sort(emissions_.begin(), emissions_.end());
    for (std::size_t i = 0; i < owned_; ++i) {
      const Emission key{state_.id[i], -1};
      auto it = std::lower_bound(emissions_.begin(), emissions_.end(), key);
      for (; it != emissions_.end() && it->id == state_.id[i]; ++it)
        emit_from_wall(noise, i, it->wall / 2, it->wall % 2);
    }
  }
  emissions_.clear();
  tally_.end_pass(); // on several ranks its terms replay in this place (OrderedTally)
}

// A diffuse thermal wall re-emits particle i as wall material at T_w would emit it (Maxwell's
// diffuse wall): normal speed from the flux-weighted law v exp(-m v^2 / 2T_w), tangential
// components (no-slip) from exp(-m v^2 / 2T_w), internal energy from u^{c_v} exp(-u/T_w)
// (000:(2.4), k = 1). Each is the equilibrium law of what crosses a plane in a fluid at T_w, so
// the wall keeps detailed balance; the energy the particle gains is the wall's inflow.
template <class M>
void Simulation<M>::emit_from_wall(const PairNoise& noise, std::size_t i, int d, int side) {
  const WallPair& wall = p_.walls[d];
  const double T_w = wall.temperature[side], m = model_.mass;
  const int index = 2 * d + side;
  const std::uint32_t id = state_.id[i], base = 64 + 1024 * static_cast<std::uint32_t>(index);
  double k_old = 0;
  for (int t = 0; t < D; ++t) k_old += state_.v[t][i] * state_.v[t][i];
  const double v_in = std::fabs(state_.v[d][i]);
  double g[4];
  noise.particle_gaussians(id, base, g[0], g[1]);
  noise.particle_gaussians(id, base + 1, g[2], g[3]);
  const double uniform = std::max(0.5 * std::erfc(-g[0] / std::sqrt(2.0)), 1e-300);
  const double v_out = std::sqrt(-2 * T_w / m * std::log(uniform));
  state_.v[d][i] = side == 0 ? v_out : -v_out;
  if (wall.no_slip)
    for (int t = 0, k = 1; t < D; ++t)
      if (t != d) state_.v[t][i] = std::sqrt(T_w / m) * g[k++];
  tally_.add(6 + index, m * (v_in + v_out));
  double k_new = 0;
  for (int t = 0; t < D; ++t) k_new += state_.v[t][i] * state_.v[t][i];
  double du = 0;
  if constexpr (M::has_energy) {
    const double u_new = T_w * gamma_variate(noise, id, base + 2, model_.cv + 1);
    du = u_new - state_.u[i];
    state_.u[i] = u_new;
  }
  tally_.add(index, 0.5 * m * (k_new - k_old) + du);
}

// Gamma(a, 1) for a >= 1 by Marsaglia & Tsang (2000), each attempt from its own counter.
template <class M>
double Simulation<M>::gamma_variate(const PairNoise& noise, std::uint32_t id, std::uint32_t counter,
                                    double a) const {
  const double dd = a - 1.0 / 3, c = 1 / std::sqrt(9 * dd);
  for (std::uint32_t attempt = 0;; ++attempt) {
    double g, h;
    noise.particle_gaussians(id, counter + attempt, g, h);
    const double v = std::pow(1 + c * g, 3);
    if (v <= 0) continue;
    const double u = 0.5 * std::erfc(-h / std::sqrt(2.0));
    if (std::log(u) < 0.5 * g * g + dd - dd * v + dd * std::log(v)) return dd * v;
  }
}

} // namespace twinflow::particle
