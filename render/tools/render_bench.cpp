// Milliseconds per frame of the renderer on a real snapshot: the paper's bed (2400 particles,
// from the cached packed bed) after `--warmup` simulated seconds of gas, drawn at --size with gas
// arrows (and again with particle arrows), read back, encoded to PNG and piped to ffmpeg.
// Speed is measured here, never asserted. Usage:
//   fluidbed_render_bench [SCENE.toml] [--warmup 0.05] [--frames 20] [--size 1280x720]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/renderer.hpp"
#include "render/video_writer.hpp"
#include "run/packed_bed.hpp"
#include "scene/scene_loader.hpp"
#include "sim/simulation.hpp"
#include "sim/snapshot.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fluidbed;
  std::string scene = std::string(FLUIDBED_ASSET_DIR) + "/scenes/xu_yu_1997.toml";
  double warmup = 0.05;
  int frames = 20, width = 1280, height = 720;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--warmup" && i + 1 < argc) warmup = std::atof(argv[++i]);
    else if (a == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (a == "--size" && i + 1 < argc) std::sscanf(argv[++i], "%dx%d", &width, &height);
    else scene = a;
  }
  Settings s = load_scene(scene, {});
  prepare_packed_bed(s);
  Simulation sim(s);
  const auto steps = static_cast<long>(warmup / s.time.dt);
  auto t0 = Clock::now();
  for (long k = 0; k < steps; ++k) sim.step();
  std::printf("scene %s: %zu particles, %ld steps of warm-up in %.1f s\n", s.scene.name.c_str(),
              sim.particle_count(), steps, ms_since(t0) / 1000.0);
  Snapshot snap;
  t0 = Clock::now();
  take_snapshot(sim, snap);
  std::printf("snapshot copy       %8.3f ms\n", ms_since(t0));

  auto ctx = render::make_context("osmesa", width, height);
  std::printf("GL                  %s\n", ctx->version_string().c_str());
  render::Renderer renderer(*ctx, std::string(FLUIDBED_ASSET_DIR) + "/fonts/DejaVuSans.ttf");
  const auto dir = std::filesystem::temp_directory_path() / "fluidbed-render-bench";
  std::filesystem::create_directories(dir);

  struct Case {
    const char* name;
    bool gas, particles;
    int samples;
  };
  for (const Case c : {Case{"gas arrows, 4x MSAA", true, false, 4},
                       Case{"gas + particle arrows, 4x MSAA", true, true, 4},
                       Case{"gas arrows, 2x MSAA", true, false, 2},
                       Case{"gas arrows, no MSAA", true, false, 1}}) {
    render::RenderSettings look;
    look.gas_arrows = c.gas;
    look.particle_arrows = c.particles;
    look.samples = c.samples;
    render::Image img = renderer.render_frame(snap, look, width, height);  // warm: shaders, atlas
    double draw = 0, png = 0, video = 0;
    render::VideoWriter writer((dir / "bench.mp4").string(), width, height, 25.0);
    for (int f = 0; f < frames; ++f) {
      t0 = Clock::now();
      img = renderer.render_frame(snap, look, width, height);
      draw += ms_since(t0);
      t0 = Clock::now();
      render::write_png((dir / "bench.png").string(), img);
      png += ms_since(t0);
      t0 = Clock::now();
      writer.write(img);
      video += ms_since(t0);
    }
    t0 = Clock::now();
    writer.close();
    video += ms_since(t0);
    std::printf("%-32s %dx%d: draw + read back %.1f ms, PNG %.1f ms, video %.1f ms per frame\n",
                c.name, width, height, draw / frames, png / frames, video / frames);
  }
  return 0;
}
