#pragma once
// The differentially heated square cavity of de Vahl Davis (1983): hot wall x = 0, cold wall
// x = 1, adiabatic y walls, gravity -y, in units where H = chi = 1 so velocities are in chi/H.

#include "continuum/parameters.hpp"

namespace twinflow::continuum::test_cases {

inline ContinuumParameters cavity(int dim, double rayleigh, unsigned coarse_cells, int refinements,
                                  bool no_slip = true) {
  ContinuumParameters p;
  p.dim = dim;
  p.model = Model::Boussinesq;
  p.box = {{1.0, 1.0, 0.25}};
  p.cells = {{coarse_cells, coarse_cells, 1}};
  p.refinements = refinements;
  p.reference_temperature = 1.0;
  p.boundary[0] = {false, {{true, true}}, {{1.5, 0.5}}, {{0, 0}}, no_slip};
  p.boundary[1] = {false, {{false, false}}, {{1, 1}}, {{0, 0}}, no_slip};
  p.boundary[2] = {true, {{false, false}}, {{1, 1}}, {{0, 0}}, no_slip}; // periodic z
  p.gravity = {{0, -1, 0}};
  set_rayleigh_prandtl(p, rayleigh, 0.71);
  p.bins = {{4, 4, 1}};
  p.write_fields = false;
  return p;
}

// The same parameters run in time to `end_time`, every step in the series.
inline ContinuumParameters in_time(ContinuumParameters p, double end_time, double time_step) {
  p.mode = Mode::Transient;
  p.end_time = end_time;
  p.time_step = time_step;
  p.series_every = 1;
  return p;
}

} // namespace twinflow::continuum::test_cases
