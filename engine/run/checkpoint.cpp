#include "run/checkpoint.hpp"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <type_traits>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/binary_io.hpp"
#include "core/errors.hpp"
#include "core/input_file.hpp"
#include "run/run_loop.hpp"

namespace fluidbed {

namespace fs = std::filesystem;

namespace {

constexpr const char* kRunTag = "FLBRUN02";
static_assert(std::is_trivially_copyable_v<CouplingDiagnostics>);

fs::path folder_of(const std::string& run_dir) {
  return fs::path(run_dir) / "checkpoint";
}

// A checkpoint replaced by a newer one is renamed aside before the new one takes its name: a
// process killed between the two renames leaves only that one.
fs::path aside_folder(const std::string& run_dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(run_dir, ec))
    if (e.path().filename().string().rfind("checkpoint.old.", 0) == 0 && e.is_directory())
      return e.path();
  return {};
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
  out.flush();
  if (!out) throw InputError("cannot write " + p.string());
}

// run.bin's head: what the simulation's state file does not hold.
struct RunHeader {
  double wall = 0.0;
  std::uint64_t hash = 0;
  CouplingDiagnostics coupling;
  EnergyLedger ledger;

  template <class Archive>
  void fields(Archive& a) {
    a(wall, hash, coupling, ledger);
  }
};

RunHeader read_header(BinarySource& src) {
  src.tag(kRunTag, "run checkpoint");
  RunHeader h;
  src(h);
  return h;
}

}  // namespace

void write_checkpoint(const std::string& run_dir, const Simulation& sim,
                      const RunRecorder& recorder, double wall, const std::string& scene_toml,
                      const nlohmann::json& options, bool bubbles,
                      const std::function<void(const std::string&)>& add_files) {
  const fs::path dir = folder_of(run_dir);
  const fs::path tmp = partial_name((fs::path(run_dir) / "checkpoint").string());
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) throw InputError("cannot create " + tmp.string() + ": " + ec.message());
  sim.save_state((tmp / "state.bin").string());
  {
    const fs::path p = tmp / "run.bin";
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    BinarySink sink(out);
    sink.tag(kRunTag);
    RunHeader h{wall, sim.state_hash(), sim.coupling_diagnostics(), sim.dem().energy_ledger()};
    sink(h);
    recorder.save(sink);
    out.flush();
    if (!out) throw InputError("cannot write " + p.string());
  }
  std::string csv = timeseries_header(bubbles, recorder.probes().size());
  for (const TimeseriesRow& row : recorder.rows()) csv += timeseries_line(row, bubbles);
  write_text(tmp / "timeseries.csv", csv);
  write_text(tmp / "scene.toml", "# the scene as run, every value resolved\n" + scene_toml);
  write_text(tmp / "options.json", options.dump(2) + "\n");
  nlohmann::json where;
  where["t_s"] = sim.time();
  where["step"] = sim.steps();
  if (sim.has_gas()) where["steps_since_gas_step"] = sim.steps_since_gas_step();
  where["wall_time_s"] = wall;
  write_text(tmp / "where.json", where.dump(2) + "\n");
  if (add_files) add_files(tmp.string());
  // The new checkpoint takes the name; the old one, renamed aside first, goes after.
  const fs::path old = fs::path(run_dir) / ("checkpoint.old." + std::to_string(::getpid()));
  fs::remove_all(old, ec);
  if (fs::exists(dir)) {
    fs::rename(dir, old, ec);
    if (ec) throw InputError("cannot replace " + dir.string() + ": " + ec.message());
  }
  fs::rename(tmp, dir, ec);
  if (ec) throw InputError("cannot write " + dir.string() + ": " + ec.message());
  fs::remove_all(old, ec);
}

