// SPDX-License-Identifier: LGPL-2.1-or-later
// Multi-channel discriminative correlation filter (MOSSE / DSST / Staple's translation filter), learnt online
// in the Fourier domain over any feature channels of a fixed-size patch, and the 1-D variant over scales.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace colortrack {

// Translation filter over a grid of feature cells.
class CorrelationFilter {
 public:
  // cells: the feature grid; sigma: width of the desired Gaussian response, in cells; lambda: regularisation.
  void init(cv::Size cells, double sigma, double lambda);
  bool empty() const { return numerator_.empty(); }
  cv::Size cells() const { return window_.size(); }

  // Learns from the channels of a patch centred on the target. rate 1 replaces the model; smaller values
  // blend it into the old one.
  void train(const std::vector<cv::Mat> &channels, double rate);

  // Correlation response over the channels of a search patch (the same grid), CV_32FC1, centred: element
  // (cols/2 + dx, rows/2 + dy) is the response to the target shifted by (dx, dy) cells. About 1 at a perfect
  // match.
  void respond(const std::vector<cv::Mat> &channels, cv::Mat &response) const;
  // Learns from the patch last given to respond(), in which the target lies `offset` cells from the centre
  // (the desired response is moved there), so that a frame needs one feature extraction, not two.
  void trainOnLastResponse(cv::Point2d offset, double rate);

 private:
  void transform(const std::vector<cv::Mat> &channels, std::vector<cv::Mat> &spectra) const;
  void trainOnSpectra(const cv::Mat &label, double rate);
  cv::Mat window_;                  // Hann window, against the patch's wrap-around edges
  cv::Mat labelSpectrum_;           // DFT of the desired response (a Gaussian peaked at zero shift)
  std::vector<cv::Mat> numerator_;  // per channel: label * conj(feature spectrum), averaged over time
  cv::Mat denominator_;             // sum over channels of |feature spectrum|^2, averaged over time
  cv::Mat inverseDenominator_;      // 1 / (denominator + lambda), what respond() multiplies by
  double lambda_ = 1e-3;
  mutable std::vector<cv::Mat> spectra_;  // of the patch last trained on or responded to
  cv::Mat shiftedLabel_;                  // scratch
  mutable cv::Mat sum_, circular_;        // scratch
};

// Scale filter (DSST): one feature column per candidate scale, correlated along the scale axis.
class ScaleFilter {
 public:
  // scales: number of candidate scales (odd); step: ratio between neighbouring scales.
  void init(int scales, double step, double sigma, double lambda);
  bool empty() const { return numerator_.empty(); }
  // Scale factors of the candidates, relative to the current size, smallest first.
  const std::vector<double> &factors() const { return factors_; }

  // samples: one row per candidate scale (CV_32FC1, scales x features).
  void train(const cv::Mat &samples, double rate);
  // The factor by which the size changed (between candidates: the peak interpolated). Keeps the samples'
  // spectrum for trainOnLastEstimate().
  double estimate(const cv::Mat &samples);
  // Learns from the samples last given to estimate(), as they were measured: the label stays on the middle
  // candidate, the size before the change. Measured on the shared sequences (docs/benchmarks-history.md): this
  // (0.608 tune / 0.485 confirm) against re-sampling at the new size as DSST does (0.604 / 0.483, 35 %
  // slower) and against moving the spectrum by the change found (0.578 / 0.479).
  void trainOnLastEstimate(double rate);

 private:
  void transform(const cv::Mat &samples, cv::Mat &spectrum);
  void trainOnSpectrum(const cv::Mat &spectrum, double rate);
  std::vector<double> factors_;
  // The Hann window over the scales and the packed DFT along the scale axis as one scales x scales matrix:
  // a sample's spectrum is its row of features times this matrix (see transform()).
  cv::Mat windowedDft_;
  cv::Mat labelSpectrum_;           // 1 x scales, packed (CCS)
  cv::Mat numerator_;               // features x scales, packed (CCS)
  std::vector<float> denominator_;  // per frequency 0 .. scales / 2
  double lambda_ = 1e-2;
  double step_ = 1.02;
  cv::Mat lastSpectrum_;  // of the samples last given to estimate()
};

// Sub-cell position of the maximum of `response` at `peak`: a parabola through the logarithms of the peak and
// its neighbours in each direction (exact for a Gaussian peak), a plain parabola where a value is not
// positive.
cv::Point2d subCellPeak(const cv::Mat &response, cv::Point peak);

// Peak-to-sidelobe ratio: (peak - mean) / standard deviation of the response outside a square of radius
// `exclude` cells around the peak. High for one sharp peak, low for a flat or many-peaked response.
double peakToSidelobe(const cv::Mat &response, cv::Point peak, int exclude);

// How high the strongest response outside the peak's own area (`halfSides` cells each way) rises, as a share
// of the peak, both above the mean of the response outside that area: near 1 when another place in the window
// answers the filter as well as the peak (a look-alike beside the target), 0 when nothing else stands out.
double rivalPeakRatio(const cv::Mat &response, cv::Point peak, cv::Size2d halfSides);
// The same share for the strongest local maximum outside that area: a second object in the window, where
// rivalPeakRatio also counts the peak's own broad shoulder. `where`, if given, receives that maximum's place
// (left alone when there is none).
double secondPeakRatio(const cv::Mat &response, cv::Point peak, cv::Size2d halfSides,
                       cv::Point *where = nullptr);

}  // namespace colortrack
