#include "study/case_file/case_file.hpp"

#include <algorithm>
#include <filesystem>

#include "io/files.hpp"
#include "study/case_record.hpp"

namespace twinflow::study {

using dealii::Patterns::Anything;

CaseFile::CaseFile() {
  registry_.declare("Case name", "", Anything(),
                    "Name of the case (used in reports); empty: the case file's name.");
  declare_scene(registry_);
  declare_particle(registry_);
  declare_transport(registry_);
  declare_compare(registry_);
  declare_continuum(registry_);
}

Case CaseFile::load(const std::string& filename, const std::vector<std::string>& settings) {
  read(filename, settings);
  Case c = resolve(filename);
  c.settings = settings;
  return c;
}

void CaseFile::read(const std::string& filename, const std::vector<std::string>& settings) {
  registry_.parse_file(filename);
  for (const auto& o : settings) registry_.set_override(o);
}

Case CaseFile::resolve(const std::string& filename) const {
  Case out;
  out.file = filename;
  CaseParameters& c = out.parameters;
  c.name = registry_.get("Case name");
  if (c.name.empty()) c.name = std::filesystem::path(filename).stem().string();
  c.scene = resolve_scene(registry_);
  c.particle = resolve_particle(registry_, c.scene);
  c.checkpoint_interval_minutes = registry_.get_double("Particle/Checkpoint interval");
  c.ensemble = static_cast<int>(registry_.get_integer("Particle/Ensemble"));
  c.transport = resolve_transport(registry_);
  resolve_compare(registry_, c);
  c.continuum = resolve_continuum(registry_, c.scene, c.particle);
  c.twin.coefficients_from_transport =
      registry_.get("Continuum/Coefficients/Source") == "transport";
  c.twin.model_chosen_automatically = registry_.get("Continuum/Model") == "auto";
  const std::vector<double> slips = registry_.get_doubles("Continuum/Slip lengths");
  c.twin.kinetic_slip_automatically =
      registry_.get("Continuum/Wall slip") == "auto" &&
      std::none_of(slips.begin(), slips.end(), [](double b) { return b > 0; });
  const std::vector<double> kapitza = registry_.get_doubles("Continuum/Kapitza conductances");
  const bool kapitza_given =
      std::any_of(kapitza.begin(), kapitza.end(), [](double h) { return h > 0; });
  const std::string jump = registry_.get("Continuum/Wall jump");
  c.twin.wall_jumps_automatically = jump == "auto" && !kapitza_given;
  c.twin.wall_jumps_from_theory =
      jump == "theory" || (c.twin.wall_jumps_automatically && c.twin.coefficients_from_transport);
  c.twin.wall_slips_from_theory =
      c.twin.kinetic_slip_automatically && c.twin.coefficients_from_transport;
  c.twin.low_mach_threshold = registry_.get_double("Continuum/Low-Mach threshold");
  c.twin.compressible_threshold = registry_.get_double("Continuum/Compressible threshold");
  out.record = registry_.resolved_json();
  for (const auto& [path, value] : out.record.items())
    out.defaults[path] = registry_.default_value(path);
  return out;
}

Case recorded_case(const std::filesystem::path& run_dir, const std::vector<std::string>& settings) {
  Case c = read_case_record(run_dir);
  if (settings.empty()) return c;
  // The Compare section as recorded, the user's assignments over it, mapped as the case file's.
  CaseFile file;
  for (const auto& [path, value] : c.record.items())
    if (path.rfind("Compare/", 0) == 0)
      file.assign(path + "=" + (value.is_string() ? value.get<std::string>() : value.dump()));
  for (const auto& s : settings) {
    if (s.rfind("Compare/", 0) != 0)
      throw io::InputError("--set " + s +
                           ": twinflow compare RUNDIR takes Compare/ keys only "
                           "(the twins in RUNDIR are compared as they ran; other sections: "
                           "twinflow run CASE --set ... --out " +
                           run_dir.string() + ")");
    file.assign(s);
  }
  resolve_compare(file.registry(), c.parameters);
  const io::Json resolved = file.registry().resolved_json();
  for (const auto& [path, value] : resolved.items())
    if (path.rfind("Compare/", 0) == 0) c.record[path] = value;
  c.settings.insert(c.settings.end(), settings.begin(), settings.end());
  return c;
}

CaseReader case_reader(const std::string& file) {
  CaseReader r;
  r.check = [file](const std::vector<std::string>& settings) { CaseFile().read(file, settings); };
  r.load = [file](const std::vector<std::string>& settings) {
    return CaseFile().load(file, settings);
  };
  r.record = [file](const std::vector<std::string>& settings) {
    CaseFile c;
    c.read(file, settings);
    return c.registry().resolved_json();
  };
  return r;
}

} // namespace twinflow::study
