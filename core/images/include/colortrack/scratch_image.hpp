// SPDX-License-Identifier: LGPL-2.1-or-later
// Image buffers that keep their memory from one frame to the next.
#pragma once

#include <opencv2/core.hpp>

namespace colortrack {

// cv::Mat::create() frees and allocates whenever the size changes, and the regions the tracker reads change
// size every frame: with large frames each fresh allocation faults in new pages (car16_1, 1280x720: some 270
// page faults a frame, a third of the element's time). view() places an image of the asked size and type in
// a buffer that only grows. The view is continuous and stays valid until the next view() of the same buffer;
// OpenCV functions given it as their output write into it when size and type match.
class ScratchImage {
 public:
  cv::Mat view(cv::Size size, int type);

 private:
  cv::Mat storage_;  // one row of bytes
};

}  // namespace colortrack
