// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/correlation_filter.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include <Eigen/Core>

namespace colortrack {

namespace {

// Peak-to-sidelobe ratios are capped here: a frame identical to the training view has almost no sidelobe.
constexpr double kMaxPeakToSidelobe = 100;

// Offset in (-0.5, 0.5) of the vertex of the parabola through three neighbouring values around a maximum;
// through their logarithms when `logarithmic` and all are positive (exact for a Gaussian peak).
double parabolicOffset(double l, double c, double r, bool logarithmic) {
  if (logarithmic && l > 0 && c > 0 && r > 0) l = std::log(l), c = std::log(c), r = std::log(r);
  const double d = l - 2 * c + r;
  return d < 0 ? std::clamp(0.5 * (l - r) / d, -0.5, 0.5) : 0.0;
}

// Circular Gaussian label peaked at index 0 (zero shift), so no shift of the response is needed in training.
cv::Mat circularGaussian(cv::Size size, double sigma) {
  cv::Mat label(size, CV_32F);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x) {
      const int dx = x <= size.width / 2 ? x : x - size.width;
      const int dy = y <= size.height / 2 ? y : y - size.height;
      label.at<float>(y, x) = static_cast<float>(std::exp(-0.5 * (dx * dx + dy * dy) / (sigma * sigma)));
    }
  return label;
}

// Moves element (0,0) to (cols/2, rows/2).
void centre(const cv::Mat &in, cv::Mat &out) {
  const int cx = in.cols / 2, cy = in.rows / 2;
  out.create(in.size(), in.type());
  for (int y = 0; y < in.rows; ++y) {
    const float *src = in.ptr<float>(y);
    float *dst = out.ptr<float>((y + cy) % in.rows);
    for (int x = 0; x < in.cols; ++x) dst[(x + cx) % in.cols] = src[x];
  }
}

}  // namespace

void CorrelationFilter::init(cv::Size cells, double sigma, double lambda) {
  CV_Assert(cells.width >= 2 && cells.height >= 2);
  cv::createHanningWindow(window_, cells, CV_32F);
  // OpenCV's Hann window is zero on its first row and column; only its shape matters here.
  cv::dft(circularGaussian(cells, sigma), labelSpectrum_, cv::DFT_COMPLEX_OUTPUT);
  lambda_ = lambda;
  numerator_.clear();
  denominator_.release();
}

void CorrelationFilter::transform(const std::vector<cv::Mat> &channels, std::vector<cv::Mat> &spectra) const {
  spectra.resize(channels.size());
  // The channels' transforms are independent, so OpenCV's thread pool takes them one at a time; with one
  // thread they run in turn. Either way each spectrum is the same to the bit.
  cv::parallel_for_(cv::Range(0, static_cast<int>(channels.size())), [&](const cv::Range &range) {
    thread_local cv::Mat windowed;
    for (int c = range.start; c < range.end; ++c) {
      CV_Assert(channels[c].size() == window_.size());
      cv::multiply(channels[c], window_, windowed);
      cv::dft(windowed, spectra[c], cv::DFT_COMPLEX_OUTPUT);
    }
  });
}

void CorrelationFilter::train(const std::vector<cv::Mat> &channels, double rate) {
  transform(channels, spectra_);
  trainOnSpectra(labelSpectrum_, rate);
}

void CorrelationFilter::trainOnLastResponse(cv::Point2d offset, double rate) {
  CV_Assert(!spectra_.empty());
  // Moving the label by `offset` multiplies its spectrum by exp(-2 pi i (u dx / W + v dy / H)), with signed
  // frequencies so that a fraction of a cell moves it smoothly.
  const int w = labelSpectrum_.cols, h = labelSpectrum_.rows;
  shiftedLabel_.create(labelSpectrum_.size(), CV_32FC2);
  for (int v = 0; v < h; ++v) {
    const double fy = (v <= h / 2 ? v : v - h) * offset.y / h;
    const cv::Vec2f *in = labelSpectrum_.ptr<cv::Vec2f>(v);
    cv::Vec2f *out = shiftedLabel_.ptr<cv::Vec2f>(v);
    for (int u = 0; u < w; ++u) {
      const double phase = -2 * CV_PI * ((u <= w / 2 ? u : u - w) * offset.x / w + fy);
      const float c = static_cast<float>(std::cos(phase)), s = static_cast<float>(std::sin(phase));
      out[u] = cv::Vec2f(in[u][0] * c - in[u][1] * s, in[u][0] * s + in[u][1] * c);
    }
  }
  trainOnSpectra(shiftedLabel_, rate);
}

