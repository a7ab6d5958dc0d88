// SPDX-License-Identifier: LGPL-2.1-or-later
// The one entry point the element uses: settings in, frame in, track out.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/edges.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/histogram.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/kalman.hpp"
#include "colortrack/scale.hpp"
#include "colortrack/search.hpp"
#include "colortrack/track.hpp"

namespace colortrack {

// How a frame is searched for the target.
enum class Method {
  // The paper's modified colour indexing: the template's per-channel histograms against every window by
  // weighted histogram intersection, scale by window-versus-ring match.
  Indexing,
  // Object-versus-surroundings colour likelihood P(object | colour), learnt from the target box and the
  // ring around it and adapted slowly; windows scored by their mean likelihood with a motion prior, box size
  // and aspect by the likelihood mass they enclose. Falls back to Indexing until it has been learnt (a
  // template file has no surroundings: the first detection teaches it).
  Discriminative,
  // Two learners fused (as in Staple): a discriminative correlation filter over gradient-orientation cells
  // and intensity (shape, learnt online in the Fourier domain) and the colour likelihood above, their
  // response maps summed; a 1-D scale filter; the fused response's peak-to-sidelobe confidence decides
  // tracking / coasting / lost and gates learning; a lost target is re-detected over the whole frame.
  Fused,
};

struct TrackerSettings {
  Method method = Method::Fused;
  ColorSpace colorSpace = ColorSpace::Hsv;
  BinLayout bins;
  ChannelWeights weights;
  double matchThreshold = 0.25;  // minimum match value of a detection (a product of three intersections)
  ScaleParams scale;
  double searchMargin = 2.0;  // search region = box grown by margin * size + 3 sigma of the prediction
  KalmanParams kalman;
  int maxCoastFrames = 10;  // frames without detection before the track is lost
  // The camera's own motion (GlobalMotion) taken out of the predictions: a panning or turning camera moves
  // every track with the picture. Threshold mode.
  bool followCamera = true;
  VerifyMode verify = VerifyMode::Both;
  double verifyTolerance = 0.5;

  // Discriminative method only.
  double likelihoodThreshold = 0.3;  // minimum mean P(object | colour) in the box for a detection
  double modelUpdateRate = 0.05;     // how fast the likelihood follows appearance changes (0 = never)
  bool adaptAspect = true;           // let the box's width and height change independently
};

struct TrackOutput {
  TrackState state = TrackState::Searching;
  bool hasBox = false;  // a track exists (tracking or coasting)
  int id = 0;           // track id, >= 1 once a track has existed; grows at every new acquisition
  cv::Rect2d box;       // filtered box, frame coordinates
  // Indexing and discriminative: match value of this frame's detection against the template (0 when
  // coasting). Fused: the frame's confidence relative to the track's usual one, capped at 1 and at
  // 1 - rival / 2 when a look-alike answers in the window (under 0.5: not a detection, a guess or doubted).
  double score = 0;
  bool verified = false;  // edge check passed (always true when verify = None)
  double scale = 1.0;     // box size relative to the template
  double vx = 0, vy = 0;  // filtered velocity, px/frame
  cv::Rect searchRegion;  // where this frame was searched (empty if nothing was searched)
};

// The smallest template side: smaller boxes hold too few pixels for a histogram or a shape filter.
constexpr int kMinTemplateSide = 8;
// Why a template (or init box) of `size` cannot be used, or "" when it can.
std::string templateSizeProblem(cv::Size size);

// Thrown for unusable input (a template larger than the frame, an empty box ...). The text names the problem.
class TrackerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Tracker : public FrameTracker {
 public:
  explicit Tracker(const TrackerSettings &settings = TrackerSettings());
  ~Tracker() override;

  // Settings may change at any time; the template model is rebuilt if the colour space or bins change.
  void setSettings(const TrackerSettings &settings);
  const TrackerSettings &settings() const { return settings_; }

  // Template from an image (CV_8UC3 BGR); a non-empty mask (CV_8UC1) selects the object's pixels.
  void setTemplate(const cv::Mat &bgr, const cv::Mat &mask = cv::Mat());
  // Template from a box of a frame; tracking starts there (the first output is `tracking` at that box).
  void setTemplateFromBox(const ImageSource &frame, const cv::Rect &box);
  bool hasTemplate() const;
  cv::Size templateSize() const;

  // Processes one frame. dt: time since the previous frame in frames (1 unless timestamps say otherwise).
  // A frame that cuts to another scene (SceneCut) loses the track at once: it is reported `lost`, and the
  // frames after it search the whole frame. Throws TrackerError when the template does not fit in the frame.
  TrackOutput process(const ImageSource &frame, double dt = 1.0);
  // process() as the element sees it: the track (if any) as the primary and only report.
  FrameReport track(const ImageSource &frame, double dt) override;

  // Forget the track (keeps the template): the next frame searches the whole frame.
  void reset() override;

 private:
  struct Impl;
  TrackerSettings settings_;
  std::unique_ptr<Impl> impl_;
};

// Loads a template image (PNG or JPEG). A PNG alpha channel becomes the mask (alpha > 127 counts).
// Throws TrackerError naming the file when it cannot be read.
void loadTemplate(const std::string &path, cv::Mat &bgr, cv::Mat &mask);

// Starts OpenCV's worker threads now. The first parallel loop of a process starts them, which costs a few
// milliseconds: called before streaming, that cost is not paid on the first frame.
void startWorkerThreads();

}  // namespace colortrack
