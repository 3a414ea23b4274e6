#include "continuum/low_mach.templates.hpp"

// One dimension per translation unit (compile memory, build-notes).
template class twinflow::continuum::LowMachProblem<3>;
