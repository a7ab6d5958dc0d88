// Threshold mode's preparation of a frame: the threshold tracker brought up to date with the properties, and
// a colour range learnt from an init-box or a click.
#include <algorithm>

#include <gst/gst.h>

#include "colortrack/blobs.hpp"
#include "colortrack-modes.h"

#define GST_CAT_DEFAULT gst_color_track_debug

namespace colortrack_gst {

namespace {

colortrack::MultiTrackerSettings multiTrackerSettings(const Settings &settings) {
  colortrack::MultiTrackerSettings m;
  m.kalman = settings.tracker.kalman;
  m.maxCoastFrames = settings.tracker.maxCoastFrames;
  m.followCamera = settings.tracker.followCamera;
  return m;
}

// Learns hsv-lower/hsv-upper from the pixels of `box` and starts over with that range. This is the one place
// the streaming thread writes a property: the properties then report the range, so it can be reused in a
// launch line.
void learnRange(GstColorTrack *self, const colortrack_gst::FrameView &view, const cv::Rect &box,
                const std::string &origin) {
  State &state = self->priv->state;
  const colortrack::HsvRange learnt = colortrack::learnRange(view, box);
  GST_OBJECT_LOCK(self);
  PropertyStore &store = self->priv->store;
  store.settings.blobs.range = learnt;
  store.settings.hsvLower = colortrack::formatHsv(learnt.lower);
  store.settings.hsvUpper = colortrack::formatHsv(learnt.upper);
  const colortrack::BlobSettings blobs = store.settings.blobs;
  state.appliedBlobsGeneration = ++store.versions[kBlobsVersion];
  GST_OBJECT_UNLOCK(self);
  state.thresholdTracker->setBlobSettings(blobs);
  state.thresholdTracker->reset();
  state.trails.clear();
  state.idle = false;
  GST_INFO_OBJECT(self, "learnt hsv-lower %s hsv-upper %s from %s",
                  colortrack::formatHsv(learnt.lower).c_str(), colortrack::formatHsv(learnt.upper).c_str(),
                  origin.c_str());
  g_object_notify(G_OBJECT(self), "hsv-lower");
  g_object_notify(G_OBJECT(self), "hsv-upper");
}

// A left click learns the colour around it; a right click stops until a new target is given.
void applyClick(GstColorTrack *self, State &state, const ClickRequest &click, int boxSize,
                const colortrack_gst::FrameView &view) {
  if (click.kind == ClickRequest::Kind::Stop) return stopTracking(state, *state.thresholdTracker);
  // The colour is sampled from the middle half of the box: a click lands near an object's centre, and a
  // sample that reached past a small object's edge would learn the background's colours too.
  const cv::Rect sample = boxAround(click.point, std::max(1, boxSize / 2), view.size());
  if (sample.empty())
    GST_INFO_OBJECT(self, "click at %.1f,%.1f lies outside the %dx%d frame: ignored", click.point.x,
                    click.point.y, view.size().width, view.size().height);
  else
    learnRange(self, view, sample, describeClick(click, sample));
}

}  // namespace

bool prepareThresholdFrame(GstColorTrack *self, const Snapshot &snapshot, const Requests &requests,
                           const colortrack_gst::FrameView &view) {
  State &state = self->priv->state;
  colortrack::ThresholdTracker &tracker = *state.thresholdTracker;
  const cv::Size size = view.size();

  if (snapshot.blobs.minArea > size.area()) {
    GST_ELEMENT_ERROR(
        self, RESOURCE, SETTINGS,
        ("Property 'min-area' %d is larger than the %dx%d frame (%d pixels): nothing can be found.",
         snapshot.blobs.minArea, size.width, size.height, size.area()),
        (nullptr));
    return false;
  }
  if (snapshot.blobsGeneration != state.appliedBlobsGeneration) {
    tracker.setBlobSettings(snapshot.blobs);
    state.appliedBlobsGeneration = snapshot.blobsGeneration;
  }
  if (snapshot.rangeGeneration != state.appliedRangeGeneration) {
    state.appliedRangeGeneration = snapshot.rangeGeneration;
    state.idle = false;  // a new range is a new target
  }
  tracker.setTrackSettings(multiTrackerSettings(snapshot));
  resetIfRequested(self, tracker);
  if (requests.initBox) {
    const InitBoxFit fit =
        checkInitBox(self, *requests.initBox, size, requests.initBoxWhileStreaming, snapshot.initBox);
    if (fit == InitBoxFit::Error) return false;
    if (fit == InitBoxFit::Fits) learnRange(self, view, *requests.initBox, "init-box " + snapshot.initBox);
  }
  if (requests.click) applyClick(self, state, *requests.click, snapshot.clickBoxSize, view);
  return true;
}

}  // namespace colortrack_gst
