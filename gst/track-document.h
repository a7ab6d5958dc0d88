// One JSON document per frame from the region-of-interest metas on a buffer, shaped like DL Streamer's
// gvametaconvert output (timestamp, source, resolution, objects[] with a pixel box and a normalised
// detection.bounding_box, confidence, label) plus what a tracker adds (id, state, score, verified, vx, vy)
// and the frame number. Built with nlohmann-json. docs/trackpublish.md shows a document.
#pragma once

#include <gst/gst.h>

#include <string>

namespace trackpublish {

struct FrameFacts {
  std::string source;
  guint64 frame = 0;           // buffers seen since start, from 0
  GstClockTime timestamp = 0;  // the buffer's PTS (GST_CLOCK_TIME_NONE: none)
  gint width = 0, height = 0;  // from the caps; 0 when unknown (no normalised box then)
};

// The document for `buffer`'s ROI metas of type `roiType`, on one line.
std::string trackDocument(GstBuffer *buffer, GQuark roiType, const FrameFacts &facts);

}  // namespace trackpublish
