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

#include "particle/decomposition.hpp"
#include "particle/pair_terms.hpp"
#include "particle/parameters.hpp"
#include "particle/system.hpp"
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

// The particles of a run on several ranks gathered on rank 0 in the one-process storage order,
// with the cell index of the one-process grid: what diagnostics and checkpoints read.
template <int D> struct GatheredParticles {
  State<D> state;
  Carried<D> carried;
  typename CellGrid<D>::ListedPositions x_listed; // empty where the run keeps no list
};

// A non-positive or non-finite internal energy, or a NaN: the run stops with this message.
struct InstabilityError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class M> class Simulation {
public:
  static constexpr int D = M::D;

  Simulation(const M& model, const ParticleParameters& p);

  void step();
  long steps_done() const { return step_; }

  double kinetic_energy() const;
  // On several ranks (decomposition.hpp): this rank's slab, the ranks, the particles it owns
  // (state() holds them first, then the ghost plane's copies).
  const Slabs& slabs() const { return slabs_; }
  std::size_t owned() const { return owned_; }
  // Collective: the owned particles of every rank on rank 0 (one-process order), the walls'
  // sums brought up to date there.
  void gather(GatheredParticles<D>& out);
  double internal_energy() const;
  double potential_energy() const;
  double total_energy() const { return kinetic_energy() + internal_energy() + potential_energy(); }

  const State<D>& state() const { return state_; }
  State<D>& state() { return state_; }
  const CellGrid<D>& grid() const { return grid_; }
  const Carried<D>& carried() const { return carried_; }
  const M& model() const { return model_; }
  // Energy that entered the fluid through each wall (index 2 d + side) since the start (on
  // several ranks: on rank 0, as of the last gather).
  std::array<double, 6> wall_energy_in() const { return wall_sums(0); }
  long wall_crossings() const { return tally_.counted(); } // particles reflected into the box
  // Per wall: the Metropolis moves of its heat exchange proposed (0-5) and accepted (6-11).
  std::array<double, 12> wall_heat_moves() const {
    std::array<double, 12> m;
    for (int k = 0; k < 12; ++k) m[k] = tally_.sums()[12 + k];
    return m;
  }
  // Momentum along each wall's inward normal given to the fluid since the start (repulsion,
  // friction and noise, reflections): its rate per area is the pressure on the wall.
  std::array<double, 6> wall_momentum_in() const { return wall_sums(6); }
  // Re-sorts and lists the pairs anew after the state was changed from outside (tests permute
  // it).
  void resort() { update_neighbours(true); }
  long pair_list_builds() const { return list_builds_; }
  long pair_list_kept_past_bound() const { return list_kept_past_bound_; }
  void prepare(); // forces at the current state (call after changing the state)

