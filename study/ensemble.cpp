#include "study/ensemble.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "io/csv.hpp"
#include "io/files.hpp"
#include "study/case.hpp"
#include "study/ranks.hpp"
#include "study/stages.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {
// sd / sqrt(K) of K values about their mean.
double spread_error(const std::vector<double>& values, double mean) {
  const double k = static_cast<double>(values.size());
  double sum2 = 0;
  for (double v : values) sum2 += (v - mean) * (v - mean);
  return values.size() > 1 ? std::sqrt(sum2 / (k - 1) / k) : 0;
}
// The error of the mean of K independent estimates from their own errors: sqrt(sum e^2) / K.
double within_error(const std::vector<double>& errors) {
  double sum2 = 0;
  for (double e : errors)
    if (std::isfinite(e)) sum2 += e * e;
  return errors.empty() ? 0 : std::sqrt(sum2) / static_cast<double>(errors.size());
}
} // namespace

statistics::Estimate ensemble_mean(const std::vector<double>& values,
                                   const std::vector<double>& errors) {
  double sum = 0;
  for (double v : values) sum += v;
  const double mean = sum / static_cast<double>(values.size());
  const double within = errors.size() == values.size() ? within_error(errors) : 0;
  return {mean, std::max(spread_error(values, mean), within)};
}

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The value of `key` in each object, or empty when one of them lacks it.
std::vector<const io::Json*> member(const std::vector<const io::Json*>& objects,
                                    const std::string& key) {
  std::vector<const io::Json*> values;
  for (const io::Json* o : objects) {
    if (!o->is_object() || !o->contains(key)) return {};
    values.push_back(&(*o)[key]);
  }
  return values;
}

std::vector<double> numbers(const std::vector<const io::Json*>& values) {
  std::vector<double> out;
  for (const io::Json* v : values) {
    if (!v->is_number()) return {};
    out.push_back(v->get<double>());
  }
  return out;
}

// Whether `key` of the objects is a number with its error beside it (KEY_stderr), in all.
bool has_error_beside(const std::vector<const io::Json*>& objects, const std::string& key) {
  return !numbers(member(objects, key)).empty() &&
         !numbers(member(objects, key + "_stderr")).empty();
}

io::Json merge_value(const std::string& key, const std::vector<const io::Json*>& values);

io::Json merge_numbers(const std::string& key, const std::vector<double>& x,
                       const io::Json& first) {
  if (std::all_of(x.begin(), x.end(), [&](double v) { return v == x[0]; })) return first;
  const double k = static_cast<double>(x.size());
  double sum = 0, sum2 = 0, largest = x[0];
  for (double v : x) sum += v, sum2 += v * v, largest = std::max(largest, v);
  if (key == "wall_seconds") return sum; // what the ensemble cost
  if (ends_with(key, "_max")) return largest;
  if (key.find("_stderr") != std::string::npos) return std::sqrt(sum2) / k; // an error's kind
  return sum / k;
}

io::Json merge_object(const std::vector<const io::Json*>& objects) {
  const io::Json& first = *objects[0];
  io::Json out = io::Json::object();
  for (auto it = first.begin(); it != first.end(); ++it) {
    const std::string& key = it.key();
    if (ends_with(key, "_stderr") &&
        has_error_beside(objects, key.substr(0, key.size() - std::string("_stderr").size())))
      continue; // written with its value
    const std::vector<const io::Json*> values = member(objects, key);
    if (values.empty()) {
      out[key] = it.value();
    } else if (has_error_beside(objects, key)) {
      const auto e = ensemble_mean(numbers(values), numbers(member(objects, key + "_stderr")));
      out[key] = e.mean;
      out[key + "_stderr"] = e.stderr_;
    } else {
      out[key] = merge_value(key, values);
    }
  }
  return out;
}

