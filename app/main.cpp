// fluidbed: a gas-fluidized bed of discrete particles (Xu & Yu 1997). See README.md and docs/
#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <iostream>

#include "build_info.hpp"
#include "cli/bench_peer.hpp"
#include "cli/commands.hpp"
#include "cli/export.hpp"
#include "cli/keys.hpp"
#include "cli/study.hpp"
#include "cli/view.hpp"
#include "core/errors.hpp"
#include "render/asset_dir.hpp"
#include "render/colour_by.hpp"
#include "sim/checks.hpp"

namespace {

void add_scene_options(CLI::App* cmd, fluidbed::app::RunArgs& a, bool scene_required) {
  auto* opt = cmd->add_option("scene", a.scene, "scene file (TOML)");
  if (scene_required) opt->required();
  cmd->add_option("--set", a.overrides, "override a scene value: section.key=value")
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_option("--until", a.until, "simulated time to reach, in seconds");
  cmd->add_option("--threads", a.threads, "threads inside a step (default 1; 0: one per core)")
      ->check(CLI::NonNegativeNumber);
}

// Frames, video, montage and VTK files of `run` (see docs/pictures.md).
void add_output_options(CLI::App* cmd, fluidbed::app::OutputArgs& o) {
  cmd->add_flag("--frames", o.frames, "write DIR/frames/*.png at every frame interval");
  cmd->add_flag("--video", o.video, "write DIR/video.mp4 (ffmpeg, H.264)");
  cmd->add_flag("--vtk", o.vtk, "write DIR/vtk/ (particles and gas, .pvd series for ParaView)");
  cmd->add_option("--montage", o.montage, "write DIR/montage.png of these times: t1,t2,... (s)");
  cmd->add_option("--frame-interval", o.frame_interval, "simulated seconds between frames (0.04)");
  cmd->add_option("--frame-size", o.frame_size, "frame size WxH in pixels (1280x720)");
  cmd->add_option("--colour", o.colour,
                  "particle colour: " +
                      fluidbed::render::joined_colour_names(fluidbed::render::colour_by_names()));
  cmd->add_option("--colour-range", o.colour_range, "colour range MIN,MAX (the quantity's unit)");
  cmd->add_flag("--gas-arrows,!--no-gas-arrows", o.gas_arrows, "gas velocity arrows (on)");
  cmd->add_flag("--gas-arrow-colour", o.gas_arrow_colour, "colour gas arrows by speed");
  cmd->add_flag("--particle-arrows", o.particle_arrows, "particle velocity arrows");
  cmd->add_flag("--porosity-background", o.porosity_background, "porosity field behind particles");
  cmd->add_flag("--bubble-outlines", o.bubble_outlines,
                "frames and montage: outlines of the bubbles and jet cavities found ([bubbles])");
  cmd->add_flag("--dark", o.dark, "dark background");
  cmd->add_option("--close-up", o.close_up,
                  "frames: beside the bed, its lower FRACTION magnified (0.4; 0: none)");
  cmd->add_option("--video-fps", o.video_fps, "video frames per second (25)");
  cmd->add_option("--gl-backend", o.gl_backend, "GL context backend: osmesa, glfw (osmesa)");
}

// The commands and their options as the parser knows them, for the manual page (`keys --format
// man`), so that it cannot list an option the program does not take.
std::vector<fluidbed::app::CommandDoc> command_docs(const CLI::App& app) {
  std::vector<fluidbed::app::CommandDoc> docs;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    fluidbed::app::CommandDoc d{sub->get_name(), sub->get_description(), {}};
    for (const CLI::Option* opt : sub->get_options()) {
      if (opt->get_name() == "--help") continue;  // every command has it
      std::string name = opt->get_name(true, true);
      name = name.substr(0, name.find('{'));  // a negated flag's "{false}"
      if (opt->get_positional()) {
        for (char& c : name) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      } else if (opt->get_type_size() != 0) {
        // "INT:NONNEGATIVE" is an INT; "TEXT:{text,toml,man}" shows its choices.
        const std::string type = opt->get_type_name();
        const auto colon = type.find(':');
        const bool choices = colon != std::string::npos && type.compare(colon + 1, 1, "{") == 0;
        name += " " + (choices ? type.substr(colon + 1) : type.substr(0, colon));
      }
      d.options.emplace_back(name, opt->get_description());
    }
    docs.push_back(std::move(d));
  }
  return docs;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fluidbed: a gas-fluidized bed of discrete particles and locally averaged gas"};
  app.require_subcommand(1);
  const std::string docs = fluidbed::render::doc_dir();
  app.footer("Documentation: " +
             (docs.empty() ? std::string("README.md and docs/ of the source tree")
                           : docs + "/README.md and " + docs + "/docs/ (one page per task)") +
             "; `fluidbed VERB --help` for a verb's options, `man fluidbed` for every key.");
  app.set_version_flag("--version", fluidbed::app::version_line(),
                       "print the version and the git commit it was built from");
  fluidbed::app::RunArgs run_args, bench_args;
  fluidbed::app::SweepArgs sweep_args;
  fluidbed::app::ReproduceArgs reproduce_args;
  fluidbed::app::ExportArgs export_args;
  fluidbed::app::StudyArgs study_args;
  fluidbed::app::ViewArgs view_args;
  fluidbed::app::KeysArgs keys_args;