  // Everything a restart needs, listed once (particle/archive.hpp). Scratch arrays are not in
  // it: each step rebuilds them before use.
  template <class A> void archive(A& a) {
    if constexpr (!A::loading) {
      if (slabs_.active()) { // one file: the particles gathered in one-process order
        GatheredParticles<D> g;
        gather(g);
        archive_arrays(a, g.state, g.carried, g.x_listed);
        return;
      }
    }
    archive_arrays(a, state_, carried_, x_listed_);
    if constexpr (A::loading) {
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
  }

private:
  template <class A>
  void archive_arrays(A& a, State<D>& s, Carried<D>& c, typename CellGrid<D>::ListedPositions& l) {
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
  std::array<double, 6> wall_sums(int first) const {
    std::array<double, 6> s;
    for (int k = 0; k < 6; ++k) s[k] = tally_.sums()[first + k];
    return s;
  }
  // ---- several ranks (decomposition.hpp)
  bool listed_key() const { return skin_ > 0 && p_.integrator != Integrator::Euler; }
  int owner_of(std::size_t i) const; // the rank whose slab holds particle i's sort cell
  void keep_owned();   // drops the particles of other ranks' slabs (a loaded checkpoint's)
  void migrate();      // sends particles to the ranks of their sort cells
  void build_ghosts(); // the upper rank's first plane into the ghost plane
  void rebuild_slab(); // update_neighbours' rebuild on a slab
  bool slab_list_still_complete(double largest, std::size_t moved);
  void resize_local(std::size_t n); // every per-particle array to n (carried included)
  // Every rank's emissions to every rank: a particle may have moved to another rank since it
  // reached the wall (the rebuild comes between); its owner emits it.
  void share_emissions();
  // The arrays a pair pass reads from the ghost plane (forward) and those it updates in it
  // (back); empty ones are skipped.
  void halo(std::initializer_list<std::vector<double>*> forward,
            std::initializer_list<std::vector<double>*> back);
  struct Halo : CellGrid<D>::PhaseHook {
    Simulation* sim = nullptr;
    std::vector<std::vector<double>*> forward_fields, back_fields;
    void forward() override;
    void back() override;
  };

  struct PairForce {
    double conservative = 0, dissipative_random = 0, phi = 0, heat = 0;
  };
  // Everything one pair contributes at the current state (v: velocities to use).
  PairForce pair_force(const PairNoise& noise, std::size_t i, std::size_t j, const double* dx,
                       double r2, const std::array<std::vector<double>, D>& v) const;

  // The initial state of this rank's particles: positions uniform, velocities Maxwell at T with
  // no net momentum, the internal energies at equilibrium or c_v T.
  void place_particles();
  void euler_impulses(const PairNoise& noise);
  void euler_energy_increments(const PairNoise& noise);
  bool update_neighbours(bool force);
  bool list_still_complete(double largest, std::size_t moved);
  // |x_i - x_listed_i|^2, minimum image: how far particle i moved since the list was built.
  double displacement2(std::size_t i) const {
    double r2 = 0;
    for (int d = 0; d < D; ++d) {
      const double r = grid_.minimum_image(state_.x[d][i] - x_listed_[d][i], d);
      r2 += r * r;
    }
    return r2;
  }
  void list_positions(); // x_listed_ = x rounded to float
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
  double theta(std::size_t i) const { return state_.u[i] / model_.cv; }
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
  [[noreturn]] void fail(std::size_t i, const char* where) const;

  M model_;
  ParticleParameters p_;
  State<D> state_;
  Carried<D> carried_;
  CellGrid<D> grid_;
  double skin_ = 0, list_cutoff_ = 1; // the pair list holds pairs closer than rc + skin
  // Positions the list was built from (skin > 0), rounded to float.
  typename CellGrid<D>::ListedPositions x_listed_;
  long list_builds_ = 0;
  long list_kept_past_bound_ = 0; // steps the list was kept after a particle moved skin/2
  std::vector<std::vector<std::uint32_t>> moved_far_; // per thread: those particles
  long step_ = 0;
  double dt_, sqrt_dt_, inv_sqrt_dt_;
  std::array<std::vector<double>, D> v_old_;
  std::vector<double> pooled_; // shardlow's K + P changes with a pair force (step_shardlow)
  std::vector<std::size_t> slab_members_;
  bool has_external_ = false; // walls or gravity: a per-particle pass, only if present
  typename M::Friction wall_friction_;
  typename M::Heat wall_heat_;
  HalfSpaceWall half_space_; // the integrated wall weights, where a wall is of that model
  // The walls' energy in (slots 2 d + side) and momentum in (6 + 2 d + side), the crossings.
  OrderedTally tally_;
  std::vector<std::vector<std::pair<int, double>>>
      tally_logs_; // per thread (for_particles_tallied)
  Slabs slabs_;
  std::size_t owned_ = 0;             // particles of this rank: state_ [0, owned_)
  std::size_t first_plane_count_ = 0; // of them, in its first plane (the lower rank's ghosts)
  std::size_t ghost_count_ = 0;       // the ghost plane: state_ [owned_, owned_ + ghost_count_)
  Halo halo_;
  struct Emission { // a particle that reached a diffuse wall this step
    std::uint32_t id;
    int wall;                  // 2 d + side
    std::uint32_t index = ~0u; // its storage index then (~0u: not known, another rank's)
    bool operator<(const Emission& o) const { return id < o.id || (id == o.id && wall < o.wall); }
  };
  std::vector<Emission> emissions_;
};

std::string stability_hint(const ParticleParameters& p);

} // namespace twinflow::particle

#include "particle/neighbour_list.tpp"
#include "particle/pair_kernels.tpp"
#include "particle/simulation.tpp"
#include "particle/slabs.tpp"
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
