// SPDX-License-Identifier: LGPL-2.1-or-later
// Parsing of the user-facing setting strings. Errors come back as text naming what is wrong, so the
// GStreamer layer can report them against the property.
#pragma once

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/histogram.hpp"

namespace colortrack {

// "16,16,8": three integers in 1..256.
std::optional<BinLayout> parseBins(const std::string &text, std::string *error = nullptr);
// "1,1,0.3": three numbers in [0,1], not all zero.
std::optional<ChannelWeights> parseWeights(const std::string &text, std::string *error = nullptr);
// "x,y,w,h": integers, x,y >= 0, w,h > 0.
std::optional<cv::Rect> parseBox(const std::string &text, std::string *error = nullptr);

// "h,s,v" with h in 0..360 and s, v in 0..1 (threshold mode's hsv-lower / hsv-upper).
std::optional<Hsv> parseHsv(const std::string &text, std::string *error = nullptr);

std::string formatBins(const BinLayout &layout);
std::string formatWeights(const ChannelWeights &weights);
std::string formatBox(const cv::Rect &box);
std::string formatHsv(const Hsv &hsv);
// A number as short text (up to 4 significant digits), for settings and messages.
std::string formatNumber(double value);

}  // namespace colortrack
