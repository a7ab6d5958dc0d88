// SPDX-License-Identifier: LGPL-2.1-or-later
// What colortrack tells the rest of the pipeline about a frame's tracks, in either mode: one ROI meta (with
// its parameters) per track with a box, and the element message. Field names come from colortrack-meta.h,
// the header applications read them with.
#pragma once

#include <gst/gst.h>
#include <gst/video/video.h>

#include <opencv2/core.hpp>

#include "colortrack/frame_tracker.hpp"

namespace colortrack_gst {

// A track's box as the meta carries it and the overlay draws it: corners rounded to whole pixels, clipped to
// the frame (empty when it lies wholly outside).
cv::Rect frameBox(const cv::Rect2d &box, cv::Size frame);

// The ROI meta of `track` with its "colortrack" parameters (see track-params.h), attached by `element`; none
// when its box lies outside the `frame`-sized frame.
void attachTrackMeta(GstElement *element, GstBuffer *buffer, const colortrack::TrackReport &track,
                     cv::Size frame);

// The "colortrack" element message for the frame `frame` (counted from 0) carried by `buffer`. Reports that
// list their tracks add the "objects" list. `stateName` replaces the primary's state (e.g. "idle").
void postTrackMessage(GstElement *element, const GstSegment &segment, GstBuffer *buffer, guint64 frame,
                      const colortrack::FrameReport &report, const char *stateName = nullptr);

}  // namespace colortrack_gst
