// dim = 3 instantiation (one translation unit per dimension: ~1.5 GB to compile, build-notes).
#include "continuum/boussinesq.templates.hpp"

template class twinflow::continuum::BoussinesqProblem<3>;
