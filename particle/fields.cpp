#include "particle/fields.hpp"

#include <cstdio>
#include <map>
#include <sstream>

#include "particle/field_list.hpp"
#include "statistics/blocking.hpp"

namespace twinflow::particle {

double BinnedFields::centre(int bin, int d) const {
  int idx = bin;
  for (int k = 0; k < d; ++k) idx /= bins[k];
  idx %= bins[d];
  return (idx + 0.5) * box[d] / bins[d];
}

std::string BinnedFields::blocks_csv() const {
  std::ostringstream out;
  out << "# T_kinetic of each block (the block means behind fields.csv's T_kinetic and its "
         "standard error); bin: the row of fields.csv, counted from 0\nblock,bin,T_kinetic\n";
  char buf[64];
  for (std::size_t k = 0; k < temperature_kinetic_blocks.size(); ++k)
    for (std::size_t b = 0; b < temperature_kinetic_blocks[k].size(); ++b) {
      std::snprintf(buf, sizeof buf, "%zu,%zu,%.10g\n", k, b, temperature_kinetic_blocks[k][b]);
      out << buf;
    }
  return out.str();
}

std::string BinnedFields::csv() const {
  std::ostringstream out;
  out << "# binned fields, cumulative over the sampled steps; error columns are block standard "
         "errors times the field's blocking factor (summary.json field_blocking_factors). Units: "
         "m = k = rc = T0 = 1\n";
  const char* axes[3] = {"x", "y", "z"};
  for (int d = 0; d < dim; ++d) out << axes[d] << ",";
  out << "density,density_se,T_kinetic,T_kinetic_se,T_internal,T_internal_se,u,u_se";
  for (int d = 0; d < dim; ++d) out << ",v" << axes[d] << ",v" << axes[d] << "_se";
  const char* flux_names[4] = {"J_conductive", "J_internal", "J_kinetic", "J_potential"};
  for (const char* name : flux_names)
    for (int d = 0; d < dim; ++d)
      out << "," << name << "_" << axes[d] << "," << name << "_" << axes[d] << "_se";
  out << "\n";
  char buf[64];
  auto put = [&](double v) {
    std::snprintf(buf, sizeof buf, ",%.8g", v);
    out << buf;
  };
  for (int b = 0; b < bin_count(); ++b) {
    for (int d = 0; d < dim; ++d) {
      std::snprintf(buf, sizeof buf, "%s%.6g", d ? "," : "", centre(b, d));
      out << buf;
    }
    for (const FieldEstimate* f :
         {&density, &temperature_kinetic, &temperature_internal, &internal_energy})
      put(f->mean[b]), put(f->stderr_[b]);
    for (const FieldEstimate* f :
         {&velocity, &flux_conductive, &flux_internal, &flux_kinetic, &flux_potential})
      for (int d = 0; d < dim; ++d) put(f->mean[b * dim + d]), put(f->stderr_[b * dim + d]);
    out << "\n";
  }
  return out.str();
}

template <int D>
FieldSampler<D>::FieldSampler(const std::array<double, 3>& box, const std::array<int, 3>& bins,
                              int blocks, long total_samples, double mass, double cv)
    : box_(box), bins_(bins), blocks_(blocks), total_(total_samples), mass_(mass), cv_(cv) {
  if (D == 2) bins_[2] = 1;
  nbins_ = bins_[0] * bins_[1] * bins_[2];
  bin_volume_ = 1;
  for (int d = 0; d < D; ++d) bin_volume_ *= box_[d] / bins_[d];
  acc_.assign(static_cast<std::size_t>(blocks_) * nbins_, Accumulator{});
  block_samples_.assign(blocks_, 0);
}

template <int D> int FieldSampler<D>::bin_of(const State<D>& s, std::size_t i) const {
  int b = 0;
  for (int d = D - 1; d >= 0; --d) {
    int k = static_cast<int>(s.x[d][i] / box_[d] * bins_[d]);
    k = std::min(std::max(k, 0), bins_[d] - 1);
    b = b * bins_[d] + k;
  }
  return b;
}

template <int D>
void FieldSampler<D>::sample(const State<D>& s, const std::vector<double>& potential,
                             const std::array<std::vector<double>, D>& conduction) {
  const int block = block_of_sample(taken_, blocks_, total_);
  ++taken_;
  ++block_samples_[block];
  Accumulator* a = &acc_[static_cast<std::size_t>(block) * nbins_];
  // This sample's means per bin: the diffusive fluxes are taken relative to them (the local rest
  // frame), which leaves out convection (density x energy x mean velocity, known from the other
  // fields) and with it most of the noise.
  now_.assign(static_cast<std::size_t>(nbins_) * (3 + D), 0.0); // n, u, phi, v[D]
  bin_.resize(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const int b = bin_of(s, i);
    bin_[i] = b;
    double* m = &now_[static_cast<std::size_t>(b) * (3 + D)];
    m[0] += 1;
    m[1] += s.u.empty() ? 0.0 : s.u[i];
    m[2] += potential.empty() ? 0.0 : potential[i];
    for (int d = 0; d < D; ++d) m[3 + d] += s.v[d][i];
  }
  for (int b = 0; b < nbins_; ++b) {
    double* m = &now_[static_cast<std::size_t>(b) * (3 + D)];
    if (m[0] > 0)
      for (int k = 1; k < 3 + D; ++k) m[k] /= m[0];
  }
  for (std::size_t i = 0; i < s.size(); ++i) {
    Accumulator& c = a[bin_[i]];
    const double* m = &now_[static_cast<std::size_t>(bin_[i]) * (3 + D)];
    c.n += 1;
    double dv[D], k = 0;
    for (int d = 0; d < D; ++d) {
      c.v[d] += s.v[d][i];
      c.v2 += s.v[d][i] * s.v[d][i];
      dv[d] = s.v[d][i] - m[3 + d];
      k += dv[d] * dv[d];
    }
    k *= 0.5 * mass_; // peculiar kinetic energy
    double du = 0;
    if (!s.u.empty()) {
      c.u += s.u[i];
      c.inv_theta += cv_ / s.u[i];
      du = s.u[i] - m[1];
    }
    const double dphi = potential.empty() ? 0.0 : potential[i] - m[2];
    // 002 section III.C's diffusive parts, Irving-Kirkwood form: energy carried by the particle's
    // motion relative to its bin. The kinetic part needs no mean subtracted: k is peculiar.
    for (int d = 0; d < D; ++d) {
      c.j_internal[d] += du * dv[d];
      c.j_kinetic[d] += k * dv[d];
      c.j_potential[d] += dphi * dv[d];
      if (!conduction[d].empty()) c.j_conductive[d] += conduction[d][i];
    }
  }
}

namespace {
// Each field sized for nbins bins, per component for vectors.
BinnedFields sized_fields(int dim, int nbins) {
  BinnedFields f;
  for (const NamedField& n : named_fields()) {
    FieldEstimate& e = f.*n.estimate;
    const std::size_t size = static_cast<std::size_t>(nbins) * (n.vector ? dim : 1);
    e.mean.assign(size, 0.0);
    e.stderr_.assign(size, 0.0);
  }
  return f;
}

// e's slot: the mean and standard error over the blocks holding samples of per_block(b), one
// estimate of the value per block; the block values also go to the field's blocking analysis.
template <class PerBlock>
void reduce_blocks(FieldEstimate& e, statistics::PooledBlocking& blocking, std::size_t slot,
                   const std::vector<long>& block_samples, PerBlock&& per_block) {
  static thread_local std::vector<double> values;
  values.clear();
  double sum = 0, sum2 = 0;
  for (std::size_t b = 0; b < block_samples.size(); ++b) {
    if (block_samples[b] == 0) continue;
    const double v = per_block(static_cast<int>(b));
    sum += v, sum2 += v * v;
    values.push_back(v);
  }
  const int k = static_cast<int>(values.size());
  const double mean = k ? sum / k : 0;
  e.mean[slot] = mean;
  e.stderr_[slot] = k > 1 ? std::sqrt(std::max(0.0, sum2 / k - mean * mean) / (k - 1)) : 0;
  blocking.add(values);
}

// Every bin's error times the field's blocking factor (statistics::PooledBlocking).
void scale_to_blocking(FieldEstimate& e, const statistics::PooledBlocking& blocking) {
  e.blocking_factor = blocking.factor();
  if (e.blocking_factor == 1) return;
  for (double& se : e.stderr_) se *= e.blocking_factor;
}

template <class Accumulator> double internal_temperature(const Accumulator& a) {
  return a.inv_theta > 0 ? a.n / a.inv_theta : 0.0; // 1/<1/theta>
}
} // namespace

// Per-block estimates of each field, then mean and standard error over blocks.
template <int D> BinnedFields FieldSampler<D>::result() const {
  BinnedFields f = sized_fields(D, nbins_);
  f.dim = D;
  f.bins = bins_;
  f.box = box_;
  const auto& samples = block_samples_;
  std::map<const FieldEstimate*, statistics::PooledBlocking> blocking; // per field
  for (int bin = 0; bin < nbins_; ++bin) {
    auto at = [&](int b) -> const Accumulator& {
      return acc_[static_cast<std::size_t>(b) * nbins_ + bin];
    };
    // per volume: density and the flux densities (the bin's sums over the sample)
    auto per_volume = [&](int b, double sum) { return sum / (samples[b] * bin_volume_); };
    auto per_particle = [&](int b, double sum) { return at(b).n > 0 ? sum / at(b).n : 0.0; };
    auto reduce = [&](FieldEstimate& e, std::size_t slot, auto&& per_block) {
      reduce_blocks(e, blocking[&e], slot, samples, per_block);
    };
    reduce(f.density, bin, [&](int b) { return per_volume(b, at(b).n); });
    reduce(f.temperature_kinetic, bin, [&](int b) { return kinetic_temperature(at(b)); });
    reduce(f.temperature_internal, bin, [&](int b) { return internal_temperature(at(b)); });
    reduce(f.internal_energy, bin, [&](int b) { return per_particle(b, at(b).u); });
    for (int d = 0; d < D; ++d) {
      const std::size_t slot = static_cast<std::size_t>(bin) * D + d;
      reduce(f.velocity, slot, [&](int b) { return per_particle(b, at(b).v[d]); });
      reduce(f.flux_conductive, slot, [&](int b) { return per_volume(b, at(b).j_conductive[d]); });
      reduce(f.flux_internal, slot, [&](int b) { return per_volume(b, at(b).j_internal[d]); });
      reduce(f.flux_kinetic, slot, [&](int b) { return per_volume(b, at(b).j_kinetic[d]); });
      reduce(f.flux_potential, slot, [&](int b) { return per_volume(b, at(b).j_potential[d]); });
    }
  }
  for (const NamedField& n : named_fields()) {
    FieldEstimate& e = f.*n.estimate;
    scale_to_blocking(e, blocking[&e]);
  }
  for (int b = 0; b < blocks_; ++b) {
    if (samples[b] == 0) continue;
    std::vector<double> t(nbins_), ti(nbins_);
    for (int bin = 0; bin < nbins_; ++bin) {
      const Accumulator& a = acc_[static_cast<std::size_t>(b) * nbins_ + bin];
      t[bin] = kinetic_temperature(a), ti[bin] = internal_temperature(a);
    }
    f.temperature_kinetic_blocks.push_back(std::move(t));
    f.temperature_internal_blocks.push_back(std::move(ti));
  }
  return f;
}

template class FieldSampler<2>;
template class FieldSampler<3>;

template <int D>
WallLayerSampler<D>::WallLayerSampler(const std::array<double, 3>& box,
                                      const std::array<bool, 3>& walls, double range,
                                      int slices_per_range, int blocks, long total_samples,
                                      double mass, double heat_capacity)
    : box_(box), slice_(range / slices_per_range), slices_(2 * slices_per_range), blocks_(blocks),
      total_(total_samples), mass_(mass), cv_(heat_capacity) {
  for (int d = 0; d < D; ++d)
    if (walls[d]) walls_.push_back(2 * d), walls_.push_back(2 * d + 1);
  const std::size_t cells = static_cast<std::size_t>(blocks_) * walls_.size() * slices_;
  n_.assign(cells, 0.0);
  v2_.assign(cells, 0.0);
  for (auto* a : {&inv_theta_, &u_, &u2_, &v4_}) a->assign(cells, 0.0);
  v_.assign(cells * D, 0.0);
  block_samples_.assign(blocks_, 0);
}

template <int D> void WallLayerSampler<D>::sample(const State<D>& s) {
  const int block = block_of_sample(taken_, blocks_, total_);
  ++taken_;
  ++block_samples_[block];
  const double inv_slice = 1 / slice_;
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const int d = walls_[k] / 2, side = walls_[k] % 2;
    const std::size_t base = (static_cast<std::size_t>(block) * walls_.size() + k) * slices_;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double h = side ? box_[d] - s.x[d][i] : s.x[d][i];
      const int slice = static_cast<int>(h * inv_slice);
      if (slice < 0 || slice >= slices_) continue;
      n_[base + slice] += 1;
      for (int e = 0; e < D; ++e) {
        const double v = s.v[e][i];
        v_[(base + slice) * D + e] += v;
        v2_[base + slice] += v * v;
        v4_[base + slice] += v * v * v * v;
      }
      if (!s.u.empty()) {
        const double u = s.u[i];
        inv_theta_[base + slice] += cv_ / u, u_[base + slice] += u, u2_[base + slice] += u * u;
      }
    }
  }
}

