// SPDX-License-Identifier: LGPL-2.1-or-later
#include "sre.hpp"

#include <cstdlib>

namespace colortrack::eval {

cv::Rect startRect(const cv::Rect2d &box, cv::Size frame) {
  const cv::Rect rounded(cvRound(box.x), cvRound(box.y), cvRound(box.width), cvRound(box.height));
  return rounded & cv::Rect(cv::Point(0, 0), frame);
}

std::vector<StartBox> startBoxes(const cv::Rect2d &groundTruth, cv::Size frame, bool sre) {
  std::vector<StartBox> starts = {{"ope", startRect(groundTruth, frame)}};
  if (!sre) return starts;
  const double dx = 0.1 * groundTruth.width, dy = 0.1 * groundTruth.height;
  auto shifted = [&](const char *name, double x, double y) {
    starts.push_back({name, startRect(groundTruth + cv::Point2d(x, y), frame)});
  };
  shifted("left", -dx, 0);
  shifted("right", dx, 0);
  shifted("up", 0, -dy);
  shifted("down", 0, dy);
  shifted("up-left", -dx, -dy);
  shifted("down-right", dx, dy);
  auto scaled = [&](const char *name, double factor) {
    const cv::Point2d centre(groundTruth.x + groundTruth.width / 2, groundTruth.y + groundTruth.height / 2);
    const cv::Size2d size(groundTruth.width * factor, groundTruth.height * factor);
    starts.push_back(
        {name, startRect(cv::Rect2d(centre - cv::Point2d(size.width / 2, size.height / 2), size), frame)});
  };
  scaled("scale0.9", 0.9);
  scaled("scale1.1", 1.1);
  return starts;
}

std::optional<cv::Point> parseStartOffset(const std::string &text) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) return std::nullopt;
  const std::string x = text.substr(0, comma), y = text.substr(comma + 1);
  char *endX = nullptr, *endY = nullptr;
  const long dx = std::strtol(x.c_str(), &endX, 10), dy = std::strtol(y.c_str(), &endY, 10);
  if (x.empty() || y.empty() || *endX != '\0' || *endY != '\0') return std::nullopt;
  return cv::Point(int(dx), int(dy));
}

}  // namespace colortrack::eval
