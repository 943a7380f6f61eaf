// `run --resume` of a run with every output on (frames, video, VTK, montage, plots, bubbles and
// their outlines): stopped by SIGTERM, or killed with SIGKILL after a periodic checkpoint, and
// resumed, it ends with the files of the run that was never stopped: the same frames, VTK series,
// montage, plots, bubbles.csv, mixing.csv and timeseries.csv byte for byte, the same summary
// numbers, and a video with the same number of frames (joined from its parts without encoding
// again, so its bytes differ). What the killed process left half-written goes.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "../test_support.hpp"

using namespace fluidbed::testing;
namespace fs = std::filesystem;

namespace {

// 300 spheres of the paper landing on the jet, 0.3 s (20,000 steps, about a second of wall time):
// 31 frames at 0.01 s, the montage's first panel before the stops and its second after them.
std::string outputs_run(const fs::path& out) {
  return "run " + std::string(FLUIDBED_ASSET_DIR) +
         "/scenes/xu_yu_1997.toml --until 0.3 --set particles.placement=lattice"
         " --set particles.count=300 --set particles.fill_height=0.06 --set domain.height=0.3"
         " --set gas.cells_y=15 --set coupling.particle_steps_per_gas_step=20"
         " --set diagnostics.output_interval=1e-3 --set diagnostics.averaging_start=0.04"
         " --frames --video --vtk --montage 0.03,0.25 --plots --bubbles --bubble-outlines"
         " --frame-size 160x96 --frame-interval 0.01 --out \"" +
         out.string() + "\"";
}
constexpr int kResumeFrames = 31;

int frames_written(const fs::path& dir) {
  std::error_code ec;
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir / "frames", ec))
    if (e.path().extension() == ".png") ++n;
  return n;
}

// Every file under `dir`, by path relative to it (the test's captures left out).
std::set<std::string> files_under(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    names.insert(fs::relative(e.path(), dir).string());
  for (const char* shell : {"out.txt", "err.txt"}) names.erase(shell);
  return names;
}

nlohmann::json numbers_of(const fs::path& summary) {
  nlohmann::json j = nlohmann::json::parse(read_file(summary));
  for (const char* k : {"wall_time_s", "wall_s_per_sim_s", "particle_steps_per_s"}) j.erase(k);
  return j;
}

int video_frames(const fs::path& video) {
  const fs::path probe = video.parent_path() / "probe.txt";
  const std::string cmd =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
      "-of csv=p=0 \"" + video.string() + "\" > \"" + probe.string() + "\"";
  if (std::system(cmd.c_str()) != 0) return -1;
  const int n = std::stoi(read_file(probe));
  fs::remove(probe);
  return n;
}

// The resumed folder against the reference: the same files, the same bytes but for what measures
// the machine (summary's wall times, render.json, status.json) and the video's encoding.
void expect_same_outputs(const fs::path& ref, const fs::path& run) {
  const std::set<std::string> names = files_under(ref), got = files_under(run);
  for (const std::string& name : got)
    EXPECT_TRUE(names.count(name)) << run / name << " is not in the unstopped run's folder";
  for (const std::string& name : names)
    EXPECT_TRUE(got.count(name)) << run / name << " is missing";
  for (const std::string& name : names) {
    if (fs::is_directory(ref / name)) continue;
    if (name == "summary.json") {
      EXPECT_EQ(numbers_of(run / name), numbers_of(ref / name));
    } else if (name == "render.json") {
      const auto a = nlohmann::json::parse(read_file(ref / name));
      const auto b = nlohmann::json::parse(read_file(run / name));
      EXPECT_EQ(b["frames"], a["frames"]);
      EXPECT_EQ(b["vtk_snapshots"], a["vtk_snapshots"]);
    } else if (name == "status.json") {
      EXPECT_EQ(nlohmann::json::parse(read_file(run / name))["status"], "completed");
    } else if (name == "video.mp4") {
      EXPECT_EQ(video_frames(run / name), kResumeFrames);
    } else {
      EXPECT_TRUE(read_file(run / name) == read_file(ref / name)) << name << " differs";
    }
  }
}

}  // namespace

TEST(RunResumeOutputs, StoppedAndResumedRunsWriteTheUnstoppedRunsFiles) {
  const fs::path dir = temp_dir("run-resume-outputs");
  const fs::path ref = dir / "reference";
  const CommandResult whole = run_fluidbed(outputs_run(ref), "resume-outputs-ref");
  ASSERT_EQ(whole.status, 0) << whole.err;
  ASSERT_EQ(frames_written(ref), kResumeFrames);
  ASSERT_EQ(video_frames(ref / "video.mp4"), kResumeFrames);

  // SIGTERM once 8 frames are on disk (t >= 0.07 s: the montage's first panel taken, not its
  // second): the checkpoint written at the stop.
  const fs::path term = dir / "term";
  fs::create_directories(term);
  const TerminatedRun t = fluidbed_terminated(outputs_run(term), term,
                                              [&] { return frames_written(term) >= 8; });
  ASSERT_TRUE(t.terminated);
  ASSERT_EQ(t.status, 130) << read_file(term / "err.txt");
  EXPECT_NE(read_file(term / "err.txt").find("resume with: fluidbed run --resume"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(term / "summary.json"));
  EXPECT_TRUE(fs::exists(term / "checkpoint" / "pictures.bin"));
  EXPECT_TRUE(fs::exists(term / "checkpoint" / "tracks.bin"));
  // Output options given again must be the run's own (the default size too: it is not the run's).
  for (const char* size : {"320x240", "1280x720"}) {
    const CommandResult changed = run_fluidbed(
        "run --resume \"" + term.string() + "\" --frame-size " + size, "resume-size");
    EXPECT_EQ(changed.status, 2) << size;
    EXPECT_NE(changed.err.find("frame_size"), std::string::npos) << changed.err;
  }
  const CommandResult resumed = run_fluidbed("run --resume \"" + term.string() + "\"", "resume-t");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  expect_same_outputs(ref, term);

  // SIGKILL after a periodic checkpoint, with frames and a video part written after it: those
  // are written again from the checkpoint.
  const fs::path kill = dir / "kill";
  fs::create_directories(kill);
  const TerminatedRun k = fluidbed_terminated(
      outputs_run(kill) + " --checkpoint-every 0.05", kill,
      [&] { return frames_written(kill) >= 18 && fs::exists(kill / "checkpoint" / "run.bin"); },
      SIGKILL);
  ASSERT_TRUE(k.terminated);
  ASSERT_EQ(k.status, -1);
  // What a process killed while writing a checkpoint leaves (the kill may also have fallen there):
  // the finished run removes it.
  fs::create_directories(kill / "checkpoint.partial.1");
  write_file(kill / "checkpoint.partial.1" / "state.bin", "half");
  // And a frame it was writing (named after a process that has ended); one of a live process's
  // stays.
  const pid_t ended = ::fork();
  if (ended == 0) ::_exit(0);
  ASSERT_GT(ended, 0);
  ::waitpid(ended, nullptr, 0);
  const fs::path half = kill / "frames" / ("frame_000019.png.partial." + std::to_string(ended));
  const fs::path live =
      kill / "frames" / ("frame_000019.png.partial." + std::to_string(::getpid()));
  write_file(half, "half");
  write_file(live, "half");
  const CommandResult finished = run_fluidbed("run --resume \"" + kill.string() + "\"", "resume-k");
  ASSERT_EQ(finished.status, 0) << finished.err;
  EXPECT_FALSE(fs::exists(half));
  EXPECT_TRUE(fs::exists(live));
  fs::remove(live);
  expect_same_outputs(ref, kill);
}
