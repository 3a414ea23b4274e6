#include "study/ranks.hpp"

#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1 // the C API only (OpenMPI's C++ bindings warn)
#endif
#include <mpi.h>

#include <omp.h>

#include <chrono>
#include <exception>
#include <filesystem>
#include <thread>

#include "io/files.hpp"
#include "particle/decomposition.hpp"
#include "study/case.hpp"

namespace twinflow::study {

namespace {
int alone_depth = 0; // > 0: inside rank_zero_runs' work on rank 0
} // namespace

int rank_count() {
  return alone_depth > 0 ? 1 : particle::Slabs::world_size();
}

bool rank_zero_alone() {
  return alone_depth > 0;
}

bool on_rank_zero() {
  if (rank_count() == 1) return true;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank == 0;
}

io::Json execution_record(int dimension) {
  const int ranks = particle::Slabs::world_size();
  io::Json j = io::Json::object();
  j["ranks"] = ranks;
  j["threads_per_rank"] = omp_get_max_threads();
  const char* axis = dimension == 3 ? "z" : "y"; // the particle slabs' axis: the last one
  j["decomposition"] =
      ranks == 1 ? std::string("1 rank") : std::to_string(ranks) + " slabs along " + axis;
  return j;
}

std::string ranks_and_threads() {
  const int ranks = particle::Slabs::world_size();
  return std::to_string(ranks) + (ranks == 1 ? " rank x " : " ranks x ") +
         std::to_string(omp_get_max_threads()) + " threads";
}

int exit_code_of(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const io::InputError&) {
    return kExitBadInput;
  } catch (const io::OutputError&) {
    return kExitOutputFailed;
  } catch (const std::filesystem::filesystem_error&) {
    return kExitOutputFailed;
  } catch (...) {
    return kExitFailed;
  }
}

int rank_zero_runs(const std::function<int()>& work) {
  if (rank_count() == 1) return work();
  int code = 0;
  std::exception_ptr error;
  if (on_rank_zero()) {
    ++alone_depth;
    try {
      code = work();
    } catch (...) {
      error = std::current_exception();
      code = exit_code_of(error);
    }
    --alone_depth;
  }
  // The others wait without spinning: rank 0 may run a long serial stage on their cores.
  MPI_Request request;
  MPI_Ibcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  for (int done = 0; !done;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (error) std::rethrow_exception(error);
  return code;
}

int every_rank_runs(const std::function<int()>& work) {
  if (rank_count() == 1) return work();
  int code = 0;
  std::exception_ptr error;
  try {
    code = work();
  } catch (...) {
    error = std::current_exception();
    code = exit_code_of(error);
  }
  int zero = code;
  MPI_Bcast(&zero, 1, MPI_INT, 0, MPI_COMM_WORLD);
  int largest = code;
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  // Rank 0 prints its own failure; another rank prints its own only when rank 0 did not fail.
  if (error && (on_rank_zero() || zero == 0)) std::rethrow_exception(error);
  return zero != 0 ? zero : largest;
}

std::string from_rank_zero(const std::string& text) {
  if (rank_count() == 1) return text;
  unsigned long size = text.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  std::string out = on_rank_zero() ? text : std::string(size, '\0');
  MPI_Bcast(out.data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD);
  return out;
}

double from_rank_zero(double value) {
  if (rank_count() == 1) return value;
  MPI_Bcast(&value, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return value;
}

} // namespace twinflow::study