void CorrelationFilter::trainOnSpectra(const cv::Mat &label, double rate) {
  if (numerator_.size() != spectra_.size()) {
    rate = 1;
    numerator_.assign(spectra_.size(), cv::Mat());
    for (cv::Mat &n : numerator_) n = cv::Mat::zeros(window_.size(), CV_32FC2);
    denominator_ = cv::Mat::zeros(window_.size(), CV_32F);
  }
  // Loops over complex values, not mulSpectrums and temporaries: this runs every frame on ~14 small spectra.
  const float keep = static_cast<float>(1 - rate), take = static_cast<float>(rate);
  const int n = window_.rows * window_.cols;
  float *den = denominator_.ptr<float>();
  for (int k = 0; k < n; ++k) den[k] *= keep;
  const cv::Vec2f *l = label.ptr<cv::Vec2f>();
  for (size_t c = 0; c < spectra_.size(); ++c) {
    const cv::Vec2f *x = spectra_[c].ptr<cv::Vec2f>();
    cv::Vec2f *num = numerator_[c].ptr<cv::Vec2f>();
    for (int k = 0; k < n; ++k) {
      // label * conj(x), and |x|^2 summed over the channels
      const float re = l[k][0] * x[k][0] + l[k][1] * x[k][1];
      const float im = l[k][1] * x[k][0] - l[k][0] * x[k][1];
      num[k] = cv::Vec2f(keep * num[k][0] + take * re, keep * num[k][1] + take * im);
      den[k] += take * (x[k][0] * x[k][0] + x[k][1] * x[k][1]);
    }
  }
  inverseDenominator_.create(window_.size(), CV_32F);
  float *inverse = inverseDenominator_.ptr<float>();
  for (int k = 0; k < n; ++k) inverse[k] = 1.0f / static_cast<float>(den[k] + lambda_);
}

void CorrelationFilter::respond(const std::vector<cv::Mat> &channels, cv::Mat &response) const {
  CV_Assert(!empty() && channels.size() == numerator_.size());
  transform(channels, spectra_);
  sum_.create(window_.size(), CV_32FC2);
  sum_.setTo(0);
  const int n = window_.rows * window_.cols;
  cv::Vec2f *total = sum_.ptr<cv::Vec2f>();
  for (size_t c = 0; c < spectra_.size(); ++c) {
    // z * label * conj(x): the correlation of the search patch with the learnt one, shaped by the label;
    // divided by the learnt energy below.
    const cv::Vec2f *z = spectra_[c].ptr<cv::Vec2f>(), *num = numerator_[c].ptr<cv::Vec2f>();
    for (int k = 0; k < n; ++k) {
      total[k][0] += z[k][0] * num[k][0] - z[k][1] * num[k][1];
      total[k][1] += z[k][0] * num[k][1] + z[k][1] * num[k][0];
    }
  }
  const float *inverse = inverseDenominator_.ptr<float>();
  for (int k = 0; k < n; ++k) total[k] *= inverse[k];
  cv::dft(sum_, circular_, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
  centre(circular_, response);
}

void ScaleFilter::init(int scales, double step, double sigma, double lambda) {
  CV_Assert(scales >= 3 && scales % 2 == 1 && step > 1);
  factors_.resize(scales);
  cv::Mat label(1, scales, CV_32F);
  for (int i = 0; i < scales; ++i) {
    const int offset = i - scales / 2;
    factors_[i] = std::pow(step, offset);
    // Peaked at the middle candidate (no change of size), so the response's peak is the best candidate.
    label.at<float>(0, i) = static_cast<float>(std::exp(-0.5 * offset * offset / (sigma * sigma)));
  }
  cv::dft(label, labelSpectrum_);
  // Column j of the matrix makes packed spectrum element j (layout below) of the windowed samples:
  // Re(k) = sum_i w_i x_i cos(2 pi k i / n), Im(k) = -sum_i w_i x_i sin(2 pi k i / n).
  windowedDft_.create(scales, scales, CV_32F);
  for (int i = 0; i < scales; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2 * CV_PI * (i + 1) / (scales + 1));  // Hann without its zero ends
    float *row = windowedDft_.ptr<float>(i);
    row[0] = static_cast<float>(w);
    for (int k = 1; 2 * k - 1 < scales; ++k) {
      const double angle = 2 * CV_PI * k * i / scales;
      row[2 * k - 1] = static_cast<float>(w * std::cos(angle));
      if (2 * k < scales) row[2 * k] = static_cast<float>(-w * std::sin(angle));
    }
  }
  lambda_ = lambda;
  step_ = step;
  numerator_.release();
  denominator_.clear();
}

