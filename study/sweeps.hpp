#pragma once
// Grids of runs (study/grid.hpp drives them): `sweep` runs `twinflow run` at every point (with
// --rayleigh: |g| for each target Ra), `stability` runs `twinflow particle` at every point and
// classifies it. Exit code 0 however many points failed; 5 when interrupted.

#include "study/grid.hpp"

namespace twinflow::study {

int sweep(const GridOptions& options, const CaseReader& reader);
int stability(const GridOptions& options, const CaseReader& reader);

} // namespace twinflow::study
