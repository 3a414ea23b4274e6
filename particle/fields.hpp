#pragma once
// Binned fields of a particle run on a regular grid (a count of 1 in a direction averages over
// it), each with a statistical error from block averages over time.

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "particle/system.hpp"

namespace twinflow::particle {

struct FieldEstimate {
  std::vector<double> mean, stderr_; // per bin (per component for vectors: bin * D + d)
};

struct BinnedFields {
  std::array<int, 3> bins{{1, 1, 1}};
  std::array<double, 3> box{{1, 1, 1}};
  int dim = 3;
  FieldEstimate density, temperature_kinetic, temperature_internal, internal_energy, velocity;
  int bin_count() const { return bins[0] * bins[1] * (dim == 3 ? bins[2] : 1); }
  double centre(int bin, int d) const; // bin centre coordinate along d
  std::string csv() const;
};

template <int D> class FieldSampler {
public:
  FieldSampler(const std::array<double, 3>& box, const std::array<int, 3>& bins, int blocks,
               long total_samples, double mass, double cv);
  void sample(const State<D>& s); // call exactly total_samples times
  BinnedFields result() const;

private:
  struct Accumulator { // per block and bin
    double n = 0, u = 0, inv_theta = 0, v2 = 0;
    std::array<double, D> v{};
  };
  int bin_of(const State<D>& s, std::size_t i) const;
  std::array<double, 3> box_;
  std::array<int, 3> bins_;
  int blocks_, nbins_;
  long total_, taken_ = 0;
  double mass_, cv_, bin_volume_;
  std::vector<Accumulator> acc_; // [block][bin]
  std::vector<long> block_samples_;
};

} // namespace twinflow::particle
