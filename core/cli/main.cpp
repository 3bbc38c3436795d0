// progsim command-line interface: run scenes, build hierarchies, measure accuracy, sweep
// parameters (through the Python package), print build information and parameters.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "cli/accuracy_command.hpp"
#include "cli/hierarchy_command.hpp"
#include "cli/run_command.hpp"
#include "cli/sweep_command.hpp"
#include "common/build_info.hpp"
#include "common/error.hpp"
#include "common/thread_budget.hpp"
#include "scene/choice_table.hpp"
#include "scene/parameter_table.hpp"

using namespace progsim;

int main(int argc, char** argv) {
  CLI::App app{"progsim: progressive simulation of cloth, shells and solids"};
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success; 2 bad input (a malformed scene or mesh), nothing "
      "written; 3 the simulation failed (a non-finite solve, an error after the start) or did "
      "not converge (the finest level, or a direct run's last step); 130 the run was cancelled "
      "(Ctrl-C / SIGINT, at the next load step, settle or refinement): summary.json says which "
      "and why.");
  app.add_option_function<int>(
         "--threads", [](int threads) { set_thread_budget(threads); },
         "threads of the parallel loops: 0 (default) chooses from the cores other processes "
         "leave idle; 1 to 1024 fixes the count")
      ->check(CLI::Range(0, 1024));
  cli::RunCommand run_options;
  CLI::App* run_cmd = cli::add_run_command(app, run_options);
  cli::HierarchyCommand hierarchy_options;
  CLI::App* hierarchy_cmd = cli::add_hierarchy_command(app, hierarchy_options);
  cli::AccuracyCommand accuracy_options;
  CLI::App* accuracy_cmd = cli::add_accuracy_command(app, accuracy_options);
  CLI::App* sweep_cmd = cli::add_sweep_command(app);
  app.add_subcommand("info", "print version and build options")->callback([] {
    std::printf("%s", build_info().c_str());
  });
  app.add_subcommand("params", "print the scene parameter and option tables (Markdown)")
      ->callback([] {
        std::printf("%s\n%s", parameter_table_markdown().c_str(), choice_table_markdown().c_str());
      });
  CLI11_PARSE(app, argc, argv);
  try {
    if (run_cmd->parsed()) return cli::run_run_command(run_options);
    if (hierarchy_cmd->parsed()) return cli::run_hierarchy_command(hierarchy_options);
    if (accuracy_cmd->parsed()) return cli::run_accuracy_command(accuracy_options);
    if (sweep_cmd->parsed()) return cli::run_sweep_command(*sweep_cmd);
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "progsim: error (%s): %s\n", status_name(e.status()), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "progsim: error: %s\n", e.what());
    return 2;
  }
}
