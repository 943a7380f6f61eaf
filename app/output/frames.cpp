#include "output/frames.hpp"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/atomic_file.hpp"
#include "core/binary_io.hpp"
#include "core/input_file.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"
#include "io/vtk_writer.hpp"
#include "run/bubble_recorder.hpp"
#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/renderer.hpp"
#include "render/video_writer.hpp"

namespace fluidbed::app {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr const char* kPicturesTag = "FLBPIC02";

// Decimals of "t = 7.32 s" that tell frames `interval` apart (two at least).
int time_decimals(double interval) {
  return std::clamp(static_cast<int>(std::ceil(-std::log10(interval) - 1e-9)), 2, 6);
}

}  // namespace

FrameOutput::FrameOutput(std::string out_dir, FrameOptions options, const Simulation& sim,
                         double until, const std::string& resume_from)
    : dir_(std::move(out_dir)), opt_(std::move(options)), dt_(sim.settings().time.dt) {
  if (!(opt_.interval > 0.0)) throw InputError("--frame-interval must be positive");
  if (opt_.width <= 0 || opt_.height <= 0) throw InputError("--frame-size must be positive");
  if (opt_.video && (opt_.width % 2 != 0 || opt_.height % 2 != 0))
    throw InputError("--video needs an even frame width and height (got " +
                     std::to_string(opt_.width) + "x" + std::to_string(opt_.height) + ")");
  if (opt_.queue < 1) opt_.queue = 1;
  if (opt_.vtk || opt_.look.bubble_outlines)
    bubbles_ = std::make_unique<BubbleAnalysis>(bubble_settings_for(sim.settings()),
                                                bubble_geometry_for(sim.settings()));
  opt_.look.time_decimals = time_decimals(opt_.interval);
  const bool resumed = !resume_from.empty();
  if (resumed) {
    const std::string p = (std::filesystem::path(resume_from) / "pictures.bin").string();
    std::ifstream in = open_input_file(p, "checkpoint pictures");
    BinarySource src(in, p);
    src.tag(kPicturesTag, "run's pictures");
    src(saved_);
    bool outlines = false;
    src(outlines);
    if (outlines != (bubbles_ != nullptr)) src.fail("inconsistent (bubble outlines)");
    if (bubbles_) bubbles_->restore(src);
    stats_ = saved_.stats;
    // Parts of the video a stopped process wrote after its last checkpoint are written again.
    std::error_code ec;
    for (int k = saved_.video_parts;
         std::filesystem::exists(video_part(k), ec) ||
         std::filesystem::exists(video_part(k) + ".part", ec);
         ++k) {
      std::filesystem::remove(video_part(k), ec);
      std::filesystem::remove(video_part(k) + ".part", ec);
    }
  }

  // Output times are steps: the nearest step to each time (within dt / 2), the same rounding the
  // run uses for its end, so the same command always gives the same frames. A resumed run
  // observed its checkpoint's step before it stopped.
  const std::int64_t first = sim.steps() + (resumed ? 1 : 0);
  const std::int64_t last = steps_for(until, dt_);
  if (opt_.frames || opt_.video || opt_.vtk) {
    const double t0 = static_cast<double>(first) * dt_;
    for (auto k = static_cast<std::int64_t>(std::ceil(t0 / opt_.interval - 1e-6));; ++k) {
      const std::int64_t n = steps_for(static_cast<double>(k) * opt_.interval, dt_);
      if (n > last) break;
      if (n >= first) due_.push_back({n, true, false});
    }
  }
  for (double t : opt_.montage) {
    const std::int64_t n = steps_for(t, dt_);
    if (resumed && n < first) continue;  // in the montage saved
    if (n < first || n > last) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "--montage time %g s is outside the run (%g to %g s)", t,
                    static_cast<double>(first) * dt_, static_cast<double>(last) * dt_);
      throw InputError(msg);
    }
    due_.push_back({n, false, true});
  }
  std::sort(due_.begin(), due_.end(), [](const Due& a, const Due& b) { return a.step < b.step; });
  std::vector<Due> merged;
  for (const Due& d : due_) {
    if (!merged.empty() && merged.back().step == d.step) {
      merged.back().frame = merged.back().frame || d.frame;
      merged.back().montage = merged.back().montage || d.montage;
    } else {
      merged.push_back(d);
    }
  }
  due_ = std::move(merged);

  worker_ = std::thread([this] { work(); });
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return ready_ || error_; });
  if (error_) {
    closing_ = true;
    lock.unlock();
    worker_.join();
    std::rethrow_exception(error_);
  }
}

