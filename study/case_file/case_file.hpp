#pragma once
// One case file describes a whole paired case. This folder is the one place that maps it onto
// the plain parameter structs of each library (study/case.hpp gathers them): io/case_file.hpp
// reads the text, each *_section.cpp declares its section's keys and maps them.

#include <filesystem>
#include <string>
#include <vector>

#include "io/case_file.hpp"
#include "study/case.hpp"
#include "study/grid.hpp"

namespace twinflow::study {

using io::Registry;

// Declares every parameter of every section (so print-parameters documents them all).
class CaseFile {
public:
  CaseFile();
  // Reads the file, applies --set assignments, checks every value: throws io::InputError.
  Case load(const std::string& filename, const std::vector<std::string>& settings);
  // The two halves of load(): read() rejects unknown keys and values outside a key's pattern;
  // resolve() the values that do not fit together or the sections' ranges.
  void read(const std::string& filename, const std::vector<std::string>& settings);
  Case resolve(const std::string& filename) const;
  const Registry& registry() const { return registry_; }
  void assign(const std::string& assignment) { registry_.set_override(assignment); } // --set's

private:
  Registry registry_;
};

// The case a run directory records (RUNDIR/case.json, study/case_record.hpp), with --set
// assignments of Compare/ keys over it: what `twinflow compare RUNDIR` compares.
Case recorded_case(const std::filesystem::path& run_dir, const std::vector<std::string>& settings);

// The case file as a grid's points read it (sweep, stability).
CaseReader case_reader(const std::string& file);

// Per-section declaration and mapping (study/case_file/*_section.cpp).
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
void resolve_compare(const Registry&, CaseParameters&); // compare and stability bounds

} // namespace twinflow::study
