// Measured figures of the suite, printed only when EPICYCLE_FIGURES is set in the environment:
//   FIGURE <free text>                                   (quoted in docs/)
//   VERIFY␟<check>␟<reference>␟<model>␟<error>␟<tolerance>␟<verdict>
// (␟ the ASCII unit separator 0x1f; a '|' inside a field is written as '\|' for markdown)
// tools/verification_table.sh collects the VERIFY lines of a suite run into the table of
// docs/verification.md, so the table is what the suite measured, not a copy.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace epicycle::test {

inline bool FiguresWanted() { return std::getenv("EPICYCLE_FIGURES") != nullptr; }

inline std::string Sci(double x, int digits = 3) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*e", digits, x);
  return buf;
}

/// A field of a VERIFY row: '|' escaped for markdown tables.
inline std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

inline void Figure(const std::string& text) {
  if (FiguresWanted()) std::printf("FIGURE %s\n", text.c_str());
}

/// A measured value with full precision: "FIGURE name: value unit".
inline void FigureValue(const std::string& name, double value, const char* unit) {
  if (FiguresWanted()) std::printf("FIGURE %s: %.17g %s\n", name.c_str(), value, unit);
}

/// One row of the verification table: the check, its reference value (or description), the
/// model's value, the error measure, the tolerance, and whether it passed. The caller asserts the
/// same condition with CHECK; `pass` is what it found.
inline void VerifyRow(const std::string& check, const std::string& reference,
                      const std::string& model, const std::string& error,
                      const std::string& tolerance, bool pass) {
  if (FiguresWanted())
    std::printf("VERIFY\x1f%s\x1f%s\x1f%s\x1f%s\x1f%s\x1f%s\n", Cell(check).c_str(),
                Cell(reference).c_str(), Cell(model).c_str(), Cell(error).c_str(),
                Cell(tolerance).c_str(), pass ? "pass" : "FAIL");
}

/// A row whose figure is reported against a stated expectation without a pass/fail verdict
/// (a known deviation explained in docs).
inline void ReportRow(const std::string& check, const std::string& reference,
                      const std::string& model, const std::string& error,
                      const std::string& expectation) {
  if (FiguresWanted())
    std::printf("VERIFY\x1f%s\x1f%s\x1f%s\x1f%s\x1f%s\x1freported\n", Cell(check).c_str(),
                Cell(reference).c_str(), Cell(model).c_str(), Cell(error).c_str(),
                Cell(expectation).c_str());
}

}  // namespace epicycle::test
