#include "app/case/case.hpp"

namespace twinflow::app {

void declare_continuum(Registry& r) {
  using namespace dealii::Patterns;
  r.declare("Continuum/Model", "boussinesq", Selection("boussinesq|heat-conduction"),
            "Equations of the continuum twin.");
  r.declare("Continuum/Refinement", "4", Integer(0, 12), "Global refinement level of the mesh.");
}

continuum::ContinuumParameters resolve_continuum(const Registry& r, const SceneParameters& scene) {
  continuum::ContinuumParameters c;
  c.dim = scene.dim;
  c.box = scene.box;
  c.model = r.get("Continuum/Model");
  c.refinement = static_cast<int>(r.get_integer("Continuum/Refinement"));
  return c;
}

} // namespace twinflow::app
