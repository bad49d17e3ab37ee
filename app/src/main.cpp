// epicycle: load sharing in planetary spur-gear transmissions with manufacturing errors.
// Exit status (README): 0 computed; 1 a computation failed (a solve that did not converge, a
// library's runtime_error, a result that could not be written); 2 bad input or usage (a command
// line CLI11 rejects, a missing or unreadable input file, std::invalid_argument from a library).
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "console.hpp"
#include "epicycle/config.h"

int main(int argc, char** argv) {
  // A file past the size limit (ulimit -f) is a write that fails with EFBIG, named with its path
  // like a full disk's, not a process killed by SIGXFSZ without a word.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"epicycle " EPICYCLE_VERSION
               ": load sharing in planetary spur-gear transmissions with manufacturing errors"};
  epicycle::app::RegisterCommands(app);
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
  } catch (const std::invalid_argument& e) {
    // The libraries' contract: invalid_argument means the input (a file, a value) breaks a rule.
    std::fprintf(stderr, "epicycle: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    // Anything else stopped a computation (or the writing of its results) on legal input.
    std::fprintf(stderr, "epicycle: failed: %s\n", e.what());
    return 1;
  }
  // The printed report is a result too: one that could not be written is a failure.
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    // errno is the flush's, or the first failed write's (a report larger than the stream's
    // buffer is written inside the call that prints it); else only the error flag is left.
    const int cause = errno != 0 ? errno : epicycle::app::StdoutErrno();
    std::fprintf(stderr, "epicycle: failed: standard output: cannot be written: %s\n",
                 cause != 0 ? std::strerror(cause) : "an earlier write failed");
    return 1;
  }
  return 0;
}
