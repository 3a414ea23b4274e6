// The compiled particle models of one family (dimension D, conservative force C; every friction
// and heat law): the run (ParticleRun, its step loop, samples and results), the benchmark's timed
// steps, and the branches on the friction and heat laws. Included by one unit per family
// (run_2d_none.cpp, ...), so that the 54 models compile in six units side by side; run.cpp
// branches on the dimension and the conservative force and calls the family.

#define TWINFLOW_FAMILY_UNIT // this unit compiles its models' simulations (simulation.hpp)
#include "particle/run_models.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <unistd.h>

#include "particle/archive.hpp"
#include "particle/diagnostics/diagnostics.hpp"
#include "particle/simulation.hpp"

namespace twinflow::particle {

namespace {

// One particle run: set-up, the step loop with its samples, and the results. The diagnostics
// are plug-ins (diagnostics/): at a sample the run measures what they share, the energies and one
// serial pass over the pairs, and hands it to each. A checkpoint holds the simulation, the run's
// own counters (archive()) and each diagnostic's state under its name.
template <class M> class ParticleRun {
public:
  static constexpr int D = M::D;
  using clock = std::chrono::steady_clock;
  using Progress = RunControl::Progress;

  ParticleRun(const M& model, const ParticleParameters& p)
      : model_(model), p_(p), sim_(model, p),
        view_grid_(box_of(p), model.rc + list_skin(p), periodic_of(p)),
        n_(static_cast<std::size_t>(p.particle_count())),
        total_steps_(p.equilibration_steps + p.steps), e0_(initial_energy()),
        diagnostics_(make_diagnostics<D>(p, facts())), pair_counts_(p.rdf_bins, 0.0) {
    for (int d = 0; d < D; ++d) volume_ *= p.box[d];
    for (const auto& d : diagnostics_) {
      needs_.distances |= d->pair_needs().distances;
      needs_.conduction |= d->pair_needs().conduction;
    }
    if constexpr (M::Heat::active)
      if (needs_.conduction)
        for (int d = 0; d < D; ++d) conduction_[d].assign(n_, 0.0);
  }

  template <class A> void archive(A& a) {
    auto s = a.nested("simulation");
    sim_.archive(s);
    a("step", step_), a("wall_seconds", wall_before_), a("e0", e0_), a("drift_max", drift_max_);
    for (const auto& d : diagnostics_) {
      auto part = a.nested(d->name());
      if constexpr (A::loading)
        d->load(part);
      else
        d->save(part);
    }
  }

  RunOutput run(const RunControl& control) {
    if (control.resume) {
      LoadArchive a(*control.resume, "");
      archive(a);
    }
    const bool root = sim_.slabs().root();
    t0_ = clock::now() -
          std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(wall_before_));
    auto last_progress = clock::now(), last_checkpoint = clock::now();
    while (step_ < total_steps_) {
      sim_.step();
      ++step_;
      if (step_ % p_.sample_interval == 0 || step_ == total_steps_) sample();
      if (root && control.progress != Progress::none &&
          clock::now() - last_progress > (control.progress == Progress::terminal
                                              ? std::chrono::seconds(2)
                                              : std::chrono::seconds(60))) {
        last_progress = clock::now();
        progress_line(control.progress == Progress::terminal ? "\r" : "",
                      control.progress_label.c_str(),
                      control.progress == Progress::terminal ? "   " : "\n");
      }
      int stop = control.stop_requested && control.stop_requested();
      const bool periodic = control.checkpoint_every_seconds > 0 &&
                            clock::now() - last_checkpoint >
                                std::chrono::duration<double>(control.checkpoint_every_seconds);
      int checkpoint = (stop || periodic) && control.write_checkpoint && step_ < total_steps_;
      if (distributed()) { // every rank stops and writes its part, or none does
        int flags[2] = {stop, checkpoint};
        MPI_Allreduce(MPI_IN_PLACE, flags, 2, MPI_INT, MPI_LOR, sim_.slabs().comm);
        stop = flags[0], checkpoint = flags[1];
      }
      if (checkpoint) {
        wall_before_ = elapsed();
        io::Checkpoint c;
        SaveArchive a(c, "");
        archive(a);
        if (root) control.write_checkpoint(c);
        last_checkpoint = clock::now();
        if (stop) {
          if (root && control.progress == Progress::terminal) std::fprintf(stderr, "\n");
          out_.interrupted = true;
          out_.steps_done = step_;
          return std::move(out_);
        }
      }
    }
    if (root && control.progress == Progress::terminal) std::fprintf(stderr, "\n");
    if (root) finish(); // on several ranks rank 0 holds the gathered samples
    out_.steps_done = step_;
    return std::move(out_);
  }

private:
  bool distributed() const { return sim_.slabs().active(); }
  static std::array<double, D> box_of(const ParticleParameters& p) {
    std::array<double, D> b;
    for (int d = 0; d < D; ++d) b[d] = p.box[d];
    return b;
  }
  static std::array<bool, D> periodic_of(const ParticleParameters& p) {
    std::array<bool, D> b;
    for (int d = 0; d < D; ++d) b[d] = !p.walls[d].present;
    return b;
  }
  // The particles the diagnostics read: the simulation's, or on several ranks the gathered
  // copy on rank 0 (the one-process state, bit for bit, and the one-process grid's cells).
  const State<D>& state() const { return distributed() ? view_.state : sim_.state(); }
  const CellGrid<D>& grid() const { return distributed() ? view_grid_ : sim_.grid(); }
  const std::vector<double>& potentials() const {
    return distributed() ? view_.carried.potential : sim_.carried().potential;
  }
  // Collective on several ranks: the gathered copy up to date on rank 0.
  void refresh_view() {
    sim_.gather(view_);
    if (!sim_.slabs().root()) return;
    view_.state.box = sim_.state().box;
    const bool listed = !view_.x_listed[0].empty();
    view_grid_.sort(view_.state, view_.carried, listed ? &view_.x_listed : nullptr, true);
  }
  double initial_energy() {
    if (distributed()) refresh_view();
    return kinetic_energy_of(state(), state().size(), model_.mass) +
           sum_of(state().u, state().size()) + sum_of(potentials(), state().size());
  }