  auto* run = app.add_subcommand("run", "run a scene and write summary.json and timeseries.csv");
  add_scene_options(run, run_args, false);  // required unless --resume (cli/run.cpp)
  run->add_option("--checkpoint-every", run_args.checkpoint_every,
                  "wall seconds between checkpoints in DIR/checkpoint/ (default: every 60 s for "
                  "runs expected to take over 2 minutes; 0: only at an interrupt)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--resume", run_args.resume,
                  "finish the run whose folder DIR holds a checkpoint (an interrupted run)");
  run->add_option("--out", run_args.out, "output folder (default out/<scene name>)");
  add_output_options(run, run_args.output);
  run->add_flag("--plots", run_args.plots,
                "write dp.png (Fig. 8), overlap.png (Fig. 15) and trajectory.png (Figs 12-13)");
  run->add_flag("--bubbles", run_args.bubbles,
                "bubble analysis: bubbles.csv, mixing.csv, summary.json `bubbles` (with --plots: "
                "bubbles.png, mixing.png)");
  run->add_option("--seeds", run_args.seeds,
                  "an ensemble over packings: N seeds from the scene's (s0, s0+1, ...) or a list "
                  "3,7,11; each run in DIR/seeds/S/, the ensemble in DIR/summary.json");
  run->add_option("--track", run_args.track,
                  "particle ids to follow for --plots: 12,345 (default: two from the jet region)");

  auto* bench = app.add_subcommand("bench", "measure speed (default scene: packing)");
  add_scene_options(bench, bench_args, false);
  bench->add_option("--out", bench_args.out, "folder for bench.json (default out/bench)");
  bench->add_option("--repeat", bench_args.repeat,
                    "the same run N times: median, min and max in bench.json (default 1)")
      ->check(CLI::PositiveNumber);
  std::string bench_peer;  // bench --peer liggghts (app/cli/bench_peer.hpp)
  bench->add_option("--peer", bench_peer, "also run the same work in another code: liggghts");

  auto* sweep = app.add_subcommand("sweep", "the paper's velocity sweep (Fig. 6) and U_mf");
  sweep->add_option("scene", sweep_args.scene, "scene file (TOML); not with --resume");
  sweep->add_option("--set", sweep_args.overrides, "override a scene value: section.key=value")
      ->take_all()
      ->allow_extra_args(false);
  sweep->add_option("--velocities", sweep_args.velocities,
                    "superficial velocities in m/s: 0.5,1.0,... (default: the paper's 23 from 0.5 to 3.2, scaled by the scene's Wen-Yu U_mf over the paper's)");
  sweep->add_option("--run-time", sweep_args.run_time, "simulated seconds per velocity (1.5)");
  sweep->add_option("--averaging-start", sweep_args.averaging_start,
                    "seconds into each run where the mean (eq 30) starts (0.5)");
  sweep->add_option("--threads", sweep_args.threads, "runs side by side (2)")->check(CLI::PositiveNumber);
  sweep->add_option("--out", sweep_args.out, "output folder (default out/sweep)");
  sweep->add_option("--seeds", sweep_args.seeds,
                    "one sweep per packing: N seeds from the scene's (s0, s0+1, ...) or a list "
                    "3,7,11; each in DIR/seeds/S/, U_mf's mean and spread in DIR/summary.json");
  sweep->add_option("--resume", sweep_args.resume,
                    "finish the sweep in folder DIR (interrupted or killed): finished runs are "
                    "kept, a stopped run continues from its checkpoint");