// The spectra here are OpenCV's packed spectra of real rows of length n (CCS): Re(0), then Re(k) at 2k - 1
// and Im(k) at 2k for k = 1 .. n/2 (n is odd, init() asserts it, so every k has its Im). Half the values of
// a full complex spectrum, and the DFT that makes them is cheaper; the loops below stand in for mulSpectrums
// on rows.
// Features x scales packed spectrum of samples (scales x features), windowed over the scales. The DFT along
// the scale axis is a product with a small fixed matrix (Eigen's blocked, vectorised product): one matrix
// product over all feature columns cost a fifth of what cv::dft took for the same rows of odd length 33,
// which OpenCV transforms one short row at a time.
void ScaleFilter::transform(const cv::Mat &samples, cv::Mat &spectrum) {
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const int scales = static_cast<int>(factors_.size());
  CV_Assert(samples.rows == scales && samples.type() == CV_32FC1 && samples.isContinuous());
  spectrum.create(samples.cols, scales, CV_32F);
  const Eigen::Map<const RowMajor> in(samples.ptr<float>(), scales, samples.cols);
  const Eigen::Map<const RowMajor> dft(windowedDft_.ptr<float>(), scales, scales);
  Eigen::Map<RowMajor> out(spectrum.ptr<float>(), samples.cols, scales);
  // Two halves of the feature columns on OpenCV's thread pool. The split falls on a multiple of 48 rows (a
  // multiple of Eigen's row blocks for every vector width) so each value is summed as one product would.
  const int split = samples.cols / 2 / 48 * 48;
  cv::parallel_for_(cv::Range(0, split > 0 ? 2 : 1), [&](const cv::Range &halves) {
    for (int h = halves.start; h < halves.end; ++h) {
      const int first = h == 0 ? 0 : split, count = h == 0 && split > 0 ? split : samples.cols - first;
      out.middleRows(first, count).noalias() = in.middleCols(first, count).transpose() * dft;
    }
  });
}

void ScaleFilter::train(const cv::Mat &samples, double rate) {
  cv::Mat spectrum;
  transform(samples, spectrum);
  trainOnSpectrum(spectrum, rate);
}

void ScaleFilter::trainOnLastEstimate(double rate) {
  CV_Assert(!lastSpectrum_.empty());
  trainOnSpectrum(lastSpectrum_, rate);
}

void ScaleFilter::trainOnSpectrum(const cv::Mat &spectrum, double rate) {
  const int n = spectrum.cols, frequencies = n / 2 + 1;
  if (numerator_.empty() || numerator_.size() != spectrum.size()) {
    rate = 1;
    numerator_ = cv::Mat::zeros(spectrum.size(), CV_32F);  // zero, so that "keep" times it stays zero
    denominator_.assign(frequencies, 0.0f);
  }
  CV_Assert(n % 2 == 1);
  const float keep = static_cast<float>(1 - rate), take = static_cast<float>(rate);
  for (float &d : denominator_) d *= keep;
  const float *__restrict label = labelSpectrum_.ptr<float>(0);
  float *__restrict den = denominator_.data();
  for (int r = 0; r < spectrum.rows; ++r) {
    const float *__restrict x = spectrum.ptr<float>(r);
    float *__restrict num = numerator_.ptr<float>(r);
    num[0] = keep * num[0] + take * label[0] * x[0];
    den[0] += take * x[0] * x[0];
    for (int k = 1; k < frequencies; ++k) {
      // label * conj(x)
      const float xr = x[2 * k - 1], xi = x[2 * k];
      const float lr = label[2 * k - 1], li = label[2 * k];
      num[2 * k - 1] = keep * num[2 * k - 1] + take * (lr * xr + li * xi);
      num[2 * k] = keep * num[2 * k] + take * (li * xr - lr * xi);
      den[k] += take * (xr * xr + xi * xi);
    }
  }
}

