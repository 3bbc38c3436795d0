#include "cli/sweep_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace progsim::cli {

CLI::App* add_sweep_command(CLI::App& app) {
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "one coarse preview per parameter combination, on Dask: runs `python3 -m progsim sweep` "
      "(the progsim Python package; PROGSIM_PYTHON names another interpreter). "
      "`progsim sweep --help` lists its options");
  sweep->prefix_command();
  sweep->set_help_flag();  // --help goes to the Python command, which documents the options
  return sweep;
}

int run_sweep_command(const CLI::App& sweep) {
  const char* env = std::getenv("PROGSIM_PYTHON");
  const std::string python = env != nullptr && *env != '\0' ? env : "python3";
  std::vector<std::string> args{python, "-m", "progsim", "sweep"};
  for (const std::string& arg : sweep.remaining()) args.push_back(arg);
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  execvp(argv[0], argv.data());
  std::fprintf(stderr,
               "progsim sweep: cannot start %s (%s); sweeps need Python with the progsim "
               "package (pip install ./bindings/python)\n",
               python.c_str(), std::strerror(errno));
  return 2;
}

}  // namespace progsim::cli
