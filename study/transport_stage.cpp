#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "io/csv.hpp"
#include "io/files.hpp"
#include "study/ranks.hpp"
#include "study/stages.hpp"
#include "transport/measurement.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What the transport stage's outputs depend on: the fluid (the Particle section, less the scene's
// run lengths and walls), the dimension, the state point and the measurement settings; not the
// scene's box, walls or gravity (with kappa from walls its box and walls, never its gravity); the
// method's version (transport::kMeasurementMethod).
io::Json measurement_inputs(const Case& c, const particle::ParticleParameters& p,
                            const transport::TransportParameters& t) {
  io::Json j = io::Json::object();
  const io::Json& resolved = c.record;
  for (const auto& [path, value] : resolved.items()) {
    const bool fluid = path.rfind("Particle/", 0) == 0 && path.rfind("Particle/Walls/", 0) != 0 &&
                       path != "Particle/Steps" && path != "Particle/Equilibration steps" &&
                       path != "Particle/Ensemble" && path != "Particle/Initial velocities" &&
                       path != "Particle/Initial internal energy" && !changes_no_result(path);
    if (fluid) j[path] = value;
  }
  j["dimension"] = p.dim;
  j["start"] = "equilibrium"; // bulk runs start at (c_v + k) T whatever the case says
  j["density"] = p.density;
  j["temperature"] = p.temperature;
  j["measure_flows"] = t.measure_flows;
  if (t.measure_flows) {
    j["flow_particles"] = t.flow_particles;
    j["flow_repeats"] = t.flow_repeats;
    j["temperature_spread"] = t.temperature_spread;
  }
  j["method"] = transport::kMeasurementMethod;
  if (t.measure_flows && t.kappa_from_slabs && c.parameters.scene.heated_direction() >= 0) {
    // the heat slabs take the scene's box and its walls' temperatures, not its gravity
    for (const auto& [path, value] : resolved.items())
      if (path.rfind("Scene/", 0) == 0 && path != "Scene/Gravity") j[path] = value;
    j["kappa_from_slabs"] = true;
  }
  for (const auto& [n, T] : transport::isobar_ends(c.parameters.scene, t))
    j["isobar_ends"].push_back({n, T});
  if (t.kappa_from_walls) { // the scene and the particle walls enter the wall run
    // Not its gravity: a conduction run must not convect, and the wall run has none
    // (transport/wall_kappa.cpp). Else each --rayleigh point would measure again, with other
    // noise, what is the same measurement.
    for (const auto& [path, value] : resolved.items())
      if ((path.rfind("Scene/", 0) == 0 && path != "Scene/Gravity") ||
          path.rfind("Particle/Walls/", 0) == 0)
        j[path] = value;
    j["kappa_from_walls"] = true;
    j["wall_steps"] = t.wall_steps;
  }
  return j;
}

// Bulk measurements are cached across run directories under the hash of their inputs, so sweeps
// and reruns do not redo them: $TWINFLOW_CACHE/transport/HASH (default $XDG_CACHE_HOME/twinflow,
// else ~/.cache/twinflow; TWINFLOW_CACHE=off disables it). Empty: no cache.
fs::path cache_directory(const std::string& hash) {
  const char* env = std::getenv("TWINFLOW_CACHE");
  fs::path root;
  if (env && *env) {
    if (std::string(env) == "off") return {};
    root = env;
  } else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    root = fs::path(xdg) / "twinflow";
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    root = fs::path(home) / ".cache" / "twinflow";
  } else {
    return {};
  }
  return root / "transport" / hash;
}

