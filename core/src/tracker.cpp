#include "colortrack/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "colortrack/fused_detector.hpp"
#include "colortrack/likelihood.hpp"

namespace colortrack {

namespace {

// Full-frame searches run on a frame reduced so that the window's smaller side is about this many pixels:
// histograms need only a sample of the pixels, and this keeps a 1080p search within a few milliseconds.
constexpr int kCoarseWindowSide = 16;
// While the track is colour-only (unverified), look over the whole frame this often for a verified target.
constexpr int kUnverifiedGlobalSearchPeriod = 5;
// Discriminative method: the motion prior's standard deviation in box sizes (sqrt of the box area), and the
// width of the surroundings the likelihood is learnt against, in box sizes per side.
constexpr double kMotionPriorSigma = 1.0;
constexpr double kSurroundings = 0.5;
// Discriminative sizing: the ring the box's mean likelihood is compared with, as a fraction of the box's
// smaller side. Narrower than the indexing ring: the likelihood map is sharper than a window's histogram,
// and a wide ring reaches neighbouring object-coloured clutter. 0.1-0.2 all give mean AUC 0.55-0.57 on the
// shared sequences, 0.25 gives 0.52, 0.5 gives 0.33 (docs/benchmarks.md).
constexpr double kLikelihoodRing = 0.15;
// Searches while tracking work on a region reduced so the box's smaller side is about this many pixels.
constexpr double kReducedWindowSide = 40;
constexpr double kAspectRate = 0.3;  // smoothing of the measured aspect ratio
// The object may have changed size while it was away: each search of the whole frame tries the next scale of
// this list (the last size first), which keeps the cost of a frame to one search.
constexpr double kSearchScales[] = {1.0, 1.0 / 1.4, 1.4, 0.5, 2.0};

// Fused method. The confidence is the fused response's peak-to-sidelobe ratio (PSR). A frame is a detection
// when its PSR is at least kLostConfidence, at least kLostRatio of the track's usual PSR, and its colour cue
// at least kLostColourRatio of the usual colour cue (a target that left takes its colours with it, while the
// shape filter can still find some texture where it was); only detections are learnt from. The usual values
// are running means (rate kConfidenceRate) over learnt frames, skipping the first kConfidenceSkip frames
// after the filters start (they match their single training view unusually well), trusted after
// kConfidenceWarmUp frames, and capped at kConfidentPsr (a video that starts with still frames would
// otherwise set the bar out of reach once things move). Chosen on the tune half of ../shared/sequences
// (docs/benchmarks.md).
constexpr double kLostConfidence = 4.0;
constexpr double kLostRatio = 0.5;
constexpr double kLostColourRatio = 0.5;
constexpr double kConfidenceRate = 0.1;
constexpr double kConfidentPsr = 12;
constexpr int kConfidenceSkip = 2;
constexpr int kConfidenceWarmUp = 5;
// Re-detection, once coasting or lost: every kRedetectPeriod frames the kRedetectCandidates strongest places
// of the colour likelihood over the whole frame and the last position are searched with both cues; the best
// is taken when its PSR reaches kRedetectConfidence and kRedetectRatio of the usual, and its colour cue
// kLostColourRatio of the usual.
constexpr double kRedetectConfidence = 6.0;
constexpr double kRedetectRatio = 0.6;
constexpr int kRedetectPeriod = 3;
constexpr int kRedetectCandidates = 4;

cv::Rect roundRect(const cv::Rect2d &r) {
  return cv::Rect(cvRound(r.x), cvRound(r.y), std::max(1, cvRound(r.width)), std::max(1, cvRound(r.height)));
}

cv::Rect2d centredBox(double cx, double cy, cv::Size2d size) {
  return cv::Rect2d(cx - size.width / 2, cy - size.height / 2, size.width, size.height);
}

// Fill the pixels outside the mask with the mean of those inside, so that the edge check sees the object's
// own edges and not the arbitrary colour of a transparent background.
cv::Mat flattenOutsideMask(const cv::Mat &gray, const cv::Mat &mask) {
  if (mask.empty()) return gray;
  cv::Mat out = gray.clone();
  const cv::Scalar inside = cv::mean(gray, mask);
  cv::Mat outside;
  cv::bitwise_not(mask, outside);
  out.setTo(inside, outside);
  return out;
}

}  // namespace

struct Tracker::Impl {
  // The model.
  cv::Mat templateBgr, templateMask;
  std::optional<BinMapper> mapper;
  Histogram model;
  EdgeVerifier verifier;

  // The track.
  KalmanFilter9 kalman;
  TrackState state = TrackState::Searching;
  int trackId = 0;
  int coastFrames = 0;
  int unverifiedFrames = 0;
  int searchFrames = 0;    // frames searched since the track was lost (picks the scale to try)
  double lastScale = 1.0;  // last measured scale
  bool lastVerified = false;

