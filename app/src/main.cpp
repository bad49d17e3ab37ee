// epicycle: load sharing in planetary spur-gear transmissions with manufacturing errors.
// Exit status: 0 computed, 1 a computation failed (provenance.hpp), 2 bad input or usage.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "epicycle/config.h"
#include "provenance.hpp"

int main(int argc, char** argv) {
  CLI::App app{"epicycle " EPICYCLE_VERSION
               ": load sharing in planetary spur-gear transmissions with manufacturing errors"};
  app.require_subcommand(1);
  app.set_version_flag("--version", EPICYCLE_VERSION);
  epicycle::app::RegisterGeometryCommands(app);
  epicycle::app::RegisterContactCommands(app);
  epicycle::app::RegisterStiffnessCommands(app);
  epicycle::app::RegisterQuasiStaticCommands(app);
  epicycle::app::RegisterDynamicCommands(app);
  epicycle::app::RegisterStudyCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message (or the help); its own codes (105 for a value out of range, ...)
    // become the documented 2, help and version stay 0.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const epicycle::app::ComputationFailed& e) {
    // Results were written and the failures listed; the run did not compute what was asked.
    std::fprintf(stderr, "epicycle: failed: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "epicycle: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
