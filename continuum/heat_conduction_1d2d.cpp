// dim = 1 and 2 instantiations of the heat-conduction model.
#include "continuum/heat_conduction.templates.hpp"

template class twinflow::continuum::HeatConductionProblem<1>;
template class twinflow::continuum::HeatConductionProblem<2>;
