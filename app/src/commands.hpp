// Subcommand registration of the `epicycle` program: one function per command family, each in
// its own file, all called by RegisterCommands (main.cpp, and the options' fuzz harness).
#pragma once

#include <CLI/CLI.hpp>

namespace epicycle::app {

void RegisterGeometryCommands(CLI::App& app);   // geometry, contacts      (geometry_commands.cpp)
void RegisterContactCommands(CLI::App& app);    // contact solve|compare   (contact_commands.cpp)
void RegisterStiffnessCommands(CLI::App& app);  // stiffness               (stiffness_commands.cpp)
void RegisterQuasiStaticCommands(CLI::App& app);  // quasistatic (quasistatic_commands.cpp)
void RegisterDynamicCommands(CLI::App& app);      // dynamic, modes (dynamic_commands.cpp)
void RegisterStudyCommands(CLI::App& app);        // study (study_commands.cpp)
/// Every command, one required, and --version (options.cpp).
void RegisterCommands(CLI::App& app);

}  // namespace epicycle::app