  RunFacts facts() const {
    RunFacts m;
    m.particles = n_;
    m.initial_energy = e0_;
    m.has_energy = M::has_energy;
    m.conservative = M::Conservative::active;
    m.rc = model_.rc;
    // A no-slip wall's friction on a particle's tangential velocity, gamma w_D(h), as the wall
    // sweep applies it: the run's friction law against a wall particle at the wall's
    // temperature (adiabatic: the particle's own), with the wall's weight.
    auto friction = model_.friction;
    friction.w = Weight(p_.wall_range, p_.dissipation.exponent);
    m.wall_friction = [friction, walls = p_.walls](int wall, double T, double h) {
      const WallPair& pair = walls[wall / 2];
      if (!pair.no_slip || !(T > 0)) return 0.0;
      double w, sqrt_w;
      friction.w.eval(h, w, sqrt_w);
      const double Tw = pair.thermal[wall % 2] ? pair.temperature[wall % 2] : T;
      return friction.ito_gamma(T, Tw) * w; // 000:(2.37), 003
    };
    return m;
  }
  double elapsed() const { return std::chrono::duration<double>(clock::now() - t0_).count(); }

  void progress_line(const char* start, const char* label, const char* end) const {
    const double secs = elapsed();
    const double rate = step_ / std::max(secs, 1e-9); // includes earlier parts of a restart
    std::fprintf(stderr,
                 "%s%sstep %ld/%ld  t = %.2f  %.0f steps/s  ETA %.0f s  T = %.4f  dE/E = %.1e%s",
                 start, label, step_, total_steps_, step_ * p_.dt, rate,
                 (total_steps_ - step_) / rate, last_t_kinetic_, drift_max_, end);
  }

  void sample() {
    if (distributed()) {
      refresh_view();
      if (!sim_.slabs().root()) return;
    }
    wall_energy_in_ = sim_.wall_energy_in(), wall_momentum_in_ = sim_.wall_momentum_in();
    const double k = kinetic_energy_of(state(), n_, model_.mass), u = sum_of(state().u, n_),
                 pot = sum_of(potentials(), n_);
    const double e = k + u + pot;
    double inflow = 0; // energy in through thermal walls: E(t) - E(0) - inflow is the error
    for (const double q : wall_energy_in_) inflow += q;
    drift_max_ = std::max(drift_max_, std::fabs(e - e0_ - inflow) / std::fabs(e0_));
    const double t_kin = 2 * k / (D * (n_ - 1.0)); // total momentum is conserved: d(N-1) dof
    last_t_kinetic_ = t_kin;
    const bool sampled = step_ > p_.equilibration_steps;
    const double virial = pair_pass(sampled);
    const double pressure = (2 * k + virial) / (D * volume_); // virial theorem, 000:(3.9)
    const Sample<D> s{step_,
                      step_ * p_.dt,
                      sampled,
                      state(),
                      grid(),
                      potentials(),
                      k,
                      u,
                      pot,
                      e,
                      t_kin,
                      pressure,
                      conduction_,
                      pair_counts_,
                      wall_momentum_in_,
                      wall_energy_in_,
                      sim_.wall_crossings(),
                      sim_.wall_heat_moves(),
                      elapsed()};
    for (const auto& d : diagnostics_) d->sample(s);
  }

