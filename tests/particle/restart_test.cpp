// Checkpoint and restart: a run stopped (at any step, more than once) and continued from its
// checkpoint gives byte-identical time series, fields and histograms to an uninterrupted run.
#include <gtest/gtest.h>

#include <omp.h>

#include <optional>
#include <string>

#include "helpers.hpp"
#include "particle/run.hpp"

using namespace twinflow::particle;
using twinflow::io::Checkpoint;

namespace {

// Runs p, stopping after each step in `stops` and continuing from the checkpoint written then
// (through its serialised bytes, as a file would hold them).
RunOutput run_with_stops(const ParticleParameters& p, const std::vector<long>& stops) {
  std::optional<Checkpoint> saved;
  std::size_t next = 0;
  long steps = 0;
  for (;;) {
    RunControl control;
    std::optional<Checkpoint> resumed = saved;
    control.resume = resumed ? &*resumed : nullptr;
    control.stop_requested = [&] { return next < stops.size() && ++steps == stops[next]; };
    control.write_checkpoint = [&](const Checkpoint& c) {
      saved = Checkpoint::deserialize(c.serialize(), "test");
    };
    RunOutput out = run_particles(p, control);
    if (!out.interrupted) return out;
    EXPECT_EQ(out.steps_done, stops[next]);
    ++next;
  }
}

void expect_identical(const RunOutput& a, const RunOutput& b) {
  EXPECT_EQ(a.thermo_csv, b.thermo_csv);
  EXPECT_EQ(a.fields_csv, b.fields_csv);
  EXPECT_EQ(a.slab_profile_csv, b.slab_profile_csv);
  EXPECT_EQ(a.histograms_csv, b.histograms_csv);
  EXPECT_EQ(a.rdf_csv, b.rdf_csv);
  EXPECT_EQ(a.correlations_csv, b.correlations_csv);
  EXPECT_EQ(a.blocks_csv, b.blocks_csv);
  EXPECT_EQ(a.wall_layers_csv, b.wall_layers_csv);
  EXPECT_EQ(a.relaxation_csv, b.relaxation_csv);
  ASSERT_EQ(a.field_snapshots.size(), b.field_snapshots.size());
  for (std::size_t k = 0; k < a.field_snapshots.size(); ++k) {
    const auto &sa = a.field_snapshots[k], &sb = b.field_snapshots[k];
    EXPECT_EQ(sa.time, sb.time);
    EXPECT_EQ(sa.particle_steps, sb.particle_steps);
    ASSERT_EQ(sa.fields.size(), sb.fields.size());
    for (std::size_t f = 0; f < sa.fields.size(); ++f) {
      EXPECT_EQ(sa.fields[f].values, sb.fields[f].values) << sa.fields[f].name;
      EXPECT_EQ(sa.fields[f].standard_error, sb.fields[f].standard_error) << sa.fields[f].name;
    }
  }
  // Every number of the summary but the timings (every diagnostic's checkpoint part).
  auto results = [](twinflow::io::Json j) {
    j.erase("wall_seconds"), j.erase("particle_steps_per_second");
    return j.dump();
  };
  EXPECT_EQ(results(a.summary), results(b.summary));
}

} // namespace

// Walls (thermal and adiabatic, no-slip), gravity and 2D bins: the heated cavity's machinery.
TEST(Restart, CavityContinuesBitwise) {
  ParticleParameters p = twinflow::particle::testing::ideal(2, Integrator::Shardlow, 10);
  p.box = {{8, 8, 1}};
  p.walls[0] = WallPair{true, {{true, true}}, {{1.5, 0.5}}, true};
  p.walls[1] = WallPair{true, {{false, false}}, {{1, 1}}, true};
  p.gravity = {{0, -0.05, 0}};
  p.bins = {{4, 4, 1}};
  p.equilibration_steps = 60, p.steps = 300, p.sample_interval = 7, p.blocks = 4;
  p.correlation_samples = 10;
  const RunOutput whole = run_particles(p);
  expect_identical(whole, run_with_stops(p, {1, 59, 137, 138, 299}));
}

// The walls' loops split over the threads (Simulation::for_particles_tallied) give the one-thread
// bytes, the walls' tallies included: each integrator on the cavity above, and shardlow with a
// repelling wall material (a conservative force).
TEST(Restart, CavityIsTheSameWhateverTheThreads) {
  struct Case {
    Integrator integrator;
    bool repulsive;
  };
  for (const Case c : {Case{Integrator::Shardlow, false}, Case{Integrator::EcVerlet, false},
                       Case{Integrator::Euler, false}, Case{Integrator::Shardlow, true}}) {
    ParticleParameters p = twinflow::particle::testing::ideal(2, c.integrator, 10);
    p.box = {{8, 8, 1}};
    p.walls[0] = WallPair{true, {{true, true}}, {{1.5, 0.5}}, true};
    p.walls[1] = WallPair{true, {{false, false}}, {{1, 1}}, true};
    p.walls[0].conduction = {{30, 30}};
    if (c.repulsive) p.conservative = ConservativeForce::Constant, p.a0 = 5;
    p.gravity = {{0, -0.05, 0}};
    p.bins = {{4, 4, 1}};
    p.equilibration_steps = 20, p.steps = 200, p.sample_interval = 7, p.blocks = 4;
    const int threads_before = omp_get_max_threads();
    omp_set_num_threads(1);
    const RunOutput one = run_particles(p);
    for (const int threads : {2, 3}) {
      SCOPED_TRACE(std::string(to_string(c.integrator)) + (c.repulsive ? ", repulsive" : "") +
                   ", " + std::to_string(threads) + " threads");
      omp_set_num_threads(threads);
      expect_identical(one, run_particles(p));
    }
    omp_set_num_threads(threads_before);
  }
}

// Heat slabs, conservative a_T forces, ec-verlet: the slab profile and the flux parts too.
TEST(Restart, SlabContinuesBitwise) {
  ParticleParameters p = twinflow::particle::testing::seed002(Integrator::EcVerlet, 0.01);
  p.box = {{8, 4, 4}};
  p.heat_slabs = {HeatSlab{0, 4, 4.5, 20}, HeatSlab{0, 0, 0.5, -20}};
  p.bins = {{4, 1, 1}};
  p.equilibration_steps = 20, p.steps = 100, p.sample_interval = 5, p.blocks = 4;
  const RunOutput whole = run_particles(p);
  ASSERT_FALSE(whole.slab_profile_csv.empty());
  expect_identical(whole, run_with_stops(p, {33, 71}));
}

// The heat and shear modes of a relaxation scene, sampled from the first step.
TEST(Restart, RelaxationContinuesBitwise) {
  ParticleParameters p = twinflow::particle::testing::ideal(3, Integrator::Shardlow, 10);
  p.temperature_perturbation = 0.2, p.shear_perturbation = 0.5;
  p.bins = {{6, 1, 1}};
  p.equilibration_steps = 0, p.steps = 120, p.sample_interval = 3, p.blocks = 4;
  const RunOutput whole = run_particles(p);
  ASSERT_FALSE(whole.relaxation_csv.empty());
  expect_identical(whole, run_with_stops(p, {2, 3, 61}));
}