  // The discriminative model and the box's shape relative to the template.
  ColorLikelihood likelihood;
  double aspect = 1.0;  // (box width / height) / (template width / height)

  // The fused method's detector and where it last found the target.
  FusedDetector fused;
  cv::Point2d fusedCentre;
  cv::Size2d fusedSize;
  cv::Size2d fusedMinSize;     // the box never shrinks below this (8 px, or the start size if smaller)
  double usualConfidence = 0;  // running mean of the confidence of learnt frames
  int confidenceSamples = 0;   // how many frames the mean has seen
  int framesLearnt = 0;        // since the filters started
  int redetectAttempts = 0;    // since the last detection (picks the size to try)
  double usualColour = 0;      // running mean of the colour cue at the peak of learnt frames

  // Scratch buffers reused across frames.
  cv::Mat bgr, small, gray, probability, integralP;
  BinImage bins, coarseBins, learnBins;

  bool hasTemplate() const { return !templateBgr.empty(); }
  cv::Rect2d centredBoxNow() const { return centredBox(kalman.x(), kalman.y(), windowSize(kalman.scale())); }
  cv::Size2d windowSize(double scale) const {
    const double a = std::sqrt(aspect);
    return cv::Size2d(templateBgr.cols * scale * a, templateBgr.rows * scale / a);
  }
  // Scale of a box: the square root of its area relative to the template's, so aspect changes leave it alone.
  double scaleOf(const cv::Rect2d &box) const {
    return std::sqrt(box.area() / (static_cast<double>(templateBgr.cols) * templateBgr.rows));
  }
  bool useLikelihood(const TrackerSettings &s) const {
    return s.method != Method::Indexing && !likelihood.empty();
  }

  void rebuildModel(const TrackerSettings &s) {
    if (!mapper || mapper->space() != s.colorSpace || !(mapper->layout() == s.bins)) {
      mapper.emplace(s.colorSpace, s.bins);
      likelihood = ColorLikelihood(s.bins);
    }
    if (!hasTemplate()) return;
    BinImage templateBins;
    mapper->map(templateBgr, templateBins.bins);
    model = histogramOf(templateBins, s.bins, cv::Rect(cv::Point(), templateBgr.size()), templateMask);
    cv::Mat templateGray;
    cv::cvtColor(templateBgr, templateGray, cv::COLOR_BGR2GRAY);
    verifier.setTemplate(flattenOutsideMask(templateGray, templateMask));
  }

  struct Detection {
    cv::Rect2d box;
    double score = 0;
    bool verified = false;
  };

  // Window search over `region` at the given scale, then scale refinement and edge check.
  std::optional<Detection> detectIn(const ImageSource &frame, const cv::Rect &region, double scale,
                                    const TrackerSettings &s, const cv::Point2d *prior = nullptr) {
    if (useLikelihood(s)) return detectByLikelihood(frame, region, scale, s, prior);
    const cv::Size2d size = windowSize(scale);
    // Room for the scale refinement's largest window and its ring.
    const int pad = cvRound(std::max(size.width, size.height) * (std::max(0.0, s.scale.maxFactor - 1.0) +
                                                                 s.scale.ringWidth * s.scale.maxFactor)) +
                    2;
    const auto reduced = readReduced(frame, region, size, pad);
    if (!reduced) return std::nullopt;
    const cv::Size window(std::max(1, cvRound(reduced->sizeL.width)),
                          std::max(1, cvRound(reduced->sizeL.height)));
    const SearchResult found = searchWindow(bins, reduced->searchL, window, model, s.weights);
    if (!found.found || found.score < s.matchThreshold) return std::nullopt;
    const ScaleResult refined = refineScale(bins, found.box, model, s.weights, s.scale);
    Detection d;
    d.box = reduced->toFull(refined.box);
    d.score = refined.match;
    d.verified = verify(frame, roundRect(d.box), s);
    return d;
  }

  // A search region read at reduced resolution into `bins`: `f` full-resolution pixels make one local pixel
  // (nearest neighbour: a sample of the pixels is enough for histograms), local coordinates start at the
  // padded region's corner. Boxes are reduced to a smaller side of about kReducedWindowSide pixels, so the
  // cost per frame stays about the same whatever the object's size.
  struct Reduced {
    cv::Rect padded;  // frame coordinates
    int f = 1;
    cv::Rect searchL;  // where windows may lie, local coordinates
    cv::Size2d sizeL;  // the window size, local
    cv::Rect2d toFull(const cv::Rect2d &b) const {
      return cv::Rect2d(padded.x + b.x * f, padded.y + b.y * f, b.width * f, b.height * f);
    }
    cv::Point2d toLocal(double x, double y) const {
      return cv::Point2d((x - padded.x) / f, (y - padded.y) / f);
    }
  };

