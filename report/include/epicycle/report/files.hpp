// Writing result files: numbers for cells (never nan or inf), CSV files written in whole lines
// and checked at every write, and whole text files (JSON, SVG). Every failed open, write, flush
// or close throws std::runtime_error naming the file and the system's reason (strerror(errno)),
// so that no result is lost without a message.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace epicycle::report {

// Numbers have one formatting function per purpose: a message's value io::Num
// (io/number_format.hpp), a figure of a report's text Figure, a CSV cell Cell.

/// A figure of a report's text: `v` formatted with `format` (fmt syntax) if finite, otherwise
/// `missing` (empty by default). Never prints nan or inf.
std::string Figure(double v, const char* format, const char* missing = "");
/// A CSV cell: `v` with 9 significant digits ("{:.9g}", printf's %.9g: the same text), empty if
/// not finite.
std::string Cell(double v);
/// Appends Cell(v) to `out` (a CSV line's cell without a string of its own).
void AppendCell(std::string& out, double v);

/// A text cell of a CSV line (RFC 4180): the text as it is, unless it holds a ',', a '"' or a
/// '#' (pandas' comment='#' would cut the line there): then in double quotes, each '"' doubled.
/// A line break becomes ';' first (a row stays one line: the files are read and resumed line by
/// line). Every text cell of every CSV the report writes goes through here.
std::string CsvText(std::string_view text);

/// Writes `text` to `path` (created or truncated) and closes it.
/// @throws std::runtime_error "PATH: cannot be written: REASON" on any failure.
void WriteTextFile(const std::string& path, std::string_view text);

/// A CSV (or any line-oriented) result file, written as results are computed: each call hands
/// its whole lines to the system in one write(2) (no buffer of this process holds a part of them),
/// so that a run that stops midway keeps the lines of every earlier call whole. A run killed
/// (SIGKILL) inside a call may leave that call's lines cut where the system stops a write of a
/// killed process (at a page boundary of the file): a reader drops a last line without its end.
class CsvFile {
 public:
  /// Creates or truncates `path` and writes `head` (its first lines: provenance, columns) at
  /// once. @throws std::runtime_error naming it if it cannot be opened or written.
  explicit CsvFile(std::string path, std::string_view head = {});
  ~CsvFile();  ///< closes the file if Close() was not called (errors there are not reported)
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;

  /// Writes `line` and "\n" at once. @throws std::runtime_error naming the file.
  void WriteLine(std::string_view line);
  /// Writes `lines` (each ending in "\n") at once. @throws std::runtime_error naming the file.
  void Write(std::string_view lines);
  /// Closes the file, checking the close. @throws std::runtime_error naming the file.
  void Close();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace epicycle::report
