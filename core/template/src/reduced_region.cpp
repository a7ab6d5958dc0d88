// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/reduced_region.hpp"

#include <algorithm>

namespace colortrack {

std::optional<ReducedRegion> RegionReader::read(const ImageSource &frame, const cv::Rect &region,
                                                cv::Size2d size, int pad, const BinMapper &mapper) {
  const cv::Rect frameRect(cv::Point(), frame.size());
  const cv::Rect searchRect = region & frameRect;
  if (searchRect.width < size.width || searchRect.height < size.height) return std::nullopt;
  ReducedRegion r;
  r.padded = cv::Rect(searchRect.x - pad, searchRect.y - pad, searchRect.width + 2 * pad,
                      searchRect.height + 2 * pad) &
             frameRect;
  r.f = std::max(1, static_cast<int>(std::min(size.width, size.height) / kReducedWindowSide));
  frame.sampledBgr(r.padded, r.f, small_);
  mapper.map(small_, bins_.bins);
  bins_.origin = cv::Point();
  const cv::Point2d tl = r.toLocal(searchRect.x, searchRect.y);
  r.searchL = cv::Rect(cvCeil(tl.x), cvCeil(tl.y), searchRect.width / r.f, searchRect.height / r.f) &
              cv::Rect(cv::Point(), bins_.bins.size());
  r.sizeL = cv::Size2d(size.width / r.f, size.height / r.f);
  if (r.searchL.width < cvRound(r.sizeL.width) || r.searchL.height < cvRound(r.sizeL.height))
    return std::nullopt;
  return r;
}

}  // namespace colortrack
