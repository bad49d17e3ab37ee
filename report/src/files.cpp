#include "epicycle/report/files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

namespace epicycle::report {

namespace {

[[noreturn]] void Fail(const std::string& path, const char* what) {
  throw std::runtime_error(path + ": " + what + ": " + std::strerror(errno));
}

void WriteAll(std::FILE* f, const std::string& path, std::string_view text) {
  errno = 0;
  if (!text.empty() && std::fwrite(text.data(), 1, text.size(), f) != text.size())
    Fail(path, "cannot be written");
  if (std::fflush(f) != 0) Fail(path, "cannot be written");
}

}  // namespace

std::string Figure(double v, const char* format, const char* missing) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string(missing);
}

std::string Cell(double v) {
  std::string s;
  AppendCell(s, v);
  return s;
}

void AppendCell(std::string& out, double v) {
  if (!std::isfinite(v)) return;
  // std::to_chars' general form with a precision is printf's %g (C locale), as is fmt's "{:.9g}":
  // the same characters, at less than half of fmt's instructions (a cell of every CSV line).
  char text[32];  // "-1.23456789e-308": 16 characters at most
  const std::to_chars_result r =
      std::to_chars(text, text + sizeof text, v, std::chars_format::general, 9);
  out.append(text, r.ptr);
}

std::string CsvText(std::string_view text) {
  std::string cell(text);
  for (char& c : cell)
    if (c == '\n' || c == '\r') c = ';';
  if (cell.find_first_of(",\"#") == std::string::npos) return cell;
  std::string quoted = "\"";
  for (char c : cell) {
    if (c == '"') quoted.push_back('"');
    quoted.push_back(c);
  }
  return quoted + '"';
}

void WriteTextFile(const std::string& path, std::string_view text) {
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) Fail(path, "cannot be written");
  try {
    WriteAll(f, path, text);
  } catch (...) {
    std::fclose(f);
    throw;
  }
  errno = 0;
  if (std::fclose(f) != 0) Fail(path, "cannot be written");
}

CsvFile::CsvFile(std::string path, std::string_view head) : path_(std::move(path)) {
  errno = 0;
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) Fail(path_, "cannot be written");
  try {
    Write(head);
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

CsvFile::~CsvFile() {
  if (fd_ >= 0) ::close(fd_);
}

void CsvFile::WriteLine(std::string_view line) {
  std::string text;
  text.reserve(line.size() + 1);
  text.append(line);
  text.push_back('\n');
  Write(text);
}

void CsvFile::Write(std::string_view lines) {
  if (fd_ < 0) {
    errno = EBADF;
    Fail(path_, "written after it was closed");
  }
  // One write(2) for all the lines (a regular file takes them whole); a short write (a full
  // disk) is continued once more to get the system's reason.
  while (!lines.empty()) {
    errno = 0;
    const ssize_t n = ::write(fd_, lines.data(), lines.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      Fail(path_, "cannot be written");
    }
    lines.remove_prefix(static_cast<std::size_t>(n));
  }
}

void CsvFile::Close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  errno = 0;
  if (::close(fd) != 0) Fail(path_, "cannot be closed");
}

}  // namespace epicycle::report
