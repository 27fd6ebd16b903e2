// Progress on stderr. On a terminal: a one-line bar redrawn in place. Otherwise (stderr to a file
// or a pipe, a batch job's log): plain lines, one when a phase starts, the first figures after it,
// then at most one per `plain_interval_s` seconds while the work runs, and one when it reaches
// 100 %, so a log shows that the run is alive without filling up.
#pragma once

#include <chrono>
#include <string>

namespace pinmask::cli {

class ProgressLine {
  public:
    // label: prefix of the plain lines ("pinmask depth"); plain_interval_s > 0.
    explicit ProgressLine(std::string label = "pinmask", double plain_interval_s = 5.0);
    ~ProgressLine();
    // True when stderr is a terminal (the bar).
    bool enabled() const { return terminal_; }
    // A named set-up phase ("building scenes"): the bar's text, or a plain line at once.
    void phase(const std::string& name);
    // fraction in [0, 1]; text follows the bar (or the percentage of a plain line). A new
    // `stage` (search's "search", then "rerank") starts over without a line of its own: its
    // first figures and its 100 % print, as after a phase.
    void update(double fraction, const std::string& text, const std::string& stage = "");
    void finish();

  private:
    using Clock = std::chrono::steady_clock;
    std::string label_;
    double interval_s_;
    bool terminal_;
    bool drawn_ = false;
    bool plain_done_ = false;  // the 100 % plain line was printed
    Clock::time_point last_plain_;
    bool print_next_ = true;  // the next update prints (the first, or the first after a phase)
    std::string stage_;       // the stage of the last update
};

}  // namespace pinmask::cli
