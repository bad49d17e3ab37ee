// The one accumulator of the project's summaries (a quasi-static sweep, a dynamic run, a
// tolerance study): count, sum, minimum, maximum and mean of values added one at a time.
//
// Rule for empty input: with no value added, count() is 0 and min(), max() and mean() are NaN,
// "no value" (a report prints "-", a JSON file null), never a made-up 0 or ±∞. sum() is 0.
#pragma once

#include <algorithm>
#include <limits>

namespace epicycle::transmission {

class Accumulator {
 public:
  /// Adds a value; callers leave out what is not finite (a failed position, a missing cell).
  void Add(double x) {
    if (count_ == 0) {
      min_ = max_ = x;
    } else {
      min_ = std::min(min_, x);
      max_ = std::max(max_, x);
    }
    sum_ += x;
    ++count_;
  }
  long count() const { return count_; }  ///< values added [-]
  bool empty() const { return count_ == 0; }
  double sum() const { return sum_; }  ///< Σ x in the order added (0 when empty)
  double min() const { return count_ > 0 ? min_ : kNaN; }
  double max() const { return count_ > 0 ? max_ : kNaN; }
  /// (Σ x)/count, the sum taken in the order added; NaN when empty.
  double mean() const { return count_ > 0 ? sum_ / static_cast<double>(count_) : kNaN; }

 private:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  long count_ = 0;
  double sum_ = 0, min_ = 0, max_ = 0;
};

}  // namespace epicycle::transmission
