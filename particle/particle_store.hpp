#pragma once
// The particles of a Simulation, whatever its pair terms: their arrays, cell grid and listed
// positions, their start, their distribution over MPI ranks (decomposition.hpp), the walls'
// tally, the failure report and the checkpoint's arrays. None of it depends on the model, so it
// compiles once per dimension at the baseline level (particle_store.cpp) instead of once per
// model and instruction-set level; the hot passes (the pair list's checks, sort and build) stay
// in Simulation<M>.

#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "particle/decomposition.hpp"
#include "particle/parameters.hpp"
#include "particle/system.hpp"

namespace twinflow::particle {

class SaveArchive;
class LoadArchive;

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

// How to run the case stably, where it stops unstable (theory.cpp).
std::string stability_hint(const ParticleParameters& p);

// What the particles are made of at the model's level: the largest cutoff, c_v, and whether
// they carry an internal energy.
struct ParticleKind {
  double rc = 1, cv = 1;
  bool has_energy = true;
};

// The pair list's skin: euler walks the cells every step and keeps none.
inline double list_skin(const ParticleParameters& p) {
  return p.integrator == Integrator::Euler ? 0.0 : p.neighbour_skin;
}

template <int D> class ParticleStore {
public:
  long steps_done() const { return step_; }
  // On several ranks (decomposition.hpp): this rank's slab, the ranks, the particles it owns
  // (state() holds them first, then the ghost plane's copies).
  const Slabs& slabs() const { return slabs_; }
  std::size_t owned() const { return owned_; }
  // Collective: the owned particles of every rank on rank 0 (one-process order), the walls'
  // sums brought up to date there.
  void gather(GatheredParticles<D>& out);
  const State<D>& state() const { return state_; }
  State<D>& state() { return state_; }
  const CellGrid<D>& grid() const { return grid_; }
  const Carried<D>& carried() const { return carried_; }
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

protected:
  // Places the particles (place_particles) and, on several ranks, keeps this rank's slab.
  ParticleStore(const ParticleParameters& p, const ParticleKind& kind);
  ~ParticleStore();
  ParticleStore(const ParticleStore&) = delete; // the halo hook points back here
  ParticleStore& operator=(const ParticleStore&) = delete;

  // The checkpoint's particle arrays (one file: on several ranks, gathered in one-process
  // order); loading re-sorts them, keeps this rank's, rebuilds the ghosts and the pair list.
  void save_particles(SaveArchive& a);
  void load_particles(LoadArchive& a);

  bool listed_key() const { return skin_ > 0 && p_.integrator != Integrator::Euler; }
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
  // Whether checking the far movers can keep the list (list_still_complete): few of them among
  // n, and a missing pair, closer than rc + 2 max|d| when listed, at most two cells apart.
  bool movers_checkable(double largest, std::size_t moved, std::size_t n) const {
    return !(moved > 8 + n / 256 || kind_.rc + 2 * std::sqrt(largest) >= 2 * grid_.smallest_side());
  }
  double theta(std::size_t i) const { return state_.u[i] / kind_.cv; }
  // Stops the run with particle i's state, its neighbours' theta and the stability hint.
  [[noreturn]] void fail(std::size_t i, const char* where) const;

  // ---- several ranks (decomposition.hpp)
  int owner_of(std::size_t i) const; // the rank whose slab holds particle i's sort cell
  void keep_owned();   // drops the particles of other ranks' slabs (a loaded checkpoint's)
  void migrate();      // sends particles to the ranks of their sort cells
  void build_ghosts(); // the upper rank's first plane into the ghost plane
  bool slab_list_still_complete(double largest, std::size_t moved);
  void resize_local(std::size_t n); // every per-particle array to n (carried included)
  // Every rank's emissions to every rank: a particle may have moved to another rank since it
  // reached the wall (the rebuild comes between); its owner emits it.
  void share_emissions();
  // The arrays a pair pass reads from the ghost plane (forward) and those it updates in it
  // (back); empty ones are skipped.
  void halo(std::initializer_list<std::vector<double>*> forward,
            std::initializer_list<std::vector<double>*> back);

  ParticleParameters p_;
  ParticleKind kind_;
  State<D> state_;
  Carried<D> carried_;
  CellGrid<D> grid_;
  double skin_ = 0, list_cutoff_ = 1; // the pair list holds pairs closer than rc + skin
  // Positions the list was built from (skin > 0), rounded to float.
  typename CellGrid<D>::ListedPositions x_listed_;
  long step_ = 0;
  // The walls' energy in (slots 2 d + side) and momentum in (6 + 2 d + side), the crossings.
  OrderedTally tally_;
  Slabs slabs_;
  std::size_t owned_ = 0; // particles of this rank: state_ [0, owned_)
  struct Emission {       // a particle that reached a diffuse wall this step
    std::uint32_t id;
    int wall;                  // 2 d + side
    std::uint32_t index = ~0u; // its storage index then (~0u: not known, another rank's)
    bool operator<(const Emission& o) const { return id < o.id || (id == o.id && wall < o.wall); }
  };
  std::vector<Emission> emissions_;

private:
  // The initial state of this rank's particles: positions uniform, velocities Maxwell at T with
  // no net momentum, the internal energies at equilibrium or c_v T.
  void place_particles();
  template <class A>
  void archive_arrays(A& a, State<D>& s, Carried<D>& c, typename CellGrid<D>::ListedPositions& l);
  std::array<double, 6> wall_sums(int first) const {
    std::array<double, 6> s;
    for (int k = 0; k < 6; ++k) s[k] = tally_.sums()[first + k];
    return s;
  }
  struct Halo : CellGrid<D>::PhaseHook {
    ParticleStore* store = nullptr;
    std::vector<std::vector<double>*> forward_fields, back_fields;
    void forward() override;
    void back() override;
  };
  std::size_t first_plane_count_ = 0; // of the owned, in the first plane (the lower's ghosts)
  std::size_t ghost_count_ = 0;       // the ghost plane: state_ [owned_, owned_ + ghost_count_)
  Halo halo_;
};

#ifndef TWINFLOW_PARTICLE_STORE_UNIT
extern template class ParticleStore<2>;
extern template class ParticleStore<3>;
#endif

} // namespace twinflow::particle
