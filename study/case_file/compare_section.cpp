#include "study/case_file/case_file.hpp"

namespace twinflow::study {

// Section Compare: the comparison's wall layer and calibrated twin, and the stability map's
// bounds (compare/parameters.hpp, study::StabilityBounds).
void declare_compare(Registry& r) {
  using namespace dealii::Patterns;
  r.declare("Compare/Calibration", "kapitza", Selection("kapitza|wall temperatures"),
            "The calibrated twin's thermal walls: kapitza: the nominal wall temperatures with a "
            "Kapitza (Robin) conductance h_K = q / jump per wall, from the particle wall's heat "
            "flux q and the fluid's temperature jump there; wall temperatures: Dirichlet at the "
            "fluid's temperature extrapolated to each wall.");
  r.declare("Compare/Effective walls", "false", Bool(),
            "The calibrated twin's walls at the particle walls' effective positions: each wall "
            "moved in by the depth of its depleted layer (the Gibbs dividing surface of the "
            "measured density profile, particle/wall_layers.csv), its fluid temperature (and so "
            "its jump) extrapolated to that plane, its heat flow compared over the scene's wall "
            "area. false: the twin fills the scene's box.");
  r.declare("Compare/Wall slip", "true", Bool(),
            "The calibrated twin's no-slip walls with Navier slip (Boussinesq twin): b = eta / "
            "zeta - (h_f - wall), zeta the particle wall's measured friction per area (integral "
            "of n(h) gamma(T(h)) w_D(h) over its layer, particle/summary.json), h_f the mean "
            "depth where it acts, wall the twin's wall position (the particle wall's friction lets "
            "the fluid slip by ~1 rc on the default cavity's hot side). false: no slip.");
  r.declare("Compare/Wall layer", "1", Double(0),
            "Thickness (length units) of the layer next to each wall left out of field errors.");
  r.declare("Compare/Rayleigh control", "gravity", Selection("gravity"),
            "How `twinflow sweep --rayleigh` reaches a target Ra = g alpha dT H^3 / (nu chi): "
            "gravity scales |g| along the case's gravity direction at fixed coefficients. (Scaling "
            "the box size H instead is not implemented.)");
  r.declare("Compare/Stability/Energy drift bound", "1e-3", Double(0),
            "twinflow stability: a run whose max |E(t) - E(0) - wall heat| / E(0) exceeds this "
            "is classified energy_drift.");
  r.declare("Compare/Stability/Temperature tolerance", "0.05", Double(0),
            "twinflow stability: a run whose T_kinetic or T_internal differs from the target "
            "(Scene/Temperature; with thermal walls the mean of their temperatures) by more than "
            "this fraction is classified temperature_off.");
  r.declare("Compare/Stability/Fluctuation bound", "1", Double(0),
            "twinflow stability: predicted_stable needs 000:(3.34)'s sqrt(B C dt*) (4 pi/3) "
            "r*^3 rho* below this. Seed 000 only asks for it to be << 1 (else the heat noise "
            "drives internal energies negative) and gives no number; 1 is where that order-of-"
            "magnitude estimate has certainly failed.");
}

void resolve_compare(const Registry& r, CaseParameters& c) {
  c.compare.wall_layer = r.get_double("Compare/Wall layer");
  c.compare.calibration = r.get("Compare/Calibration");
  c.compare.effective_walls = r.get_bool("Compare/Effective walls");
  c.compare.wall_slip = r.get_bool("Compare/Wall slip");
  c.compare.rayleigh_control = r.get("Compare/Rayleigh control");
  c.stability.energy_drift = r.get_double("Compare/Stability/Energy drift bound");
  c.stability.temperature_tolerance = r.get_double("Compare/Stability/Temperature tolerance");
  c.stability.fluctuation_number = r.get_double("Compare/Stability/Fluctuation bound");
}

} // namespace twinflow::study
