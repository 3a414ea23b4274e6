// dim = 3 instantiation of the heat-conduction model (own unit: compile memory, docs/build.md).
#include "continuum/heat_conduction.templates.hpp"

template class twinflow::continuum::HeatConductionProblem<3>;
