#pragma once
// Internal to the Slurm engine: running the scheduler's commands (sbatch, squeue, scontrol,
// scancel) and reading what they print. No shell is involved in what the arguments mean: each is
// single-quoted for /bin/sh, so a path with spaces or quotes stays one argument.
#include <string>
#include <vector>

namespace cropsight::batch::detail {

struct CommandOutput {
  int exit_code = -1;  ///< the command's exit status; 127 when it could not be started
  std::string out;     ///< stdout and stderr together
};

std::string shell_quote(const std::string& arg);
CommandOutput run_command(const std::vector<std::string>& argv);

}  // namespace cropsight::batch::detail
