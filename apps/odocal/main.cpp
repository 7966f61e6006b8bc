// odocal: calibrates a vehicle's wheel-odometry model off-line from a logged drive.

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "calibrate_command.hpp"
#include "deadreckon_command.hpp"
#include "demo_command.hpp"
#include "doctor_command.hpp"
#include "exit_codes.hpp"
#include "experiment_command.hpp"
#include "import_command.hpp"
#include "large_buffers.hpp"
#include "message_text.hpp"
#include "odocal/error.hpp"
#include "report_command.hpp"
#include "simulate_command.hpp"
#include "validate_command.hpp"

int main(int argc, char** argv) {
  using namespace odocal::cli;
  map_large_buffers_on_huge_pages(argv);
  return_large_buffers_to_the_system();
  CLI::App app{"odocal: off-line calibration of wheel odometry from logged drives"};
  app.require_subcommand(1);
  add_calibrate_command(app);
  add_deadreckon_command(app);
  add_demo_command(app);
  add_doctor_command(app);
  add_report_command(app);
  add_experiment_command(app, argc, argv);
  add_import_command(app);
  add_simulate_command(app);
  add_validate_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, like every other error (CLI11 adds a second one pointing at --help).
    fmt::print(stderr, "odocal: usage: {} (see odocal --help)\n", printable_line(e.what()));
    return kExitBadInput;
  } catch (const odocal::InputError& e) {
    fmt::print(stderr, "odocal: error: {}\n", printable_line(e.what()));
    return kExitBadInput;
  } catch (const NotUsableResult& e) {
    fmt::print(stderr, "odocal: not usable: {}\n", printable_line(e.what()));
    return kExitNotIdentifiable;
  } catch (const odocal::InsufficientDataError& e) {
    fmt::print(stderr, "odocal: cannot identify: {}\n", printable_line(e.what()));
    return kExitNotIdentifiable;
  } catch (const std::exception& e) {
    fmt::print(stderr, "odocal: error: {}\n", printable_line(e.what()));
    return kExitFailure;
  }
  return kExitOk;
}
