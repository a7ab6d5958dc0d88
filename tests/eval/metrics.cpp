// SPDX-License-Identifier: LGPL-2.1-or-later
#include "metrics.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <sstream>

#include "scene.hpp"

namespace colortrack::eval {

std::string format(const char *fmt, ...) {
  char buffer[1024];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

namespace {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

bool isJpegName(const std::string &name) {
  const std::string lower = lowercase(name);
  auto endsWith = [&lower](const std::string &tail) {
    return lower.size() > tail.size() && lower.compare(lower.size() - tail.size(), tail.size(), tail) == 0;
  };
  return endsWith(".jpg") || endsWith(".jpeg");
}

// Splits "img0042.jpg" into "img", "0042", ".jpg" (the last run of digits is the index).
bool splitIndexedName(const std::string &name, std::string &prefix, std::string &digits,
                      std::string &suffix) {
  const std::size_t dot = name.rfind('.');
  const std::string stem = name.substr(0, dot);
  std::size_t end = stem.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
  std::size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  if (begin == end) return false;
  prefix = stem.substr(0, begin);
  digits = stem.substr(begin, end - begin);
  suffix = name.substr(end);
  return true;
}

}  // namespace

bool parseGroundTruth(const std::string &text, double originOffset, std::vector<GroundTruthBox> &boxes,
                      std::string *error) {
  boxes.clear();
  std::vector<GroundTruthBox> parsed;
  int pendingBlank = 0;  // blank lines count only when a box follows them
  std::istringstream lines(text);
  std::string line;
  int lineNumber = 0;
  while (std::getline(lines, line)) {
    ++lineNumber;
    std::replace_if(
        line.begin(), line.end(), [](char c) { return c == ',' || c == '\t' || c == '\r' || c == ';'; }, ' ');
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.empty()) {
      ++pendingBlank;
      continue;
    }
    if (pendingBlank > 0) {
      if (error)
        *error = "line " + std::to_string(lineNumber - pendingBlank) + ": blank line inside the file";
      return false;
    }
    std::vector<double> values;
    for (const std::string &token : tokens) {
      // strtod takes "NaN"/"nan" as well as numbers; anything left over is not a number.
      char *end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') {
        if (error) *error = "line " + std::to_string(lineNumber) + ": not a number: \"" + token + "\"";
        return false;
      }
      values.push_back(value);
    }
    const bool anyNan = std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); });
    if (anyNan && values.size() <= 4) {
      parsed.emplace_back(std::nullopt);
      continue;
    }
    if (values.size() != 4) {
      if (error)
        *error = "line " + std::to_string(lineNumber) + ": expected x,y,w,h (4 numbers), got " +
                 std::to_string(values.size());
      return false;
    }
    const cv::Rect2d box(values[0] - originOffset, values[1] - originOffset, values[2], values[3]);
    if (box.width > 0 && box.height > 0)
      parsed.emplace_back(box);
    else
      parsed.emplace_back(std::nullopt);
  }
  boxes = std::move(parsed);
  return true;
}

double overlap(const cv::Rect2d &a, const cv::Rect2d &b) {
  return scene::iou(a, b);  // the one IoU of the tests, the demo and the evaluation
}

double centreDistance(const cv::Rect2d &a, const cv::Rect2d &b) {
  const cv::Point2d ca(a.x + a.width / 2, a.y + a.height / 2), cb(b.x + b.width / 2, b.y + b.height / 2);
  return cv::norm(ca - cb);
}

SequenceScore scoreSequence(const std::vector<GroundTruthBox> &groundTruth,
                            const std::vector<std::optional<cv::Rect2d>> &tracked) {
  SequenceScore score;
  std::vector<int> successCount(kSuccessSteps, 0), precisionCount(kPrecisionSteps, 0);
  for (std::size_t frame = 0; frame < groundTruth.size(); ++frame) {
    if (!groundTruth[frame]) continue;
    ++score.scoredFrames;
    const bool hasBox = frame < tracked.size() && tracked[frame].has_value();
    const double iou = hasBox ? overlap(*tracked[frame], *groundTruth[frame]) : 0.0;
    const double error = hasBox ? centreDistance(*tracked[frame], *groundTruth[frame])
                                : std::numeric_limits<double>::infinity();
    // OTB: success counts IoU strictly above the threshold, precision counts errors at or below it.
    for (int step = 0; step < kSuccessSteps; ++step)
      if (iou > step / double(kSuccessSteps - 1)) ++successCount[step];
    for (int step = 0; step < kPrecisionSteps; ++step)
      if (error <= step) ++precisionCount[step];
  }
  const double frames = std::max(score.scoredFrames, 1);
  for (int count : successCount) score.success.push_back(count / frames);
  for (int count : precisionCount) score.precision.push_back(count / frames);
  score.auc = cv::mean(score.success)[0];
  score.precisionAt20 = score.precision[static_cast<int>(kPrecisionThresholdPx)];
  return score;
}

