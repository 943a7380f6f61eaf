#include "run/run_folder.hpp"

#include <time.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "core/hash.hpp"
#include "core/input_file.hpp"
#include "run/checkpoint.hpp"
#include "run/live_folder.hpp"
#include "run/packed_bed.hpp"
#include "scene/scene_loader.hpp"

namespace fluidbed {
namespace {

namespace fs = std::filesystem;

double thread_cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// What decides the run's bits besides the scene: kept in its checkpoint (job.json) and, as a
// digest, in its finished marker.
nlohmann::json job_identity(const RunJob& job, double until) {
  return {{"format", 1},
          {"until_s", until},
          {"bubbles", job.bubbles},
          {"start_state", job.start_state.empty() ? std::string() : file_digest(job.start_state)}};
}

// A resumed job's checkpoint must be of the same run: InputError naming what changed.
void check_same_job(const std::string& dir, const Checkpoint& c, const std::string& scene_toml,
                    const nlohmann::json& identity) {
  const std::string head = "cannot resume " + dir + ": ";
  if (c.scene_toml != scene_toml)
    throw InputError(head + "the scene is not the one the run started with (" +
                     first_difference(scene_toml, c.scene_toml) + ")");
  if (!c.job.is_object())
    throw InputError(head +
                     "its checkpoint was written by another version of fluidbed: run it "
                     "again from its start");
  for (const auto& [key, value] : identity.items())
    if (c.job.value(key, nlohmann::json()) != value)
      throw InputError(head + "its checkpoint is of another run (" + key + " " +
                       c.job.value(key, nlohmann::json()).dump() + ", now " + value.dump() + ")");
}

// A run that ended before (completed or failed) and is this job's: read back.
std::optional<RunEnd> read_back(const std::string& dir, const std::string& digest) {
  const std::optional<nlohmann::json> status = read_run_status(dir);
  if (!status || !run_ended(dir) || status->value("job", std::string()) != digest)
    return std::nullopt;  // none, or another run's: run it (again)
  RunEnd e;
  e.read_back = e.resumed = true;
  e.t = status->value("t_s", 0.0);
  e.wall = status->value("wall_time_s", 0.0);
  e.record = status->value("result", nlohmann::json::object());
  if (status->value("status", std::string()) == "failed") {
    e.how = RunEnd::How::failed;
    e.error = status->value("reason", std::string());
    return e;
  }
  std::ifstream in(fs::path(dir) / "summary.json");
  e.result.summary = nlohmann::json::parse(in, nullptr, false);
  if (!in || e.result.summary.is_discarded()) return std::nullopt;  // unreadable: run it again
  e.how = RunEnd::How::finished;
  return e;
}

// The marker of a run that failed before its live folder existed (a start that cannot be built).
void mark_failed(const std::string& dir, const std::string& scene, const std::string& reason,
                 const nlohmann::json& extra) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  LiveRunFolder live(dir, scene, false);
  live.failed(reason, extra);
}

}  // namespace

std::optional<nlohmann::json> read_run_status(const std::string& dir) {
  std::ifstream in(fs::path(dir) / "status.json");
  if (!in) return std::nullopt;
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  return j;
}

bool run_ended(const std::string& dir) {
  const std::optional<nlohmann::json> s = read_run_status(dir);
  if (!s) return false;
  const std::string status = s->value("status", std::string());
  return status == "completed" || status == "failed";
}

