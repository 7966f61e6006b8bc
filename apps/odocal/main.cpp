// odocal: calibrates a vehicle's wheel-odometry model off-line from a logged drive.

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "calibrate_command.hpp"
#include "deadreckon_command.hpp"
#include "demo_command.hpp"
#include "exit_codes.hpp"
#include "experiment_command.hpp"
#include "import_command.hpp"
#include "odocal/error.hpp"
#include "simulate_command.hpp"
#include "validate_command.hpp"

int main(int argc, char** argv) {
  using namespace odocal::cli;
  CLI::App app{"odocal: off-line calibration of wheel odometry from logged drives"};
  app.require_subcommand(1);
  add_calibrate_command(app);
  add_deadreckon_command(app);
  add_demo_command(app);
  add_experiment_command(app, argc, argv);
  add_import_command(app);
  add_simulate_command(app);
  add_validate_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? kExitOk : kExitBadInput;
  } catch (const odocal::InputError& e) {
    fmt::print(stderr, "odocal: error: {}\n", e.what());
    return kExitBadInput;
  } catch (const NotUsableResult& e) {
    fmt::print(stderr, "odocal: not usable: {}\n", e.what());
    return kExitNotIdentifiable;
  } catch (const odocal::InsufficientDataError& e) {
    fmt::print(stderr, "odocal: cannot identify: {}\n", e.what());
    return kExitNotIdentifiable;
  } catch (const std::exception& e) {
    fmt::print(stderr, "odocal: error: {}\n", e.what());
    return kExitFailure;
  }
  return kExitOk;
}
