// SPDX-License-Identifier: LGPL-2.1-or-later
// Parsing of the user-facing setting strings. A failure comes back as a Result's Status naming what is wrong,
// so the GStreamer layer can report it against the property.
#pragma once

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/histogram.hpp"
#include "colortrack/status.hpp"

namespace colortrack {

// "16,16,8": three integers in 1..256.
Result<BinLayout> parseBins(const std::string &text);
// "1,1,0.3": three numbers in [0,1], not all zero.
Result<ChannelWeights> parseWeights(const std::string &text);
// "x,y,w,h": integers, x,y >= 0, w,h > 0.
Result<cv::Rect> parseBox(const std::string &text);

// "h,s,v" with h in 0..360 and s, v in 0..1 (threshold mode's hsv-lower / hsv-upper).
Result<Hsv> parseHsv(const std::string &text);

std::string formatBins(const BinLayout &layout);
std::string formatWeights(const ChannelWeights &weights);
std::string formatBox(const cv::Rect &box);
std::string formatHsv(const Hsv &hsv);
// A number as short text (up to 4 significant digits), for settings and messages.
std::string formatNumber(double value);

}  // namespace colortrack
