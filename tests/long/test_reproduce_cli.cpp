// `fluidbed reproduce` end to end on a small bed: every figure (the bubble figures and the
// uniform-distributor run's included) and the report's table are made.
#include <gtest/gtest.h>

#include <filesystem>

#include "../test_support.hpp"

using namespace fluidbed::testing;

TEST(ReproduceCli, WritesEveryFigureAndTheReport) {
  const auto dir = temp_dir("reproduce");
  const CommandResult r = run_fluidbed(
      "reproduce --quick --threads 1 --out " + dir.string() +
          " --set particles.placement=lattice --set particles.count=300"
          " --set particles.fill_height=0.12 --set time.end=0.3",
      "reproduce");
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  for (const char* f : {"report.md", "sweep/sweep.png", "sweep/sweep.csv", "sweep/summary.json",
                        "paper_bed/dp.png", "paper_bed/overlap.png", "paper_bed/trajectory.png",
                        "paper_bed/summary.json", "paper_bed/bubbles.png", "paper_bed/bubbles.csv",
                        "paper_bed/dp_spectrum.png", "paper_bed/mixing.png", "uniform/dp.png",
                        "uniform/summary.json", "uniform/bubbles.png", "ideal/dp.png",
                        "ideal/summary.json", "ideal/bubbles.png",
                        "studies/integrators/stability.png", "studies/coupling/pareto.png",
                        "studies/failures/study.csv"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  const std::string report = read_file(dir / "report.md");
  for (const char* row :
       {"U_mf", "mean dp at 2.8 m/s, uniform distributor", "mean dp at 2.8 m/s, central jet",
        "jetted bed: regime", "jetted bed: eruptions against the dominant frequency",
        "uniform distributor: mean rise velocity", "start-up peak", "max overlap ratio at start-up",
        "ideal case", "cost of 1 s", "wall time of this report", "particles.count=300",
        "## Studies", "Integrators and time step", "from 1 packing (lattice seed",
        "`--quick` runs one"})
    EXPECT_NE(report.find(row), std::string::npos) << row;
}