  std::optional<Reduced> readReduced(const ImageSource &frame, const cv::Rect &region, cv::Size2d size,
                                     int pad) {
    const cv::Rect frameRect(cv::Point(), frame.size());
    const cv::Rect searchRect = region & frameRect;
    if (searchRect.width < size.width || searchRect.height < size.height) return std::nullopt;
    Reduced r;
    r.padded = cv::Rect(searchRect.x - pad, searchRect.y - pad, searchRect.width + 2 * pad,
                        searchRect.height + 2 * pad) &
               frameRect;
    r.f = std::max(1, static_cast<int>(std::min(size.width, size.height) / kReducedWindowSide));
    frame.sampledBgr(r.padded, r.f, small);
    mapper->map(small, bins.bins);
    bins.origin = cv::Point();
    const cv::Point2d tl = r.toLocal(searchRect.x, searchRect.y);
    r.searchL = cv::Rect(cvCeil(tl.x), cvCeil(tl.y), searchRect.width / r.f, searchRect.height / r.f) &
                cv::Rect(cv::Point(), bins.bins.size());
    r.sizeL = cv::Size2d(size.width / r.f, size.height / r.f);
    if (r.searchL.width < cvRound(r.sizeL.width) || r.searchL.height < cvRound(r.sizeL.height))
      return std::nullopt;
    return r;
  }

  // Full-frame search: a coarse pass on a reduced frame, then a full-resolution search around its best.
  std::optional<Detection> detectEverywhere(const ImageSource &frame, double scale,
                                            const TrackerSettings &s) {
    const cv::Size frameSize = frame.size();
    const cv::Size2d size = windowSize(scale);
    if (size.width > frameSize.width || size.height > frameSize.height) return std::nullopt;
    const int factor = std::max(1, static_cast<int>(std::min(size.width, size.height) / kCoarseWindowSide));
    if (factor == 1) return detectIn(frame, cv::Rect(cv::Point(), frameSize), scale, s);

    // A sample of the pixels is enough for histograms; no need for a filtered image.
    frame.sampledBgr(cv::Rect(cv::Point(), frameSize), factor, small);
    mapper->map(small, coarseBins.bins);
    coarseBins.origin = cv::Point();
    const cv::Size coarseWindow(std::max(1, cvRound(size.width / factor)),
                                std::max(1, cvRound(size.height / factor)));
    cv::Point coarseBest;
    if (useLikelihood(s)) {
      likelihood.map(coarseBins, probability);
      cv::Mat meanP;  // mean likelihood of the window centred at each pixel
      cv::boxFilter(probability, meanP, CV_32F, coarseWindow, cv::Point(-1, -1), true, cv::BORDER_CONSTANT);
      const int x0 = coarseWindow.width / 2, y0 = coarseWindow.height / 2;
      const cv::Rect valid(x0, y0, small.cols - coarseWindow.width + 1, small.rows - coarseWindow.height + 1);
      if (valid.width <= 0 || valid.height <= 0) return std::nullopt;
      cv::Point at;
      cv::minMaxLoc(meanP(valid), nullptr, nullptr, nullptr, &at);
      coarseBest = at;
    } else {
      const SearchResult coarse =
          searchWindow(coarseBins, cv::Rect(cv::Point(), small.size()), coarseWindow, model, s.weights);
      if (!coarse.found) return std::nullopt;
      coarseBest = coarse.box.tl();
    }
    const cv::Rect around(coarseBest.x * factor - 2 * factor, coarseBest.y * factor - 2 * factor,
                          cvRound(size.width) + 4 * factor, cvRound(size.height) + 4 * factor);
    return detectIn(frame, around, scale, s);
  }

