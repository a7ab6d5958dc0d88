// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode: the threshold tracker, brought up to date with the properties before it tracks a frame, and
// a colour range learnt from an init-box or a click.
#include <algorithm>
#include <optional>

#include <gst/gst.h>

#include "colortrack/blobs.hpp"
#include "colortrack-mode.h"

namespace colortrack_gst {

namespace {

colortrack::MultiTrackerSettings multiTrackerSettings(const Settings &settings) {
  colortrack::MultiTrackerSettings m;
  m.kalman = settings.tracker.kalman;
  m.maxCoastFrames = settings.tracker.maxCoastFrames;
  m.followCamera = settings.tracker.followCamera;
  return m;
}

class ThresholdMode : public Mode {
 public:
  explicit ThresholdMode(std::unique_ptr<ElementSink> sink) : sink_(std::move(sink)) {}

  bool start(const Snapshot &snapshot) override {
    tracker_.emplace(snapshot.blobs);
    return true;
  }
  bool prepare(const Snapshot &snapshot, const Requests &requests, const FrameView &view) override;
  Readiness readiness(cv::Size) override { return Readiness::Ready; }
  colortrack::FrameTracker &tracker() override { return *tracker_; }
  bool listsTracks() const override { return true; }

 private:
  void learnRange(const FrameView &view, const cv::Rect &box, const std::string &origin);
  void applyClick(const ClickRequest &click, int boxSize, const FrameView &view);

  std::unique_ptr<ElementSink> sink_;
  std::optional<colortrack::ThresholdTracker> tracker_;
};

bool ThresholdMode::prepare(const Snapshot &snapshot, const Requests &requests, const FrameView &view) {
  const cv::Size size = view.size();
  if (snapshot.blobs.minArea > size.area()) {
    sink_->error(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_SETTINGS,
                 "Property 'min-area' " + std::to_string(snapshot.blobs.minArea) + " is larger than the " +
                     std::to_string(size.width) + "x" + std::to_string(size.height) + " frame (" +
                     std::to_string(size.area()) + " pixels): nothing can be found.");
    return false;
  }
  if (snapshot.changed.has(Settings::Change::Blobs)) tracker_->setBlobSettings(snapshot.blobs);
  if (snapshot.changed.has(Settings::Change::Range)) {
    sink_->resumed();  // a new range is a new target for the tracks there are
  }
  tracker_->setTrackSettings(multiTrackerSettings(snapshot));
  resetIfRequested(*sink_, *tracker_);
  if (requests.initBox) {
    const InitBoxFit fit =
        checkInitBox(*sink_, *requests.initBox, size, requests.initBoxWhileStreaming, snapshot.initBox);
    if (fit == InitBoxFit::Error) return false;
    if (fit == InitBoxFit::Fits) learnRange(view, *requests.initBox, "init-box " + snapshot.initBox);
  }
  if (requests.click) applyClick(*requests.click, snapshot.clickBoxSize, view);
  return true;
}

// Learns hsv-lower/hsv-upper from the pixels of `box` and starts over with that range. This is the one place
// the streaming thread writes a property: the properties then report the range, so it can be reused in a
// launch line.
void ThresholdMode::learnRange(const FrameView &view, const cv::Rect &box, const std::string &origin) {
  const colortrack::HsvRange learnt = colortrack::learnRange(view, box);
  tracker_->setBlobSettings(sink_->writeLearntRange(learnt));
  tracker_->reset();
  sink_->targetChanged();
  sink_->info("learnt hsv-lower " + colortrack::formatHsv(learnt.lower) + " hsv-upper " +
              colortrack::formatHsv(learnt.upper) + " from " + origin);
}

// A left click learns the colour around it; a right click stops until a new target is given.
void ThresholdMode::applyClick(const ClickRequest &click, int boxSize, const FrameView &view) {
  if (click.kind == ClickRequest::Kind::Stop) return stopTracking(*sink_, *tracker_);
  // The colour is sampled from the middle half of the box: a click lands near an object's centre, and a
  // sample that reached past a small object's edge would learn the background's colours too.
  const cv::Rect sample = boxAround(click.point, std::max(1, boxSize / 2), view.size());
  if (sample.empty())
    ignoreClickOutside(*sink_, click, view.size());
  else
    learnRange(view, sample, describeClick(click, sample));
}

}  // namespace

std::unique_ptr<Mode> makeThresholdMode(std::unique_ptr<ElementSink> sink) {
  return std::make_unique<ThresholdMode>(std::move(sink));
}

}  // namespace colortrack_gst
