#pragma once
// One DPDE (or isothermal DPD) particle system and its three integrators. The model is a
// compile-time combination of pair terms (pair_terms.hpp); the integrator is chosen per run.

#include <omp.h>

#include <cmath>
#include <exception>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "particle/pair_terms.hpp"
#include "particle/particle_store.hpp"
#include "particle/wall_weights.hpp"

namespace twinflow::particle {

template <int D_, class Conservative_, class Friction_, class Heat_> struct Model {
  static constexpr int D = D_;
  using Conservative = Conservative_;
  using Friction = Friction_;
  using Heat = Heat_;
  static constexpr bool has_energy = !Friction::isothermal;
  Conservative conservative;
  Friction friction;
  Heat heat;
  double mass = 1, cv = 1, rc = 1; // rc: the largest active cutoff
};

template <int D> struct PairScratch;

// The energies of particles [0, n) of a state, summed in storage order (a run on several ranks
// sums the gathered particles this way: the one-process sums).
template <int D> double kinetic_energy_of(const State<D>& s, std::size_t n, double mass) {
  double k = 0;
  for (int d = 0; d < D; ++d)
    for (std::size_t i = 0; i < n; ++i) k += s.v[d][i] * s.v[d][i];
  return 0.5 * mass * k;
}
inline double sum_of(const std::vector<double>& a, std::size_t n) {
  double s = 0;
  for (std::size_t i = 0; i < n && i < a.size(); ++i) s += a[i];
  return s;
}

template <class M> class Simulation : public ParticleStore<M::D> {
  using Store = ParticleStore<M::D>;
  using Store::build_ghosts, Store::displacement2, Store::fail, Store::halo, Store::list_positions,
      Store::listed_key, Store::migrate, Store::movers_checkable, Store::resize_local,
      Store::share_emissions, Store::slab_list_still_complete, Store::theta;
  using Store::p_, Store::state_, Store::carried_, Store::grid_, Store::skin_, Store::list_cutoff_,
      Store::x_listed_, Store::step_, Store::tally_, Store::slabs_, Store::owned_,
      Store::emissions_;
  using typename Store::Emission;

public:
  static constexpr int D = M::D;

  Simulation(const M& model, const ParticleParameters& p);

  void step();

  double kinetic_energy() const;
  double internal_energy() const;
  double potential_energy() const;
  double total_energy() const { return kinetic_energy() + internal_energy() + potential_energy(); }

  const M& model() const { return model_; }
  // Re-sorts and lists the pairs anew after the state was changed from outside (tests permute
  // it).
  void resort() { update_neighbours(true); }
  long pair_list_builds() const { return list_builds_; }
  long pair_list_kept_past_bound() const { return list_kept_past_bound_; }
  void prepare(); // forces at the current state (call after changing the state)

  // Everything a restart needs, listed once (particle/archive.hpp). Scratch arrays are not in
  // it: each step rebuilds them before use.
  template <class A> void archive(A& a) {
    if constexpr (A::loading)
      this->load_particles(a);
    else
      this->save_particles(a);
  }

private:
  void rebuild_slab(); // update_neighbours' rebuild on a slab (several ranks)

  struct PairForce {
    double conservative = 0, dissipative_random = 0, phi = 0, heat = 0;
  };
  // Everything one pair contributes at the current state (v: velocities to use).
  PairForce pair_force(const PairNoise& noise, std::size_t i, std::size_t j, const double* dx,
                       double r2, const std::array<std::vector<double>, D>& v) const;

  void euler_impulses(const PairNoise& noise);
  void euler_energy_increments(const PairNoise& noise);
  bool update_neighbours(bool force);
  bool list_still_complete(double largest, std::size_t moved);
  void step_ec_verlet();
  void step_euler();
  void step_shardlow();
  void shardlow_first_kick(bool kicks, bool offset, bool pooled); // walls, kick, drift
  void shardlow_second_kick(bool offset, bool pooled);            // external forces, kick
  // ec-verlet / VV force evaluation
  // external: with external_forces (shardlow adds them particle by particle in its second kick)
  void conservative_pass(bool with_velocity_terms, bool zeroed = false, bool external = true);
  void potential_pass();
  // Pair passes over the grid's pair list (pair_kernels.tpp).
  std::size_t pair_geometry(const std::uint32_t*& i, const std::uint32_t*& j, std::size_t n,
                            PairScratch<D>& s) const;
  std::size_t pairs_within_cutoff(const std::uint32_t* i, const std::uint32_t* j, std::size_t n,
                                  PairScratch<D>& s) const;
  void pair_gather(const std::uint32_t* i, const std::uint32_t* j, std::size_t n, PairScratch<D>& s,
                   bool velocities) const;
  void pair_noise_and_weights(const PairNoise& noise, const std::uint32_t* i,
                              const std::uint32_t* j, std::size_t n, PairScratch<D>& s) const;
  void conservative_blocks();
  void force_blocks(const PairNoise& noise);
  void shardlow_sweep(const PairNoise& noise);
  PairNoise pair_noise() const { // this step's pair noises, of the run's law
    return PairNoise(p_.seed, static_cast<std::uint64_t>(step_), PairNoise::Pair, p_.uniform_noise);
  }
  void apply_heat_slabs();
  // Walls and external fields (walls.tpp).
  struct WallCoupling { // a wall's weights at distance h: friction (normal, tangent), heat
    double normal = 0, sqrt_normal = 0, tangent = 0, sqrt_tangent = 0, heat = 0, sqrt_heat = 0;
    bool half_space = false;
  };
  double wall_range(int d, int side) const;
  double wall_temperature(int d, int side, double th_i) const;
  WallCoupling wall_coupling(int d, int side, double h) const;
  void wall_heat(const WallCoupling& c, double th_i, double th_wall, double& rate,
                 double& amplitude) const;
  double wall_gamma(const WallCoupling& c, double th_i, double th_wall) const;
  // Wall repulsion, gravity, Poiseuille force into carried f (times scale) and potential.
  void external_forces(double scale = 1, bool potentials = true);
  void external_force(std::size_t i, double scale, bool potentials, TallyTerms& tally);
  // body(i, TallyTerms&) for each owned particle, over the threads (the particle's own state
  // only; the tally's sums as on one thread).
  template <class Body> void for_particles_tallied(Body body);
  void wall_sweep_particle(const PairNoise& noise, std::size_t i, TallyTerms& tally); // shardlow
  void wall_sweep_one(const PairNoise& noise, std::size_t i, int d, int side, TallyTerms& tally);
  double exchange_wall_heat(const PairNoise& noise, std::size_t i, int index, const WallCoupling& c,
                            double th_wall, double g, TallyTerms& tally);
  void wall_heat_pass(); // ec-verlet, euler
  void wall_forces(const std::array<std::vector<double>, D>& v,
                   std::array<std::vector<double>, D>& f, double scale); // ec-verlet, euler
  bool wall_force(const PairNoise& noise, const std::array<std::vector<double>, D>& v,
                  std::size_t i, int d, int side, double* force) const;
  void wall_work_split(std::vector<double>& du); // euler without the energy offset
  void reflect_at_walls();
  bool diffuse_wall(int d, int side) const;
  void emit_from_walls();
  void emit_from_wall(const PairNoise& noise, std::size_t i, int d, int side);
  double gamma_variate(const PairNoise& noise, std::uint32_t id, std::uint32_t counter,
                       double a) const;
  // One S1 update of velocity component `v` against a wall (infinite mass, at rest).
  double wall_s1(double& v, double w, double sqrt_w, double gamma, double th_i, double th_wall,
                 double xi) const;
  void book_offset(std::size_t i, double change, bool pooled);
  void add_pooled(ExactSum& pool) const;
  void share_pool(ExactSum& pool);
  bool bad_particle(std::size_t i) const;
  void check_energies(const char* where) const;

  M model_;
  long list_builds_ = 0;
  long list_kept_past_bound_ = 0; // steps the list was kept after a particle moved skin/2
  std::vector<std::vector<std::uint32_t>> moved_far_; // per thread: those particles
  double dt_, sqrt_dt_, inv_sqrt_dt_;
  std::array<std::vector<double>, D> v_old_;
  std::vector<double> pooled_; // shardlow's K + P changes with a pair force (step_shardlow)
  std::vector<std::size_t> slab_members_;
  bool has_external_ = false; // walls or gravity: a per-particle pass, only if present
  typename M::Friction wall_friction_;
  typename M::Heat wall_heat_;
  HalfSpaceWall half_space_; // the integrated wall weights, where a wall is of that model
  std::vector<std::vector<std::pair<int, double>>>
      tally_logs_; // per thread (for_particles_tallied)
};

} // namespace twinflow::particle

