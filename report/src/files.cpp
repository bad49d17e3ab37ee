#include "epicycle/report/files.hpp"

#include <cerrno>
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

std::string Num(double v, const char* format, const char* missing) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : std::string(missing);
}

std::string CsvText(std::string text) {
  for (char& c : text)
    if (c == ',' || c == '\n' || c == '\r') c = ';';
  return text;
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

CsvFile::CsvFile(std::string path) : path_(std::move(path)) {
  errno = 0;
  file_ = std::fopen(path_.c_str(), "wb");
  if (!file_) Fail(path_, "cannot be written");
}

CsvFile::~CsvFile() {
  if (file_) std::fclose(file_);
}

void CsvFile::WriteLine(std::string_view line) {
  std::string text;
  text.reserve(line.size() + 1);
  text.append(line);
  text.push_back('\n');
  Write(text);
}

void CsvFile::Write(std::string_view lines) {
  if (!file_) {
    errno = EBADF;
    Fail(path_, "written after it was closed");
  }
  WriteAll(file_, path_, lines);
}

void CsvFile::Close() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  errno = 0;
  if (std::fclose(f) != 0) Fail(path_, "cannot be closed");
}

}  // namespace epicycle::report