RunEnd run_in_folder(const std::string& dir, RunJob& job, const RunControl& control) {
  Settings& s = job.scene;
  const double until = job.until >= 0.0 ? job.until : s.time.end;
  const std::string scene_toml = to_toml(s);
  const nlohmann::json identity = job_identity(job, until);
  const std::string digest = hex_digest(scene_toml + identity.dump());
  if (control.resume)
    if (std::optional<RunEnd> done = read_back(dir, digest)) return std::move(*done);

  std::optional<Checkpoint> checkpoint;
  if (control.resume && has_checkpoint(dir)) {
    checkpoint = read_checkpoint(dir);
    check_same_job(dir, *checkpoint, scene_toml, identity);
  } else if (fs::exists(dir)) {
    remove_checkpoint(dir);  // an earlier run's: this one starts afresh
  }

  RunEnd end;
  end.resumed = checkpoint.has_value();
  const double wall_before = checkpoint ? checkpoint->wall : 0.0;
  const auto start = std::chrono::steady_clock::now();
  auto wall = [&] {
    return wall_before +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  auto marker = [&](nlohmann::json result) {
    return nlohmann::json{{"wall_time_s", wall()}, {"job", digest}, {"result", std::move(result)}};
  };
  std::optional<LiveRunFolder> live;
  try {
    prepare_packed_bed(s);
    Simulation sim(s);
    if (!job.start_state.empty()) sim.continue_from(job.start_state);
    if (checkpoint) restore_simulation(*checkpoint, sim);
    for (auto& o : job.outputs) {
      if (checkpoint)
        o->restore(checkpoint->folder, sim, until);
      else
        o->start(sim, until);
    }
    // The folder says what the run is doing while it runs (run/live_folder.hpp); its timeseries
    // has the recorder's probe columns (the scene's probes, measured in a gas only).
    const std::size_t probes = sim.has_gas() ? s.diagnostics.probes.size() : 0;
    live.emplace(dir, s.scene.name, job.bubbles, probes, 1.0,
                 checkpoint ? checkpoint->timeseries_csv : std::string());
    if (!job.scene_note.empty()) {
      std::ofstream scene_out(fs::path(dir) / "scene.toml");
      scene_out << job.scene_note << scene_toml;
    }
    RunOptions opt;
    opt.until = until;
    opt.bubbles = job.bubbles;
    if (!job.outputs.empty())
      opt.on_step = [&](const Simulation& x) {
        for (auto& o : job.outputs) o->observe(x);
      };
    opt.on_row = [&](const TimeseriesRow& row) { live->row(row); };
    opt.stop = control.stop;
    opt.progress = control.progress;
    // Checkpoints (run/checkpoint.hpp): periodic and at a stop, with the job's identity and the
    // outputs' state beside the run's.
    opt.checkpoint = [&](const Simulation& x, const RunRecorder& rec, double w) {
      write_checkpoint(dir, x, rec, w, scene_toml, job.started, job.bubbles,
                       [&](const std::string& folder) {
                         std::ofstream(fs::path(folder) / "job.json") << identity.dump(2) << "\n";
                         for (auto& o : job.outputs) o->save(folder);
                       });
    };
    opt.checkpoint_interval = control.checkpoint_every < 0.0 ? 60.0 : control.checkpoint_every;
    opt.checkpoint_min_run = control.checkpoint_every < 0.0 ? 120.0 : 0.0;
    if (checkpoint) {
      opt.restore = [&](RunRecorder& rec) { restore_recorder(*checkpoint, rec); };
      opt.wall_before = checkpoint->wall;
      if (control.log) {
        char line[96];
        std::snprintf(line, sizeof line, "resumed at t = %.6g s", sim.time());
        control.log(line);
      }
    }
    const double cpu0 = thread_cpu_now();
    end.result = run_simulation(sim, opt);
    end.cpu = thread_cpu_now() - cpu0;
    end.t = sim.time();
    if (!end.result.completed) {
      end.how = RunEnd::How::stopped;
      live->interrupted(sim.time(), control.stop_reason ? control.stop_reason() : "stopped");
      end.wall = wall();
      return end;
    }
    FinishedRun finished{dir, sim, end.result, end.record};
    for (auto& o : job.outputs) o->finish(finished);
    write_run_outputs(dir, end.result);
    if (!job.final_state.empty()) sim.save_state((fs::path(dir) / job.final_state).string());
    if (!s.diagnostics.save_state.empty())
      sim.save_state((fs::path(dir) / s.diagnostics.save_state).string());
    // The finished folder holds what an unstopped run's does: the checkpoint goes, then what it
    // named (a video's parts), and last the marker.
    remove_checkpoint(dir);
    for (auto& o : job.outputs) o->cleanup(dir);
    end.wall = wall();
    live->completed(sim.time(), marker(end.record));
  } catch (const SimulationFailure& e) {
    end.how = RunEnd::How::failed;
    end.error = e.what();
    end.wall = wall();
    if (live)
      live->failed(end.error, marker(nlohmann::json::object()));
    else
      mark_failed(dir, s.scene.name, end.error, marker(nlohmann::json::object()));
  }
  return end;
}

}  // namespace fluidbed
