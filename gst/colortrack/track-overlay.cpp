// SPDX-License-Identifier: LGPL-2.1-or-later
#include "track-overlay.h"

#include <algorithm>
#include <cstdio>

#include "overlay.h"
#include "track-report.h"

namespace colortrack_gst {

namespace {

constexpr int kBoxThickness = 2;
constexpr int kTrailThickness = 2;

}  // namespace

void Trails::update(const std::vector<colortrack::TrackReport> &tracks, std::size_t length) {
  for (auto it = byId_.begin(); it != byId_.end();) {
    const bool reported = std::any_of(tracks.begin(), tracks.end(),
                                      [&](const colortrack::TrackReport &t) { return t.id == it->first; });
    it = reported ? std::next(it) : byId_.erase(it);
  }
  if (length == 0) return;
  for (const colortrack::TrackReport &t : tracks) {
    std::deque<cv::Point2d> &trail = byId_[t.id];
    trail.push_back(t.centre);
    while (trail.size() > length) trail.pop_front();
  }
}

const std::deque<cv::Point2d> *Trails::of(int id) const {
  const auto it = byId_.find(id);
  return it == byId_.end() ? nullptr : &it->second;
}

void drawTracks(GstVideoFrame *frame, const colortrack::FrameReport &report, const Trails &trails,
                const OverlayParts &parts) {
  if (!parts.any()) return;
  using colortrack::TrackState;
  namespace colors = colortrack_gst::colors;
  colortrack_gst::FrameCanvas canvas(frame);
  const cv::Size size(GST_VIDEO_FRAME_WIDTH(frame), GST_VIDEO_FRAME_HEIGHT(frame));
  if (parts.mask && !report.mask.empty()) canvas.tintMask(report.mask, report.maskStep, colors::kMagenta);
  if (parts.searchWindow && !report.searchRegion.empty())
    canvas.boxOutline(report.searchRegion, colors::kBlue, 1);
  const bool byId = report.listsTracks;
  for (const colortrack::TrackReport &t : report.tracks) {
    const colortrack_gst::Rgb idColour = colortrack_gst::idColour(t.id);
    const std::deque<cv::Point2d> *trail = trails.of(t.id);
    if (parts.trail && trail && trail->size() >= 2) {
      std::vector<cv::Point> points;
      points.reserve(trail->size());
      for (const cv::Point2d &p : *trail) points.emplace_back(cvRound(p.x), cvRound(p.y));
      canvas.polyline(points, byId ? idColour : colors::kYellow, kTrailThickness);
    }
    const cv::Rect box = frameBox(t.box, size);
    if (box.empty()) continue;
    const bool coasting = t.state == TrackState::Coasting;
    if (parts.box) {
      // Several tracks: the id colour says which, a thin outline that it is coasting. One track: the colour
      // says how sure.
      if (byId)
        canvas.boxOutline(box, idColour, coasting ? 1 : kBoxThickness);
      else
        canvas.boxOutline(box,
                          coasting     ? colors::kOrange
                          : t.verified ? colors::kGreen
                                       : colors::kRed,
                          kBoxThickness);
    }
    if (parts.label) {
      char text[64];
      if (byId)
        std::snprintf(text, sizeof text, "%d %.0f %s", t.id, t.area.value_or(0.0),
                      colortrack::toString(t.state));
      else
        std::snprintf(text, sizeof text, "%d %.2f %s", t.id, t.score, colortrack::toString(t.state));
      canvas.label(text, cv::Point(box.x, box.y - 4));
    }
  }
}

}  // namespace colortrack_gst