FrameOutput::~FrameOutput() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    jobs_.clear();  // an aborted run: nothing more is drawn, the video is not finished
    if (!error_) error_ = std::make_exception_ptr(std::runtime_error("frame output stopped"));
  }
  changed_.notify_all();
  worker_.join();
}

void FrameOutput::rethrow_if_failed() {
  if (error_) std::rethrow_exception(error_);
}

void FrameOutput::observe(const Simulation& sim) {
  if (next_ >= due_.size() || due_[next_].step != sim.steps()) return;
  const Due due = due_[next_++];
  const auto t0 = Clock::now();
  std::shared_ptr<Snapshot> snap = channel_.acquire();
  take_snapshot(sim, *snap);
  if (bubbles_) add_bubble_fields(*bubbles_, sim, *snap);  // on the engine thread (about 2 ms)
  channel_.publish(snap);  // the newest state, for any live reader
  stats_.snapshot_s += seconds_since(t0);
  push({std::move(snap), due.frame, due.montage,
        steps_for(sim.time(), opt_.interval)});
}

void FrameOutput::push(Job job) {
  const auto t0 = Clock::now();
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] {
    return jobs_.size() < static_cast<std::size_t>(opt_.queue) || error_;
  });
  rethrow_if_failed();
  jobs_.push_back(std::move(job));
  lock.unlock();
  changed_.notify_all();
  stats_.wait_s += seconds_since(t0);
}

FrameStats FrameOutput::finish() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  worker_.join();
  rethrow_if_failed();
  return stats_;
}

void remove_video_parts(const std::string& dir) {
  std::error_code ec;
  std::filesystem::remove_all(std::filesystem::path(dir) / "video-parts", ec);
}

std::string FrameOutput::video_part(int k) const {
  char name[32];
  std::snprintf(name, sizeof name, "%03d.mp4", k);
  return (std::filesystem::path(dir_) / "video-parts" / name).string();
}

void FrameOutput::checkpoint(const std::string& folder) {
  Job job;
  job.checkpoint = true;
  push(std::move(job));
  Saved s;
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return checkpoint_done_ || error_; });
    rethrow_if_failed();
    checkpoint_done_ = false;
    s = saved_;
  }
  const std::string p = (std::filesystem::path(folder) / "pictures.bin").string();
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  BinarySink sink(out);
  sink.tag(kPicturesTag);
  // The engine thread's own costs are its, up to now.
  s.stats.snapshot_s = stats_.snapshot_s;
  s.stats.wait_s = stats_.wait_s;
  sink(s, bubbles_ != nullptr);
  if (bubbles_) bubbles_->save(sink);
  out.flush();
  if (!out) throw InputError("cannot write " + p);
}

