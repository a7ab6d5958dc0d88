// SPDX-License-Identifier: LGPL-2.1-or-later
// OTB-style success and precision plots (OpenCV drawing, legend sorted by score).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace colortrack::eval {

struct Curve {
  std::string label;
  std::vector<double> values;
  double score;
};

// Draws `curves` over 0..xMax (values in 0..1) into a PNG at `path`; throws when it cannot be written.
void drawPlot(const std::string &title, const std::string &xLabel, double xMax, double xTickStep,
              const char *tickFormat, std::vector<Curve> curves, const std::filesystem::path &path);

}  // namespace colortrack::eval
