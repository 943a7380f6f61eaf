#include "run/live_folder.hpp"

#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "run/run_loop.hpp"

namespace fluidbed {

namespace fs = std::filesystem;

LiveRunFolder::LiveRunFolder(std::string dir, const std::string& scene, bool bubbles,
                             std::size_t probes, double flush_interval,
                             const std::string& start_csv)
    : dir_(std::move(dir)),
      scene_(scene),
      bubbles_(bubbles),
      probes_(probes),
      flush_interval_(flush_interval) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw InputError("cannot create output folder " + dir_ + ": " + ec.message());
  fs::remove(fs::path(dir_) / "summary.json", ec);
  status("running", "");
  const std::string path = (fs::path(dir_) / "timeseries.csv").string();
  csv_ = std::fopen(path.c_str(), "w");
  if (!csv_) throw InputError("cannot write " + path);
  std::fputs(
      start_csv.empty() ? timeseries_header(bubbles_, probes_).c_str() : start_csv.c_str(), csv_);
  std::fflush(csv_);
  last_flush_ = std::chrono::steady_clock::now();
}

LiveRunFolder::~LiveRunFolder() { close(); }

void LiveRunFolder::close() {
  flush();
  if (csv_) std::fclose(csv_);
  csv_ = nullptr;
}

// Whole rows only: the rows since the last flush in one write, so that the file ends at the end
// of a row whenever the process dies.
void LiveRunFolder::flush() {
  if (!csv_ || pending_.empty()) return;
  std::fwrite(pending_.data(), 1, pending_.size(), csv_);
  std::fflush(csv_);
  pending_.clear();
}

void LiveRunFolder::row(const TimeseriesRow& r) {
  if (!csv_) return;
  pending_ += timeseries_line(r, bubbles_);
  t_ = r.t;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_flush_).count() >= flush_interval_) {
    flush();
    last_flush_ = now;
    status("running", "");  // with the time the timeseries has reached
  }
}

void LiveRunFolder::status(const char* state, const std::string& reason,
                           const nlohmann::json& extra) {
  nlohmann::json j;
  j["status"] = state;
  j["scene"] = scene_;
  j["t_s"] = t_;  // the last timeseries row's time
  if (!reason.empty()) j["reason"] = reason;
  if (std::string(state) == "running") {
    // Still so when the process is gone (kill -9, a crash, a power cut): then the run is
    // unfinished, and the timeseries holds what it computed up to t_s or a little beyond.
    j["pid"] = static_cast<long long>(::getpid());
    j["finished"] = false;
  } else {
    j["finished"] = std::string(state) == "completed";
  }
  for (const auto& [key, value] : extra.items()) j[key] = value;
  write_file_atomically((fs::path(dir_) / "status.json").string(),
                        [&](std::ostream& o) { o << j.dump(2) << "\n"; });
}

void LiveRunFolder::completed(double t, const nlohmann::json& extra) {
  pending_.clear();  // the finished run has rewritten timeseries.csv whole
  close();
  t_ = t;
  status("completed", "", extra);
}

void LiveRunFolder::interrupted(double t, const std::string& reason) {
  close();
  t_ = t;
  status("interrupted", reason);
}

void LiveRunFolder::failed(const std::string& reason, const nlohmann::json& extra) {
  close();
  status("failed", reason, extra);
}

}  // namespace fluidbed
