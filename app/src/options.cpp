#include "options.hpp"

#include "commands.hpp"
#include "epicycle/config.h"

namespace epicycle::app {

void RegisterCommands(CLI::App& app) {
  app.require_subcommand(1);
  app.set_version_flag("--version", EPICYCLE_VERSION);
  RegisterGeometryCommands(app);
  RegisterContactCommands(app);
  RegisterStiffnessCommands(app);
  RegisterQuasiStaticCommands(app);
  RegisterDynamicCommands(app);
  RegisterStudyCommands(app);
}

}  // namespace epicycle::app
