// SPDX-License-Identifier: LGPL-2.1-or-later
// One JSON document per frame from the region-of-interest metas on a buffer, in DL Streamer's gvametaconvert
// schema (timestamp in stream time, source, resolution, tags, objects[] with roi_type, a pixel box and a
// normalised detection.bounding_box, confidence, label, label_id) plus what a tracker adds (id, state,
// score, verified, vx, vy), the frame number and the run. Built with nlohmann-json. docs/trackpublish.md
// shows a document.
#pragma once

#include <gst/gst.h>

#include <nlohmann/json.hpp>

#include <string>

#include "colortrack/status.hpp"

namespace trackpublish {

struct FrameFacts {
  std::string source;
  std::string run;              // new at every start: documents of two runs never look like repeats
  nlohmann::ordered_json tags;  // an object, or null: none
  bool addEmptyResults = false;
  guint64 frame = 0;           // buffers seen since start, from 0
  GstClockTime timestamp = 0;  // the buffer's stream time (GST_CLOCK_TIME_NONE: none)
  gint width = 0, height = 0;  // from the caps; 0 when unknown (no normalised box then)
};

// The document for `buffer`'s ROI metas of type `roiType`, on one line; empty for a frame without one
// unless facts.addEmptyResults.
std::string trackDocument(GstBuffer *buffer, GQuark roiType, const FrameFacts &facts);

// Whether `tags` is a JSON object a consumer can read (no key twice, no NUL), or why not.
colortrack::Status checkTags(const std::string &tags);

}  // namespace trackpublish
