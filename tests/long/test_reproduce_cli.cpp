// `fluidbed reproduce` end to end on a small bed, interrupted and resumed: every figure (the
// bubble figures and the uniform-distributor run's included) and the report's table are made.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "../test_support.hpp"

using namespace fluidbed::testing;

TEST(ReproduceCli, WritesEveryFigureAndTheReportAfterAnInterrupt) {
  // The report is stopped by SIGTERM two seconds into the ideal case (after the paper's bed and
  // the uniform bed finished), then finished by `reproduce --resume DIR`, which keeps the
  // finished runs as they were and continues the stopped one from the checkpoint it wrote at the
  // interrupt.
  const auto dir = temp_dir("reproduce");
  const std::string out = (dir / "out.txt").string(), err = (dir / "err.txt").string();
  const std::string cmd =
      "sh -c '\"" + std::string(FLUIDBED_BINARY) + "\" reproduce --quick --threads 1 --out \"" +
      dir.string() +
      "\" --set particles.placement=lattice --set particles.count=300"
      " --set particles.fill_height=0.12 --set time.end=0.3 > \"" + out + "\" 2> \"" + err +
      "\" & p=$!; until grep -q \"== the ideal case\" \"" + out +
      "\" 2> /dev/null || ! kill -0 $p 2> /dev/null; do sleep 0.1; done; sleep 2; kill -TERM $p; "
      "wait $p; echo $? > \"" + (dir / "rc.txt").string() + "\"'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  ASSERT_EQ(std::stoi(read_file(dir / "rc.txt")), 130) << read_file(dir / "err.txt");
  EXPECT_NE(read_file(dir / "err.txt").find("resume with: fluidbed reproduce --resume"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "report.md"));
  const bool stopped_run_kept = std::filesystem::exists(dir / "ideal/checkpoint/run.bin") ||
                                std::filesystem::exists(dir / "ideal_geometric/checkpoint/run.bin");
  EXPECT_TRUE(stopped_run_kept);
  // Every seed's run is in its folder of the ensemble (paper_bed/seeds/S/); --quick runs seed 1.
  const auto paper_written =
      std::filesystem::last_write_time(dir / "paper_bed/seeds/1/summary.json");
  const CommandResult r = run_fluidbed("reproduce --resume " + dir.string(), "reproduce");
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_EQ(std::filesystem::last_write_time(dir / "paper_bed/seeds/1/summary.json"),
            paper_written);
  for (const char* run : {"ideal/checkpoint", "ideal_geometric/checkpoint"})
    EXPECT_FALSE(std::filesystem::exists(dir / run)) << run;
  for (const char* f : {"report.md", "sweep/sweep.png", "sweep/sweep.csv", "sweep/summary.json",
                        "paper_bed/seeds/1/dp.png", "paper_bed/seeds/1/overlap.png",
                        "paper_bed/seeds/1/trajectory.png", "paper_bed/summary.json",
                        "paper_bed/seeds/1/bubbles.png", "paper_bed/seeds/1/bubbles.csv",
                        "paper_bed/seeds/1/dp_spectrum.png", "paper_bed/seeds/1/mixing.png",
                        "uniform/seeds/1/dp.png", "uniform/summary.json",
                        "uniform/seeds/1/bubbles.png", "ideal/dp.png", "ideal/summary.json",
                        "ideal/bubbles.png", "studies/integrators/stability.png",
                        "studies/coupling/pareto.png", "studies/failures/study.csv"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  const std::string report = read_file(dir / "report.md");
  for (const char* row :
       {"U_mf", "mean dp at 2.8 m/s, uniform distributor", "mean dp at 2.8 m/s, central jet",
        "jetted bed: regime", "jetted bed: eruptions against the dominant frequency",
        "uniform distributor: mean rise velocity", "start-up peak", "max overlap ratio at start-up",
        "ideal case", "cost of 1 s", "wall time of this report", "particles.count=300",
        "## Studies", "Integrators and time step", "from 1 packing (lattice seed",
        "`--quick` runs one", "## The second bed: van Wachem et al. (2001)",
        "Not run: `--quick` leaves it out."})
    EXPECT_NE(report.find(row), std::string::npos) << row;
}
