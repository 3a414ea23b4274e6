#pragma once
// The transport stage's coefficients as the continuum twin takes them: one function for the twin
// (study/continuum_stage.cpp) and for `sweep --rayleigh`, which sets each point's gravity from
// the twin it will run.

#include "continuum/parameters.hpp"
#include "transport/coefficients.hpp"

namespace twinflow::study {

// Sets the twin's eta and kappa laws (a measured exponent replaces the case's law), c_p and
// alpha from `k` (transport::read_coefficients at the twin's reference temperature).
void take_coefficients(const transport::Coefficients& k, continuum::ContinuumParameters& p);

} // namespace twinflow::study
