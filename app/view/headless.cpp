#include "view/headless.hpp"

#include <algorithm>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "chart/chart.hpp"
#include "core/errors.hpp"
#include "core/steps.hpp"
#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/renderer.hpp"
#include "render/video_writer.hpp"
#include "view/curve_chart.hpp"
#include "view/script_runner.hpp"
#include "view/session.hpp"

namespace fluidbed::app {
namespace {

constexpr double kDpWindow = 4.0;  // s of dp against time beside the bed

// `src` (chart pixels, RGB rows from the top) into `dst` at (x0, y0).
void paste(render::Image& dst, const chart::Image& src, int x0, int y0) {
  const auto& px = src.pixels();
  for (int y = 0; y < src.height() && y0 + y < dst.height; ++y) {
    const auto n = static_cast<std::size_t>(std::min(src.width(), dst.width - x0)) * 3;
    std::copy_n(
        px.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(src.width()) * 3, n,
        dst.rgb.data() + (static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(dst.width) +
                          static_cast<std::size_t>(x0)) *
                             3);
  }
}

// Pictures of what the window would show: the bed (renderer, caption band, regime), and for a
// bed with gas the live curve and dp against time on the right.
class Painter {
 public:
  Painter(const FrameOptions& fo, bool gas)
      : fo_(fo), gas_(gas), font_(chart::Font::load({fo.font})) {
    context_ = render::make_context("osmesa", fo_.width, fo_.height);
    renderer_ = std::make_unique<render::Renderer>(*context_, fo_.font);
  }

  render::Image paint(const Snapshot& snap, const render::RenderSettings& look,
                      const CurveState& curve, const std::deque<std::pair<double, double>>& dp) {
    const int side = gas_ ? static_cast<int>(std::lround(0.4 * fo_.width)) : 0;
    render::Image frame = renderer_->render_frame(snap, look, fo_.width - side, fo_.height);
    if (side == 0) return frame;
    render::Image out;
    out.width = fo_.width;
    out.height = fo_.height;
    out.rgb.assign(static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height) * 3,
                   255);
    for (int y = 0; y < frame.height; ++y)
      std::copy_n(
          frame.pixel(0, y), static_cast<std::size_t>(frame.width) * 3,
          out.rgb.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(out.width) * 3);
    // The curve changes only when a point is added: drawn again then.
    const int curve_h = fo_.height * 11 / 20;
    if (!curve_img_ || curve.version != curve_version_ || curve_img_->height() != curve_h) {
      chart::Chart c = curve_chart(curve);
      c.title = "Fig. 6 as it builds: mean dp against U";
      curve_img_ = std::make_unique<chart::Image>(chart::render(c, side, curve_h, font_, scale()));
      curve_version_ = curve.version;
    }
    paste(out, *curve_img_, fo_.width - side, 0);
    chart::Chart d;
    d.title = "dp against time";
    d.x.label = "t (s)";
    d.y.label = "dp (Pa)";
    d.legend = false;
    chart::Series s;
    for (const auto& [t, p] : dp) {
      s.x.push_back(t);
      s.y.push_back(p);
    }
    if (s.x.size() < 2) {
      s.x = {snap.time, snap.time + 1e-3};
      s.y = {snap.dp, snap.dp};
    }
    d.series.push_back(std::move(s));
    d.hlines.push_back({curve.weight_per_area, "W/A", {90, 90, 90}, true, 1.5});
    paste(out, chart::render(d, side, fo_.height - curve_h, font_, scale()), fo_.width - side,
          curve_h);
    return out;
  }

 private:
  // The charts' text and lines as in an 800 x 500 chart at 720 px high (legible in a video).
  double scale() const { return std::max(0.6, fo_.height / 720.0); }

