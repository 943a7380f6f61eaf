// fluidbed._core: the native half of the Python module (`import fluidbed`), another front end over
// the engine beside the command line. A Simulation of a scene file stepped from Python, its state
// as NumPy arrays, pictures from the offscreen renderer, and the command line's verbs (run, sweep,
// study, keys) called as they are. app/python/fluidbed/__init__.py is the face users see: it turns
// Python values into the command line's texts and the verbs' folders into dicts and columns.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "analysis/pressure_probe.hpp"
#include "build_info.hpp"
#include "cli/commands.hpp"
#include "cli/study.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"
#include "output/frames.hpp"
#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/renderer.hpp"
#include "run/bubble_recorder.hpp"
#include "run/recorder.hpp"
#include "run/run_loop.hpp"
#include "scene/scene_keys.hpp"
#include "scene/scene_loader.hpp"
#include "sim/checks.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot.hpp"
#include "view/session.hpp"

namespace py = pybind11;

namespace fluidbed::python {
namespace {

using Array = py::array_t<double>;

// A blow-up whose message already names its likely cause (failure_hint at the velocity in use).
struct HintedFailure : SimulationFailure {
  using SimulationFailure::SimulationFailure;
};

// A copy of `v` as a NumPy array of the given shape (the engine's buffer is not shared: the array
// stays valid after the next step).
Array copy_array(const std::vector<double>& v, std::vector<py::ssize_t> shape) {
  Array a(shape);
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// Columns side by side: an N x columns.size() array.
Array stack_columns(const std::vector<const std::vector<double>*>& columns) {
  const auto n = static_cast<py::ssize_t>(columns.front()->size());
  const auto m = static_cast<py::ssize_t>(columns.size());
  Array a({n, m});
  double* out = a.mutable_data();
  for (py::ssize_t i = 0; i < n; ++i)
    for (py::ssize_t k = 0; k < m; ++k)
      out[i * m + k] = (*columns[static_cast<std::size_t>(k)])[static_cast<std::size_t>(i)];
  return a;
}

// A scene file with the command line's --set texts, loaded and checked as `fluidbed run` does.
Settings load_checked(const std::string& scene, const std::vector<std::string>& overrides,
                      int threads) {
  Settings s = load_scene(scene, overrides);
  refuse_unsafe_scene(s);
  s.threads = threads;
  return s;
}

class PySimulation {
 public:
  PySimulation(const std::string& scene, const std::vector<std::string>& overrides, int threads)
      : settings_(load_checked(scene, overrides, threads)) {
    {
      py::gil_scoped_release free;  // a packing not yet cached takes minutes
      model_ = std::make_unique<app::ViewModel>(settings_);
    }
    check_start(model_->sim());
    start_recording();
  }

  // The measurements (summary, energy budget, timeseries) start afresh: at construction, and
  // when reset() or the ideal case replaces the simulation. A run of `fluidbed run` records the
  // same way (run/recorder.hpp), with no end step here.
  void start_recording() {
    recorder_ = std::make_unique<RunRecorder>(model_->sim(),
                                              std::numeric_limits<std::int64_t>::max());
    wall_ = 0.0;
  }

  // Steps until `last_step`, the GIL released, looking at Python's signals about ten times per
  // wall second: Ctrl+C raises KeyboardInterrupt between two steps, the state whole.
  // `progress` (may be None) is called with the simulated time between chunks.
  void step_to(std::int64_t last_step, const py::object& progress) {
    const RunOptions checks;
    Simulation& sim = model_->sim();  // rebuilt only by the controls, never while it steps
    try {
      step_chunks(sim, last_step, checks, progress);
    } catch (const SimulationFailure& e) {
      // The hint names the velocity in use, which the controls may have changed from the scene's.
      const double u = sim.has_gas() ? sim.gas()->superficial_velocity() : -1.0;
      throw HintedFailure(e.what() + failure_hint(e.what(), u));
    }
  }

  // step_to's loop: chunks of about 100 ms of stepping, Python's signals and progress between.
  void step_chunks(Simulation& sim, std::int64_t last_step, const RunOptions& checks,
                   const py::object& progress) {
    using Clock = std::chrono::steady_clock;
    while (sim.steps() < last_step) {
      snapshot_valid_ = false;
      {
        py::gil_scoped_release free;
        const auto start = Clock::now();
        const auto until = start + std::chrono::milliseconds(100);
        do {
          sim.step();
          if (recorder_->after_step(sim)) check_gas_step(sim, checks);
        } while (sim.steps() < last_step && Clock::now() < until);
        wall_ += std::chrono::duration<double>(Clock::now() - start).count();
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress.is_none()) progress(sim.time());
    }
  }

  void step(std::int64_t n) {
    if (n < 0) throw py::value_error("step(n): n must be 0 or more, got " + std::to_string(n));
    step_to(model_->sim().steps() + n, py::none());
  }

  void run(double until, const py::object& progress) {
    if (!(until >= 0.0)) throw py::value_error("run(until): until must be 0 s or more");
    step_to(steps_for(until, settings_.time.dt), progress);
  }

  const Snapshot& snapshot() {
    if (!snapshot_valid_) {
      take_snapshot(model_->sim(), snap_);
      snapshot_valid_ = true;
    }
    return snap_;
  }

  bool thick() const { return model_->sim().dem().particles().has_depth(); }

  // (N, 2) in a monolayer, (N, 3) in a thick slab.
  Array vectors(const std::vector<double>& a, const std::vector<double>& b,
                const std::vector<double>& c) {
    if (thick()) return stack_columns({&a, &b, &c});
    return stack_columns({&a, &b});
  }

  py::dict particles() {
    const Snapshot& s = snapshot();
    const auto n = static_cast<py::ssize_t>(s.particles());
    py::dict d;
    d["positions"] = vectors(s.x, s.y, s.z);
    d["velocities"] = vectors(s.vx, s.vy, s.vz);
    d["forces"] = vectors(s.fx, s.fy, s.fz);
    if (thick()) {
      d["spins"] = stack_columns({&s.spin_x, &s.spin_y, &s.spin});
      d["torques"] = stack_columns({&s.torque_x, &s.torque_y, &s.torque});
    } else {
      d["spins"] = copy_array(s.spin, {n});
      d["torques"] = copy_array(s.torque, {n});
    }
    d["radii"] = copy_array(s.radius, {n});
    py::array_t<std::int64_t> ids(n);
    for (py::ssize_t i = 0; i < n; ++i) ids.mutable_data()[i] = i;
    d["ids"] = ids;
    return d;
  }

  // None without gas.
  py::object gas() {
    const Snapshot& s = snapshot();
    if (!s.has_gas()) return py::none();
    const py::ssize_t nx = s.nx, ny = s.ny;
    py::dict d;
    // Cell centres: from `from`, (k + 1/2) cells of length/count (y from a plenum's bottom).
    const auto centres = [](py::ssize_t count, double from, double length) {
      std::vector<double> c(static_cast<std::size_t>(count));
      for (std::size_t k = 0; k < c.size(); ++k)
        c[k] = from + (static_cast<double>(k) + 0.5) * length / static_cast<double>(count);
      return copy_array(c, {count});
    };
    d["x"] = centres(nx, 0.0, s.width);
    d["y"] = centres(ny, s.gas_bottom, s.height - s.gas_bottom);
    d["u"] = copy_array(s.gas_ux, {ny, nx});
    d["v"] = copy_array(s.gas_uy, {ny, nx});
    d["p"] = copy_array(s.pressure, {ny, nx});
    d["porosity"] = copy_array(s.porosity, {ny, nx});
    return d;
  }

  // The bubble analysis of this state (analysis/bubbles.hpp, the scene's [bubbles] settings):
  // the regions found, bubbles and jet cavities, as `run --bubbles` finds them at its frames.
  // Calls in a row track the regions (ids, velocities) as the run's frames do.
  py::dict bubbles() {
    const BubbleFrame& f = analysed().frame();
    py::list regions;
    for (const Bubble& b : f.regions) {
      py::dict r;
      r["id"] = b.id;
      r["x"] = b.x;
      r["y"] = b.y;
      r["d_eq"] = b.d_eq;
      r["area"] = b.area;
      r["width"] = b.width;
      r["height"] = b.height;
      r["vx"] = b.has_velocity ? py::cast(b.vx) : py::none();
      r["vy"] = b.has_velocity ? py::cast(b.vy) : py::none();
      r["slug"] = b.slug;
      r["jet_cavity"] = b.touches_jet;
      regions.append(r);
    }
    py::dict d;
    d["t"] = f.t;
    d["regions"] = regions;
    d["spout"] = f.spout;
    d["median_speed"] = f.median_speed;
    d["surface"] = copy_array(f.surface, {static_cast<py::ssize_t>(f.surface.size())});
    return d;
  }

  // summary.json of the steps since the measurements started, as `fluidbed run` writes it.
  std::string summary() const { return recorder_->summary(model_->sim(), wall_).dump(); }

  // timeseries.csv of the steps since the measurements started: its header and rows as `fluidbed
  // run` writes them.
  std::string timeseries() const {
    std::string csv = timeseries_header(false, recorder_->probes().size());
    for (const TimeseriesRow& row : recorder_->rows()) csv += timeseries_line(row, false);
    return csv;
  }

  // Pa, each of diagnostics.probes now: the timeseries' p_probe_N of this state.
  std::vector<double> probes() const {
    std::vector<double> out;
    const Simulation& sim = model_->sim();
    if (!sim.has_gas()) return out;
    for (const ProbePoint& q : recorder_->probes())
      out.push_back(probe_pressure(sim.gas()->grid(), sim.gas()->pressure(), q.x, q.y));
    return out;
  }

  // The command line's frame of this state: `look` holds `run`'s picture options (--colour,
  // --frame-size, ...), checked as `run` checks them.
  py::array_t<std::uint8_t> render(const app::OutputArgs& look) {
    const app::FrameOptions fo = app::frame_options(look, app::asset_dir(), settings_);
    const Snapshot* s = &snapshot();
    Snapshot outlined;  // a copy only for the outlines
    if (fo.look.bubble_outlines) {
      outlined = *s;
      add_bubble_fields(analysed(), outlined);
      s = &outlined;
    }
    if (!context_ || context_->width() != fo.width || context_->height() != fo.height ||
        backend_ != fo.backend) {
      renderer_.reset();
      context_ = render::make_context(fo.backend, fo.width, fo.height);
      backend_ = fo.backend;
      renderer_ = std::make_unique<render::Renderer>(*context_, fo.font);
    }
    context_->make_current();
    const render::Image img = renderer_->render_frame(*s, fo.look, fo.width, fo.height);
    py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(img.height),
                                   static_cast<py::ssize_t>(img.width), py::ssize_t{3}});
    std::copy(img.rgb.begin(), img.rgb.end(), out.mutable_data());
    return out;
  }

