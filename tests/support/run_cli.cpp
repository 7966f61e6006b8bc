#include "run_cli.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace odocal::testing {

std::string read_text_file(const std::string& path) {
  std::ifstream stream(path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

CliRun run_cli(const std::string& arguments) {
  const std::string stem =
      (std::filesystem::temp_directory_path() / ("odocal-cli-" + std::to_string(::getpid())))
          .string();
  const std::string command =
      std::string(ODOCAL_CLI_PATH) + " " + arguments + " >" + stem + ".out 2>" + stem + ".err";
  const int raw = std::system(command.c_str());
  CliRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = read_text_file(stem + ".out");
  run.err = read_text_file(stem + ".err");
  std::filesystem::remove(stem + ".out");
  std::filesystem::remove(stem + ".err");
  return run;
}

}  // namespace odocal::testing