  // The one serial pass over the pairs at a sample, whatever the diagnostics: the virial
  // (returned) and, on sampled steps, what they asked for (PairNeeds): this sample's pairs per
  // g(r) bin, each particle's share of the conductive flux.
  double pair_pass(bool sampled) {
    const auto& s = state();
    const bool distances = sampled && needs_.distances;
    const bool conduction = sampled && needs_.conduction;
    if (distances) std::fill(pair_counts_.begin(), pair_counts_.end(), 0.0);
    if constexpr (M::Heat::active)
      if (conduction)
        for (auto& c : conduction_) std::fill(c.begin(), c.end(), 0.0);
    double virial = 0;
    grid().for_each_pair_serial(
        s, model_.rc, [&](std::size_t i, std::size_t j, const double* dx, double r2) {
          const double r = std::sqrt(r2);
          double th_i = 1, th_j = 1;
          if constexpr (M::has_energy) th_i = s.u[i] / model_.cv, th_j = s.u[j] / model_.cv;
          if constexpr (M::Conservative::active) {
            if (r < model_.conservative.rc) {
              double fc, phi;
              model_.conservative.eval(r, th_i, th_j, fc, phi);
              virial += r * fc; // r_ij . F^C_ij
            }
          }
          if (distances) {
            const int b = static_cast<int>(r / model_.rc * pair_counts_.size());
            if (b < static_cast<int>(pair_counts_.size())) pair_counts_[b] += 1;
          }
          if constexpr (M::Heat::active) {
            if (conduction && r < model_.heat.w.rc) { // the mean heat rate into i: from j to i
              double rate, amplitude;
              heat_terms(model_.heat, r, th_i, th_j, rate, amplitude);
              for (int d = 0; d < D; ++d) {
                conduction_[d][i] += 0.5 * rate * dx[d]; // Irving-Kirkwood, half to each end
                conduction_[d][j] += 0.5 * rate * dx[d];
              }
            }
          }
        });
    return virial;
  }

  void finish() {
    const double wall = elapsed();
    io::Json& j = out_.summary;
    j = io::Json::object();
    j["N"] = static_cast<long>(n_);
    j["dim"] = D;
    j["steps"] = p_.steps;
    j["equilibration_steps"] = p_.equilibration_steps;
    j["dt"] = p_.dt;
    j["integrator"] = to_string(p_.integrator);
    j["energy_offset"] = p_.energy_offset;
    j["wall_seconds"] = wall;
    j["particle_steps_per_second"] = n_ * static_cast<double>(total_steps_) / wall;
    // |E(t) - E(0) - energy in through walls| / E(0): the integrator's energy error
    j["energy_relative_drift_max"] = drift_max_;
    j["samples"] = sampled_count(p_);
    j["blocks"] = p_.blocks;
    j["stability_hint"] = stability_hint(p_);
    for (const auto& d : diagnostics_) d->finish(out_);
  }