  // Likelihood search: every window of the current size scored by its mean P(object | colour), weighted by
  // a Gaussian motion prior around `prior` (none while searching the whole frame); then the width and
  // height that enclose the most likelihood mass above one half.
  std::optional<Detection> detectByLikelihood(const ImageSource &frame, const cv::Rect &region, double scale,
                                              const TrackerSettings &s, const cv::Point2d *prior) {
    const cv::Size2d size = windowSize(scale);
    const int pad = cvRound(std::max(size.width, size.height) * std::max(0.0, s.scale.maxFactor - 1.0)) + 2;
    const auto reduced = readReduced(frame, region, size, pad);
    if (!reduced) return std::nullopt;
    likelihood.map(bins, probability);
    cv::integral(probability, integralP, CV_64F);
    const cv::Rect limits(cv::Point(), probability.size());
    const cv::Size2d sizeL = reduced->sizeL;
    const cv::Size window(std::max(1, cvRound(sizeL.width)), std::max(1, cvRound(sizeL.height)));
    const cv::Rect searchL = reduced->searchL;
    const std::optional<cv::Point2d> priorL =
        prior ? std::optional<cv::Point2d>(reduced->toLocal(prior->x, prior->y)) : std::nullopt;
    const double sigma = kMotionPriorSigma * std::sqrt(sizeL.width * sizeL.height);
    auto windowScore = [&](int x, int y) {
      const double mean = boxSum(integralP, cv::Rect(x, y, window.width, window.height)) / window.area();
      if (!priorL) return mean;
      const double dx = x + window.width / 2.0 - priorL->x, dy = y + window.height / 2.0 - priorL->y;
      return mean * std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
    };
    // A coarse grid, then every pixel around its best.
    const int step = std::max(1, std::min(window.width, window.height) / 12);
    const int maxX = searchL.br().x - window.width, maxY = searchL.br().y - window.height;
    cv::Point best = searchL.tl();
    double bestScore = -1;
    for (int y = searchL.y; y <= maxY; y += step)
      for (int x = searchL.x; x <= maxX; x += step)
        if (const double v = windowScore(x, y); v > bestScore) bestScore = v, best = cv::Point(x, y);
    const cv::Point coarse = best;
    for (int y = std::max(searchL.y, coarse.y - step); y <= std::min(maxY, coarse.y + step); ++y)
      for (int x = std::max(searchL.x, coarse.x - step); x <= std::min(maxX, coarse.x + step); ++x)
        if (const double v = windowScore(x, y); v > bestScore) bestScore = v, best = cv::Point(x, y);

    // Size: the box whose mean likelihood most exceeds that of the ring around it, i.e. the box that sits on
    // the border between object-like and background-like pixels. (A fixed level such as sum(P - 1/2) shrinks
    // the box onto the most object-like part whenever the object holds colours the background shares.)
    const cv::Point2d centre(best.x + window.width / 2.0, best.y + window.height / 2.0);
    cv::Rect2d boxL = centredBox(centre.x, centre.y, sizeL);
    double bestMass = -1e18;
    const double stepFactor = s.scale.step > 0 ? s.scale.step : 1.0;
    for (double fw = s.scale.minFactor; fw <= s.scale.maxFactor + 1e-9; fw += stepFactor)
      for (double fh = s.scale.minFactor; fh <= s.scale.maxFactor + 1e-9; fh += stepFactor) {
        if (!s.adaptAspect && std::abs(fw - fh) > 1e-9) continue;
        const cv::Rect2d box =
            centredBox(centre.x, centre.y, cv::Size2d(sizeL.width * fw, sizeL.height * fh));
        const cv::Rect r = roundRect(box);
        if ((r & limits) != r) continue;
        const int ring = std::max(1, cvRound(kLikelihoodRing * std::min(box.width, box.height)));
        const cv::Rect outer =
            cv::Rect(r.x - ring, r.y - ring, r.width + 2 * ring, r.height + 2 * ring) & limits;
        const double inside = boxSum(integralP, r);
        const double ringArea = outer.area() - r.area();
        const double ringMean = ringArea > 0 ? (boxSum(integralP, outer) - inside) / ringArea : 0;
        // Prefer the current size on ties, so noise does not make the box wander.
        const double mass = inside / r.area() - ringMean - 1e-6 * (std::abs(fw - 1) + std::abs(fh - 1));
        if (mass > bestMass) bestMass = mass, boxL = box;
      }
    const cv::Rect r = roundRect(boxL) & limits;
    if (likelihood.confidence(bins, r) < s.likelihoodThreshold) return std::nullopt;
    Detection d;
    d.box = reduced->toFull(boxL);
    // The score reported is the paper's match value against the template, so that it means the same in both
    // methods; acceptance here is the likelihood's (the template was one frame's look, the likelihood follows
    // the object as it changes).
    d.score = windowMatch(bins, r, model, s.weights);
    d.verified = verify(frame, roundRect(d.box), s);
    return d;
  }

  // Learns the likelihood from `box` and the ring around it (rate 1 replaces the model).
  void learnLikelihood(const ImageSource &frame, const cv::Rect2d &box, double rate) {
    const cv::Rect frameRect(cv::Point(), frame.size());
    const double grow = kSurroundings * std::max(box.width, box.height);
    const cv::Rect object = roundRect(box) & frameRect;
    const cv::Rect around =
        roundRect(cv::Rect2d(box.x - grow, box.y - grow, box.width + 2 * grow, box.height + 2 * grow)) &
        frameRect;
    if (object.empty()) return;
    // A sample of the pixels, as in the search: learning every pixel of a large box and its surroundings
    // would cost more than the search itself.
    const int f = std::max(1, static_cast<int>(std::min(box.width, box.height) / kReducedWindowSide));
    frame.sampledBgr(around, f, small);
    mapper->map(small, learnBins.bins);
    learnBins.origin = cv::Point();
    const cv::Rect objectL(cvRound(double(object.x - around.x) / f), cvRound(double(object.y - around.y) / f),
                           std::max(1, object.width / f), std::max(1, object.height / f));
    likelihood.learn(learnBins, objectL, cv::Rect(cv::Point(), learnBins.bins.size()), rate);
  }

