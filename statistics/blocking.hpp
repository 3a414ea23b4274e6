#pragma once
// Block statistics of a correlated time series (Flyvbjerg & Petersen 1989, J. Chem. Phys. 91,
// 461): cut into B equal consecutive blocks, the scatter of the block means gives the standard
// error of the mean once the blocks outlast the series' memory. Merging adjacent blocks shows
// whether they do: the error stops growing with the block length.
//
// Two entry points, one per kind of input: a raw series (block_average, blocking_errors: the
// particle run's time series) and estimates already made per block (block_estimate,
// merged_blocking_errors: a quantity derived from binned fields block by block). Each keeps the
// arithmetic its callers' published numbers were computed with.

#include <cmath>
#include <numeric>
#include <vector>

namespace twinflow::statistics {

struct Estimate {
  double mean = 0, stderr_ = 0;
};

// The means of `blocks` equal consecutive blocks (empty when a block would hold no sample).
inline std::vector<double> block_means(const std::vector<double>& series, int blocks) {
  const std::size_t per = series.size() / blocks;
  if (per == 0) return {};
  std::vector<double> means(blocks, 0.0);
  for (int b = 0; b < blocks; ++b) {
    for (std::size_t k = 0; k < per; ++k) means[b] += series[b * per + k];
    means[b] /= per;
  }
  return means;
}

// Pearson's correlation coefficient of two series' block means (NaN below two blocks).
inline double block_correlation(const std::vector<double>& a, const std::vector<double>& b,
                                int blocks) {
  const std::vector<double> x = block_means(a, blocks), y = block_means(b, blocks);
  if (x.size() < 2 || y.size() != x.size()) return std::nan("");
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / x.size(),
               my = std::accumulate(y.begin(), y.end(), 0.0) / y.size();
  double sxx = 0, syy = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double dx = x[k] - mx, dy = y[k] - my;
    sxx += dx * dx, syy += dy * dy, sxy += dx * dy;
  }
  return sxy / std::sqrt(sxx * syy);
}

// Mean of the whole series and the standard error from `blocks` equal blocks (a remainder of
// fewer than `blocks` samples at the end is left out of the blocks, not of the mean).
inline Estimate block_average(const std::vector<double>& series, int blocks) {
  Estimate e;
  if (series.empty()) return e;
  e.mean = std::accumulate(series.begin(), series.end(), 0.0) / series.size();
  const std::vector<double> means = block_means(series, blocks);
  if (means.empty()) return e;
  const double m = std::accumulate(means.begin(), means.end(), 0.0) / blocks;
  double var = 0;
  for (const double b : means) var += (b - m) * (b - m);
  e.stderr_ = std::sqrt(var / (blocks - 1) / blocks); // of the mean of the block means
  return e;
}

// Mean and standard error of the mean of per-block estimates taken as independent (0 error
// below two).
inline Estimate block_estimate(const std::vector<double>& per_block) {
  Estimate e;
  const double n = static_cast<double>(per_block.size());
  for (const double x : per_block) e.mean += x / n;
  double ss = 0;
  for (const double x : per_block) ss += (x - e.mean) * (x - e.mean);
  e.stderr_ = per_block.size() > 1 ? std::sqrt(ss / (n - 1) / n) : 0.0;
  return e;
}

// The levels of a blocking analysis: error(merge) for 1, 2 and 4 blocks merged into one, while
// at least two merged blocks remain.
template <class ErrorOfMerged>
std::vector<double> blocking_levels(std::size_t blocks, ErrorOfMerged&& error) {
  std::vector<double> errors;
  for (std::size_t merge = 1; merge <= 4 && blocks / merge >= 2; merge *= 2)
    errors.push_back(error(merge));
  return errors;
}

// The standard error of a series' mean with B blocks, then with B/2 and B/4 (blocks twice and
// four times as long): equal errors say the blocks are longer than the series' memory; else
// the largest is the honest figure.
inline std::vector<double> blocking_errors(const std::vector<double>& series, int blocks) {
  return blocking_levels(blocks, [&](std::size_t merge) {
    return block_average(series, blocks / static_cast<int>(merge)).stderr_;
  });
}

// The same for per-block estimates: the standard error of their mean with 1, 2 and 4 adjacent
// blocks averaged into one (a partial last group is left out).
inline std::vector<double> merged_blocking_errors(const std::vector<double>& per_block) {
  return blocking_levels(per_block.size(), [&](std::size_t merge) {
    std::vector<double> merged(per_block.size() / merge, 0.0);
    for (std::size_t k = 0; k < merged.size() * merge; ++k)
      merged[k / merge] += per_block[k] / merge;
    return block_estimate(merged).stderr_;
  });
}

// The blocking levels of many estimates at once (the bins of a field): the squares of each one's
// merged_blocking_errors summed level by level, and the factor by which the first level's errors
// fall short of the largest level's, sqrt(max_m sum se_m^2 / sum se_1^2) >= 1. Pooled because
// one bin's merged errors rest on 4-19 degrees of freedom, too few to take the largest of bin by
// bin without inflating every error; the factor assumes the bins share the slowest memory.
class PooledBlocking {
public:
  void add(const std::vector<double>& per_block) {
    const std::vector<double> levels = merged_blocking_errors(per_block);
    if (sums_.size() < levels.size()) sums_.resize(levels.size(), 0.0);
    for (std::size_t k = 0; k < levels.size(); ++k) sums_[k] += levels[k] * levels[k];
  }
  double factor() const {
    if (sums_.empty() || !(sums_[0] > 0)) return 1.0;
    double largest = sums_[0];
    for (const double s : sums_) largest = s > largest ? s : largest;
    return std::sqrt(largest / sums_[0]);
  }

private:
  std::vector<double> sums_;
};

} // namespace twinflow::statistics
