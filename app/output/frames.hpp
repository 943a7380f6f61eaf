#pragma once
// Pictures and files of a run at exact simulated times: PNG frames, an MP4, a montage of chosen
// times, VTK files for ParaView. The engine thread only copies a snapshot at each such time and
// hands it over; one worker thread draws (it alone touches GL), encodes and writes. The queue
// between them is bounded: no frame is ever dropped, and the engine waits only when the worker is
// that many frames behind. Output never changes the physics: the run steps exactly as without it.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "analysis/bubbles.hpp"
#include "core/binary_io.hpp"
#include "io/vtk_writer.hpp"
#include "output/output_args.hpp"
#include "render/render_settings.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot.hpp"

namespace fluidbed::app {

struct FrameOptions {
  bool frames = false;              // DIR/frames/frame_NNNNNN.png
  bool video = false;               // DIR/video.mp4
  bool vtk = false;                 // DIR/vtk/*.vtp, *.vti, particles.pvd, gas.pvd
  std::vector<double> montage;      // s: DIR/montage.png with these times side by side
  double interval = 0.04;           // s of simulated time between frames (25 per simulated s)
  int width = 1280, height = 720;   // px, frames and video
  double video_fps = 25.0;          // frames per second of the video
  std::string backend = "osmesa";   // GL context backend
  std::string font;                 // TrueType font file
  int queue = 4;                    // snapshots the worker may be behind before the engine waits
  render::RenderSettings look;

  bool any() const { return frames || video || vtk || !montage.empty(); }
  bool needs_gl() const { return frames || video || !montage.empty(); }
};

// Costs measured by the worker and the engine thread, for the report and the benchmark.
struct FrameStats {
  int frames = 0, vtk_files = 0;
  double render_s = 0, png_s = 0, video_s = 0, vtk_s = 0;  // worker wall time by task
  double snapshot_s = 0;  // engine thread: copying snapshots
  double wait_s = 0;      // engine thread: waiting for room in the queue
  std::string gl_version;
};

class FrameOutput {
 public:
  // Plans the output times of a run from the simulation's current step to `until` (s), starts
  // the worker and waits until it is ready (GL context, shaders, font, ffmpeg). Throws InputError
  // for bad options (unknown backend, montage time outside the run, odd video size), and what the
  // worker could not start with. A resumed run passes its checkpoint's folder: the output goes on
  // from what checkpoint() saved there (the outputs after the checkpoint's step only, the frame
  // count, the montage's snapshots so far, the VTK series, the video's finished parts).
  FrameOutput(std::string out_dir, FrameOptions options, const Simulation& sim, double until,
              const std::string& resume_from = "");
  ~FrameOutput();  // stops the worker if finish() was not called (files left incomplete)
  FrameOutput(const FrameOutput&) = delete;
  FrameOutput& operator=(const FrameOutput&) = delete;

  // The run's per-step observer: takes a snapshot when this step is an output time. Also called
  // once before the run for the starting state. Rethrows the worker's error, which ends the run.
  void observe(const Simulation& sim);
  // Waits for the worker to write everything (the video closed and joined from its parts, the
  // montage drawn) and reports. The parts stay until remove_video_parts.
  FrameStats finish();
  // For a run's checkpoint (cli/run.cpp), on the engine thread between steps: waits until the
  // worker has written every snapshot taken so far and closed the video's current part
  // (DIR/video-parts/NNN.mp4; finish() joins the parts into DIR/video.mp4), then writes what the
  // output needs to go on into `folder`/pictures.bin.
  void checkpoint(const std::string& folder);

 private:
  struct Job {
    std::shared_ptr<const Snapshot> snapshot;
    bool frame = false, montage = false;
    std::int64_t index = 0;  // frame number: round(t / interval)
    bool checkpoint = false;  // no snapshot: close the video's part and report (checkpoint())
  };
  // The worker's side of a checkpoint, handed over under the mutex.
  struct Saved {
    FrameStats stats;
    std::vector<std::shared_ptr<const Snapshot>> montage;
    VtkSeries::Written vtk;
    int video_parts = 0;

    // pictures.bin's fields (core/binary_io.hpp), the montage's snapshots in their own format.
    template <class Archive>
    void fields(Archive& a) {
      FrameStats& f = stats;
      a(f.frames, f.vtk_files, f.render_s, f.png_s, f.video_s, f.vtk_s, f.snapshot_s, f.wait_s);
      std::uint64_t panels = montage.size();
      a(panels);
      if constexpr (std::is_same_v<Archive, BinarySource>) {
        if (panels > 10000) a.fail("inconsistent (montage)");
        montage.clear();
        for (std::uint64_t k = 0; k < panels; ++k) {
          auto snap = std::make_shared<Snapshot>();
          load_snapshot(a, *snap);
          montage.push_back(std::move(snap));
        }
      } else {
        for (const auto& snap : montage) save_snapshot(a.stream(), *snap);
      }
      a(vtk.times, vtk.gas, vtk.void_fraction, video_parts);
    }
  };
  struct Due {
    std::int64_t step;
    bool frame, montage;
  };

  void work();
  void push(Job job);
  void rethrow_if_failed();
  std::string video_part(int k) const;

  std::string dir_;
  FrameOptions opt_;
  std::vector<Due> due_;  // output steps in order
  std::size_t next_ = 0;
  double dt_ = 0.0;
  SnapshotChannel channel_;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  bool closing_ = false, ready_ = false;
  std::exception_ptr error_;
  FrameStats stats_;
  Saved saved_;                // the worker's state at the last checkpoint, and a resumed run's
  bool checkpoint_done_ = false;
  std::thread worker_;
  // The fine void fraction and the bubble outlines for the snapshots (VTK, --bubble-outlines).
  std::unique_ptr<BubbleAnalysis> bubbles_;
};

// Removes DIR/video-parts/ (the parts of DIR/video.mp4): once the run's checkpoint, which may
// name them, is gone.
void remove_video_parts(const std::string& dir);

// The gas arrows' reference speed for `scene` (render::gas_arrow_reference_for its superficial
// velocity; 10 m/s without gas).
double gas_arrow_reference(const Settings& scene);

// The options of `run` as FrameOptions (font from `assets`), the gas arrows scaled to `scene`
// (gas_arrow_reference); InputError names a bad value.
FrameOptions frame_options(const OutputArgs& a, const std::string& assets, const Settings& scene);

// Prints what was written and its cost, and writes DIR/render.json (milliseconds per frame by
// task, the engine thread's share, the GL version): the renderer's benchmark record.
void report_frame_output(const std::string& dir, const OutputArgs& a, const FrameStats& stats,
                         double run_wall_s);

}  // namespace fluidbed::app