  auto* reproduce = app.add_subcommand("reproduce", "every figure of the paper, with a report");
  reproduce->add_option("--out", reproduce_args.out, "output folder (default out/reproduce)");
  reproduce->add_flag("--quick", reproduce_args.quick, "shorter runs: every figure in minutes");
  reproduce->add_option("--threads", reproduce_args.threads, "threads inside a step");
  reproduce->add_option("--seeds", reproduce_args.seeds,
                        "packings of the paper's bed, its uniform twin and the sweep: N or a list "
                        "3,7,11 (default 3; --quick: 1); figures as mean +- std");
  reproduce->add_option("--set", reproduce_args.overrides,
                        "override a value in every scene: section.key=value")
      ->take_all()
      ->allow_extra_args(false);
  reproduce->add_option("--resume", reproduce_args.resume,
                        "finish the report in folder DIR (interrupted or killed): finished runs, "
                        "sweep runs and studies are kept");

  // The viewer: a window with a control panel (docs/teaching.md); headless frames without one.
  auto* view = app.add_subcommand("view", "watch a scene live with a control panel (default scene: teaching)");
  add_scene_options(view, view_args.run_like, false);
  add_output_options(view, view_args.output);
  // The window opens at ViewArgs::kWindowSize unless --frame-size says otherwise.
  view->get_option("--frame-size")
      ->description(std::string("window size WxH in pixels (") +
                    fluidbed::app::ViewArgs::kWindowSize + "; headless: the frames' size)");
  view->add_option("--script", view_args.script, "drive the viewer from a file (docs/teaching.md)");
  view->add_option("--lesson", view_args.lesson,
                   "run a lesson of assets/lessons (a script with captions); headless: DIR/video.mp4");
  view->add_flag("--list-lessons", view_args.list_lessons, "list the lessons and exit");
  view->add_flag("--umf", view_args.umf_only,
                 "print the scene's U_mf, as the presets use it (measured from the way down of "
                 "its sweep once, then cached), and exit");
  view->add_option("--beside", view_args.beside,
                   "a second scene beside the first, its own engine; run, reset and the gas act "
                   "on both (--set too)");
  view->add_flag("--present", view_args.present,
                 "open in the presenter mode: large text, the bed beside a large live Fig. 6, "
                 "words in the bed (the p key switches it; docs/teaching.md)");
  view->add_option("--max-fps", view_args.max_fps,
                   "the window draws at most this many frames per second (30; 0: no cap)")
      ->check(CLI::NonNegativeNumber);
  view->add_option("--out", view_args.out, "folder for screenshots, recordings, headless frames (out/view)");

  auto* exporter = app.add_subcommand("export", "write the scene for another code (LIGGGHTS, OpenFOAM)");
  exporter->add_option("scene", export_args.scene, "scene file (TOML)")->required();
  exporter->add_option("--set", export_args.overrides, "override a scene value: section.key=value")
      ->take_all()
      ->allow_extra_args(false);
  exporter->add_option("--to", export_args.to, "target: liggghts, openfoam")->required();
  exporter->add_option("dir", export_args.dir, "folder to write")->required();

