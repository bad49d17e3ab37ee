#include "epicycle/io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace epicycle::io {

namespace {

const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string Size(std::uintmax_t bytes) {
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string ReadInputFile(const std::string& path, const std::string& what,
                          std::uintmax_t max_bytes) {
  auto fail = [&](const std::string& text) { throw std::invalid_argument(path + ": " + text); };
  // O_NONBLOCK: opening a FIFO without a writer must not block (it is refused below).
  errno = 0;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == EISDIR) fail("is a directory, not a " + what);
    fail(std::string("cannot be opened: ") + std::strerror(errno));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) fail(std::string("cannot be read: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) {
    const std::string kind = KindOf(st.st_mode);
    fail(kind == "not a regular file" ? kind + ", not a " + what
                                      : "is " + kind + ", not a " + what + ": give a regular file");
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes)
    fail(std::to_string(size) + " bytes: larger than the " + Size(max_bytes) + " a " + what +
         " may have");
  // Read to the end, never past max_bytes (a file that grows while it is read is refused too).
  std::string text;
  text.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0) {
      if (errno == EINTR) continue;
      fail(std::string("cannot be read: ") + std::strerror(errno));
    }
    if (got == 0) break;
    text.append(buffer, static_cast<std::size_t>(got));
    if (text.size() > max_bytes)
      fail("grew past the " + Size(max_bytes) + " a " + what + " may have while it was read");
  }
  return text;
}

}  // namespace epicycle::io
