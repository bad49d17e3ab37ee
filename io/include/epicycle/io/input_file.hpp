// Reading an input file (a scene, a study, a contact problem) whole, refusing up front what is not
// a regular file (a directory, a FIFO that would block, a device such as /dev/zero that never
// ends, a symlink to one) and what is larger than the kind of file can be, so that a wrong path
// is a message and never a hang or gigabytes read.
//
// Part of the bottom layer io/ (library epicycle_io: no TOML library), read by every layer that
// reads a file, the contact core's problem files included.
#pragma once

#include <cstdint>
#include <string>

namespace epicycle::io {

/// The bytes of `path`, a `what` ("scene file (TOML)"), of at most `max_bytes`.
/// @throws std::invalid_argument "PATH: is a directory, not a WHAT", "PATH: is a FIFO (named pipe),
///         not a WHAT: give a regular file", "PATH: N bytes: larger than the M a WHAT may have",
///         "PATH: cannot be opened: REASON" (the system's reason).
std::string ReadInputFile(const std::string& path, const std::string& what,
                          std::uintmax_t max_bytes);

}  // namespace epicycle::io
