#pragma once
// Plain parameters of the continuum twin, filled from the case file by app/case.

#include <array>
#include <string>

namespace twinflow::continuum {

struct ContinuumParameters {
  int dim = 2;
  std::array<double, 3> box{{1, 1, 1}};
  std::string model = "boussinesq";
  int refinement = 4;
};

} // namespace twinflow::continuum
