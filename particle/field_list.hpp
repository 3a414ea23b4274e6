#pragma once
// The binned fields by name (fields.h5, summary.json): the one list that sizes them, blocks
// their errors and writes them.

#include <vector>

#include "particle/fields.hpp"

namespace twinflow::particle {

struct NamedField {
  const char* name;
  FieldEstimate BinnedFields::*estimate;
  bool vector; // dim components per bin, else one
};

inline const std::vector<NamedField>& named_fields() {
  static const std::vector<NamedField> list = {
      {"density", &BinnedFields::density, false},
      {"temperature_kinetic", &BinnedFields::temperature_kinetic, false},
      {"temperature_internal", &BinnedFields::temperature_internal, false},
      {"internal_energy", &BinnedFields::internal_energy, false},
      {"velocity", &BinnedFields::velocity, true},
      {"flux_conductive", &BinnedFields::flux_conductive, true},
      {"flux_internal", &BinnedFields::flux_internal, true},
      {"flux_kinetic", &BinnedFields::flux_kinetic, true},
      {"flux_potential", &BinnedFields::flux_potential, true}};
  return list;
}

} // namespace twinflow::particle
