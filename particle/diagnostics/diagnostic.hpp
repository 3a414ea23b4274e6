#pragma once
// A particle run's diagnostics as plug-ins (the model: Mirheo's plugins, ASPECT's
// postprocessors). The run owns a list of them, made for its scene (diagnostics.hpp: a scene
// without walls has no wall plug-ins; plugins.hpp: those it chooses from). At every sample the run
// measures once what several of them use (energies, the virial pressure, the one serial pair pass)
// and hands it to each; at the end each writes its own results; a checkpoint holds each one's state
// under its name.

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "particle/archive.hpp"
#include "particle/parameters.hpp"
#include "particle/run.hpp"
#include "particle/system.hpp"

namespace twinflow::particle {

// What diagnostics know of the run beyond its parameters: facts of the compiled model (its type
// stays in the run) and of the initial state.
struct RunFacts {
  std::size_t particles = 0;
  double initial_energy = 0;
  bool has_energy = true;   // DPDE (false: isothermal DPD, no internal energies)
  bool conservative = true; // a conservative pair force
  double rc = 1;            // the largest active cutoff (g(r) spans [0, rc))
  // A no-slip wall's friction coefficient gamma w_D(h) on a particle at temperature T and
  // distance h from wall 2 d + side (the run's friction law).
  std::function<double(int wall, double T, double h)> wall_friction;
};

// One sample as the run measured it: the state and the sums every diagnostic shares.
template <int D> struct Sample {
  long step = 0;
  double time = 0;
  bool sampled = false; // past equilibration: averages take only these
  const State<D>& state;
  const CellGrid<D>& grid;              // minimum images
  const std::vector<double>& potential; // each particle's share of the potential energy
  double kinetic = 0, internal = 0, potential_energy = 0, energy = 0;
  double t_kinetic = 0; // 2 K / (D (N - 1)): total momentum is conserved
  double pressure = 0;  // from the virial of the pair pass
  // From the pair pass, on sampled steps only: each particle's share of the conductive flux
  // sum_j q_ij (x_i - x_j) / 2 (empty without a heat law), and this sample's pairs per g(r) bin.
  const std::array<std::vector<double>, D>& conduction;
  const std::vector<double>& pair_counts;
  const std::array<double, 6>& wall_momentum_in; // since the start, per wall 2 d + side
  const std::array<double, 6>& wall_energy_in;
  long wall_crossings = 0;
  std::array<double, 12> wall_heat_moves{}; // per wall: proposed (0-5), accepted (6-11)
  double elapsed_seconds = 0; // wall clock since the run began, earlier parts of a restart too
};

// What the one serial pair pass must compute for a diagnostic (the virial it always does).
struct PairNeeds {
  bool distances = false;  // Sample::pair_counts
  bool conduction = false; // Sample::conduction
};

template <int D> class Diagnostic {
public:
  // name: its section of a checkpoint, unique within a run; needs: what it takes from the pair
  // pass.
  explicit Diagnostic(std::string name, PairNeeds needs = {})
      : name_(std::move(name)), needs_(needs) {}
  virtual ~Diagnostic() = default;
  const std::string& name() const { return name_; }
  PairNeeds pair_needs() const { return needs_; }
  // At every sample, equilibration included (Sample::sampled tells them apart).
  virtual void sample(const Sample<D>&) {}
  // Its results: summary keys, a csv of RunOutput. Called once, in the list's order.
  virtual void finish(RunOutput& out) = 0;
  virtual void save(SaveArchive&) {}
  virtual void load(LoadArchive&) {}

private:
  std::string name_;
  PairNeeds needs_;
};

// A diagnostic with state lists it once, in `template <class A> void archive(A& a)`, and
// derives from Archived<D, Itself>: saving and loading then walk the same list.
template <int D, class Derived> class Archived : public Diagnostic<D> {
public:
  using Diagnostic<D>::Diagnostic;
  void save(SaveArchive& a) override { static_cast<Derived&>(*this).archive(a); }
  void load(LoadArchive& a) override { static_cast<Derived&>(*this).archive(a); }
};

// A diagnostic without state of its own that at the end fits what others measured (the binned
// fields, a slab profile): `fit` writes its results.
template <int D> class Fit : public Diagnostic<D> {
public:
  Fit(std::string name, std::function<void(RunOutput&)> fit)
      : Diagnostic<D>(std::move(name)), fit_(std::move(fit)) {}
  void finish(RunOutput& out) override { fit_(out); }

private:
  std::function<void(RunOutput&)> fit_;
};

template <int D> using DiagnosticPtr = std::unique_ptr<Diagnostic<D>>;
template <int D> using DiagnosticList = std::vector<DiagnosticPtr<D>>;

// The number of sampled (post-equilibration) samples of a run: the block statistics' length.
long sampled_count(const ParticleParameters& p);
// The box with a unit third side in 2D (the binned samplers' box).
std::array<double, 3> box3(const ParticleParameters& p);

} // namespace twinflow::particle