io::Json merge_value(const std::string& key, const std::vector<const io::Json*>& values) {
  const io::Json& first = *values[0];
  if (const std::vector<double> x = numbers(values); !x.empty())
    return merge_numbers(key, x, first);
  const auto same_kind = [&](bool (io::Json::*is)() const noexcept) {
    return std::all_of(values.begin(), values.end(), [&](const io::Json* v) { return (v->*is)(); });
  };
  if (same_kind(&io::Json::is_object)) return merge_object(values);
  if (same_kind(&io::Json::is_array) &&
      std::all_of(values.begin(), values.end(),
                  [&](const io::Json* v) { return v->size() == first.size(); })) {
    io::Json out = io::Json::array();
    for (std::size_t i = 0; i < first.size(); ++i) {
      std::vector<const io::Json*> elements;
      for (const io::Json* v : values) elements.push_back(&(*v)[i]);
      out.push_back(merge_value(key, elements));
    }
    return out;
  }
  return first; // text, flags, null: as the first realisation has it
}

double cell_number(const std::string& cell, const std::string& name) {
  std::size_t used = 0;
  const double v = std::stod(cell, &used);
  if (used != cell.size()) throw std::runtime_error(name + ": '" + cell + "' is not a number");
  return v;
}

// One merged cell of column c: the cells as they are when all are equal, else their mean (a
// column with an error column beside it is merged with it, in merge_table).
std::string merged_cell(const std::vector<io::CsvTable>& t, std::size_t row, std::size_t c,
                        const std::string& name) {
  const std::string& first = t[0].rows[row][c];
  if (std::all_of(t.begin(), t.end(),
                  [&](const io::CsvTable& x) { return x.rows[row][c] == first; }))
    return first;
  double sum = 0;
  for (const auto& x : t) sum += cell_number(x.rows[row][c], name);
  return exact_text(sum / static_cast<double>(t.size()));
}

// The realisations' tables, parsed; their columns (and with same_rows their row counts) equal.
std::vector<io::CsvTable> parse_alike(const std::vector<std::string>& tables,
                                      const std::string& name, bool same_rows = true) {
  std::vector<io::CsvTable> t;
  for (const auto& text : tables) t.push_back(io::parse_csv(text));
  for (const auto& x : t)
    if (x.header != t[0].header || (same_rows && x.rows.size() != t[0].rows.size()))
      throw std::runtime_error(name + ": the realisations' tables differ in their columns or rows");
  return t;
}

std::string csv_line(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t c = 0; c < cells.size(); ++c) line += (c ? "," : "") + cells[c];
  return line + "\n";
}

} // namespace

io::Json merge_results(const std::vector<io::Json>& results) {
  std::vector<const io::Json*> all;
  for (const auto& r : results) all.push_back(&r);
  return merge_object(all);
}

std::string merge_table(const std::vector<std::string>& tables, const std::string& name) {
  const std::vector<io::CsvTable> t = parse_alike(tables, name);
  const auto& header = t[0].header;
  std::string out = t[0].comments + csv_line(header);
  for (std::size_t row = 0; row < t[0].rows.size(); ++row) {
    std::vector<std::string> cells(header.size());
    for (std::size_t c = 0; c < header.size(); ++c) {
      const int error = t[0].find(header[c] + "_se");
      if (ends_with(header[c], "_se") && t[0].find(header[c].substr(0, header[c].size() - 3)) >= 0)
        continue; // written with its value
      if (error < 0) {
        cells[c] = merged_cell(t, row, c, name);
        continue;
      }
      std::vector<double> values, errors;
      for (const auto& x : t) {
        values.push_back(cell_number(x.rows[row][c], name));
        errors.push_back(cell_number(x.rows[row][static_cast<std::size_t>(error)], name));
      }
      const auto e = ensemble_mean(values, errors);
      cells[c] = exact_text(e.mean);
      cells[static_cast<std::size_t>(error)] = exact_text(e.stderr_);
    }
    out += csv_line(cells);
  }
  return out;
}

std::string concatenate_blocks(const std::vector<std::string>& tables, const std::string& name) {
  const std::vector<io::CsvTable> t = parse_alike(tables, name, false);
  std::string out = t[0].comments + csv_line(t[0].header);
  long offset = 0;
  for (const auto& x : t) {
    const std::size_t block = x.column("block", name);
    long last = -1;
    for (auto row : x.rows) {
      const long b = std::stol(row[block]);
      last = std::max(last, b);
      row[block] = std::to_string(b + offset);
      out += csv_line(row);
    }
    offset += last + 1;
  }
  return out;
}

