// epicycle: load sharing in planetary spur-gear transmissions with manufacturing errors.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "epicycle/config.h"

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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "epicycle: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
