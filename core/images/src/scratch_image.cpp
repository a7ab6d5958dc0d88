// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/scratch_image.hpp"

#include <algorithm>

namespace colortrack {

cv::Mat ScratchImage::view(cv::Size size, int type) {
  CV_Assert(size.width >= 0 && size.height >= 0);
  const size_t bytes = std::max<size_t>(1, size.area() * CV_ELEM_SIZE(type));
  if (storage_.empty() || storage_.total() < bytes) {
    // A quarter more than asked, so a region that grows a little each frame does not reallocate each time.
    storage_.create(1, static_cast<int>(bytes + bytes / 4), CV_8UC1);
  }
  return cv::Mat(size, type, storage_.data);
}

}  // namespace colortrack