SequenceScore averageScores(const std::vector<SequenceScore> &scores) {
  SequenceScore mean;
  mean.success.assign(kSuccessSteps, 0.0);
  mean.precision.assign(kPrecisionSteps, 0.0);
  if (scores.empty()) return mean;
  for (const SequenceScore &s : scores) {
    mean.scoredFrames += s.scoredFrames;
    for (int i = 0; i < kSuccessSteps; ++i) mean.success[i] += s.success[i] / scores.size();
    for (int i = 0; i < kPrecisionSteps; ++i) mean.precision[i] += s.precision[i] / scores.size();
  }
  mean.auc = cv::mean(mean.success)[0];
  mean.precisionAt20 = mean.precision[static_cast<int>(kPrecisionThresholdPx)];
  return mean;
}

AlarmFigures &AlarmFigures::operator+=(const AlarmFigures &o) {
  wrongFrames += o.wrongFrames;
  wrongTracking += o.wrongTracking;
  runs += o.runs;
  lossRuns += o.lossRuns;
  reacquiredRuns += o.reacquiredRuns;
  afterLossFrames += o.afterLossFrames;
  afterLossFound += o.afterLossFound;
  afterLossInView += o.afterLossInView;
  afterLossInViewFound += o.afterLossInViewFound;
  return *this;
}

AlarmFigures alarmFigures(const std::vector<GroundTruthBox> &groundTruth,
                          const std::vector<std::optional<cv::Rect2d>> &boxes,
                          const std::vector<std::string> &states, cv::Size frameSize) {
  AlarmFigures figures;
  figures.runs = 1;
  const cv::Rect2d frame(0, 0, frameSize.width, frameSize.height);
  bool lost = false;
  for (std::size_t i = 1; i < groundTruth.size(); ++i) {
    const std::string state = i < states.size() ? states[i] : "";
    const bool hasBox = i < boxes.size() && boxes[i].has_value();
    // The frame that declares the loss is not "after" it: its IoU says nothing about coming back.
    const bool afterLoss = lost;
    if (!lost && (state == "lost" || state == "searching")) {
      lost = true;
      ++figures.lossRuns;
    }
    if (!groundTruth[i]) continue;
    const cv::Rect2d &truth = *groundTruth[i];
    const double iou = hasBox ? overlap(*boxes[i], truth) : 0.0;
    if (iou < kWrongIou) {
      ++figures.wrongFrames;
      if (hasBox && state == "tracking") ++figures.wrongTracking;
    }
    if (!afterLoss) continue;
    const bool found = iou >= kFoundIou;
    const bool inView = (truth & frame).area() >= 0.5 * truth.area();
    ++figures.afterLossFrames;
    figures.afterLossFound += found;
    figures.afterLossInView += inView;
    figures.afterLossInViewFound += inView && found;
  }
  figures.reacquiredRuns = figures.afterLossFound > 0 ? 1 : 0;
  return figures;
}

std::string FramePattern::printfPattern() const {
  // '%' in a file name would be read as a conversion by multifilesrc.
  auto escape = [](const std::string &text) {
    std::string out;
    for (char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out;
  };
  const std::string index = digits > 0 ? "%0" + std::to_string(digits) + "d" : "%d";
  return escape(prefix) + index + escape(suffix);
}

bool detectFramePattern(const std::vector<std::string> &fileNames, FramePattern &pattern,
                        std::string *error) {
  auto fail = [error](const std::string &message) {
    if (error) *error = message;
    return false;
  };
  std::vector<std::string> names;
  std::copy_if(fileNames.begin(), fileNames.end(), std::back_inserter(names), isJpegName);
  if (names.empty()) return fail("no .jpg frames");

  FramePattern found;
  std::vector<long> indices;
  bool sameWidth = true, leadingZero = false;
  std::size_t width = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::string prefix, digits, suffix;
    if (!splitIndexedName(names[i], prefix, digits, suffix))
      return fail("no frame number in \"" + names[i] + "\"");
    if (i == 0) {
      found.prefix = prefix;
      found.suffix = suffix;
      width = digits.size();
    } else if (prefix != found.prefix || suffix != found.suffix) {
      return fail("frame names do not share one pattern: \"" + names[0] + "\" and \"" + names[i] + "\"");
    }
    sameWidth = sameWidth && digits.size() == width;
    leadingZero = leadingZero || (digits.size() > 1 && digits[0] == '0');
    indices.push_back(std::stol(digits));
  }
  // Zero-padded names all have one width; unpadded ones ("1.jpg" ... "10.jpg") must never start with 0.
  if (sameWidth)
    found.digits = static_cast<int>(width);
  else if (!leadingZero)
    found.digits = 0;
  else
    return fail("frame numbers are zero-padded to different widths");

  std::sort(indices.begin(), indices.end());
  for (std::size_t i = 1; i < indices.size(); ++i)
    if (indices[i] != indices[i - 1] + 1)
      return fail("frame numbers are not consecutive: " + std::to_string(indices[i - 1]) + " then " +
                  std::to_string(indices[i]));
  found.startIndex = static_cast<int>(indices.front());
  found.count = static_cast<int>(indices.size());
  pattern = found;
  return true;
}

}  // namespace colortrack::eval
