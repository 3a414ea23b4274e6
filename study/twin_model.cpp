#include "study/twin_model.hpp"

#include <sstream>

namespace twinflow::study {

continuum::Model automatic_model(const scene::SceneParameters& scene, double particle_mass,
                                 bool conservative_force, double low_mach_threshold,
                                 double compressible_threshold) {
  if (scene.stratification(particle_mass) > compressible_threshold)
    return continuum::Model::Compressible;
  if (scene.thermal_wall_epsilon() > low_mach_threshold)
    return conservative_force ? continuum::Model::Compressible : continuum::Model::LowMach;
  return continuum::Model::Boussinesq;
}

std::string automatic_model_reason(const scene::SceneParameters& scene, double particle_mass,
                                   continuum::Model chosen, double low_mach_threshold,
                                   double compressible_threshold) {
  const double stratification = scene.stratification(particle_mass);
  const bool stratified = stratification > compressible_threshold;
  std::ostringstream why;
  why << "stratification g H / c^2 " << stratification << (stratified ? " > " : " <= ")
      << compressible_threshold;
  if (!stratified)
    why << ", the thermal walls' epsilon " << scene.thermal_wall_epsilon()
        << (chosen == continuum::Model::Boussinesq ? " <= " : " > ") << low_mach_threshold;
  if (!stratified && chosen == continuum::Model::Compressible)
    why << " with a conservative force, which the low-Mach twin's p = n k T leaves out";
  return why.str();
}

} // namespace twinflow::study