  // Keeps the discriminative model current: learnt from scratch the first time (a template file gives no
  // surroundings), then adapted slowly.
  void learn(const ImageSource &frame, const cv::Rect2d &box, const TrackerSettings &s) {
    if (s.method == Method::Indexing) return;
    if (likelihood.empty())
      learnLikelihood(frame, box, 1.0);
    else if (s.modelUpdateRate > 0)
      learnLikelihood(frame, box, s.modelUpdateRate);
  }

  bool verify(const ImageSource &frame, const cv::Rect &box, const TrackerSettings &s) {
    if (s.verify == VerifyMode::None) return true;
    const cv::Rect inside = box & cv::Rect(cv::Point(), frame.size());
    if (inside.area() <= 0) return false;
    frame.bgr(inside, bgr);
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    if (!templateMask.empty()) {
      cv::Mat mask;
      cv::resize(templateMask, mask, gray.size(), 0, 0, cv::INTER_NEAREST);
      gray = flattenOutsideMask(gray, mask);
    }
    return verifier.verify(verifier.signature(gray), s.verify, s.verifyTolerance);
  }

  void startTrack(const Detection &d, const TrackerSettings &s) {
    searchFrames = 0;
    kalman.setParams(s.kalman);
    measureShape(d.box, 1.0);
    kalman.init(d.box.x + d.box.width / 2, d.box.y + d.box.height / 2, lastScale);
    ++trackId;
    state = TrackState::Tracking;
    coastFrames = 0;
    unverifiedFrames = 0;
  }

  // Scale (for the Kalman filter) and aspect (smoothed here: it changes slowly and the filter has no state
  // for it) of a measured box.
  void measureShape(const cv::Rect2d &box, double aspectRate) {
    const double boxAspect =
        (box.width / box.height) / (static_cast<double>(templateBgr.cols) / templateBgr.rows);
    aspect = std::clamp((1 - aspectRate) * aspect + aspectRate * boxAspect, 0.25, 4.0);
    lastScale = scaleOf(box);
  }

  void updateTrack(const Detection &d) {
    measureShape(d.box, kAspectRate);
    kalman.correct(d.box.x + d.box.width / 2, d.box.y + d.box.height / 2, lastScale);
    state = TrackState::Tracking;
    coastFrames = 0;
  }

  // Fused method: starts the detector's filters on a detection (a box of at least a pixel).
  void startFused(const ImageSource &frame, const cv::Rect2d &box) {
    const cv::Rect2d fitted(box.x, box.y, std::max(1.0, box.width), std::max(1.0, box.height));
    stopFused();
    fused.start(frame, fitted);
    fusedCentre = cv::Point2d(fitted.x + fitted.width / 2, fitted.y + fitted.height / 2);
    fusedSize = fitted.size();
    fusedMinSize = cv::Size2d(std::min(8.0, fusedSize.width), std::min(8.0, fusedSize.height));
  }
  // Forgets the fused filters (a new template, another method, another colour model): the next detection of
  // the colour search starts them again.
  void stopFused() {
    fused.stop();
    usualConfidence = 0;
    confidenceSamples = 0;
    framesLearnt = 0;
    usualColour = 0;
    redetectAttempts = 0;
  }

  // A frame's confidence relative to the track's usual one. Until that is known, relative to the lowest
  // usual PSR a detection could have, so that the same 0.5 separates detections from the rest.
  double relativeConfidence(double confidence) const {
    return confidenceSamples >= kConfidenceWarmUp ? confidence / std::min(usualConfidence, kConfidentPsr)
                                                  : confidence * kLostRatio / kLostConfidence;
  }
  double relativeColour(double colour) const {
    return confidenceSamples >= kConfidenceWarmUp && usualColour > 0 ? colour / usualColour : 1.0;
  }
  void noteConfidence(const FusedDetector::Estimate &e) {
    // The first frames after the filters start match their single training view unusually well.
    if (++framesLearnt <= kConfidenceSkip) return;
    ++confidenceSamples;
    const double rate = std::max(kConfidenceRate, 1.0 / confidenceSamples);
    usualConfidence = (1 - rate) * usualConfidence + rate * e.confidence;
    usualColour = (1 - rate) * usualColour + rate * e.colourPeak;
  }

  // A fused estimate as a detection: the box, its confidence as the score, the edge check.
  Detection fusedDetection(const ImageSource &frame, const FusedDetector::Estimate &e,
                           const TrackerSettings &s) {
    Detection d;
    d.box = centredBox(e.centre.x, e.centre.y, e.size);
    d.score = e.confidence;
    d.verified = verify(frame, roundRect(d.box) & cv::Rect(cv::Point(), frame.size()), s);
    return d;
  }

