// SPDX-License-Identifier: LGPL-2.1-or-later
// The modes by colortrack::TrackingMode: one row a mode.
#include "colortrack-mode.h"

#include <stdexcept>
#include <utility>

namespace colortrack_gst {

namespace {

struct ModeRow {
  colortrack::TrackingMode mode;
  std::unique_ptr<Mode> (*make)(std::unique_ptr<ElementSink> sink);
};

constexpr ModeRow kModes[] = {
    {colortrack::TrackingMode::Template, makeTemplateMode},
    {colortrack::TrackingMode::Threshold, makeThresholdMode},
};

}  // namespace

std::unique_ptr<Mode> makeMode(colortrack::TrackingMode mode, std::unique_ptr<ElementSink> sink) {
  for (const ModeRow &row : kModes)
    if (row.mode == mode) return row.make(std::move(sink));
  throw std::logic_error("colortrack: no mode for this TrackingMode");
}

}  // namespace colortrack_gst
