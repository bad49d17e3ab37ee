// `epicycle contact solve|compare`: the contact core on problem files.
#include "commands.hpp"

namespace epicycle::app {

void RegisterContactCommands(CLI::App& /*app*/) {
  // Registered once the contact core lands (issue: contact problem with interchangeable back ends).
}

}  // namespace epicycle::app
