// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

#include <string>

namespace pinmask::cli {

class ProgressLine {
  public:
    ProgressLine();
    ~ProgressLine();
    bool enabled() const { return enabled_; }
    // fraction in [0, 1]; text follows the bar.
    void update(double fraction, const std::string& text);
    void finish();

  private:
    bool enabled_;
    bool drawn_ = false;
};

}  // namespace pinmask::cli
