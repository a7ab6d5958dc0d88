// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/settings.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

namespace colortrack {

namespace {

std::string_view trimmed(std::string_view s) {
  const auto isSpace = [](char c) { return c == ' ' || c == '\t'; };
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitFields(std::string_view text) {
  std::vector<std::string_view> fields;
  for (;;) {
    const auto comma = text.find(',');
    fields.push_back(trimmed(text.substr(0, comma)));
    if (comma == std::string_view::npos) return fields;
    text.remove_prefix(comma + 1);
  }
}

// std::from_chars is locale independent, unlike strtod/istream: a GStreamer application may have set a
// locale whose decimal separator is a comma.
template <typename T>
bool parseNumber(std::string_view field, T &value) {
  if (field.empty()) return false;
  const char *end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  return ec == std::errc() && ptr == end;
}

template <typename T, std::size_t N>
std::optional<std::array<T, N>> parseList(const std::string &text) {
  const auto fields = splitFields(text);
  if (fields.size() != N) return std::nullopt;
  std::array<T, N> values{};
  for (std::size_t i = 0; i < N; ++i)
    if (!parseNumber(fields[i], values[i])) return std::nullopt;
  return values;
}

Status fail(const std::string &message) {
  return Status::failure(message);
}

std::string quoted(const std::string &text) {
  return "\"" + text + "\"";
}

std::string formatWeight(double value) {
  std::array<char, 32> buffer{};
  // Three significant digits keep "0.3" as "0.3" rather than "0.29999999999999999".
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::general, 3);
  return std::string(buffer.data(), result.ptr);
}

}  // namespace

Result<BinLayout> parseBins(const std::string &text) {
  const auto values = parseList<int, 3>(text);
  if (!values) return fail("expected three integers 1..256 separated by commas, got " + quoted(text));
  for (int n : *values)
    if (n < 1 || n > 256)
      return fail("bins per channel must be 1..256, got " + std::to_string(n) + " in " + quoted(text));
  BinLayout layout;
  layout.bins = *values;
  return layout;
}

constexpr double kMinWeightSum = 1e-3;

Result<ChannelWeights> parseWeights(const std::string &text) {
  const auto values = parseList<double, 3>(text);
  if (!values) return fail("expected three numbers 0..1 separated by commas, got " + quoted(text));
  for (double w : *values)
    if (!(w >= 0.0 && w <= 1.0))  // also rejects NaN
      return fail("channel weights must be in [0, 1], got " + quoted(text));
  // A weight too small to count (1e-320) is as good as zero: the weights must add up to something.
  if ((*values)[0] + (*values)[1] + (*values)[2] < kMinWeightSum)
    return fail(
        "the channel weights must add up to at least 0.001 (all zero would make every window a "
        "perfect match), got " +
        quoted(text));
  ChannelWeights weights;
  for (int c = 0; c < 3; ++c) weights.w[c] = (*values)[c] + 0.0;  // -0 reads back as 0
  return weights;
}

Result<cv::Rect> parseBox(const std::string &text) {
  const auto values = parseList<int, 4>(text);
  if (!values) return fail("expected four integers x,y,w,h separated by commas, got " + quoted(text));
  const auto [x, y, w, h] = *values;
  if (x < 0 || y < 0) return fail("box x and y must be >= 0, got " + quoted(text));
  if (w <= 0 || h <= 0) return fail("box width and height must be > 0, got " + quoted(text));
  if (x > std::numeric_limits<int>::max() - w || y > std::numeric_limits<int>::max() - h)
    return fail("box extends past the largest coordinate, got " + quoted(text));
  return cv::Rect(x, y, w, h);
}

std::string formatBins(const BinLayout &layout) {
  return std::to_string(layout.bins[0]) + "," + std::to_string(layout.bins[1]) + "," +
         std::to_string(layout.bins[2]);
}

std::string formatWeights(const ChannelWeights &weights) {
  return formatWeight(weights.w[0]) + "," + formatWeight(weights.w[1]) + "," + formatWeight(weights.w[2]);
}

std::string formatBox(const cv::Rect &box) {
  return std::to_string(box.x) + "," + std::to_string(box.y) + "," + std::to_string(box.width) + "," +
         std::to_string(box.height);
}

std::string formatNumber(double value) {
  std::array<char, 32> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::general, 4);
  return std::string(buffer.data(), result.ptr);
}

Result<Hsv> parseHsv(const std::string &text) {
  const auto fields = splitFields(text);
  std::array<double, 3> values{};
  bool numbers = fields.size() == 3;
  for (std::size_t i = 0; numbers && i < 3; ++i)
    numbers = parseNumber(fields[i], values[i]) && std::isfinite(values[i]);
  if (!numbers) return fail("expected \"h,s,v\" (h in degrees 0-360, s and v 0-1), got \"" + text + "\"");
  if (values[0] < 0 || values[0] > 360)
    return fail("hue must be 0-360 degrees, got " + formatNumber(values[0]) + " in \"" + text + "\"");
  if (values[1] < 0 || values[1] > 1)
    return fail("saturation must be 0-1, got " + formatNumber(values[1]) + " in \"" + text + "\"");
  if (values[2] < 0 || values[2] > 1)
    return fail("value must be 0-1, got " + formatNumber(values[2]) + " in \"" + text + "\"");
  return Hsv{values[0], values[1], values[2]};
}

std::string formatHsv(const Hsv &hsv) {
  return formatNumber(hsv.h) + "," + formatNumber(hsv.s) + "," + formatNumber(hsv.v);
}

}  // namespace colortrack