  // The bubble analysis with a frame of the state now: one frame per simulated time (bubbles()
  // and a picture with outlines of the same state share it), started afresh when the time went
  // back (reset).
  const BubbleAnalysis& analysed() {
    const Simulation& sim = model_->sim();
    if (bubbles_ && sim.time() < analysed_t_) bubbles_.reset();
    if (!bubbles_) {
      bubbles_ = std::make_unique<BubbleAnalysis>(bubble_settings_for(settings_),
                                                  bubble_geometry_for(settings_));
      analysed_t_ = -1.0;
    }
    if (sim.time() != analysed_t_) {
      bubbles_->analyse(sim.time(), sim.dem().particles());
      analysed_t_ = sim.time();
    }
    return *bubbles_;
  }

  Simulation& sim() { return model_->sim(); }
  // The viewer's controls (app/view/session.hpp): the ideal case rebuilds the contact law and
  // carries the state across bit for bit; reset goes back to the starting state.
  app::ViewModel& model() {
    snapshot_valid_ = false;
    return *model_;
  }
  // A control that replaces the simulation (reset, the ideal case) starts the measurements afresh.
  void reset() {
    model().reset();
    start_recording();
  }
  void set_ideal(bool on) {
    if (on == model_->ideal()) return;
    model().set_ideal(on);
    start_recording();
  }
  const Settings& settings() const { return settings_; }

