// SPDX-License-Identifier: LGPL-2.1-or-later
#include "eval_plot.hpp"

#include <algorithm>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "metrics.hpp"

namespace fs = std::filesystem;

namespace colortrack::eval {

namespace {

cv::Scalar curveColour(std::size_t index) {
  static const cv::Scalar palette[] = {{40, 40, 220}, {200, 90, 20},   {40, 160, 40},  {180, 40, 180},
                                       {0, 140, 255}, {170, 160, 0},   {40, 70, 130},  {120, 120, 120},
                                       {0, 0, 0},     {220, 120, 160}, {30, 120, 120}, {110, 30, 60}};
  return palette[index % (sizeof palette / sizeof palette[0])];
}

}  // namespace

void drawPlot(const std::string &title, const std::string &xLabel, double xMax, double xTickStep,
              const char *tickFormat, std::vector<Curve> curves, const fs::path &path) {
  const cv::Size canvasSize(1000, 620);
  const cv::Rect plot(80, 50, 560, 500);
  cv::Mat canvas(canvasSize, CV_8UC3, cv::Scalar::all(255));
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  auto toPixel = [&](double x, double y) {
    return cv::Point(plot.x + cvRound(x / xMax * plot.width),
                     plot.y + plot.height - cvRound(y * plot.height));
  };
  // Grid and tick labels.
  for (double x = 0; x <= xMax + 1e-9; x += xTickStep) {
    cv::line(canvas, toPixel(x, 0), toPixel(x, 1), cv::Scalar::all(225), 1);
    const std::string text = format(tickFormat, x);
    const cv::Size size = cv::getTextSize(text, font, 0.45, 1, nullptr);
    cv::putText(canvas, text, toPixel(x, 0) + cv::Point(-size.width / 2, 20), font, 0.45, cv::Scalar::all(0),
                1, cv::LINE_AA);
  }
  for (int i = 0; i <= 10; ++i) {
    const double y = i / 10.0;
    cv::line(canvas, toPixel(0, y), toPixel(xMax, y), cv::Scalar::all(225), 1);
    cv::putText(canvas, format("%.1f", y), toPixel(0, y) + cv::Point(-34, 5), font, 0.45, cv::Scalar::all(0),
                1, cv::LINE_AA);
  }
  cv::rectangle(canvas, plot, cv::Scalar::all(0), 1);
  const cv::Size titleSize = cv::getTextSize(title, font, 0.7, 2, nullptr);
  cv::putText(canvas, title, cv::Point(plot.x + (plot.width - titleSize.width) / 2, 32), font, 0.7,
              cv::Scalar::all(0), 2, cv::LINE_AA);
  const cv::Size xLabelSize = cv::getTextSize(xLabel, font, 0.55, 1, nullptr);
  cv::putText(canvas, xLabel, cv::Point(plot.x + (plot.width - xLabelSize.width) / 2, plot.br().y + 50), font,
              0.55, cv::Scalar::all(0), 1, cv::LINE_AA);
  cv::Mat yLabel(24, 200, CV_8UC3, cv::Scalar::all(255));
  cv::putText(yLabel, xMax > 1 ? "Precision" : "Success rate", cv::Point(40, 18), font, 0.55,
              cv::Scalar::all(0), 1, cv::LINE_AA);
  cv::rotate(yLabel, yLabel, cv::ROTATE_90_COUNTERCLOCKWISE);
  yLabel.copyTo(canvas(cv::Rect(6, plot.y + plot.height / 2 - 100, 24, 200)));

  // Colours follow the order given on the command line; the legend follows the score.
  for (std::size_t i = 0; i < curves.size(); ++i) {
    std::vector<cv::Point> points;
    const std::size_t n = curves[i].values.size();
    for (std::size_t k = 0; k < n; ++k)
      points.push_back(toPixel(xMax * k / double(n - 1), std::clamp(curves[i].values[k], 0.0, 1.0)));
    cv::polylines(canvas, points, false, curveColour(i), i == 0 ? 3 : 2, cv::LINE_AA);
  }
  std::vector<std::size_t> order(curves.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return curves[a].score > curves[b].score; });
  int y = plot.y + 14;
  for (std::size_t i : order) {
    const cv::Point left(plot.br().x + 20, y);
    cv::line(canvas, left, left + cv::Point(30, 0), curveColour(i), i == 0 ? 3 : 2, cv::LINE_AA);
    cv::putText(canvas, format("%s [%.3f]", curves[i].label.c_str(), curves[i].score),
                left + cv::Point(38, 5), font, 0.45, cv::Scalar::all(0), 1, cv::LINE_AA);
    y += 24;
  }
  if (!cv::imwrite(path.string(), canvas)) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace colortrack::eval