  // Fused method: the best re-detection over the whole frame (colour candidates and the last position, each
  // searched with both cues), if it is confident enough.
  std::optional<FusedDetector::Estimate> redetectFused(const ImageSource &frame) {
    // The target may come back at another size: each attempt tries the next size of a short list (the last
    // one first), as the colour search does.
    const double factor = kSearchScales[redetectAttempts++ % std::size(kSearchScales)];
    const cv::Size2d size = fitSize(fusedSize * factor, frame.size());
    std::vector<cv::Point2d> candidates =
        fused.colourCandidates(frame, size, *mapper, likelihood, kRedetectCandidates);
    candidates.push_back(fusedCentre);
    std::optional<FusedDetector::Estimate> best;
    for (const cv::Point2d &c : candidates) {
      const FusedDetector::Estimate e = fused.locate(frame, c, size, *mapper, likelihood, false);
      if (!best || e.confidence > best->confidence) best = e;
    }
    // The filter's window tapers towards its edges: judge the best candidate again with the window centred
    // where it was found.
    if (best) best = fused.locate(frame, best->centre, size, *mapper, likelihood, false);
    if (!best || best->confidence < kRedetectConfidence ||
        relativeConfidence(best->confidence) < kRedetectRatio ||
        relativeColour(best->colourPeak) < kLostColourRatio)
      return std::nullopt;
    return best;
  }

  // A fused size kept between the minimum and the frame.
  cv::Size2d fitSize(cv::Size2d size, cv::Size frameSize) const {
    return cv::Size2d(std::clamp(size.width, std::min(fusedMinSize.width, double(frameSize.width)),
                                 double(frameSize.width)),
                      std::clamp(size.height, std::min(fusedMinSize.height, double(frameSize.height)),
                                 double(frameSize.height)));
  }

  // Fused method, once its filters have started: the frame's state change and the output's score.
  void processFused(const ImageSource &frame, double dt, const TrackerSettings &s, TrackOutput &out) {
    const cv::Rect frameRect(cv::Point(), frame.size());
    if (state == TrackState::Tracking || state == TrackState::Coasting) {
      kalman.predict(dt);
      // Searched around the last measured position, not the Kalman prediction: the filter's window is wide
      // enough for the motion between frames, and the prediction overshoots when the target stops or turns
      // (tune half: 0.626 from the last position, 0.605 from the prediction).
      const cv::Point2d centre = fusedCentre;
      FusedDetector::Estimate e = fused.locate(frame, centre, fusedSize, *mapper, likelihood);
      out.searchRegion = roundRect(centredBox(centre.x, centre.y, fused.windowFor(fusedSize))) & frameRect;
      const auto accepted = [&](const FusedDetector::Estimate &e) {
        return e.confidence >= kLostConfidence && relativeConfidence(e.confidence) >= kLostRatio &&
               relativeColour(e.colourPeak) >= kLostColourRatio;
      };
      if (!accepted(e) && state == TrackState::Coasting && coastFrames % kRedetectPeriod == 0) {
        if (const auto found = redetectFused(frame)) e = *found;
        out.searchRegion = frameRect;
      }
      out.score = std::min(1.0, relativeConfidence(e.confidence));
      if (accepted(e)) {
        e.size = fitSize(e.size, frame.size());
        redetectAttempts = 0;
        const Detection d = fusedDetection(frame, e, s);
        updateTrack(d);
        lastVerified = d.verified;
        fusedCentre = e.centre;
        fusedSize = e.size;
        noteConfidence(e);
        fused.learn(frame, e);
        learn(frame, d.box, s);
      } else {
        kalman.holdForCoasting();
        ++coastFrames;
        state = coastFrames > s.maxCoastFrames ? TrackState::Lost : TrackState::Coasting;
      }
      return;
    }
    out.searchRegion = frameRect;
    if (searchFrames++ % kRedetectPeriod != 0) return;
    auto found = redetectFused(frame);
    if (!found) return;
    found->size = fitSize(found->size, frame.size());
    const Detection d = fusedDetection(frame, *found, s);
    startTrack(d, s);
    lastVerified = d.verified;
    fusedCentre = found->centre;
    fusedSize = found->size;
    redetectAttempts = 0;
    out.score = std::min(1.0, relativeConfidence(found->confidence));
  }

