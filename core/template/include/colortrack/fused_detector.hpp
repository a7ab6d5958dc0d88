// SPDX-License-Identifier: LGPL-2.1-or-later
// The fused method's detector: a correlation filter over gradient-orientation cells and intensity (shape) and
// the object-versus-surroundings colour likelihood (colour), their response maps summed as in Staple
// (Bertinetto et al. 2016), with a DSST scale filter and a peak-to-sidelobe confidence.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/cell_features.hpp"
#include "colortrack/color.hpp"
#include "colortrack/correlation_filter.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/likelihood.hpp"
#include "colortrack/scratch_image.hpp"

namespace colortrack {

class FusedDetector {
 public:
  struct Estimate {
    cv::Point2d centre;         // frame coordinates
    cv::Size2d size;            // the target's size after the scale filter
    cv::Size2d extent{1, 1};    // what the colour map says of the size: report size * extent
    cv::Point2d offset{0, 0};   // ... and of the centre: report at centre + offset (frame px)
    double colourContrast = 1;  // ... and how object-like its best box is (1 without a colour cue)
    cv::Size2d shrink{1, 1};    // ... and, where that box is its smallest on both axes, a step towards it
    double confidence = 0;      // peak-to-sidelobe ratio of the fused response
    double colourPeak = 0;      // the mean colour likelihood of the target window at the peak
    double rival = 0;           // rivalPeakRatio of the fused response: another place nearly as good
    double secondPeak = 0;      // secondPeakRatio of the fused response: another object nearly as good
    std::optional<cv::Point2d> secondCentre;  // ... and where it puts the target's centre (frame px)
    unsigned long window = 0;                 // which locate() call measured it
  };

  // Whether a colour contrast (Estimate::colourContrast) shows an object at all: the bar under which the
  // colour vote leaves the box alone.
  static bool showsObject(double colourContrast);

  // Learns both filters from scratch on `box`.
  void start(const ImageSource &frame, const cv::Rect2d &box);
  bool started() const { return !translation_.empty(); }
  void stop() { translation_ = CorrelationFilter(); }

  // The fused response in a window around `centre` at the target size `size`; the scale filter then runs at
  // the position found. `colors` and `likelihood` give the colour cue (an empty likelihood leaves it out).
  Estimate locate(const ImageSource &frame, cv::Point2d centre, cv::Size2d size, const BinMapper &colors,
                  const ColorLikelihood &likelihood, bool withScale = true);

  // The search window around a target of `size`, frame px (what locate() reads).
  cv::Size2d windowFor(cv::Size2d size) const;

  // Adapts both filters to the target found by `e`. When `e` comes from the latest locate(), the filters
  // learn from the window and scale samples it measured; otherwise the window is read again from `frame`.
  void learn(const ImageSource &frame, const Estimate &e);

  // A place over the whole frame where the target could be: its centre, the size tried there and the mean
  // colour likelihood of a target-sized window at it (comparable with Estimate::colourPeak).
  struct Candidate {
    cv::Point2d centre;
    cv::Size2d size;
    double colour = 0;
  };
  // Candidates for re-detection: for each of `sizes`, the `countPerSize` strongest, well-separated maxima of
  // the colour likelihood averaged over a window of that size, on one reduced copy of the frame; then the
  // `imageCountPerSize` strongest of the likelihood against the whole frame (ColorLikelihood::
  // mapAgainstImage). Every candidate's colour is read on the first map.
  std::vector<Candidate> colourCandidates(const ImageSource &frame, const std::vector<cv::Size2d> &sizes,
                                          const BinMapper &colors, const ColorLikelihood &likelihood,
                                          int countPerSize, int imageCountPerSize = 0);

 private:
  // The search window around `centre` for a target of `size`: readWindow() resamples it into patch_ (colour)
  // and gray_, windowFeatures() also computes its feature channels.
  void windowFeatures(const ImageSource &frame, cv::Point2d centre, cv::Size2d size);
  void readWindow(const ImageSource &frame, cv::Point2d centre, cv::Size2d size);
  void scaleSamples(const ImageSource &frame, cv::Point2d centre, cv::Size2d size);
  // The point of the normalised window (px) that response element `element` (cells, fractions allowed)
  // stands for: the target centred there gives that element's value, for the colour cue as for the filter.
  cv::Point2d windowPoint(cv::Point2d element) const;
  // What the colour likelihood map of the last colourResponse() says of the box at the peak: fills in `e`'s
  // extent and offset.
  void colourVote(cv::Point2d peakCells, cv::Point2d zoom, Estimate &e) const;
  void colourResponse(const BinMapper &colors, const ColorLikelihood &likelihood, cv::Size2d targetNormalised,
                      cv::Mat &response);

  CorrelationFilter translation_;
  ScaleFilter scale_;
  cv::Size window_;             // the normalised search window, px (whole cells)
  cv::Size2d windowRatio_;      // window size / target size in the frame
  cv::Rect2d windowRect_;       // the frame rectangle the last window's features came from
  cv::Size scaleModel_;         // the normalised patch of each scale sample, px (whole cells)
  bool scaleMeasured_ = false;  // locate() ran the scale filter: learn() trains it on the same samples
  unsigned long locates_ = 0;   // locate() calls so far

  // Scratch reused across frames.
  PatchSampler sampler_;
  cv::Mat patch_, grayBytes_, gray_, scaleSamples_, bins_, probability_, integral_;
  // colourCandidates(): the reduced frame, its bins, the two likelihoods and their means
  ScratchImage candidateScratch_[6];
  ImageColours imageColours_;  // colourCandidates(): the reduced frame's colours, counted once for all sizes
  std::vector<cv::Mat> channels_;
  CellFeatureIntegral scaleIntegral_;
};

}  // namespace colortrack