// coefficients.csv as a person reads it on the console: aligned columns, "n/a (why)" where the
// file has nan (a coefficient not measured, or without an estimate to compare with).
std::string console_table(const std::string& csv) {
  const io::CsvTable table = io::parse_csv(csv, false);
  std::vector<std::vector<std::string>> rows = table.rows;
  const std::string& comment = table.comments;
  if (rows.empty()) return csv;
  const auto is_nan = [](const std::string& text) {
    return text == "nan" || text == "-nan" || text == "inf" || text == "-inf";
  };
  for (std::size_t r = 1; r < rows.size(); ++r) {
    auto& row = rows[r];
    const bool measured = row.size() > 3 && !is_nan(row[3]);
    for (std::size_t k = 1; k < row.size(); ++k)
      if (is_nan(row[k]))
        row[k] = !measured && (k == 3 || k == 4) ? "n/a (not measured)"
                 : !measured                     ? "n/a"
                                                 : "n/a (no estimate)";
  }
  std::vector<std::size_t> width;
  for (const auto& row : rows)
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (width.size() <= k) width.push_back(0);
      width[k] = std::max(width[k], row[k].size());
    }
  std::string out = comment;
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t k = 0; k < row.size(); ++k) {
      line += row[k];
      if (k + 1 < row.size()) line += std::string(width[k] + 2 - row[k].size(), ' ');
    }
    out += line + "\n";
  }
  return out;
}

const char* kCachedFiles[] = {"coefficients.csv", "rdf.csv", "summary.json"};

// A cache entry's summary.json, or null when it is missing, unreadable or without results (the
// cache is a convenience, never a reason to fail).
std::optional<io::Json> cached_summary(const fs::path& entry) {
  for (const char* f : kCachedFiles)
    if (!fs::exists(entry / f)) return std::nullopt;
  io::Json summary;
  try {
    summary = io::read_json(entry / "summary.json");
  } catch (const std::exception& e) {
    // The parser's message may quote the damaged bytes: one printable line of it.
    std::string why = e.what();
    why = why.substr(0, why.find('\n')).substr(0, 160);
    for (char& ch : why)
      if (static_cast<unsigned char>(ch) < 32 || static_cast<unsigned char>(ch) > 126) ch = '?';
    std::cerr << "transport: cache entry " << entry.string() << " unreadable (" << why
              << "): measuring\n";
    return std::nullopt;
  }
  if (!io::find(summary, {"provenance"}) || !io::find(summary, {"results"})) {
    std::cerr << "transport: cache entry " << entry.string()
              << " incomplete (summary.json without results): measuring\n";
    return std::nullopt;
  }
  return summary;
}

// Each file as it was stored (content hashes, written with the entry): a truncated or altered
// file is a miss, never a wrong coefficient.
bool cached_files_intact(const fs::path& entry, const io::Json& summary) {
  const io::Json* hashes = io::find(summary, {"cache_files"});
  if (!hashes) return true;
  for (const char* f : {"coefficients.csv", "rdf.csv"}) {
    const std::string stored = io::text(*hashes, {f});
    std::string now;
    try {
      now = io::content_hash(io::read_file(entry / f));
    } catch (const std::exception&) {
    }
    if (stored.empty() || stored != now) {
      std::cerr << "transport: cache entry " << entry.string() << ": " << f
                << " is truncated or altered (content hash differs): measuring\n";
      return false;
    }
  }
  return true;
}

// Copies a cached result into the stage, with this case's name and parameters. False: no usable
// entry.
bool restore_from_cache(const fs::path& entry, const io::StageDirectory& stage, const Case& c,
                        const Clock::time_point started) {
  std::optional<io::Json> summary = cached_summary(entry);
  if (!summary || !cached_files_intact(entry, *summary)) return false;
  const io::Json made_by = summary->at("provenance");
  const io::Json* revision = io::find(made_by, {"twinflow_git_revision"});
  const io::Json now = io::provenance();
  if (revision && *revision != now.at("twinflow_git_revision"))
    std::cout << "transport: the cached measurements were made by twinflow " << revision->dump()
              << " (this is " << now.at("twinflow_git_revision").dump()
              << "); --force or TWINFLOW_CACHE=off measures again\n";
  (*summary)["cache"] = {{"entry", entry.string()}, {"made_by", made_by}};
  summary->erase("cache_files");
  (*summary)["case"] = c.parameters.name;
  (*summary)["provenance"] = now;
  (*summary)["execution"] = execution_record(c.parameters.particle.dim);
  (*summary)["stage_wall_time_s"] = seconds_since(started);
  (*summary)["parameters"] = c.record;
  stage.create();
  io::write_file_atomically(stage.file("coefficients.csv"),
                            io::read_file(entry / "coefficients.csv"));
  io::write_file_atomically(stage.file("rdf.csv"), io::read_file(entry / "rdf.csv"));
  io::write_file_atomically(stage.file("summary.json"), io::dump(*summary));
  return true;
}