std::vector<io::Snapshot> merge_snapshots(const std::vector<io::FieldFile::Contents>& files) {
  const auto& first = files[0];
  for (const auto& f : files)
    if (!(f.grid == first.grid) || f.snapshots.size() != first.snapshots.size())
      throw std::runtime_error("fields.h5: the realisations differ in their grid or snapshots");
  std::vector<io::Snapshot> merged;
  for (std::size_t s = 0; s < first.snapshots.size(); ++s) {
    io::Snapshot m;
    m.time = first.snapshots[s].time;
    for (const auto& f : files) {
      m.wall_seconds += f.snapshots[s].wall_seconds;
      m.particle_steps += f.snapshots[s].particle_steps;
    }
    for (const io::Field& field : first.snapshots[s].fields) {
      io::Field out{field.name, field.components, {}, {}};
      std::vector<const io::Field*> each;
      for (const auto& f : files) {
        each.push_back(f.snapshots[s].find(field.name));
        if (!each.back() || each.back()->values.size() != field.values.size())
          throw std::runtime_error("fields.h5: a realisation lacks " + field.name);
      }
      for (std::size_t i = 0; i < field.values.size(); ++i) {
        std::vector<double> values, errors;
        for (const io::Field* x : each) {
          values.push_back(x->values.at(i));
          if (!x->standard_error.empty()) errors.push_back(x->standard_error.at(i));
        }
        const auto e = ensemble_mean(values, errors);
        out.values.push_back(e.mean);
        if (!field.standard_error.empty()) out.standard_error.push_back(e.stderr_);
      }
      m.fields.push_back(std::move(out));
    }
    merged.push_back(std::move(m));
  }
  return merged;
}

namespace {

// Realisation k: the case with seed Seed + k.
Case realisation_case(const Case& c, int k) {
  Case one = c;
  one.parameters.particle.seed = c.parameters.particle.seed + static_cast<std::uint64_t>(k);
  one.record_value("Particle/Seed", std::to_string(one.parameters.particle.seed));
  return one;
}

std::string realisation_name(int k) {
  char name[16];
  std::snprintf(name, sizeof name, "%02d", k);
  return name;
}

// Whether `dir` holds a finished run of exactly this case (a --restart keeps it).
bool finished_run_of(const fs::path& dir, const Case& c) {
  if (!fs::exists(dir / "summary.json")) return false;
  const io::Json summary = io::read_json(dir / "summary.json");
  return without_keys_that_change_no_result(summary.value("parameters", io::Json::object())) ==
         without_keys_that_change_no_result(c.record);
}

// The options for the next realisation: --wall-time counts from the ensemble's start (past it,
// the next one checkpoints at once: a --restart goes on from there).
RunOptions time_left(const RunOptions& options, std::chrono::steady_clock::time_point started) {
  RunOptions left = options;
  if (options.wall_time_limit > 0) {
    const double used =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    left.wall_time_limit = std::max(options.wall_time_limit - used, 1e-9);
  }
  return left;
}

// Per field of the last snapshot: the spread's error over the blocks', rms over the cells (the
// spread's variance is unbiased, so 1 when the blocks' errors are right; > 1 where they are short).
io::Json spread_over_blocks(const std::vector<io::FieldFile::Contents>& files) {
  io::Json out = io::Json::object();
  for (const io::Field& field : files[0].snapshots.back().fields) {
    if (field.standard_error.empty()) continue;
    std::vector<const io::Field*> each;
    for (const auto& f : files) each.push_back(f.snapshots.back().find(field.name));
    double sum2 = 0;
    std::size_t cells = 0;
    for (std::size_t i = 0; i < field.values.size(); ++i) {
      std::vector<double> values, errors;
      for (const io::Field* x : each) {
        values.push_back(x->values[i]);
        errors.push_back(x->standard_error[i]);
      }
      const double within = within_error(errors);
      if (!(within > 0)) continue;
      const double ratio = ensemble_mean(values, {}).stderr_ / within;
      sum2 += ratio * ratio, ++cells;
    }
    if (cells) out[field.name] = std::sqrt(sum2 / static_cast<double>(cells));
  }
  return out;
}
} // namespace

