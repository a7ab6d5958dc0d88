// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode as one tracker: the frame segmented into blobs (blobs.hpp), the blobs followed by the
// multi-object tracker (multi_tracker.hpp).
#pragma once

#include <vector>

#include "colortrack/blobs.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/global_motion.hpp"
#include "colortrack/multi_tracker.hpp"

namespace colortrack {

// The width of the copy threshold mode measures the camera's motion on (GlobalMotion): the association gates
// are at least 12 px plus half the object wide, so a few pixels of error do not matter, and the default copy
// cost as much as the segmentation.
inline constexpr double kCameraCopyWidth = 128;

// What GlobalMotion leaves out in threshold mode: every blob's box grown by 4 px (its motion since the last
// frame).
std::vector<cv::Rect2d> movingObjects(const std::vector<Blob> &blobs);

class ThresholdTracker : public FrameTracker {
 public:
  explicit ThresholdTracker(const BlobSettings &blobs = BlobSettings(),
                            const MultiTrackerSettings &tracks = MultiTrackerSettings());

  // A new range, clean-up or size limit applies from the next frame; the tracks go on.
  void setBlobSettings(const BlobSettings &settings);
  const BlobSettings &blobSettings() const { return detector_.settings(); }
  // Its minObjectArea is replaced by the blob settings' minArea.
  void setTrackSettings(const MultiTrackerSettings &settings);

  // Reports every confirmed track (by id); the primary target is the largest.
  FrameReport track(const ImageSource &frame, double dt) override;
  void reset() override {
    tracks_.reset();
    camera_.reset();
  }

 private:
  void followCamera(const SampledFrame &frame, const std::vector<Blob> &blobs);

  BlobDetector detector_;
  MultiTracker tracks_;
  GlobalMotion camera_{kCameraCopyWidth};  // how the picture moved since the last frame
  cv::Mat converted_;                      // the frame as BGR, for sources that cannot be read in place
};

}  // namespace colortrack