  auto* study = app.add_subcommand("study", "speed against accuracy, stability, model choices");
  study->add_option("name", study_args.name, "the study (see --list)");
  study->add_flag("--list", study_args.list, "name the studies and how long each takes");
  study->add_option("--out", study_args.out, "output folder (default out/study-NAME)");
  study->add_option("--size", study_args.size, "full (default) or tiny (seconds, a small bed)")
      ->check(CLI::IsMember({"full", "tiny"}));
  study->add_flag("--quick", study_args.quick, "the same as --size tiny");
  auto* study_resume = study->add_option("--resume", study_args.resume,
                    "finish the study in folder DIR (interrupted or killed; without DIR: the "
                    "--out folder): its finished points are read back, the rest measured; the "
                    "same NAME and --size as it was started with")
      ->expected(0, 1);
  study->add_option("--scene", study_args.scene,
                    "sensitivity: the scene file (TOML) to study");
  study->add_option("--vary", study_args.vary,
                    "sensitivity: KEY=V1,V2,... or KEY1,KEY2=A1:B1,A2:B2, one key (or tuple) "
                    "varied at a time from the scene; repeat for more")
      ->take_all()
      ->allow_extra_args(false);
  study->add_option("--set", study_args.overrides,
                    "sensitivity: override a value of the studied scene: section.key=value")
      ->take_all()
      ->allow_extra_args(false);
  study->add_option("--until", study_args.until,
                    "sensitivity: simulated time of each run, s (default: the scene's time.end)")
      ->check(CLI::PositiveNumber);
  study->add_option("--seeds", study_args.seeds,
                    "over several packings of the bed (stiffness, coupling, model-form): N seeds "
                    "from the scene's or a list 3,7,11; each study in DIR/seeds/S/, the ensemble "
                    "in DIR/ensemble.csv and DIR/summary.md");
  study->add_option("--jobs", study_args.jobs, "points at once (default: one per core)")
      ->check(CLI::NonNegativeNumber);

  fluidbed::app::CheckArgs check_args;
  auto* check = app.add_subcommand(
      "check", "inspect a scene: derived figures, warnings and refusals, nothing run");
  check->add_option("scene", check_args.scene, "scene file (TOML)")->required();
  check->add_option("--set", check_args.overrides, "override a scene value: section.key=value")
      ->take_all()
      ->allow_extra_args(false);

  auto* keys = app.add_subcommand("keys", "every scene key: default, unit, range and help");
  keys->add_option("section", keys_args.section, "only this section (e.g. contact)");
  keys->add_option("--format", keys_args.format,
                   "text (a table), toml (a complete scene at the defaults), man (the manual page)")
      ->check(CLI::IsMember({"text", "toml", "man"}));

  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (const auto* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      known = known || sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::cerr << "fluidbed: unknown command '" << argv[1] << "' (known: " << names << ")\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "fluidbed: " << e.what() << "\n";
    return 2;
  }

  try {
    if (*run) {
      run_args.threads_given = run->count("--threads") > 0;
      fluidbed::app::RunArgs given = run_args;
      fluidbed::app::visit_output_options(given, [&](const char* option, const char* key, auto&) {
        if (run->count(option) > 0) run_args.outputs_given.push_back(key);
      });
      return fluidbed::app::run_command(run_args);
    }
    if (*bench)
      return bench_peer.empty() ? fluidbed::app::bench_command(bench_args)
                                : fluidbed::app::bench_peer_command(bench_args, bench_peer);
    if (*sweep) {
      sweep_args.threads_given = sweep->count("--threads") > 0;
      for (const char* o : {"scene", "--set", "--velocities", "--run-time", "--averaging-start",
                            "--seeds"})
        sweep_args.options_given = sweep_args.options_given || sweep->count(o) > 0;
      return fluidbed::app::sweep_command(sweep_args);
    }
    if (*reproduce) {
      reproduce_args.threads_given = reproduce->count("--threads") > 0;
      for (const char* o : {"--quick", "--seeds", "--set"})
        reproduce_args.options_given = reproduce_args.options_given || reproduce->count(o) > 0;
      return fluidbed::app::reproduce_command(reproduce_args);
    }
    if (*exporter) return fluidbed::app::export_command(export_args);
    if (*study) {
      study_args.resume_out = study_resume->count() > 0 && study_args.resume.empty();
      return fluidbed::app::study_command(study_args);
    }
    if (*view) {
      view_args.frame_interval_given = view->count("--frame-interval") > 0;
      return fluidbed::app::view_command(view_args);
    }
    if (*check) return fluidbed::app::check_command(check_args);
    if (*keys) return fluidbed::app::keys_command(keys_args, command_docs(app));
  } catch (const fluidbed::InputError& e) {
    std::cerr << "fluidbed: error: " << e.what() << "\n";
    return 2;
  } catch (const fluidbed::SimulationFailure& e) {
    std::cerr << "fluidbed: the simulation failed: " << e.what() << fluidbed::failure_hint(e.what())
              << "\n";
    return 3;
  } catch (const std::runtime_error& e) {
    // Pictures or files that could not be made (no GL context, ffmpeg failed).
    std::cerr << "fluidbed: output failed: " << e.what() << "\n";
    return 4;
  }
  return 2;
}
