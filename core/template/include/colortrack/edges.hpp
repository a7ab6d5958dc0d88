// SPDX-License-Identifier: LGPL-2.1-or-later
// Edge density / edge energy verification: rejects same-colour false positives.
#pragma once

#include <opencv2/core.hpp>

#include "colortrack/choice.hpp"

namespace colortrack {

enum class VerifyMode { None, EdgeDensity, EdgeEnergy, Both };
inline constexpr Choice<VerifyMode> kVerifyModes[] = {
    {VerifyMode::None, "none", "No check: every colour match is verified"},
    {VerifyMode::EdgeDensity, "edge-density", "Edge density close to the template's"},
    {VerifyMode::EdgeEnergy, "edge-energy", "Edge energy close to the template's"},
    {VerifyMode::Both, "both", "Edge density and energy both close to the template's"},
};

// Edges are computed on a patch resized to the template's size, capped at 96 px a side (so values compare
// across scales, and the check stays cheap), after stretching its contrast (so they hold under lighting
// changes).
struct EdgeSignature {
  double density = 0;  // edge pixels / patch area
  double energy =
      0;  // k Σ|e - C|^2 over edge pixels, k = N_template / N_window, divided by N_template * area
  int edgeCount = 0;
  bool valid() const { return edgeCount > 0; }
};

class EdgeVerifier {
 public:
  // templateGray: CV_8UC1 template (its size becomes the normalised size).
  void setTemplate(const cv::Mat &templateGray);
  bool hasTemplate() const { return !normSize_.empty(); }
  const EdgeSignature &templateSignature() const { return template_; }

  // Signature of a window's gray patch (any size; resized to the template size).
  EdgeSignature signature(const cv::Mat &windowGray) const;

  // True when the window's values lie within `tolerance` (relative) of the template's for the chosen mode.
  bool verify(const EdgeSignature &window, VerifyMode mode, double tolerance) const;

 private:
  cv::Size normSize_;
  EdgeSignature template_;
};

// Signature of a gray patch at its own size; `referenceCount` is N_template for the k factor (pass 0 to use
// the patch's own count, i.e. k = 1).
EdgeSignature edgeSignature(const cv::Mat &gray, int referenceCount);

}  // namespace colortrack