// The worker: owns the GL context, the renderer, the video encoder and the VTK series.
void FrameOutput::work() {
  try {
    namespace fs = std::filesystem;
    std::unique_ptr<render::GlContext> context;
    std::unique_ptr<render::Renderer> renderer;
    std::optional<render::VideoWriter> video;
    std::optional<VtkSeries> vtk;
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) throw InputError("cannot create output folder " + dir_ + ": " + ec.message());
    if (opt_.needs_gl()) {
      context = render::make_context(opt_.backend, opt_.width, opt_.height);
      renderer = std::make_unique<render::Renderer>(*context, opt_.font);
      stats_.gl_version = context->version_string();
    }
    if (opt_.frames) {
      fs::create_directories(fs::path(dir_) / "frames", ec);
      if (ec) throw InputError("cannot create " + dir_ + "/frames: " + ec.message());
    }
    // The video is written in parts, one between checkpoints, joined at the end.
    int video_parts = saved_.video_parts;
    auto open_video = [&] {
      fs::create_directories(fs::path(dir_) / "video-parts", ec);
      if (ec) throw InputError("cannot create " + dir_ + "/video-parts: " + ec.message());
      video.emplace(video_part(video_parts), opt_.width, opt_.height, opt_.video_fps);
    };
    if (opt_.video) open_video();
    if (opt_.vtk) vtk.emplace((fs::path(dir_) / "vtk").string(), saved_.vtk);
    {
      std::lock_guard lock(mutex_);
      ready_ = true;
    }
    changed_.notify_all();

    std::vector<std::shared_ptr<const Snapshot>> montage = saved_.montage;
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [this] { return !jobs_.empty() || closing_; });
        if (jobs_.empty()) {
          if (error_) return;  // aborted
          break;
        }
        job = std::move(jobs_.front());
        jobs_.pop_front();
      }
      changed_.notify_all();
      if (job.checkpoint) {
        if (video && video->frames() > 0) {
          const auto t0 = Clock::now();
          video->close();
          video.reset();
          ++video_parts;
          stats_.video_s += seconds_since(t0);
        }
        {
          std::lock_guard lock(mutex_);
          // The worker's own figures (the engine thread keeps snapshot_s and wait_s).
          saved_.stats.frames = stats_.frames;
          saved_.stats.vtk_files = stats_.vtk_files;
          saved_.stats.render_s = stats_.render_s;
          saved_.stats.png_s = stats_.png_s;
          saved_.stats.video_s = stats_.video_s;
          saved_.stats.vtk_s = stats_.vtk_s;
          saved_.montage = montage;
          saved_.vtk = vtk ? vtk->written() : VtkSeries::Written{};
          saved_.video_parts = video_parts;
          checkpoint_done_ = true;
        }
        changed_.notify_all();
        continue;
      }
      if (job.frame && renderer) {
        auto t0 = Clock::now();
        const render::Image img = renderer->render_frame(*job.snapshot, opt_.look, opt_.width, opt_.height);
        stats_.render_s += seconds_since(t0);
        if (opt_.frames) {
          t0 = Clock::now();
          char name[32];
          std::snprintf(name, sizeof name, "frame_%06lld.png", static_cast<long long>(job.index));
          render::write_png((fs::path(dir_) / "frames" / name).string(), img);
          stats_.png_s += seconds_since(t0);
        }
        if (opt_.video) {
          t0 = Clock::now();
          if (!video) open_video();
          video->write(img);
          stats_.video_s += seconds_since(t0);
        }
        ++stats_.frames;
      }
      if (job.frame && vtk) {
        const auto t0 = Clock::now();
        vtk->write(*job.snapshot);
        stats_.vtk_s += seconds_since(t0);
        ++stats_.vtk_files;
      }
      if (job.montage) montage.push_back(job.snapshot);
    }
    if (!montage.empty()) {
      std::vector<const Snapshot*> panels;
      for (const auto& s : montage) panels.push_back(s.get());
      render::write_png((fs::path(dir_) / "montage.png").string(),
                        renderer->render_montage(panels, opt_.look, opt_.height));
    }
    if (opt_.video) {
      const auto t0 = Clock::now();
      if (video && (video->frames() > 0 || video_parts == 0)) {
        video->close();
        ++video_parts;
      }
      video.reset();
      std::vector<std::string> parts;
      for (int k = 0; k < video_parts; ++k) parts.push_back(video_part(k));
      render::join_videos(parts, (fs::path(dir_) / "video.mp4").string());
      stats_.video_s += seconds_since(t0);
    }
  } catch (...) {
    {
      std::lock_guard lock(mutex_);
      if (!error_) error_ = std::current_exception();
      jobs_.clear();
    }
    changed_.notify_all();
  }
}

}  // namespace fluidbed::app

namespace fluidbed::app {
namespace {

// "A,B,C" as numbers; InputError naming the option on anything else.
std::vector<double> parse_list(const std::string& text, const std::string& option) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v))
      throw InputError(option + " expects numbers separated by commas, got '" + text + "'");
    values.push_back(v);
    start = end + 1;
  }
  return values;
}

}  // namespace

double gas_arrow_reference(const Settings& scene) {
  return render::gas_arrow_reference_for(scene.gas.enabled ? scene.inlet.superficial_velocity
                                                           : 0.0);
}