  // The search region around the prediction: the window grown by the margin on each side and by three
  // standard deviations of the predicted position.
  cv::Rect predictionRegion(const TrackerSettings &s) const {
    const cv::Size2d size = windowSize(kalman.scale());
    const double growX = s.searchMargin * size.width / 2 + 3 * kalman.stdX();
    const double growY = s.searchMargin * size.height / 2 + 3 * kalman.stdY();
    return roundRect(cv::Rect2d(kalman.x() - size.width / 2 - growX, kalman.y() - size.height / 2 - growY,
                                size.width + 2 * growX, size.height + 2 * growY));
  }
};

Tracker::Tracker(const TrackerSettings &settings) : settings_(settings), impl_(std::make_unique<Impl>()) {
  impl_->kalman.setParams(settings_.kalman);
  impl_->rebuildModel(settings_);
}

Tracker::~Tracker() = default;

void Tracker::setSettings(const TrackerSettings &settings) {
  const bool modelChanged = settings.colorSpace != settings_.colorSpace || !(settings.bins == settings_.bins);
  // The fused filters were learnt with the old colour model, or went stale while another method tracked.
  if (modelChanged || settings.method != settings_.method) impl_->stopFused();
  settings_ = settings;
  impl_->kalman.setParams(settings_.kalman);
  if (modelChanged) impl_->rebuildModel(settings_);
}

std::string templateSizeProblem(cv::Size size) {
  if (size.width >= kMinTemplateSide && size.height >= kMinTemplateSide) return "";
  return "the template is " + std::to_string(size.width) + "x" + std::to_string(size.height) +
         " pixels; it must be at least " + std::to_string(kMinTemplateSide) + "x" +
         std::to_string(kMinTemplateSide);
}

void Tracker::setTemplate(const cv::Mat &bgr, const cv::Mat &mask) {
  if (bgr.empty() || bgr.type() != CV_8UC3)
    throw TrackerError("the template must be a non-empty 8-bit colour image");
  if (const std::string problem = templateSizeProblem(bgr.size()); !problem.empty())
    throw TrackerError(problem);
  if (!mask.empty() && (mask.size() != bgr.size() || mask.type() != CV_8UC1))
    throw TrackerError("the template mask must be 8-bit, one channel, the template's size");
  if (!mask.empty() && cv::countNonZero(mask) == 0) throw TrackerError("the template mask selects no pixel");
  impl_->templateBgr = bgr.clone();
  impl_->templateMask = mask.empty() ? cv::Mat() : mask.clone();
  impl_->likelihood = ColorLikelihood(settings_.bins);
  impl_->stopFused();
  impl_->aspect = 1.0;
  impl_->rebuildModel(settings_);
  reset();
  impl_->lastScale = 1.0;
}

void Tracker::setTemplateFromBox(const ImageSource &frame, const cv::Rect &box) {
  const cv::Rect frameRect(cv::Point(), frame.size());
  if (box.width <= 0 || box.height <= 0)
    throw TrackerError("the box " + std::to_string(box.width) + "x" + std::to_string(box.height) +
                       " is empty");
  if ((box & frameRect) != box)
    throw TrackerError("the box " + std::to_string(box.x) + "," + std::to_string(box.y) + "," +
                       std::to_string(box.width) + "," + std::to_string(box.height) +
                       " does not lie inside the " + std::to_string(frameRect.width) + "x" +
                       std::to_string(frameRect.height) + " frame");
  cv::Mat bgr;
  frame.bgr(box, bgr);
  setTemplate(bgr);
  Impl::Detection start;
  start.box = box;
  start.verified = true;
  impl_->startTrack(start, settings_);
  impl_->learn(frame, start.box, settings_);
  if (settings_.method == Method::Fused) impl_->startFused(frame, start.box);
  // The first process() call predicts one frame ahead; start from zero motion at the box.
}

bool Tracker::hasTemplate() const {
  return impl_->hasTemplate();
}

cv::Size Tracker::templateSize() const {
  return impl_->templateBgr.size();
}

void Tracker::reset() {
  impl_->state = TrackState::Searching;
  impl_->coastFrames = 0;
  impl_->unverifiedFrames = 0;
  impl_->searchFrames = 0;
  impl_->kalman = KalmanFilter9(settings_.kalman);
}

TrackOutput Tracker::process(const ImageSource &frame, double dt) {
  Impl &m = *impl_;
  TrackOutput out;
  if (!m.hasTemplate()) return out;
  const cv::Size frameSize = frame.size();
  if (m.templateBgr.cols > frameSize.width || m.templateBgr.rows > frameSize.height)
    throw TrackerError("the template (" + std::to_string(m.templateBgr.cols) + "x" +
                       std::to_string(m.templateBgr.rows) + ") is larger than the frame (" +
                       std::to_string(frameSize.width) + "x" + std::to_string(frameSize.height) + ")");

  const TrackerSettings &s = settings_;
  // A lost track is reported for one frame; the frame after it searches again.
  if (m.state == TrackState::Lost) m.state = TrackState::Searching;

  std::optional<Impl::Detection> detection;
  if (s.method == Method::Fused && m.fused.started()) {
    m.processFused(frame, dt, s, out);
  } else if (m.state == TrackState::Tracking || m.state == TrackState::Coasting) {
    m.kalman.predict(dt);
    // Keep the predicted scale sane: the window must fit in the frame.
    const double maxScale = std::min(static_cast<double>(frameSize.width) / m.templateBgr.cols,
                                     static_cast<double>(frameSize.height) / m.templateBgr.rows);
    // Search around the last measured size, not the predicted one: a scale velocity learnt from noisy sizes
    // would otherwise run ahead of the +-6% the refinement can pull back each frame, and collapse the box.
    const double scale = std::clamp(m.lastScale, 0.1, maxScale);
    out.searchRegion = m.predictionRegion(s) & cv::Rect(cv::Point(), frameSize);
    const cv::Point2d predicted(m.kalman.x(), m.kalman.y());
    detection = m.detectIn(frame, out.searchRegion, scale, s, &predicted);
    // A colour-only track may be a same-colour decoy: look over the whole frame now and then for a verified
    // target and move to it (a new track, since it is another object).
    bool switched = false;
    if (detection && !detection->verified && s.verify != VerifyMode::None &&
        ++m.unverifiedFrames % kUnverifiedGlobalSearchPeriod == 0) {
      const auto global = m.detectEverywhere(frame, scale, s);
      if (global && global->verified) {
        m.startTrack(*global, s);
        m.learn(frame, global->box, s);
        out.searchRegion = cv::Rect(cv::Point(), frameSize);
        out.score = global->score;
        m.lastVerified = true;
        switched = true;
      }
    }
    if (!switched && detection) {
      if (detection->verified) m.unverifiedFrames = 0;
      m.updateTrack(*detection);
      m.learn(frame, detection->box, s);
      out.score = detection->score;
      m.lastVerified = detection->verified;
    } else if (!switched) {
      m.kalman.holdForCoasting();
      ++m.coastFrames;
      m.state = m.coastFrames > s.maxCoastFrames ? TrackState::Lost : TrackState::Coasting;
    }
  } else {
    out.searchRegion = cv::Rect(cv::Point(), frameSize);
    const double factor = kSearchScales[m.searchFrames++ % std::size(kSearchScales)];
    detection = m.detectEverywhere(frame, std::clamp(m.lastScale * factor, 0.1, 10.0), s);
    if (detection) {
      m.startTrack(*detection, s);
      m.learn(frame, detection->box, s);
      out.score = detection->score;
      m.lastVerified = detection->verified;
    }
  }

  // The fused method starts its filters on the first detection of a template given as an image.
  if (s.method == Method::Fused && !m.fused.started() && m.state == TrackState::Tracking)
    m.startFused(frame, m.centredBoxNow());

  out.state = m.state;
  out.id = m.trackId;
  if (m.state == TrackState::Tracking || m.state == TrackState::Coasting) {
    out.hasBox = true;
    const double scale = m.kalman.scale();
    out.box = m.centredBoxNow();
    out.scale = scale;
    out.vx = m.kalman.vx();
    out.vy = m.kalman.vy();
    out.verified = m.state == TrackState::Tracking && m.lastVerified;
  }
  return out;
}

FrameReport Tracker::track(const ImageSource &frame, double dt) {
  const TrackOutput out = process(frame, dt);
  FrameReport report;
  TrackReport &r = report.primary;
  r.id = out.id;
  r.state = out.state;
  if (out.hasBox) {
    r.box = out.box;
    r.centre = cv::Point2d(out.box.x + out.box.width / 2, out.box.y + out.box.height / 2);
  }
  r.score = out.score;
  r.verified = out.verified;
  r.scale = out.scale;
  r.vx = out.vx;
  r.vy = out.vy;
  if (out.hasBox) report.tracks.push_back(r);
  report.searchRegion = out.searchRegion;
  return report;
}

void loadTemplate(const std::string &path, cv::Mat &bgr, cv::Mat &mask) {
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception &e) {
    throw TrackerError("cannot read the template image \"" + path + "\": " + e.what());
  }
  if (image.empty())
    throw TrackerError("cannot read the template image \"" + path +
                       "\" (missing, unreadable or not PNG/JPEG)");
  if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 257);
  mask.release();
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
      break;
    case 3:
      bgr = image;
      break;
    case 4: {
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      cv::extractChannel(image, mask, 3);
      cv::threshold(mask, mask, 127, 255, cv::THRESH_BINARY);
      if (cv::countNonZero(mask) == 0)
        throw TrackerError("the template image \"" + path + "\" is fully transparent");
      break;
    }
    default:
      throw TrackerError("the template image \"" + path + "\" has an unsupported number of channels");
  }
}

}  // namespace colortrack