  const FrameOptions& fo_;
  bool gas_;
  chart::Font font_;
  std::unique_ptr<render::GlContext> context_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<chart::Image> curve_img_;
  std::uint64_t curve_version_ = 0;
};

// What one picture shows, copied on the engine's side: the worker draws it while the bed steps on.
struct PictureJob {
  std::shared_ptr<Snapshot> snapshot;
  render::RenderSettings look;
  CurveState curve;
  std::deque<std::pair<double, double>> dp;
  int frame = -1;    // >= 0: a frame of the film (PNG and video)
  std::string file;  // else: a screenshot
};

// Draws, encodes and writes the pictures on its own thread (its own GL context), so the bed and
// the pictures share the two cores; a bounded queue: the bed waits only when the pictures are
// that far behind. A failure to write ends the run at the next picture asked for.
class PictureWorker {
 public:
  PictureWorker(const HeadlessView& o, bool gas) : o_(o), gas_(gas) {
    thread_ = std::thread([this] { work(); });
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return ready_ || error_; });
    rethrow();
  }
  ~PictureWorker() {
    {
      std::lock_guard lock(mutex_);
      closing_ = true;
      if (!finished_) jobs_.clear();  // an aborted run: the video is not finished
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  void push(PictureJob job) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return jobs_.size() < kQueue || error_; });
    rethrow();
    jobs_.push_back(std::move(job));
    changed_.notify_all();
  }
  // Waits for every picture, closes the video.
  void finish() {
    {
      std::lock_guard lock(mutex_);
      finished_ = closing_ = true;
    }
    changed_.notify_all();
    thread_.join();
    std::lock_guard lock(mutex_);
    rethrow();
  }

 private:
  static constexpr std::size_t kQueue = 4;
  void rethrow() {
    if (error_) std::rethrow_exception(error_);
  }
  void work() {
    namespace fs = std::filesystem;
    try {
      Painter painter(o_.frames, gas_);
      std::unique_ptr<render::VideoWriter> video;
      if (o_.frames.video)
        video = std::make_unique<render::VideoWriter>((fs::path(o_.out) / "video.mp4").string(),
                                                      o_.frames.width & ~1, o_.frames.height & ~1,
                                                      o_.frames.video_fps);
      {
        std::lock_guard lock(mutex_);
        ready_ = true;
      }
      changed_.notify_all();
      for (;;) {
        PictureJob job;
        {
          std::unique_lock lock(mutex_);
          changed_.wait(lock, [this] { return !jobs_.empty() || closing_; });
          if (jobs_.empty()) break;
          job = std::move(jobs_.front());
          jobs_.pop_front();
        }
        changed_.notify_all();
        const render::Image img = painter.paint(*job.snapshot, job.look, job.curve, job.dp);
        if (job.frame < 0) {
          const auto parent = fs::path(job.file).parent_path();
          std::error_code e;
          if (!parent.empty()) fs::create_directories(parent, e);
          render::write_png(job.file, img);
          std::printf("wrote %s\n", job.file.c_str());
          continue;
        }
        if (o_.frames.frames) {
          char name[32];
          std::snprintf(name, sizeof name, "frame_%06d.png", job.frame);
          render::write_png((fs::path(o_.out) / "frames" / name).string(), img);
        }
        if (video) video->write(img);
      }
      bool finished = false;
      {
        std::lock_guard lock(mutex_);
        finished = finished_;
      }
      if (video && finished) video->close();  // an aborted run leaves no video
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
    }
    changed_.notify_all();
  }

  const HeadlessView& o_;
  bool gas_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<PictureJob> jobs_;
  bool ready_ = false, closing_ = false, finished_ = false;
  std::exception_ptr error_;
};

// The script's commands without a window (ScriptTarget, view/script_runner.hpp): the gas, the
// contact law, the live curve's times and the reset go to the session as the window's engine
// thread applies them; captions, the outlines, the colours and layers, saved curves and
// screenshots act on the pictures at their simulated times; wait, zoom, track and recordings
// have no meaning here and say so.
class HeadlessTarget : public ScriptTarget {
 public:
  HeadlessTarget(ViewSession& session, render::RenderSettings& look, const HeadlessView& o)
      : session_(session), look_(look), o_(o) {}

  std::function<void(const std::string&)> screenshot_taker;

  void run_to(double t) override {
    target_step_ = steps_for(t, session_.sim().settings().time.dt);
  }
  bool busy() override { return session_.sim().steps() < target_step_; }
  bool stopped() const override { return quit_; }
  void unsupported(const ScriptLine& l) override {
    std::fprintf(stderr, "fluidbed view: headless: script line %d has no effect without a window\n",
                 l.line);
  }
  double umf() const override { return session_.umf().umf; }
  double sim_time() const override { return session_.sim().time(); }
  double sim_step() const override { return session_.sim().settings().time.dt; }
  bool velocity(double u) override { return send(ViewCommand::Kind::velocity, u); }
  bool ideal(bool on) override { return send(ViewCommand::Kind::ideal, on ? 1.0 : 0.0); }
  bool stiffness(double k) override { return send(ViewCommand::Kind::stiffness, k); }
  bool settle(double s) override { return send(ViewCommand::Kind::settle, s); }
  bool average(double s) override { return send(ViewCommand::Kind::average, s); }
  // A new start (a reset, new particles) goes back to t = 0: the last `at T` is behind it.
  bool reset() override {
    target_step_ = 0;
    return send(ViewCommand::Kind::reset, 0.0);
  }
  bool particles(double diameter, double density) override {
    target_step_ = 0;
    const std::uint64_t changes = session_.particles_changes();
    session_.apply({ViewCommand::Kind::particles, diameter, density},
                   [](const std::string& line) { std::printf("%s\n", line.c_str()); });
    if (session_.particles_changes() != changes) {
      const UmfEstimate& u = session_.umf();
      if (u.umf > 0.0)
        std::printf("U_mf = %.3f m/s for the new particles (%s)\n", u.umf, u.method().c_str());
    }
    std::printf("%zu spheres of %.4g mm and %.5g kg/m^3, time step %.4g s, from a packed bed\n",
                session_.sim().particle_count(),
                1000.0 * session_.sim().settings().particles.diameter,
                session_.sim().settings().particles.density, session_.sim().settings().time.dt);
    return true;
  }
  bool save_curve(const std::string& file) override {
    write_curve_file(file, session_.curve(), o_.frames.font);
    std::printf("wrote %s\n", file.c_str());
    return true;
  }
  bool caption(const std::string& text) override {
    look_.caption = text;
    return true;
  }
  bool colour(const std::string& mode) override {
    render::set_colour_by(look_, render::parse_viewer_colour(mode));
    return true;
  }
  bool gas_arrows(bool on) override { return set(look_.gas_arrows, on); }
  bool particle_arrows(bool on) override { return set(look_.particle_arrows, on); }
  bool porosity(bool on) override { return set(look_.porosity_background, on); }
  bool bubbles(bool on) override {
    look_.bubble_outlines = on;
    // A bed without gas has no bubbles: its pictures carry no outlines.
    return send(ViewCommand::Kind::bubbles, on && session_.sim().has_gas() ? 1.0 : 0.0);
  }
  bool screenshot(const std::string& file) override {
    screenshot_taker(file);
    return true;
  }
  bool quit() override {
    quit_ = true;
    return true;
  }