#include "particle/neighbour_list.tpp"
#include "particle/pair_kernels.tpp"
#include "particle/simulation.tpp"
#include "particle/walls.tpp"

// The simulations of the compiled models (run_models.tpp's nine per dimension and conservative
// force), instantiated once by the library's family units; other units (the tests) link to
// those instead of compiling them again.
#define TWINFLOW_EACH_SIMULATION(PREFIX, D, C)                                                     \
  PREFIX template class Simulation<Model<D, C, IsothermalFriction, NoHeat>>;                       \
  PREFIX template class Simulation<Model<D, C, ConstantGamma, NoHeat>>;                            \
  PREFIX template class Simulation<Model<D, C, ConstantGamma, InverseConstantHeat>>;               \
  PREFIX template class Simulation<Model<D, C, ConstantGamma, InverseSeed002Heat>>;                \
  PREFIX template class Simulation<Model<D, C, ConstantGamma, LinearHeat>>;                        \
  PREFIX template class Simulation<Model<D, C, ConstantSigma, NoHeat>>;                            \
  PREFIX template class Simulation<Model<D, C, ConstantSigma, InverseConstantHeat>>;               \
  PREFIX template class Simulation<Model<D, C, ConstantSigma, InverseSeed002Heat>>;                \
  PREFIX template class Simulation<Model<D, C, ConstantSigma, LinearHeat>>;
#ifndef TWINFLOW_FAMILY_UNIT
namespace twinflow::particle {
TWINFLOW_EACH_SIMULATION(extern, 2, NoConservative)
TWINFLOW_EACH_SIMULATION(extern, 2, ConstantRepulsion)
TWINFLOW_EACH_SIMULATION(extern, 2, TemperatureRepulsion)
TWINFLOW_EACH_SIMULATION(extern, 3, NoConservative)
TWINFLOW_EACH_SIMULATION(extern, 3, ConstantRepulsion)
TWINFLOW_EACH_SIMULATION(extern, 3, TemperatureRepulsion)
} // namespace twinflow::particle
#endif
