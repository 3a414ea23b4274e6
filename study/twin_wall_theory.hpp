#pragma once
// The nominal twin's thermal walls from the particle wall model alone (docs/theory.md, "The wall
// layer"): each half-space thermal wall's extrapolation length b from transport::solve_wall_layer
// at the wall's temperature and the fluid's density there, taken as the Robin (Kapitza)
// conductance kappa / b where b > 0; where the wall holds its layer at T_w (b < 0) the twin's
// wall stands |b| inside the scene's plane with T = T_w there (the layer's particles left out of
// its count). No number measured in
// a cavity or wall slab enters: the fluid's coefficients from the transport stage (bulk runs,
// heat slabs), the wall's from the case.

#include <array>
#include <string>

#include "continuum/parameters.hpp"
#include "continuum/results.hpp"
#include "study/case.hpp"
#include "transport/coefficients.hpp"

namespace twinflow::study {

// A field's value at each wall, [direction][side] (NaN: not known).
using WallValues = std::array<std::array<double, 2>, 3>;

// Sets the Kapitza conductances of the twin's walls that stand for half-space thermal walls, or
// moves a wall in over its pinned layer; returns how many it set or moved. The fluid's density at
// each wall: `at_walls` where given (the twin's own), else the ideal gas's isobar through the
// scene's mean density.
int take_wall_jumps(const CaseParameters& c, const transport::Coefficients& k,
                    continuum::ContinuumParameters& twin, const WallValues* at_walls = nullptr);

// Sets the slip lengths of the twin's no-slip walls that stand for half-space walls, diffuse
// (thermal) or bounce-back (adiabatic), from transport::solve_slip_layer at the fluid's state
// there (a thermal wall's temperature, an adiabatic wall's the scene's; the density as for the
// jumps), in place of the kinetic slip; returns how many it set. Where the layer sticks (b <=
// 0.001 rc) the wall stays no-slip.
// `temperatures`: the twin's own at each wall, else an adiabatic wall's is the scene's.
int take_wall_slips(const CaseParameters& c, continuum::ContinuumParameters& twin,
                    const WallValues* at_walls = nullptr, const WallValues* temperatures = nullptr);

// A twin's `field` at each wall plane: the mean of its first two layers of bins along the wall
// (over the twin's own domain: BinAverages::own_values), extrapolated linearly (NaN where the
// twin has no such field: density in Boussinesq).
WallValues wall_values(const continuum::BinAverages& bins, int dim, const std::string& field);
inline WallValues wall_densities(const continuum::BinAverages& bins, int dim) {
  return wall_values(bins, dim, "n");
}

} // namespace twinflow::study
