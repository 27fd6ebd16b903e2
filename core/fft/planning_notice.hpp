// A notice before FFTW measures a plan the wisdom does not hold (core/fft/fft.cpp). Measuring
// takes up to kFftPlanTimeLimitSeconds per plan, once per size and kept in the wisdom file, so a
// face can say what the wait is. The function is called under the planner's lock with the
// transform's size; libraries never print, the command line prints one line per size. An empty
// function (the default) says nothing.
#pragma once

#include <functional>

namespace pinmask {

void set_fft_planning_notice(std::function<void(int rows, int cols)> notice);

}  // namespace pinmask