double ScaleFilter::estimate(const cv::Mat &samples) {
  CV_Assert(!empty());
  transform(samples, lastSpectrum_);
  const int n = lastSpectrum_.cols, frequencies = n / 2 + 1;
  CV_Assert(n % 2 == 1);
  cv::Mat sum = cv::Mat::zeros(1, n, CV_32F);
  float *__restrict total = sum.ptr<float>(0);
  for (int r = 0; r < lastSpectrum_.rows; ++r) {
    const float *__restrict z = lastSpectrum_.ptr<float>(r), *__restrict num = numerator_.ptr<float>(r);
    total[0] += z[0] * num[0];
    for (int k = 1; k < frequencies; ++k) {
      const float zr = z[2 * k - 1], zi = z[2 * k];
      const float nr = num[2 * k - 1], ni = num[2 * k];
      total[2 * k - 1] += zr * nr - zi * ni;
      total[2 * k] += zr * ni + zi * nr;
    }
  }
  total[0] /= static_cast<float>(denominator_[0] + lambda_);
  for (int k = 1; k < frequencies; ++k) {
    const float inverse = 1.0f / static_cast<float>(denominator_[k] + lambda_);
    total[2 * k - 1] *= inverse;
    total[2 * k] *= inverse;
  }
  cv::Mat circular;
  cv::dft(sum, circular, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
  cv::Point peak;
  cv::minMaxLoc(circular, nullptr, nullptr, nullptr, &peak);
  double offset = 0;
  if (peak.x > 0 && peak.x < n - 1)
    offset = parabolicOffset(circular.at<float>(0, peak.x - 1), circular.at<float>(0, peak.x),
                             circular.at<float>(0, peak.x + 1), false);
  return std::pow(step_, peak.x + offset - n / 2);
}

cv::Point2d subCellPeak(const cv::Mat &response, cv::Point peak) {
  auto at = [&](int y, int x) { return static_cast<double>(response.at<float>(y, x)); };
  auto offset = [](double l, double c, double r) { return parabolicOffset(l, c, r, true); };
  cv::Point2d p(peak);
  if (peak.x > 0 && peak.x < response.cols - 1)
    p.x += offset(at(peak.y, peak.x - 1), at(peak.y, peak.x), at(peak.y, peak.x + 1));
  if (peak.y > 0 && peak.y < response.rows - 1)
    p.y += offset(at(peak.y - 1, peak.x), at(peak.y, peak.x), at(peak.y + 1, peak.x));
  return p;
}

double peakToSidelobe(const cv::Mat &response, cv::Point peak, int exclude) {
  cv::Mat mask(response.size(), CV_8U, cv::Scalar(255));
  const cv::Rect centreArea(peak.x - exclude, peak.y - exclude, 2 * exclude + 1, 2 * exclude + 1);
  mask(centreArea & cv::Rect(cv::Point(), response.size())).setTo(0);
  if (cv::countNonZero(mask) < 2) return 0;
  cv::Scalar mean, deviation;
  cv::meanStdDev(response, mean, deviation, mask);
  const double peakValue = response.at<float>(peak);
  return (peakValue - mean[0]) /
         std::max(deviation[0], std::max(1e-6, std::abs(peakValue) / kMaxPeakToSidelobe));
}

namespace {

// The strongest response outside the peak's own area (`halfSides` cells each way), among local maxima only
// if `modesOnly`, as a share of the peak, both above the mean of the response outside that area; `where`, if
// given, receives its place.
double strongestOutsideShare(const cv::Mat &response, cv::Point peak, cv::Size2d halfSides, bool modesOnly,
                             cv::Point *where = nullptr) {
  cv::Mat outside(response.size(), CV_8U, cv::Scalar(255));
  // Rounded from its corner, the area can lie one element to one side when a half side ends in .5. Centring
  // it exactly moved the core harness's SRE tune mean by -0.005, within its noise; the figures in
  // docs/benchmarks-history.md are with this form.
  const cv::Rect own(cvRound(peak.x - halfSides.width), cvRound(peak.y - halfSides.height),
                     cvRound(2 * halfSides.width) + 1, cvRound(2 * halfSides.height) + 1);
  outside(own & cv::Rect(cv::Point(), response.size())).setTo(0);
  if (cv::countNonZero(outside) == 0) return 0;
  const double mean = cv::mean(response, outside)[0];
  cv::Mat candidates = outside;
  if (modesOnly) {
    cv::Mat grown, modes;
    cv::dilate(response, grown, cv::Mat());  // 3 x 3: a local maximum is its neighbourhood's largest
    cv::compare(response, grown, modes, cv::CMP_GE);
    candidates = modes & outside;
    if (cv::countNonZero(candidates) == 0) return 0;
  }
  double strongest = 0;
  cv::Point strongestAt;
  cv::minMaxLoc(response, nullptr, &strongest, nullptr, &strongestAt, candidates);
  if (where) *where = strongestAt;
  const double peakValue = response.at<float>(peak);
  return peakValue > mean ? std::max(0.0, (strongest - mean) / (peakValue - mean)) : 0;
}

}  // namespace

double rivalPeakRatio(const cv::Mat &response, cv::Point peak, cv::Size2d halfSides) {
  return strongestOutsideShare(response, peak, halfSides, false);
}

double secondPeakRatio(const cv::Mat &response, cv::Point peak, cv::Size2d halfSides, cv::Point *where) {
  return strongestOutsideShare(response, peak, halfSides, true, where);
}

}  // namespace colortrack