namespace {
// The realisations' files merged into `stage` (rank 0), summary.json last.
io::Json write_merged(const Case& c, const io::StageDirectory& stage,
                      const std::vector<fs::path>& dirs, double stage_seconds) {
  const auto read_all = [&](const std::string& name) {
    std::vector<std::string> texts;
    for (const auto& d : dirs) texts.push_back(io::read_file(d / name));
    return texts;
  };
  for (const char* name : {"thermo.csv", "histograms.csv", "rdf.csv", "correlations.csv",
                           "fields.csv", "wall_layers.csv", "relaxation.csv", "slab_profile.csv"})
    if (fs::exists(dirs[0] / name))
      io::write_file_atomically(stage.file(name), merge_table(read_all(name), name));
  if (fs::exists(dirs[0] / "blocks.csv"))
    io::write_file_atomically(stage.file("blocks.csv"),
                              concatenate_blocks(read_all("blocks.csv"), "blocks.csv"));
  io::Json spread = io::Json::object();
  if (fs::exists(dirs[0] / "fields.h5")) {
    std::vector<io::FieldFile::Contents> files;
    for (const auto& d : dirs) files.push_back(io::FieldFile::read(d / "fields.h5"));
    io::FieldFile merged(stage.file("fields"), files[0].grid);
    for (auto& snapshot : merge_snapshots(files)) merged.append(std::move(snapshot));
    spread = spread_over_blocks(files);
  }
  std::vector<io::Json> summaries, results;
  for (const auto& d : dirs) {
    summaries.push_back(io::read_json(d / "summary.json"));
    results.push_back(summaries.back().at("results"));
  }
  io::Json summary = summaries[0];
  summary["stage_wall_time_s"] = stage_seconds;
  summary["results"] = merge_results(results);
  io::Json& ensemble = summary["results"]["ensemble"];
  ensemble["realisations"] = dirs.size();
  for (const auto& r : summaries)
    ensemble["seeds"].push_back(io::text(r, {"parameters", "Particle/Seed"}));
  ensemble["directory"] = "realisations";
  ensemble["error_rule"] = "the larger of the spread's, sd / sqrt(K), and the blocks', "
                           "sqrt(sum e_k^2) / K";
  ensemble["spread_over_blocks"] = spread;
  summary["parameters"] = c.record;
  io::write_file_atomically(stage.file("summary.json"), io::dump(summary)); // last: complete
  return summary["results"];
}
} // namespace

int ensemble_particle_stage(const Case& c, const RunOptions& options) {
  const CaseParameters& p = c.parameters;
  const bool root = on_rank_zero();
  const auto started = std::chrono::steady_clock::now();
  const fs::path run_dir = run_directory(options, p.name);
  const io::StageDirectory stage(run_dir, "particle", options.force && !options.restart);
  const fs::path realisations = stage.path() / "realisations";
  if (root) {
    stage.create();
    if (!options.restart) fs::remove_all(realisations); // a fresh ensemble starts afresh
  }
  const fs::path checkpoint = particle_checkpoint(run_dir); // the running realisation's
  std::vector<fs::path> dirs;
  for (int k = 0; k < p.ensemble; ++k) {
    const Case one = realisation_case(c, k);
    const io::StageDirectory dir(realisations, realisation_name(k), true);
    dirs.push_back(dir.path());
    const std::string seed = std::to_string(one.parameters.particle.seed);
    const bool done = from_rank_zero(options.restart && finished_run_of(dir.path(), one) ? 1. : 0.);
    if (root)
      std::cout << "particle: realisation " << k + 1 << " of " << p.ensemble << " (seed " << seed
                << (done ? "): done earlier, kept" : ")") << std::endl;
    if (done) continue;
    const bool resume = from_rank_zero(options.restart && fs::exists(checkpoint) ? 1. : 0.);
    if (const int rc = particle_run(one, time_left(options, started), dir, checkpoint, resume))
      return rc;
  }
  if (!root) return 0;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const io::Json r = write_merged(c, stage, dirs, seconds);
  std::cout << "particle: ensemble of " << p.ensemble
            << ": T_kinetic = " << io::number(r, {"T_kinetic"}) << " +- "
            << io::number(r, {"T_kinetic_stderr"})
            << ", T_internal = " << io::number(r, {"T_internal"}) << " +- "
            << io::number(r, {"T_internal_stderr"})
            << "\noutputs: " << fs::absolute(stage.path()).string() << "\n";
  return 0;
}

} // namespace twinflow::study