 private:
  static bool set(bool& flag, bool on) {
    flag = on;
    return true;
  }
  // A refused value or a failed rebuild ends the run: the exception leaves view_headless.
  bool send(ViewCommand::Kind kind, double value) {
    session_.apply({kind, value});
    return true;
  }
  ViewSession& session_;
  render::RenderSettings& look_;
  const HeadlessView& o_;
  std::int64_t target_step_ = 0;  // of the last `at T`
  bool quit_ = false;
};

}  // namespace

int view_headless(const Settings& scene, const ViewScript& script, const HeadlessView& o) {
  namespace fs = std::filesystem;
  ViewSession session(scene);
  session.set_umf(o.umf, o.umf_shipped);
  const bool gas = session.sim().has_gas();
  // The end: --until, else the script's quit (at the last time it named), else the scene's end.
  double until = scene.time.end;
  {
    double t = 0.0;
    for (const ScriptLine& l : script.lines) {
      if (l.at >= 0.0) t = std::max(t, l.at);
      if (l.kind == ScriptLine::Kind::quit) {
        until = t;
        break;
      }
    }
  }
  if (o.until >= 0.0) until = o.until;
  render::RenderSettings look = o.frames.look;
  look.caption_band = true;
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (o.frames.frames) fs::create_directories(fs::path(o.out) / "frames", ec);
  if (ec) throw InputError("cannot create " + o.out + ": " + ec.message());
  PictureWorker pictures(o, gas);
  std::deque<std::pair<double, double>> dp;  // (t, dp) of the last kDpWindow seconds
  const auto picture = [&](int frame, const std::string& file) {
    PictureJob job;
    job.snapshot = std::make_shared<Snapshot>();
    session.snapshot(*job.snapshot);
    if (const auto v = session.bubbles(); v && gas) look.bed_label = regime_words(*v);
    job.look = look;
    job.curve = session.curve();
    job.dp = dp;
    job.frame = frame;
    job.file = file;
    pictures.push(std::move(job));
  };
  // Frame k at the step nearest k intervals of simulated time stepped (a reset goes back in
  // time, the video goes on; new particles bring another step: the time stepped before it is
  // counted at the old one).
  std::int64_t stepped = 0, stepped_before = 0;
  double dt = scene.time.dt, time_before = 0.0;
  int frames = 0;
  const auto frame_if_due = [&] {
    if (const double now = session.sim().settings().time.dt; now != dt) {
      time_before += static_cast<double>(stepped - stepped_before) * dt;
      stepped_before = stepped;
      dt = now;
    }
    const double due = static_cast<double>(frames) * o.frames.interval - time_before;
    if (stepped - stepped_before < steps_for(due, dt)) return;
    picture(frames++, "");
  };

  ScriptRunner runner(script.lines);
  HeadlessTarget target(session, look, o);
  target.screenshot_taker = [&](const std::string& file) { picture(-1, file); };
  if (look.bubble_outlines) target.bubbles(true);  // as the window asks its engine
  runner.advance(target);  // the lines before the first `at` act on the first frame
  frame_if_due();
  for (;; runner.advance(target)) {
    if (target.stopped() || session.sim().steps() >= steps_for(until, session.sim().settings().time.dt))
      break;
    // A SimulationFailure ends the run: exit status 3, nothing more written.
    const std::optional<PlotSample> sample = session.step();
    ++stepped;
    if (sample && gas) {  // the window's dp against time, its last kDpWindow seconds
      if (!dp.empty() && sample->t < dp.back().first) dp.clear();  // a new start (reset, particles)
      dp.emplace_back(sample->t, sample->dp);
      while (!dp.empty() && dp.front().first < sample->t - kDpWindow) dp.pop_front();
    }
    frame_if_due();
  }
  pictures.finish();
  std::printf("wrote %d frames%s%s to %s (t = 0 to %.4g s)\n", frames,
              o.frames.frames ? " (frames/)" : "", o.frames.video ? " and video.mp4" : "",
              o.out.c_str(), session.sim().time());
  if (gas) std::printf("%s\n", describe_curve(session.curve()).c_str());
  return 0;
}

}  // namespace fluidbed::app
