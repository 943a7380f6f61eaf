#pragma once
// A run's output folder while the run goes, so that a run stopped by any means (an interrupt, a
// failure, kill -9, a power cut) leaves what it computed and says that it did not finish:
//   DIR/status.json     {"status": "running" | "completed" | "interrupted" | "failed",
//                        "finished": bool, "t_s": the timeseries' last time, "reason", and "pid"
//                        while running; the run's end adds its wall time, job digest and
//                        result (run/run_folder.hpp: the finished marker)}, replaced atomically at
//                        each change and each flush; a folder whose status says "running" but
//                        whose process is gone holds an unfinished run (killed, crashed);
//   DIR/timeseries.csv  the rows appended as they are recorded, flushed to the system at least
//                        every flush_interval wall seconds; the finished run rewrites it whole
//                        (the same bytes) with its other files.
// A summary.json left in DIR by an earlier run is removed at the start: the folder never holds a
// summary that is not this run's finished result.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "run/recorder.hpp"

namespace fluidbed {

class LiveRunFolder {
 public:
  // Creates DIR, removes an old summary.json, writes status "running" and the timeseries header.
  // Throws InputError when the folder or its files cannot be written.
  // A resumed run (run/checkpoint.hpp) passes the checkpoint's timeseries.csv as `start_csv`
  // (header included): the live file starts again from it, dropping any rows written after the
  // checkpoint by the process that stopped. `probes`: the timeseries' probe columns.
  LiveRunFolder(std::string dir, const std::string& scene, bool bubbles, std::size_t probes = 0,
                double flush_interval = 1.0, const std::string& start_csv = {});
  ~LiveRunFolder();
  LiveRunFolder(const LiveRunFolder&) = delete;
  LiveRunFolder& operator=(const LiveRunFolder&) = delete;

  // One more row of the timeseries.
  void row(const TimeseriesRow& r);
  // The run's end, after its outputs are written (completed), or without them; `extra`'s keys
  // go into status.json beside the status.
  void completed(double t, const nlohmann::json& extra = nlohmann::json::object());
  void interrupted(double t, const std::string& reason);
  void failed(const std::string& reason, const nlohmann::json& extra = nlohmann::json::object());

 private:
  void status(const char* state, const std::string& reason,
              const nlohmann::json& extra = nlohmann::json::object());
  void flush();
  void close();

  std::string dir_, scene_;
  bool bubbles_ = false;
  std::size_t probes_ = 0;
  double flush_interval_ = 1.0;
  std::FILE* csv_ = nullptr;
  std::string pending_;  // rows not yet written
  double t_ = 0.0;  // s, the last row's time
  std::chrono::steady_clock::time_point last_flush_;
};

}  // namespace fluidbed