template <int D>
typename WallLayerSampler<D>::Block WallLayerSampler<D>::block_profile(
    int b, std::size_t k, double area, const std::vector<double>& h,
    const std::function<double(int, double, double)>& friction) const {
  const std::size_t base = (static_cast<std::size_t>(b) * walls_.size() + k) * slices_;
  Block out;
  out.n.assign(slices_, 0.0), out.v.assign(static_cast<std::size_t>(slices_) * D, 0.0);
  for (auto* f : {&out.t, &out.ti, &out.gamma, &out.kurtosis}) f->assign(slices_, 0.0);
  for (int j = 0; j < slices_; ++j) {
    out.n[j] = n_[base + j] / (block_samples_[b] * area * slice_);
    for (int e = 0; e < D; ++e)
      out.v[j * D + e] = n_[base + j] > 0 ? v_[(base + j) * D + e] / n_[base + j] : 0.0;
    if (j >= slices_ / 2) out.reference += out.n[j] / (slices_ - slices_ / 2);
    out.t[j] = rest_frame_temperature<D>(mass_, n_[base + j], &v_[(base + j) * D], v2_[base + j]);
    const double c = n_[base + j];
    if (c < 2) continue;
    out.ti[j] = inv_theta_[base + j] > 0 ? c / inv_theta_[base + j] : 0.0;
    const double mean_u = u_[base + j] / c;
    out.gamma[j] =
        mean_u > 0 ? (u2_[base + j] / c - mean_u * mean_u) * (cv_ + 1) / (mean_u * mean_u) : 0.0;
    const double v2 = v2_[base + j] / (c * D), v4 = v4_[base + j] / (c * D);
    out.kurtosis[j] = v2 > 0 ? v4 / (v2 * v2) : 0.0;
  }
  // The Gibbs depth and the wall friction integrated over the layer (the inner half).
  double zeta_h = 0;
  for (int j = 0; j < slices_ / 2; ++j) {
    out.depth += (1 - out.n[j] / out.reference) * slice_;
    if (n_[base + j] < 2) continue;
    const double z = out.n[j] * friction(walls_[k], out.t[j], h[j]) * slice_;
    out.zeta += z, zeta_h += z * h[j];
  }
  out.zeta_depth = out.zeta > 0 ? zeta_h / out.zeta : 0.0;
  return out;
}