  M model_;
  ParticleParameters p_;
  Simulation<M> sim_;
  GatheredParticles<D> view_; // several ranks: the particles gathered on rank 0 at a sample
  CellGrid<D> view_grid_;     // and the one-process grid's cells of them
  std::array<double, 6> wall_energy_in_{}, wall_momentum_in_{}; // at the sample
  std::size_t n_;
  long step_ = 0, total_steps_;
  double e0_, volume_ = 1, drift_max_ = 0, last_t_kinetic_ = 0, wall_before_ = 0;
  DiagnosticList<D> diagnostics_;
  PairNeeds needs_;
  // What the pair pass hands the diagnostics: per g(r) bin; per particle, at the current sample.
  std::vector<double> pair_counts_;
  std::array<std::vector<double>, D> conduction_;
  clock::time_point t0_;
  RunOutput out_;
};

template <class M>
RunOutput drive(const M& model, const ParticleParameters& p, const RunControl& control) {
  return ParticleRun<M>(model, p).run(control);
}

// ---- resolving the case into a compiled combination (the only place that branches on physics)
// The nine combinations of friction and heat law here are the ones simulation.hpp lists for the
// other units (TWINFLOW_EACH_SIMULATION); a model missing there is only compiled twice.

template <int D, class C, class F, class V>
auto with_heat(const ParticleParameters& p, const C& c, const F& f, V&& visit) {
  const Weight w(p.heat_weight.cutoff, p.heat_weight.exponent);
  auto model = [&](const auto& h) {
    return visit(
        Model<D, C, F, std::decay_t<decltype(h)>>{c, f, h, p.mass, p.cv, p.largest_cutoff()});
  };
  if constexpr (!F::isothermal) {
    if (p.heat == HeatLaw::Inverse && p.heat_coefficient == HeatCoefficient::Constant)
      return model(InverseConstantHeat{p.kappa0, w});
    if (p.heat == HeatLaw::Inverse) return model(InverseSeed002Heat{p.kappa0, p.cv, w});
    if (p.heat == HeatLaw::Linear)
      return model(LinearHeat{p.cv * p.kappa0, p.cv, p.linear_noise_factor, w});
  }
  return model(NoHeat{});
}

template <int D, class C, class V>
auto with_friction(const ParticleParameters& p, const C& c, V&& visit) {
  const Weight w(p.dissipation.cutoff, p.dissipation.exponent);
  if (p.energy == EnergyModel::Isothermal)
    return with_heat<D>(
        p, c, IsothermalFriction{p.gamma, std::sqrt(2 * p.temperature * p.gamma), w}, visit);
  if (p.friction == Friction::ConstantGamma)
    return with_heat<D>(p, c, ConstantGamma{p.gamma, p.cv, w}, visit);
  return with_heat<D>(p, c, ConstantSigma{p.sigma, w}, visit);
}

} // namespace

namespace detail {

template <int D, class C>
RunOutput run_family(const ParticleParameters& p, const C& conservative,
                     const RunControl& control) {
  return with_friction<D>(p, conservative,
                          [&](const auto& model) { return drive(model, p, control); });
}

template <int D, class C>
BenchResult bench_family(const ParticleParameters& p, const C& conservative, long steps) {
  return with_friction<D>(p, conservative, [&](const auto& model) {
    using M = std::decay_t<decltype(model)>;
    Simulation<M> sim(model, p);
    sim.step(); // warm caches and thread pool
    const long builds = sim.pair_list_builds();
    const Slabs& slabs = sim.slabs();
    if (slabs.active()) MPI_Barrier(slabs.comm);
    const auto t0 = std::chrono::steady_clock::now();
    for (long s = 0; s < steps; ++s) sim.step();
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::size_t owned = std::max<std::size_t>(sim.owned(), 1);
    double ghosts = static_cast<double>(sim.state().size() - sim.owned()) / owned;
    if (slabs.active()) {
      MPI_Allreduce(MPI_IN_PLACE, &secs, 1, MPI_DOUBLE, MPI_MAX, slabs.comm);
      MPI_Allreduce(MPI_IN_PLACE, &ghosts, 1, MPI_DOUBLE, MPI_MAX, slabs.comm);
    }
    BenchResult r;
    r.particles = p.particle_count();
    r.seconds = secs;
    r.ranks = slabs.ranks;
    r.ghosts_per_owned = ghosts;
    r.particle_steps_per_second = r.particles * static_cast<double>(steps) / secs;
    r.steps_per_list = static_cast<double>(steps) / std::max(1L, sim.pair_list_builds() - builds);
    // Resident per-particle arrays: state (x, v, u, id), carried (f, q, potential), the sort's
    // cell index and permutation, and the sort's temporary copy of the largest array; on a
    // slab per owned particle, its ghost copies included.
    r.bytes_per_particle =
        (1 + ghosts) * ((2 * M::D + (M::has_energy ? 1 : 0)) * 8 + 4 + (M::D + 2) * 8 + 4 + 4 + 8);
    return r;
  });
}

} // namespace detail

} // namespace twinflow::particle
