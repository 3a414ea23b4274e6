#pragma once
// One case file describes a whole paired case. This folder is the one place that maps it onto
// the plain parameter structs of each library (study/case.hpp gathers them).

#include <string>
#include <vector>

#include "io/case_file.hpp"
#include "study/case.hpp"

namespace twinflow::app {

using io::Registry;

// Declares every parameter of every section (so print-parameters documents them all).
class CaseFile {
public:
  CaseFile();
  // Reads the file, applies --set assignments, checks every value: throws io::InputError.
  study::Case load(const std::string& filename, const std::vector<std::string>& settings);
  // The case a stage recorded in its summary.json ("parameters": path -> value), with the later
  // stages' --set assignments (Transport/, Continuum/, Compare/) over it: those sections may
  // change without rerunning the particles.
  study::Case load_recorded(const io::Json& recorded, const std::string& name,
                            const std::vector<std::string>& settings = {});
  // The two halves of load(): read() rejects unknown keys and values outside a key's pattern;
  // resolve() the values that do not fit together or the sections' ranges.
  void read(const std::string& filename, const std::vector<std::string>& settings);
  study::Case resolve(const std::string& filename) const;
  const Registry& registry() const { return registry_; }

private:
  Registry registry_;
};

// Per-section declaration and mapping (app/case/*_section.cpp).
void declare_scene(Registry&);
scene::SceneParameters resolve_scene(const Registry&);
void declare_particle(Registry&);
particle::ParticleParameters resolve_particle(const Registry&, const scene::SceneParameters&);
void declare_continuum(Registry&);
continuum::ContinuumParameters resolve_continuum(const Registry&, const scene::SceneParameters&,
                                                 const particle::ParticleParameters&);
void declare_transport(Registry&);
transport::TransportParameters resolve_transport(const Registry&);
void declare_compare(Registry&);
void resolve_compare(const Registry&, study::CaseParameters&); // compare and stability bounds

} // namespace twinflow::app
