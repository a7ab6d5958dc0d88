// SPDX-License-Identifier: LGPL-2.1-or-later
// Method::Indexing: the colour search with the template histogram as its cue.
#include "colortrack/method_indexing.hpp"

#include <algorithm>

#include "colortrack/box.hpp"
#include "colortrack/scale.hpp"
#include "colortrack/search.hpp"

namespace colortrack {

std::optional<Detection> HistogramCue::detectIn(const ImageSource &frame, const cv::Rect &region,
                                                double scale, const cv::Point2d *) {
  const TrackerSettings &s = context_.settings;
  const cv::Size2d size = context_.track.windowSize(scale);
  // Room for the scale refinement's largest window and its ring.
  const int pad = cvRound(std::max(size.width, size.height) *
                          (std::max(0.0, s.scale.maxFactor - 1.0) + s.scale.ringWidth * s.scale.maxFactor)) +
                  2;
  const auto reduced = reader_.read(frame, region, size, pad, context_.model.mapper());
  if (!reduced) return std::nullopt;
  const BinImage &bins = reader_.bins();
  const Histogram &model = context_.model.histogram();
  const cv::Size window(std::max(1, cvRound(reduced->sizeL.width)),
                        std::max(1, cvRound(reduced->sizeL.height)));
  const SearchResult found = searchWindow(bins, reduced->searchL, window, model, s.weights);
  if (!found.found || found.score < s.matchThreshold) return std::nullopt;
  const ScaleResult refined = refineScale(bins, found.box, model, s.weights, s.scale);
  Detection d;
  d.box = reduced->toFull(refined.box);
  d.score = refined.match;
  d.verified = context_.model.verify(frame, roundRect(d.box), s);
  return d;
}

std::optional<cv::Point> HistogramCue::bestCoarseWindow(const BinImage &coarse, cv::Size window) {
  const SearchResult found = searchWindow(coarse, cv::Rect(cv::Point(), coarse.bins.size()), window,
                                          context_.model.histogram(), context_.settings.weights);
  if (!found.found) return std::nullopt;
  return found.box.tl();
}

std::unique_ptr<DetectionMethod> makeIndexingMethod(const MethodContext &context) {
  return std::make_unique<ColorSearchMethod<HistogramCue>>(context);
}

}  // namespace colortrack