 private:
  Settings settings_;
  std::unique_ptr<app::ViewModel> model_;
  Snapshot snap_;
  bool snapshot_valid_ = false;
  std::unique_ptr<RunRecorder> recorder_;
  double wall_ = 0.0;  // s, stepping since the measurements started
  std::unique_ptr<BubbleAnalysis> bubbles_;
  double analysed_t_ = -1.0;  // s, the time of its last frame
  std::unique_ptr<render::GlContext> context_;
  std::unique_ptr<render::Renderer> renderer_;
  std::string backend_;
};

// A verb of the command line, the GIL released while it runs. Ctrl+C reaches it as it reaches the
// program (the verb's own handler: it stops with a checkpoint and returns 130).
template <class Args, class Verb>
int call_verb(const Args& args, Verb verb) {
  py::gil_scoped_release free;
  return verb(args);
}

}  // namespace
}  // namespace fluidbed::python

PYBIND11_MODULE(_core, m) {
  using namespace fluidbed;
  using namespace fluidbed::python;
  m.doc() = "The native half of fluidbed (import fluidbed instead).";
  // The verbs' lines a line at a time, as in a terminal: in Jupyter they reach the cell through a
  // pipe (fluidbed/__init__.py, _call_verb), whose block buffer would hold them to the end.
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  m.attr("__version__") = std::string(app::version());

  static py::exception<InputError> scene_error(m, "SceneError", PyExc_ValueError);
  static py::exception<SimulationFailure> simulation_error(m, "SimulationError",
                                                           PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(scene_error.ptr(), e.what());
    } catch (const HintedFailure& e) {
      PyErr_SetString(simulation_error.ptr(), e.what());
    } catch (const SimulationFailure& e) {
      PyErr_SetString(simulation_error.ptr(),
                      (std::string(e.what()) + failure_hint(e.what())).c_str());
    }
  });

  py::class_<app::OutputArgs>(m, "OutputArgs")
      .def(py::init<>())
      .def_readwrite("frames", &app::OutputArgs::frames)
      .def_readwrite("video", &app::OutputArgs::video)
      .def_readwrite("vtk", &app::OutputArgs::vtk)
      .def_readwrite("montage", &app::OutputArgs::montage)
      .def_readwrite("frame_interval", &app::OutputArgs::frame_interval)
      .def_readwrite("frame_size", &app::OutputArgs::frame_size)
      .def_readwrite("colour", &app::OutputArgs::colour)
      .def_readwrite("colour_range", &app::OutputArgs::colour_range)
      .def_readwrite("gas_arrows", &app::OutputArgs::gas_arrows)
      .def_readwrite("gas_arrow_colour", &app::OutputArgs::gas_arrow_colour)
      .def_readwrite("particle_arrows", &app::OutputArgs::particle_arrows)
      .def_readwrite("porosity_background", &app::OutputArgs::porosity_background)
      .def_readwrite("bubble_outlines", &app::OutputArgs::bubble_outlines)
      .def_readwrite("dark", &app::OutputArgs::dark)
      .def_readwrite("close_up", &app::OutputArgs::close_up)
      .def_readwrite("video_fps", &app::OutputArgs::video_fps)
      .def_readwrite("gl_backend", &app::OutputArgs::gl_backend);

  py::class_<PySimulation>(m, "Simulation")
      .def(py::init<const std::string&, const std::vector<std::string>&, int>(), py::arg("scene"),
           py::arg("overrides"), py::arg("threads"))
      .def("step", &PySimulation::step, py::arg("n"))
      .def("run", &PySimulation::run, py::arg("until"), py::arg("progress"))
      .def_property_readonly("time", [](PySimulation& s) { return s.sim().time(); })
      .def_property_readonly("steps", [](PySimulation& s) { return s.sim().steps(); })
      .def_property_readonly("dt", [](PySimulation& s) { return s.settings().time.dt; })
      .def_property_readonly("end_time", [](PySimulation& s) { return s.settings().time.end; })
      .def_property_readonly("dp", [](PySimulation& s) { return s.sim().pressure_drop(); })
      .def_property_readonly("state_hash", [](PySimulation& s) { return s.sim().state_hash(); })
      .def_property_readonly("scene_name",
                             [](PySimulation& s) { return s.settings().scene.name; })
      .def_property_readonly("scene_toml", [](PySimulation& s) { return to_toml(s.settings()); })
      .def_property(
          "superficial_velocity",
          [](PySimulation& s) {
            return s.sim().has_gas() ? s.sim().gas()->superficial_velocity() : 0.0;
          },
          [](PySimulation& s, double u) {
            if (!s.sim().has_gas()) throw InputError("this scene has no gas to set a velocity of");
            if (!(u >= 0.0)) throw InputError("superficial velocity must be 0 m/s or more");
            s.model().set_velocity(u);
          })
      .def_property(
          "ideal_collisions", [](PySimulation& s) { return s.model().ideal(); },
          [](PySimulation& s, bool on) { s.set_ideal(on); })
      .def("reset", &PySimulation::reset)
      .def("summary", &PySimulation::summary)
      .def("timeseries", &PySimulation::timeseries)
      .def("probes", &PySimulation::probes)
      .def_property_readonly("probe_points",
                             [](PySimulation& s) {
                               std::vector<std::pair<double, double>> out;
                               for (const ProbePoint& q : s.settings().diagnostics.probes)
                                 out.emplace_back(q.x, q.y);
                               return out;
                             })
      .def("particles", &PySimulation::particles)
      .def("gas", &PySimulation::gas)
      .def("render", &PySimulation::render, py::arg("look"))
      .def("bubbles", &PySimulation::bubbles);

  m.def("keys", [] {
    py::list out;
    for (const SceneKey& k : scene_keys()) {
      py::dict d;
      d["key"] = k.section + "." + k.name;
      d["type"] = k.type;
      d["default"] = k.default_value;
      d["unit"] = k.unit;
      d["range"] = k.range;
      d["help"] = k.help;
      py::dict choices;
      for (const auto& [name, help] : k.choices) choices[py::str(name)] = help;
      d["choices"] = choices;
      out.append(d);
    }
    return out;
  });

  py::class_<app::RunArgs>(m, "RunArgs")
      .def(py::init<>())
      .def_readwrite("scene", &app::RunArgs::scene)
      .def_readwrite("overrides", &app::RunArgs::overrides)
      .def_readwrite("until", &app::RunArgs::until)
      .def_readwrite("out", &app::RunArgs::out)
      .def_readwrite("threads", &app::RunArgs::threads)
      .def_readwrite("output", &app::RunArgs::output)
      .def_readwrite("plots", &app::RunArgs::plots)
      .def_readwrite("bubbles", &app::RunArgs::bubbles)
      .def_readwrite("seeds", &app::RunArgs::seeds)
      .def_readwrite("resume", &app::RunArgs::resume)
      .def_readwrite("threads_given", &app::RunArgs::threads_given)
      .def_readwrite("outputs_given", &app::RunArgs::outputs_given);
  m.def("run_command", [](const app::RunArgs& a) { return call_verb(a, app::run_command); });

  py::class_<app::SweepArgs>(m, "SweepArgs")
      .def(py::init<>())
      .def_readwrite("scene", &app::SweepArgs::scene)
      .def_readwrite("overrides", &app::SweepArgs::overrides)
      .def_readwrite("velocities", &app::SweepArgs::velocities)
      .def_readwrite("run_time", &app::SweepArgs::run_time)
      .def_readwrite("averaging_start", &app::SweepArgs::averaging_start)
      .def_readwrite("threads", &app::SweepArgs::threads)
      .def_readwrite("out", &app::SweepArgs::out)
      .def_readwrite("seeds", &app::SweepArgs::seeds)
      .def_readwrite("resume", &app::SweepArgs::resume)
      .def_readwrite("threads_given", &app::SweepArgs::threads_given)
      .def_readwrite("options_given", &app::SweepArgs::options_given);
  m.def("sweep_command", [](const app::SweepArgs& a) { return call_verb(a, app::sweep_command); });

  py::class_<app::StudyArgs>(m, "StudyArgs")
      .def(py::init<>())
      .def_readwrite("name", &app::StudyArgs::name)
      .def_readwrite("out", &app::StudyArgs::out)
      .def_readwrite("size", &app::StudyArgs::size)
      .def_readwrite("jobs", &app::StudyArgs::jobs)
      .def_readwrite("resume", &app::StudyArgs::resume)
      .def_readwrite("seeds", &app::StudyArgs::seeds)
      .def_readwrite("scene", &app::StudyArgs::scene)
      .def_readwrite("overrides", &app::StudyArgs::overrides)
      .def_readwrite("vary", &app::StudyArgs::vary)
      .def_readwrite("until", &app::StudyArgs::until);
  m.def("study_command", [](const app::StudyArgs& a) { return call_verb(a, app::study_command); });

  m.def("asset_dir", [] { return app::asset_dir(); });
  m.def("flush_output", [] {
    std::fflush(stdout);
    std::fflush(stderr);
  });
  m.def("write_png", [](const std::string& path,
                        const py::array_t<std::uint8_t, py::array::c_style>& rgb) {
    if (rgb.ndim() != 3 || rgb.shape(2) != 3)
      throw InputError("save_png: an (height, width, 3) uint8 array is needed");
    render::write_png(path, static_cast<int>(rgb.shape(1)), static_cast<int>(rgb.shape(0)),
                      rgb.data());
  });
}
