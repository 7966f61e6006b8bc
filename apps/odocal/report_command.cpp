#include "report_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "odocal/error.hpp"

namespace odocal::cli {
namespace {

// The report is drawn with plotly from Debian's python3: this command hands its arguments to
// the odocal_report package, found in the build tree or where cmake --install put it.
[[noreturn]] void run_report(const std::vector<std::string>& arguments) {
  std::string path = ODOCAL_PYTHON_BUILD_DIR ":" ODOCAL_PYTHON_INSTALL_DIR;
  if (const char* existing = std::getenv("PYTHONPATH"); existing && *existing)
    path += std::string(":") + existing;
  ::setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> args = {"/usr/bin/python3", "-m", "odocal_report"};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  throw Error(std::string("cannot run /usr/bin/python3 for the report: ") + std::strerror(errno));
}

}  // namespace

void add_report_command(CLI::App& app) {
  auto arguments = std::make_shared<std::vector<std::string>>();
  CLI::App* command = app.add_subcommand(
      "report", "One calibration as a static HTML page (RESULT.json --log LOG --out FILE.html)");
  command->prefix_command();  // every argument goes to the report, --help included
  command->allow_extras();
  command->callback([command, arguments] {
    *arguments = command->remaining();
    run_report(*arguments);
  });
}

}  // namespace odocal::cli
