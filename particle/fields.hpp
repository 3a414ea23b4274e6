#pragma once
// Binned fields of a particle run on a regular grid (a count of 1 in a direction averages over
// it), each with a statistical error from block averages over time.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "particle/system.hpp"

namespace twinflow::particle {

// Kinetic temperature of n particles in their rest frame from the sums of v (per component) and
// of v^2: m (<v^2> - <v>^2) / D, unbiased (n / (n - 1)); 0 below two particles.
template <int D>
double rest_frame_temperature(double mass, double n, const double* v_sum, double v2_sum) {
  if (n < 2) return 0.0;
  double mean2 = 0;
  for (int d = 0; d < D; ++d) mean2 += (v_sum[d] / n) * (v_sum[d] / n);
  return mass * (v2_sum / n - mean2) / D * n / (n - 1);
}

// The time block of sample number `taken` when `total` samples fill `blocks` equal blocks.
inline int block_of_sample(long taken, int blocks, long total) {
  return static_cast<int>(std::min<long>(taken * blocks / std::max(total, 1L), blocks - 1));
}

struct FieldEstimate {
  std::vector<double> mean, stderr_; // per bin (per component for vectors: bin * D + d)
  // stderr_ is the block error times this (statistics::PooledBlocking): where the blocks are
  // shorter than the field's slowest memory, the errors of longer blocks.
  double blocking_factor = 1;
};

struct BinnedFields {
  std::array<int, 3> bins{{1, 1, 1}};
  std::array<double, 3> box{{1, 1, 1}};
  int dim = 3;
  FieldEstimate density, temperature_kinetic, temperature_internal, internal_energy, velocity;
  // Energy-flux parts (vectors, per bin: Irving-Kirkwood volume averages, which equal the flux
  // through the bin's planes in a steady state): conduction by pair heat exchange, and the
  // internal, kinetic and potential energy carried by particles moving relative to their bin's
  // mean velocity (002 section III.C's diffusive parts; convection is rho u v from the fields).
  FieldEstimate flux_conductive, flux_internal, flux_kinetic, flux_potential;
  // T_kinetic and T_internal of each block [block][bin] (the estimates behind their means and
  // stderrs): a quantity derived from several bins takes its error from these, the bins'
  // correlations included.
  std::vector<std::vector<double>> temperature_kinetic_blocks, temperature_internal_blocks;
  int bin_count() const { return bins[0] * bins[1] * (dim == 3 ? bins[2] : 1); }
  double centre(int bin, int d) const; // bin centre coordinate along d
  std::string csv() const;
  std::string blocks_csv() const; // temperature_kinetic_blocks: block, bin, T_kinetic
};

template <int D> class FieldSampler {
public:
  FieldSampler(const std::array<double, 3>& box, const std::array<int, 3>& bins, int blocks,
               long total_samples, double mass, double cv);
  // Call exactly total_samples times. potential: each particle's share of the pair and external
  // potentials; conduction: each particle's share of sum_pairs q_ij (x_i - x_j) (either may be
  // empty: that flux part is then zero).
  void sample(const State<D>& s, const std::vector<double>& potential = {},
              const std::array<std::vector<double>, D>& conduction = {});
  BinnedFields result() const;
  long total_samples() const { return total_; }

  template <class A> void archive(A& a) {
    static_assert(sizeof(Accumulator) == kAccumulatorDoubles * sizeof(double));
    std::vector<double> flat(acc_.size() * kAccumulatorDoubles);
    if constexpr (!A::loading) std::memcpy(flat.data(), acc_.data(), flat.size() * sizeof(double));
    a("accumulators", flat);
    if constexpr (A::loading) {
      if (flat.size() != acc_.size() * kAccumulatorDoubles)
        throw std::invalid_argument("checkpoint: field accumulators of another size");
      std::memcpy(static_cast<void*>(acc_.data()), flat.data(), flat.size() * sizeof(double));
    }
    a("block_samples", block_samples_);
    a("taken", taken_);
  }

private:
  struct Accumulator { // per block and bin
    double n = 0, u = 0, inv_theta = 0, v2 = 0;
    std::array<double, D> v{}, j_conductive{}, j_internal{}, j_kinetic{}, j_potential{};
  };
  static constexpr std::size_t kAccumulatorDoubles = 4 + 5 * D;
  int bin_of(const State<D>& s, std::size_t i) const;
  double kinetic_temperature(const Accumulator& c) const { // in the bin's rest frame
    return rest_frame_temperature<D>(mass_, c.n, c.v.data(), c.v2);
  }
  std::array<double, 3> box_;
  std::array<int, 3> bins_;
  int blocks_, nbins_;
  long total_, taken_ = 0;
  double mass_, cv_, bin_volume_;
  std::vector<Accumulator> acc_; // [block][bin]
  std::vector<long> block_samples_;
  std::vector<double> now_; // scratch: this sample's bin means
  std::vector<int> bin_;    // scratch: each particle's bin
};

// The layer next to each wall, in thin slices parallel to it: density and mean velocity against
// the distance h from the wall plane, per time block. From the density the wall's effective
// position (the calibrated continuum twin's wall).
struct WallLayerProfile {
  int wall = 0;                                 // 2 d + side (x lower, x upper, y lower, ...)
  double slice = 0;                             // slice thickness
  double reference = 0, reference_stderr = 0;   // density over [range, 2 range): beyond the wall
  std::vector<double> h;                        // slice centres, distance from the wall plane
  FieldEstimate density, temperature, velocity; // per slice (velocity: slice * D + d);
                                                // temperature: kinetic, in the slice's frame
  // The equilibrium laws inside the layer (an energy-conserving fluid): T_internal = 1 / <1 /
  // theta>, the internal energies' Var(u) (c_v + 1) / <u>^2 (1 for the Gamma law u^{c_v}
  // exp(-u/T), 000:(2.4)) and the velocity components' kurtosis <v^4> / <v^2>^2 (3 for a
  // Gaussian), per slice.
  FieldEstimate temperature_internal, gamma_ratio, kurtosis;
  // Gibbs (1878) dividing surface: integral over [0, range) of (1 - n(h) / reference) dh, the depth
  // of a step profile with the same particle count; per block, its mean and block error.
  double effective_position = 0, effective_position_stderr = 0;
  // The wall's tangential friction per area and slip velocity, zeta = integral n(h) gamma(T(h))
  // w_D(h) dh (T the slice's kinetic temperature), and the mean distance at which it acts.
  double friction = 0, friction_stderr = 0, friction_depth = 0;
};

template <int D> class WallLayerSampler {
public:
  // Walls present per direction; `range` the wall force's (the slices span [0, 2 range)).
  WallLayerSampler(const std::array<double, 3>& box, const std::array<bool, 3>& walls, double range,
                   int slices_per_range, int blocks, long total_samples, double mass,
                   double heat_capacity);
  void sample(const State<D>& s); // call exactly total_samples times
  // friction(wall, T, h): the friction coefficient gamma w_D(h) of a particle at temperature T
  // and distance h from that wall.
  std::vector<WallLayerProfile>
  result(const std::function<double(int, double, double)>& friction) const;
  static std::string csv(const std::vector<WallLayerProfile>& profiles, int dim);

  template <class A> void archive(A& a) {
    a("wall_layer_counts", n_), a("wall_layer_velocity", v_), a("wall_layer_v2", v2_);
    a("wall_layer_taken", taken_), a("wall_layer_inverse_theta", inv_theta_);
    a("wall_layer_u", u_), a("wall_layer_u2", u2_), a("wall_layer_v4", v4_);
    a("wall_layer_block_samples", block_samples_);
  }

private:
  // One block's slice profiles at one wall, and the layer's integrals.
  struct Block {
    std::vector<double> n, v, t, ti, gamma, kurtosis;
    double reference = 0, depth = 0, zeta = 0, zeta_depth = 0;
  };
  Block block_profile(int block, std::size_t wall, double area, const std::vector<double>& h,
                      const std::function<double(int, double, double)>& friction) const;
  void block_statistics(const std::vector<Block>& blocks, WallLayerProfile& p) const;

  std::array<double, 3> box_;
  std::vector<int> walls_; // 2 d + side of each wall present
  double slice_;
  int slices_, blocks_;
  long total_, taken_ = 0;
  double mass_, cv_;
  std::vector<double> n_, v_, v2_; // [block][wall][slice] (v_: times D)
  std::vector<double> inv_theta_, u_, u2_,
      v4_; // [block][wall][slice]: sums of 1/theta, u, u^2, v^4
  std::vector<long> block_samples_;
};

} // namespace twinflow::particle