Checkpoint read_checkpoint(const std::string& run_dir) {
  std::error_code ec;
  if (!fs::exists(run_dir, ec)) throw InputError("cannot resume " + run_dir + ": no such folder");
  if (!fs::is_directory(run_dir, ec))
    throw InputError("cannot resume " + run_dir +
                     ": it is not a folder (give the run's output folder)");
  fs::path dir = folder_of(run_dir);
  if (!fs::is_directory(dir, ec)) dir = aside_folder(run_dir);
  if (dir.empty() || !fs::exists(dir / "run.bin", ec))
    throw InputError("cannot resume " + run_dir + ": it holds no checkpoint (" +
                     folder_of(run_dir).string() + " is missing)");
  Checkpoint c;
  c.folder = dir.string();
  {
    std::ifstream in = open_input_file((dir / "scene.toml").string(), "checkpoint scene");
    std::ostringstream text;
    text << in.rdbuf();
    c.scene_toml = text.str();
    const std::string head = "# the scene as run, every value resolved\n";
    if (c.scene_toml.rfind(head, 0) == 0) c.scene_toml.erase(0, head.size());
  }
  {
    std::ifstream in = open_input_file((dir / "timeseries.csv").string(), "checkpoint timeseries");
    std::ostringstream text;
    text << in.rdbuf();
    c.timeseries_csv = text.str();
  }
  {
    const std::string p = (dir / "options.json").string();
    std::ifstream in = open_input_file(p, "checkpoint options");
    c.options = nlohmann::json::parse(in, nullptr, false);
    if (c.options.is_discarded() || !c.options.is_object())
      throw InputError(p + ": not a checkpoint's options (JSON object)");
  }
  if (std::ifstream in(dir / "job.json"); in) {
    c.job = nlohmann::json::parse(in, nullptr, false);
    if (c.job.is_discarded()) c.job = nullptr;
  }
  const std::string p = (dir / "run.bin").string();
  std::ifstream in = open_input_file(p, "checkpoint");
  BinarySource src(in, p);
  c.wall = read_header(src).wall;
  return c;
}

void restore_simulation(const Checkpoint& c, Simulation& sim) {
  const fs::path dir(c.folder);
  sim.load_state((dir / "state.bin").string());
  const std::string p = (dir / "run.bin").string();
  std::ifstream in = open_input_file(p, "checkpoint");
  BinarySource src(in, p);
  const RunHeader h = read_header(src);
  sim.set_coupling_diagnostics(h.coupling);
  sim.dem().set_energy_ledger(h.ledger);
  if (sim.state_hash() != h.hash)
    throw InputError(c.folder + ": the state loaded is not the state saved (state hash differs)");
}

void restore_recorder(const Checkpoint& c, RunRecorder& recorder) {
  const std::string p = (fs::path(c.folder) / "run.bin").string();
  std::ifstream in = open_input_file(p, "checkpoint");
  BinarySource src(in, p);
  read_header(src);
  recorder.restore(src);
}

bool has_checkpoint(const std::string& run_dir) {
  std::error_code ec;
  fs::path dir = folder_of(run_dir);
  if (!fs::is_directory(dir, ec)) dir = aside_folder(run_dir);
  return !dir.empty() && fs::exists(dir / "run.bin", ec);
}

void remove_checkpoint(const std::string& run_dir) {
  std::error_code ec;
  fs::remove_all(folder_of(run_dir), ec);
  // With the ones set aside, and the half-written ones of a process killed while writing.
  std::vector<fs::path> leftovers;
  for (const auto& e : fs::directory_iterator(run_dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("checkpoint.old.", 0) == 0 || name.rfind("checkpoint.partial.", 0) == 0)
      leftovers.push_back(e.path());
  }
  for (const fs::path& p : leftovers) fs::remove_all(p, ec);
  remove_partial_files(run_dir);
}

void remove_partial_files(const std::string& run_dir) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (const fs::path& dir : {fs::path(run_dir), fs::path(run_dir) / "frames",
                             fs::path(run_dir) / "vtk"}) {
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      if (!e.is_regular_file(ec)) continue;
      const std::string name = e.path().filename().string();
      const std::optional<pid_t> owner = partial_owner(name);
      if (!owner) continue;
      const pid_t pid = *owner;
      // A live process's (this one's, or another's writing beside it) is being written.
      if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
      stale.push_back(e.path());
    }
  }
  for (const fs::path& p : stale) fs::remove(p, ec);
}

}  // namespace fluidbed