FrameOptions frame_options(const OutputArgs& a, const std::string& assets, const Settings& scene) {
  FrameOptions o;
  o.frames = a.frames;
  o.video = a.video;
  o.vtk = a.vtk;
  if (!a.montage.empty()) o.montage = parse_list(a.montage, "--montage");
  o.interval = a.frame_interval;
  if (!(o.interval > 0.0)) throw InputError("--frame-interval must be positive");
  {
    int w = 0, h = 0;
    char extra = 0;
    if (std::sscanf(a.frame_size.c_str(), "%dx%d%c", &w, &h, &extra) != 2 || w < 16 || h < 16 ||
        w > 8192 || h > 8192)
      throw InputError("--frame-size expects WxH between 16 and 8192 pixels, got '" +
                       a.frame_size + "'");
    o.width = w;
    o.height = h;
  }
  o.look.colour_by = render::parse_colour_by(a.colour);
  if (!a.colour_range.empty()) {
    const auto r = parse_list(a.colour_range, "--colour-range");
    if (r.size() != 2 || !(r[0] < r[1]))
      throw InputError("--colour-range expects MIN,MAX with MIN < MAX, got '" + a.colour_range + "'");
    o.look.range_min = r[0];
    o.look.range_max = r[1];
  }
  o.look.gas_arrows = a.gas_arrows;
  o.look.gas_arrow_reference = gas_arrow_reference(scene);
  o.look.gas_arrows_coloured = a.gas_arrow_colour;
  o.look.particle_arrows = a.particle_arrows;
  o.look.porosity_background = a.porosity_background;
  o.look.bubble_outlines = a.bubble_outlines;
  o.look.dark_background = a.dark;
  if (!(a.close_up >= 0.0 && a.close_up < 1.0))
    throw InputError("--close-up expects a fraction of the bed's height in [0, 1), got " +
                     std::to_string(a.close_up));
  o.look.close_up = a.close_up;
  if (!(a.video_fps > 0.0)) throw InputError("--video-fps must be positive");
  o.video_fps = a.video_fps;
  o.backend = a.gl_backend;
  o.font = assets + "/fonts/DejaVuSans.ttf";
  return o;
}

void report_frame_output(const std::string& dir, const OutputArgs& a, const FrameStats& st,
                         double run_wall_s) {
  const auto per = [](double total, int n) { return n > 0 ? 1000.0 * total / n : 0.0; };
  const int outputs = std::max(st.frames, st.vtk_files);
  nlohmann::json j = {
      {"frames", st.frames},
      {"vtk_snapshots", st.vtk_files},
      {"frame_size", a.frame_size},
      {"frame_interval_s", a.frame_interval},
      {"gl", st.gl_version},
      {"render_ms_per_frame", per(st.render_s, st.frames)},
      {"png_ms_per_frame", per(st.png_s, st.frames)},
      {"video_ms_per_frame", per(st.video_s, st.frames)},
      {"vtk_ms_per_snapshot", per(st.vtk_s, st.vtk_files)},
      {"snapshot_ms_per_output", per(st.snapshot_s, outputs)},
      {"engine_wait_s", st.wait_s},
      {"engine_output_s", st.snapshot_s + st.wait_s},
      {"run_wall_s", run_wall_s},
  };
  write_file_atomically((std::filesystem::path(dir) / "render.json").string(),
                        [&](std::ostream& out) { out << j.dump(2) << "\n"; });
  if (st.frames > 0)
    std::printf("wrote %d frames%s%s (%s): %.1f ms drawing, %.1f ms PNG, %.1f ms video per frame\n",
                st.frames, a.frames ? " to " : "", a.frames ? (dir + "/frames").c_str() : "",
                a.frame_size.c_str(), per(st.render_s, st.frames), per(st.png_s, st.frames),
                per(st.video_s, st.frames));
  if (a.video) std::printf("wrote %s/video.mp4\n", dir.c_str());
  if (!a.montage.empty()) std::printf("wrote %s/montage.png\n", dir.c_str());
  if (st.vtk_files > 0)
    std::printf("wrote %d snapshots to %s/vtk (particles.pvd, gas.pvd)\n", st.vtk_files, dir.c_str());
  std::printf("engine thread spent %.3g s of %.3g s on output (snapshots and waiting)\n",
              st.snapshot_s + st.wait_s, run_wall_s);
}

}  // namespace fluidbed::app
