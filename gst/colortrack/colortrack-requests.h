// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's mailbox: what the application thread asks of the next frame (an init-box, a click) and what
// the streaming thread tells the property checks (the frame size). Under the object lock, in the store.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

namespace colortrack_gst {

// A mouse click from a GstNavigation event, waiting for the next frame: a left click starts tracking at
// `point` (element frame coordinates), a right click stops.
struct ClickRequest {
  enum class Kind { Track, Stop } kind = Kind::Track;
  cv::Point2d point;
};

// A click and an init-box replace each other: the latest request wins.
struct Requests {
  // A parsed init-box waiting for the next frame, and whether it was set while streaming (then a box that
  // does not fit the frame is a warning, not an error).
  std::optional<cv::Rect> initBox;
  bool initBoxWhileStreaming = false;
  std::optional<ClickRequest> click;
};

struct Shared {
  Requests requests;
  cv::Size frameSize;  // from the caps (empty before), to judge a min-area set while playing
};

}  // namespace colortrack_gst
