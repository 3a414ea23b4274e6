#pragma once
// Walled scenes: each wall's pressure and heat flux (WallFluxes), the fluid layer along it
// (WallLayers: effective position, friction), and the Kapitza fit of a conducting pair of thermal
// walls (WallProfileFit, from the binned fields).

#include <memory>

#include "particle/diagnostics/binned_fields.hpp"
#include "particle/diagnostics/diagnostic.hpp"
#include "particle/fields.hpp"

namespace twinflow::particle {

// "x_lower", "x_upper", "y_lower", ... for wall 2 d + side.
const char* wall_name(int wall);

// Per wall, over the interval since the last sample: pressure (momentum in per time and area) and
// heat flux density in; the energy in since the start.
template <int D> class WallFluxes : public Archived<D, WallFluxes<D>> {
public:
  explicit WallFluxes(const ParticleParameters& p);
  std::string name() const override { return "wall_fluxes"; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
  template <class A> void archive(A& a) {
    a("last_momentum", last_momentum_), a("last_energy", last_energy_);
    a("last_step", last_step_), a("crossings", crossings_);
    a("pressure", pressure_), a("heat_flux", heat_flux_);
  }

private:
  ParticleParameters p_;
  std::array<double, 6> last_momentum_{}, last_energy_{}; // at the last sample
  long last_step_ = 0, crossings_ = 0;
  std::vector<std::vector<double>> pressure_ = std::vector<std::vector<double>>(6),
                                   heat_flux_ = std::vector<std::vector<double>>(6);
};

// Density and velocity in thin slices along each wall (wall_layers.csv) and, into the summary's
// "walls", each wall's effective position and, for no-slip walls, its friction.
template <int D> class WallLayers : public Archived<D, WallLayers<D>> {
public:
  WallLayers(const ParticleParameters& p, const RunFacts& m);
  std::string name() const override { return "wall_layers"; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
  template <class A> void archive(A& a) { sampler_.archive(a); }

private:
  ParticleParameters p_;
  std::function<double(int, double, double)> friction_;
  WallLayerSampler<D> sampler_;
};

// Thermal walls at different temperatures along d, fields binned along d only: a line through
// T_internal in the central 60% and the jump T_wall - T_line(wall) at each wall (Kapitza).
template <int D> class WallProfileFit : public Diagnostic<D> {
public:
  WallProfileFit(const ParticleParameters& p, int direction, const Fields<D>& fields)
      : p_(p), direction_(direction), fields_(fields) {}
  std::string name() const override { return "wall_profile_fit"; }
  void finish(RunOutput& out) override;

private:
  ParticleParameters p_;
  int direction_;
  const Fields<D>& fields_;
};
// The direction such a fit applies to, or -1.
int wall_profile_direction(const ParticleParameters& p);

} // namespace twinflow::particle
