#include "app/case/case.hpp"

#include <filesystem>

namespace twinflow::app {

using dealii::Patterns::Anything;

bool SceneParameters::has_walls() const {
  for (int d = 0; d < dim; ++d)
    if (!boundary[d].periodic) return true;
  return false;
}

Case::Case() {
  registry_.declare("Case name", "", Anything(),
                    "Name of the case (used in reports); empty: the case file's name.");
  declare_scene(registry_);
  declare_particle(registry_);
  declare_transport_and_compare(registry_);
  declare_continuum(registry_);
}

CaseParameters Case::load(const std::string& filename, const std::vector<std::string>& overrides) {
  registry_.parse_file(filename);
  for (const auto& o : overrides) registry_.set_override(o);
  return resolve(std::filesystem::path(filename).stem().string());
}

CaseParameters Case::load_resolved(const io::Json& resolved, const std::string& name) {
  if (!resolved.is_object()) throw io::InputError("recorded case parameters: not an object");
  for (const auto& [path, value] : resolved.items())
    registry_.set_override(path + "=" + (value.is_string() ? value.string() : value.dump()));
  return resolve(name);
}

CaseParameters Case::resolve(const std::string& default_name) {
  CaseParameters c;
  c.name = registry_.get("Case name");
  if (c.name.empty()) c.name = default_name;
  c.scene = resolve_scene(registry_);
  c.particle = resolve_particle(registry_, c.scene);
  c.transport.source = registry_.get("Transport/Source");
  c.transport.measure_flows = registry_.get_bool("Transport/Measure kappa and eta");
  c.transport.temperature = registry_.get_double("Transport/Temperature");
  c.compare.wall_layer = registry_.get_double("Compare/Wall layer");
  c.continuum = resolve_continuum(registry_, c.scene);
  return c;
}

void declare_transport_and_compare(Registry& r) {
  using namespace dealii::Patterns;
  r.declare("Transport/Source", "estimated", Selection("estimated|measured"),
            "Which coefficients feed the continuum twin: theory estimates or measured by short "
            "particle runs.");
  r.declare("Transport/Temperature", "0", Double(0),
            "State-point temperature of the transport stage (units of T0); 0: the mean of the "
            "thermal walls, or Scene/Temperature without walls. `twinflow run` sets it to the "
            "particle fluid's measured mean temperature unless the case or --set gives one.");
  r.declare("Transport/Measure kappa and eta", "false", Bool(),
            "Also measure kappa by thermal relaxation and eta by reverse Poiseuille flow (two "
            "particle runs of several relaxation times each: minutes at seed 002's state point).");
  r.declare("Compare/Wall layer", "1", Double(0),
            "Thickness (length units) of the layer next to each wall left out of field errors.");
}

} // namespace twinflow::app