template <int D>
void WallLayerSampler<D>::block_statistics(const std::vector<Block>& blocks,
                                           WallLayerProfile& p) const {
  auto mean_se = [&](auto value, double& mean, double& se) {
    std::vector<double> per_block(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b) per_block[b] = value(blocks[b]);
    const statistics::Estimate e = statistics::block_estimate(per_block);
    mean = e.mean, se = e.stderr_;
  };
  for (auto* f : {&p.density, &p.temperature, &p.temperature_internal, &p.gamma_ratio, &p.kurtosis})
    f->mean.resize(slices_), f->stderr_.resize(slices_);
  p.velocity.mean.resize(static_cast<std::size_t>(slices_) * D);
  p.velocity.stderr_.resize(static_cast<std::size_t>(slices_) * D);
  for (int j = 0; j < slices_; ++j) {
    mean_se([&](const Block& b) { return b.n[j]; }, p.density.mean[j], p.density.stderr_[j]);
    mean_se([&](const Block& b) { return b.t[j]; }, p.temperature.mean[j],
            p.temperature.stderr_[j]);
    mean_se([&](const Block& b) { return b.ti[j]; }, p.temperature_internal.mean[j],
            p.temperature_internal.stderr_[j]);
    mean_se([&](const Block& b) { return b.gamma[j]; }, p.gamma_ratio.mean[j],
            p.gamma_ratio.stderr_[j]);
    mean_se([&](const Block& b) { return b.kurtosis[j]; }, p.kurtosis.mean[j],
            p.kurtosis.stderr_[j]);
    for (int e = 0; e < D; ++e)
      mean_se([&](const Block& b) { return b.v[j * D + e]; }, p.velocity.mean[j * D + e],
              p.velocity.stderr_[j * D + e]);
  }
  double unused = 0;
  mean_se([](const Block& b) { return b.reference; }, p.reference, p.reference_stderr);
  mean_se([](const Block& b) { return b.depth; }, p.effective_position,
          p.effective_position_stderr);
  mean_se([](const Block& b) { return b.zeta; }, p.friction, p.friction_stderr);
  mean_se([](const Block& b) { return b.zeta_depth; }, p.friction_depth, unused);
}

