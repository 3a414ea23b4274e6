#pragma once
// The nominal twin's thermal walls from the particle wall model alone (docs/theory.md, "The wall
// layer"): each half-space thermal wall's extrapolation length b from transport::solve_wall_layer
// at the wall's temperature and the fluid's density there, taken as the Robin (Kapitza)
// conductance kappa / b where b > 0; where the wall holds its layer at T_w (b <= 0) the twin
// keeps T = T_w at the plane. No number measured in
// a cavity or wall slab enters: the fluid's coefficients from the transport stage (bulk runs,
// heat slabs), the wall's from the case.

#include <array>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"
#include "study/case.hpp"
#include "transport/coefficients.hpp"

namespace twinflow::study {

// The fluid's number density at each wall, [direction][side] (NaN: not known).
using WallDensities = std::array<std::array<double, 2>, 3>;

// Sets the Kapitza conductances of the twin's walls that stand for half-space thermal walls;
// returns how many it set. The fluid's density at each wall: `at_walls` where given (the twin's
// own), else the ideal gas's isobar through the scene's mean density.
int take_wall_jumps(const CaseParameters& c, const transport::Coefficients& k,
                    continuum::ContinuumParameters& twin, const WallDensities* at_walls = nullptr);

// A twin's density at each wall plane: the mean of its first two layers of bins along the wall,
// extrapolated linearly (NaN where the twin has no density field: Boussinesq).
WallDensities wall_densities(const continuum::BinAverages& bins, int dim);

} // namespace twinflow::study
