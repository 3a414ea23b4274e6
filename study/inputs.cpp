#include "study/inputs.hpp"

#include <iostream>

#include "io/files.hpp"
#include "study/ranks.hpp"

namespace twinflow::study {

namespace fs = std::filesystem;

bool changes_no_result(const std::string& path) {
  return path == "Particle/Checkpoint interval";
}

io::Json without_keys_that_change_no_result(io::Json record) {
  for (auto it = record.begin(); it != record.end();)
    it = changes_no_result(it.key()) ? record.erase(it) : std::next(it);
  return record;
}

fs::path run_directory(const RunOptions& options, const std::string& case_name) {
  return options.out.empty() ? fs::path("twinflow-runs") / case_name : options.out;
}

StageInputs stage_inputs(const Case& c, std::initializer_list<const char*> sections,
                         const std::vector<std::string>& upstream_hashes, int method) {
  StageInputs s;
  io::Json parameters = io::Json::object();
  for (const auto& [path, value] : c.record.items())
    for (const char* section : sections)
      if (path.rfind(section, 0) == 0 && !changes_no_result(path)) {
        parameters[path] = value;
        s.defaults[path] = c.defaults.value(path, io::Json());
      }
  s.inputs["parameters"] = parameters;
  s.inputs["upstream"] = io::Json::array();
  for (const auto& h : upstream_hashes) s.inputs["upstream"].push_back(h);
  if (method) s.inputs["method"] = method;
  s.hash = io::content_hash(s.inputs.dump());
  s.inputs["twinflow_git_revision"] = io::provenance().at("twinflow_git_revision");
  s.inputs["hash"] = s.hash;
  return s;
}

namespace {
bool same_inputs(const io::Json& recorded, const StageInputs& s) {
  const io::Json* then = io::find(recorded, {"parameters"});
  const io::Json* upstream = io::find(recorded, {"upstream"});
  if (!then || !upstream || *upstream != s.inputs.at("upstream")) return false;
  if (recorded.value("method", io::Json()) != s.inputs.value("method", io::Json())) return false;
  for (const auto& [path, value] : s.inputs.at("parameters").items()) {
    const io::Json* old = io::find(*then, {path});
    if (old ? *old != value : value != s.defaults.value(path, io::Json())) return false;
  }
  return true;
}
} // namespace

bool reusable(const fs::path& stage_dir, const StageInputs& s) {
  if (!fs::exists(stage_dir / "summary.json") || !fs::exists(stage_dir / "inputs.json"))
    return false;
  const io::Json recorded = io::read_json(stage_dir / "inputs.json");
  const std::string hash = io::text(recorded, {"hash"});
  if (hash.empty() || (hash != s.hash && !same_inputs(recorded, s))) return false;
  const std::string then = io::text(recorded, {"twinflow_git_revision"});
  const std::string now = io::text(s.inputs, {"twinflow_git_revision"});
  if (!then.empty() && !now.empty() && then != now)
    std::cout << "run: " << stage_dir.filename().string() << ": made by revision " << then
              << " (this is " << now << ")\n";
  return true;
}

int run_or_reuse(const fs::path& stage_dir, const StageInputs& s, bool force,
                 const std::function<int()>& stage, Ranks ranks) {
  bool reuse = false;
  if (const int rc = rank_zero_runs([&] {
        reuse = !force && reusable(stage_dir, s);
        if (reuse)
          std::cout << "run: " << stage_dir.filename().string() << ": inputs unchanged (" << s.hash
                    << "), results reused\n";
        else
          fs::remove(stage_dir / "inputs.json"); // stale until the stage finishes again
        return 0;
      }))
    return rc;
  if (from_rank_zero(reuse ? "reuse" : "run") == "reuse") return 0;
  const int rc = ranks == Ranks::Every ? every_rank_runs(stage) : rank_zero_runs(stage);
  if (rc != 0) return rc;
  return rank_zero_runs([&] {
    io::write_file_atomically(stage_dir / "inputs.json", io::dump(s.inputs));
    return 0;
  });
}

} // namespace twinflow::study