template <int D>
std::vector<WallLayerProfile>
WallLayerSampler<D>::result(const std::function<double(int, double, double)>& friction) const {
  std::vector<WallLayerProfile> out;
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const int d = walls_[k] / 2;
    double area = 1; // of the wall plane
    for (int e = 0; e < D; ++e)
      if (e != d) area *= box_[e];
    WallLayerProfile p;
    p.wall = walls_[k];
    p.slice = slice_;
    for (int j = 0; j < slices_; ++j) p.h.push_back((j + 0.5) * slice_);
    std::vector<Block> blocks; // the blocks with samples
    for (int b = 0; b < blocks_; ++b)
      if (block_samples_[b] > 0) blocks.push_back(block_profile(b, k, area, p.h, friction));
    block_statistics(blocks, p);
    out.push_back(std::move(p));
  }
  return out;
}

template <int D>
std::string WallLayerSampler<D>::csv(const std::vector<WallLayerProfile>& profiles, int dim) {
  std::ostringstream out;
  out << "# the layer at each wall in slices parallel to it: h = distance from the wall plane "
         "(rc), number density, kinetic temperature and mean velocity components, the internal "
         "temperature 1/<1/theta>, Var(u) (c_v + 1) / <u>^2 (1: the Gamma law) and the velocity "
         "components' kurtosis (3: Gaussian), with block standard errors\n"
         "wall,h,density,density_se,T_kinetic,T_kinetic_se";
  const char* axes = "xyz";
  for (int e = 0; e < dim; ++e) out << ",v" << axes[e] << ",v" << axes[e] << "_se";
  out << ",T_internal,T_internal_se,u_gamma_ratio,u_gamma_ratio_se,kurtosis,kurtosis_se\n";
  const char* names[6] = {"x_lower", "x_upper", "y_lower", "y_upper", "z_lower", "z_upper"};
  char buf[128];
  for (const auto& p : profiles)
    for (std::size_t j = 0; j < p.h.size(); ++j) {
      out << names[p.wall];
      std::snprintf(buf, sizeof buf, ",%.6g,%.8g,%.8g,%.8g,%.8g", p.h[j], p.density.mean[j],
                    p.density.stderr_[j], p.temperature.mean[j], p.temperature.stderr_[j]);
      out << buf;
      for (int e = 0; e < dim; ++e) {
        std::snprintf(buf, sizeof buf, ",%.8g,%.8g", p.velocity.mean[j * dim + e],
                      p.velocity.stderr_[j * dim + e]);
        out << buf;
      }
      for (const auto* f : {&p.temperature_internal, &p.gamma_ratio, &p.kurtosis}) {
        std::snprintf(buf, sizeof buf, ",%.8g,%.8g", f->mean[j], f->stderr_[j]);
        out << buf;
      }
      out << "\n";
    }
  return out.str();
}

template class WallLayerSampler<2>;
template class WallLayerSampler<3>;

} // namespace twinflow::particle
