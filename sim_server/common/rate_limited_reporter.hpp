#pragma once
// Reports of events that can come in floods (rejected messages, real-time overruns): at most one
// line per kind per interval, the next line shown saying how many of its kind were not shown, so
// that a burst cannot fill the log or slow the loop down, and nothing goes uncounted.
#include <cstdint>
#include <functional>
#include <map>
#include <string>

namespace tongue::common {

class RateLimitedReporter {
 public:
  using Clock = std::function<double()>;                 // s, never decreasing
  using Sink = std::function<void(const std::string&)>;  // takes one line, without '\n'

  // Lines go to sink (default: stderr); interval_s is measured on clock (default: the steady
  // clock). Throws std::invalid_argument when interval_s is negative or not a number.
  explicit RateLimitedReporter(double interval_s = 1.0, Sink sink = {}, Clock clock = {});

  // Writes line for kind, unless a line of kind was written less than the interval ago: then it
  // only counts it. A line written after some were held back ends with
  // " (and N more of this kind not shown)". Returns whether line was written.
  bool report(const std::string& kind, const std::string& line);

  // Lines of kind held back since the last one written.
  std::int64_t not_shown(const std::string& kind) const;

 private:
  struct Kind {
    double last_shown = 0.0;  // clock s
    std::int64_t not_shown = 0;
  };
  double interval_s_;
  Sink sink_;
  Clock clock_;
  std::map<std::string, Kind> kinds_;
};

}  // namespace tongue::common
