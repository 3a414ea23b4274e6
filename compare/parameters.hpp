#pragma once
// How the twins are compared and how the calibrated twin is made (case file section Compare).

#include <string>

namespace twinflow::compare {

struct CompareParameters {
  double wall_layer = 1.0;             // thickness excluded from field errors
  std::string calibration = "kapitza"; // kapitza | wall temperatures
  bool effective_walls = false; // calibrated twin's walls at the particle walls' Gibbs depths
  bool wall_slip = true;        // calibrated twin's no-slip walls with the measured Navier slip
  std::string rayleigh_control = "gravity"; // how a sweep reaches a target Ra
};

} // namespace twinflow::compare
