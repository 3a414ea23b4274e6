#pragma once
// Continuum/Model = auto: which continuum twin a scene takes, and why (a physics decision made
// in one place; the case file's Continuum section and the compare stage's re-choice call it).

#include <string>

#include "continuum/parameters.hpp"
#include "scene/scene.hpp"

namespace twinflow::study {

// Compressible where the scene's stratification g H / c^2 exceeds its threshold (the low-Mach
// and Boussinesq twins have no hydrostatic density gradient), else where the thermal walls'
// epsilon exceeds its threshold low-Mach, or compressible for a fluid with a conservative force
// (the low-Mach twin takes the ideal gas's p only), else Boussinesq.
continuum::Model automatic_model(const scene::SceneParameters& scene, double particle_mass,
                                 bool conservative_force, double low_mach_threshold,
                                 double compressible_threshold);

// The numbers automatic_model compared for `chosen`, in its order, as one clause.
std::string automatic_model_reason(const scene::SceneParameters& scene, double particle_mass,
                                   continuum::Model chosen, double low_mach_threshold,
                                   double compressible_threshold);

} // namespace twinflow::study
