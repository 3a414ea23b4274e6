#pragma once
// Runs a shipped case through the twinflow binary and reads its particle summary.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "../run_twinflow.hpp"
#include "io/files.hpp"
#include "io/json.hpp"

namespace twinflow::testing {

inline std::string case_path(const std::string& name) {
  return std::string(TWINFLOW_SOURCE_DIR) + "/cases/" + name + ".prm";
}

// Runs `twinflow particle CASE --out DIR extra` and returns the particle stage's "results".
inline io::Json run_case(const std::string& name, const std::string& extra,
                         std::filesystem::path* dir_out = nullptr) {
  const auto dir = fresh_dir("scenes", name);
  const Result r =
      run_twinflow("particle " + case_path(name) + " --out " + dir.string() + " " + extra);
  EXPECT_EQ(r.code, 0) << r.output;
  if (dir_out) *dir_out = dir;
  if (r.code != 0) return io::Json::object();
  std::cout << r.output;
  const io::Json summary = io::read_json(dir / "particle" / "summary.json");
  return *twinflow::io::find(summary, {"results"});
}

// The number at "results.walls.x_lower.pressure": a test fails where it is absent.
inline double number(const io::Json& j, const std::string& dotted) {
  std::vector<std::string> path;
  for (std::size_t start = 0, dot = 0; dot != std::string::npos; start = dot + 1) {
    dot = dotted.find('.', start);
    path.push_back(dotted.substr(start, dot - start));
  }
  const io::Json* v = io::find(j, path);
  EXPECT_TRUE(v && v->is_number()) << dotted;
  return v && v->is_number() ? v->get<double>() : std::nan("");
}

} // namespace twinflow::testing