// The measurement's files in the stage, its cache entry, its table on the console.
int write_measurement(const Case& c, const io::StageDirectory& stage,
                      const transport::TransportMeasurement& m, const std::string& key,
                      const io::Json& key_inputs, const fs::path& cache,
                      const Clock::time_point started) {
  const CaseParameters& cp = c.parameters;
  io::write_file_atomically(stage.file("coefficients.csv"), m.coefficients_csv);
  io::write_file_atomically(stage.file("rdf.csv"), m.rdf_csv);
  io::Json summary = io::Json::object();
  summary["stage"] = "transport";
  summary["case"] = cp.name;
  summary["provenance"] = io::provenance();
  summary["execution"] = execution_record(cp.particle.dim);
  summary["stage_wall_time_s"] = seconds_since(started);
  summary["parameters"] = c.record;
  summary["results"] = m.results;
  summary["measurement_key"] = key;
  io::write_file_atomically(stage.file("summary.json"), io::dump(summary));
  if (!cache.empty()) {
    // summary.json last: an interrupted copy leaves no entry. Best effort (read-only home, full
    // disk): the stage's own results are already written.
    try {
      fs::create_directories(cache);
      io::write_file_atomically(cache / "inputs.json", io::dump(key_inputs));
      io::write_file_atomically(cache / "coefficients.csv", m.coefficients_csv);
      io::write_file_atomically(cache / "rdf.csv", m.rdf_csv);
      io::Json entry_summary = summary;
      io::Json hashes = io::Json::object();
      hashes["coefficients.csv"] = io::content_hash(m.coefficients_csv);
      hashes["rdf.csv"] = io::content_hash(m.rdf_csv);
      entry_summary["cache_files"] = hashes;
      io::write_file_atomically(cache / "summary.json", io::dump(entry_summary));
    } catch (const std::exception& e) {
      std::cerr << "transport: not cached (" << e.what() << ")\n";
    }
  }
  std::cout << console_table(m.coefficients_csv)
            << "outputs: " << fs::absolute(stage.path()).string() << "\n";
  return 0;
}
} // namespace

int transport_stage(const Case& c, const RunOptions& options) {
  const Clock::time_point started = Clock::now();
  const CaseParameters& cp = c.parameters;
  const fs::path run_dir = run_directory(options, cp.name);
  const particle::ParticleParameters bulk =
      transport::bulk_fluid(cp.scene, cp.particle, cp.transport);
  const io::Json key_inputs = measurement_inputs(c, bulk, cp.transport);
  const std::string key = io::content_hash(key_inputs.dump());
  const fs::path cache = cache_directory(key);
  // Under mpirun rank 0 alone reads and writes the folder and the cache and prints; every rank
  // takes part in the measurement's particle runs (study/ranks.hpp).
  std::optional<io::StageDirectory> stage;
  bool restored = false;
  if (const int rc = rank_zero_runs([&] {
        stage.emplace(run_dir, "transport", options.force);
        // --force measures again (and refreshes the entry).
        restored =
            !cache.empty() && !options.force && restore_from_cache(cache, *stage, c, started);
        if (restored)
          std::cout << console_table(io::read_file(stage->file("coefficients.csv")))
                    << "transport: measurements reused from the cache (" << cache.string()
                    << "; TWINFLOW_CACHE=off recomputes)\noutputs: "
                    << fs::absolute(stage->path()).string() << "\n";
        else
          stage->create();
        return 0;
      }))
    return rc;
  if (from_rank_zero(restored ? "restored" : "measure") == "restored") return 0;
  transport::TransportMeasurement m;
  if (const int rc = every_rank_runs([&] {
        m = transport::measure_transport(cp.scene, cp.particle, bulk, cp.transport);
        return 0;
      }))
    return rc;
  return rank_zero_runs(
      [&] { return write_measurement(c, *stage, m, key, key_inputs, cache, started); });
}

} // namespace twinflow::study
