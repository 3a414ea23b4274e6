#pragma once
// The resolved case as typed JSON, RUNDIR/case.json: the parameter structs member by member
// (io/json_fields.hpp), beside the text record of every key (provenance). `twinflow run` writes
// it before its twins, `twinflow continuum` after its twin; `twinflow compare RUNDIR` reads it
// back: the structs as they ran, without the case file's text.

#include <filesystem>
#include <vector>

#include "io/json.hpp"
#include "study/case.hpp"

namespace twinflow::study {

io::Json case_parameters_json(const CaseParameters&);
// Throws io::InputError naming the member that does not read.
CaseParameters case_parameters_from_json(const io::Json&);

// RUNDIR/case.json, written atomically.
std::filesystem::path case_record_file(const std::filesystem::path& run_dir);
void write_case_record(const Case& c, const std::filesystem::path& run_dir);
// The case RUNDIR/case.json holds; throws io::InputError when it is missing or does not read.
Case read_case_record(const std::filesystem::path& run_dir);

} // namespace twinflow::study
