// fluidbed: a gas-fluidized bed of discrete particles (Xu & Yu 1997). See README.md.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "core/errors.hpp"

namespace {

void add_scene_options(CLI::App* cmd, fluidbed::app::RunArgs& a, bool scene_required) {
  auto* opt = cmd->add_option("scene", a.scene, "scene file (TOML)");
  if (scene_required) opt->required();
  cmd->add_option("--set", a.overrides, "override a scene value: section.key=value")
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_option("--until", a.until, "simulated time to reach, in seconds");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fluidbed: a gas-fluidized bed of discrete particles and locally averaged gas"};
  app.require_subcommand(1);
  fluidbed::app::RunArgs run_args, bench_args;

  auto* run = app.add_subcommand("run", "run a scene and write summary.json and timeseries.csv");
  add_scene_options(run, run_args, true);
  run->add_option("--out", run_args.out, "output folder (default out/<scene name>)");

  auto* bench = app.add_subcommand("bench", "measure speed (default scene: packing)");
  add_scene_options(bench, bench_args, false);
  bench->add_option("--out", bench_args.out, "folder for bench.json (default out/bench)");

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
  } catch (const CLI::ParseError& e) {
    std::cerr << "fluidbed: " << e.what() << "\n";
    return 2;
  }

  try {
    if (*run) return fluidbed::app::run_command(run_args);
    if (*bench) return fluidbed::app::bench_command(bench_args);
  } catch (const fluidbed::InputError& e) {
    std::cerr << "fluidbed: error: " << e.what() << "\n";
    return 2;
  } catch (const fluidbed::SimulationFailure& e) {
    std::cerr << "fluidbed: the simulation failed: " << e.what() << "\n";
    return 3;
  }
  return 2;
}
