// SPDX-License-Identifier: LGPL-2.1-or-later
// YUV frames read as BGR (yuvToBgr): the colorimetry's matrix against OpenCV's, the bytes videoconvert gives,
// every layout and siting, and the promise behind it: the same frame delivered as RGB or as YUV gives the
// tracker the same image, the same histogram and the same track. (tests/gst/test_frame_view.cpp checks the
// same against videoconvert itself.)
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "colortrack/histogram.hpp"
#include "colortrack/tracker.hpp"
#include "colortrack/yuv_image.hpp"
#include "scene.hpp"

using namespace colortrack;

namespace {

YuvColorimetry jpegColorimetry() {
  YuvColorimetry c;  // BT.601, full range: what jpegdec's I420 says
  c.fullRange = true;
  return c;
}

// A BGR image encoded as Y, U, V planes at full resolution by the inverse of the colorimetry's matrix.
void encodeYuv(const cv::Mat &bgr, const YuvColorimetry &colorimetry, cv::Mat planes[3]) {
  const cv::Matx34f toBgr = colorimetry.toBgrMatrix();
  const cv::Matx33f linear(toBgr(0, 0), toBgr(0, 1), toBgr(0, 2), toBgr(1, 0), toBgr(1, 1), toBgr(1, 2),
                           toBgr(2, 0), toBgr(2, 1), toBgr(2, 2));
  const cv::Matx33f inverse = linear.inv();
  const cv::Vec3f offset = -(inverse * cv::Vec3f(toBgr(0, 3), toBgr(1, 3), toBgr(2, 3)));
  const cv::Matx34f toYuv(inverse(0, 0), inverse(0, 1), inverse(0, 2), offset[0], inverse(1, 0),
                          inverse(1, 1), inverse(1, 2), offset[1], inverse(2, 0), inverse(2, 1),
                          inverse(2, 2), offset[2]);
  cv::Mat yuv;
  cv::transform(bgr, yuv, toYuv);
  cv::split(yuv, planes);
}

// One frame in the three layouts (4:2:0 chroma averaged over 2x2 blocks, YUY2's 4:2:2 over 2x1), and its
// planes.
struct YuvLayouts {
  cv::Mat luma, u, v, u422, v422;
  cv::Mat i420, nv12Chroma, yuy2;
  SampledFrame i420Frame, nv12Frame, yuy2Frame;
};

YuvLayouts makeLayouts(const cv::Mat &bgr, const YuvColorimetry &colorimetry) {
  cv::Mat planes[3];
  encodeYuv(bgr, colorimetry, planes);
  const cv::Size size = bgr.size(), half(size.width / 2, size.height / 2);
  YuvLayouts l;
  l.luma = planes[0];
  cv::resize(planes[1], l.u, half, 0, 0, cv::INTER_AREA);
  cv::resize(planes[2], l.v, half, 0, 0, cv::INTER_AREA);
  cv::resize(planes[1], l.u422, cv::Size(half.width, size.height), 0, 0, cv::INTER_AREA);
  cv::resize(planes[2], l.v422, cv::Size(half.width, size.height), 0, 0, cv::INTER_AREA);
  cv::vconcat(std::vector<cv::Mat>{l.luma, l.u.reshape(1, half.height / 2), l.v.reshape(1, half.height / 2)},
              l.i420);
  l.i420Frame = sampledI420(l.i420, size, colorimetry);
  cv::merge(std::vector<cv::Mat>{l.u, l.v}, l.nv12Chroma);
  const cv::Mat uvBytes = l.nv12Chroma.reshape(1, half.height);
  l.nv12Frame = l.i420Frame;
  l.nv12Frame.channels = {ChannelSampler{l.luma, 0, 1, 1, 1}, ChannelSampler{uvBytes, 0, 2, 2, 2},
                          ChannelSampler{uvBytes, 1, 2, 2, 2}};
  // Y0 U Y1 V per two pixels.
  std::vector<cv::Mat> y01(2);
  cv::split(l.luma.reshape(2, size.height), y01);
  cv::merge(std::vector<cv::Mat>{y01[0], l.u422, y01[1], l.v422}, l.yuy2);
  const cv::Mat yuy2Bytes = l.yuy2.reshape(1, size.height);
  l.yuy2Frame = l.i420Frame;
  l.yuy2Frame.channels = {ChannelSampler{yuy2Bytes, 0, 2, 1, 1}, ChannelSampler{yuy2Bytes, 1, 4, 2, 1},
                          ChannelSampler{yuy2Bytes, 3, 4, 2, 1}};
  return l;
}

// The planes with each chroma sample repeated over its block, read with the standard matrix by another
// route: OpenCV's resize and its JPEG YCrCb conversion (full-range BT.601).
cv::Mat standardBgr(const cv::Mat &luma, const cv::Mat &u, const cv::Mat &v) {
  cv::Mat uFull, vFull, ycrcb, bgr;
  cv::resize(u, uFull, luma.size(), 0, 0, cv::INTER_NEAREST);
  cv::resize(v, vFull, luma.size(), 0, 0, cv::INTER_NEAREST);
  cv::merge(std::vector<cv::Mat>{luma, vFull, uFull}, ycrcb);
  cv::cvtColor(ycrcb, bgr, cv::COLOR_YCrCb2BGR);
  return bgr;
}

double meanAbsDifference(const cv::Mat &a, const cv::Mat &b) {
  const cv::Scalar d = cv::mean(cv::abs(a - b) + cv::abs(b - a));
  return (d[0] + d[1] + d[2]) / 3;
}

scene::SceneConfig sceneConfig() {
  scene::SceneConfig config;
  config.frames = 120;
  config.brightness = 0.2;
  config.rotationDegrees = 20;
  return config;
}

}  // namespace

TEST(YuvColorimetry, FullRangeBt601IsOpenCvsJpegYCrCb) {
  const YuvColorimetry jpeg = jpegColorimetry();
  for (const cv::Vec3b &ycrcb : {cv::Vec3b(90, 200, 60), cv::Vec3b(180, 100, 150), cv::Vec3b(16, 128, 128)}) {
    cv::Mat bgr;
    cv::cvtColor(cv::Mat(1, 1, CV_8UC3, cv::Scalar(ycrcb[0], ycrcb[1], ycrcb[2])), bgr, cv::COLOR_YCrCb2BGR);
    const std::array<double, 3> rgb = jpeg.toRgb(ycrcb[0], ycrcb[2], ycrcb[1]);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], bgr.at<cv::Vec3b>(0, 0)[2 - c], 1.0);
  }
}

TEST(YuvColorimetry, LimitedRangeBt601IsOpenCvsI420) {
  cv::Mat i420(6, 4, CV_8UC1, cv::Scalar(128)), bgr;
  i420.rowRange(0, 4).setTo(180);
  i420.rowRange(4, 5).setTo(90);   // U
  i420.rowRange(5, 6).setTo(200);  // V
  cv::cvtColor(i420, bgr, cv::COLOR_YUV2BGR_I420);
  const std::array<double, 3> rgb = YuvColorimetry().toRgb(180, 90, 200);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], bgr.at<cv::Vec3b>(1, 1)[2 - c], 1.5);
}

// Samples and the BGR bytes `videoconvert ! video/x-raw,format=BGRx` made of them (GStreamer 1.22.0 and
// 1.26.2 alike, I420 frames of 2x2 blocks), for the colorimetries decoders give: its integer maths reads a
// little darker than the standard matrix (limited-range luma has no offset: 16 is not quite black).
TEST(YuvToBgr, BytesAreVideoconverts) {
  struct Sample {
    int y, u, v;
    int b, g, r;
  };
  YuvColorimetry bt709;
  bt709.kr = 0.2126;
  bt709.kb = 0.0722;
  const struct {
    const char *name;
    YuvColorimetry colorimetry;
    std::vector<Sample> samples;
  } cases[] = {
      {"jpeg (full-range BT.601)",
       jpegColorimetry(),
       {{90, 60, 200, 0, 61, 191},
        {180, 150, 100, 219, 191, 141},
        {16, 128, 128, 16, 16, 16},
        {235, 16, 240, 37, 192, 255},
        {0, 255, 0, 226, 47, 0},
        {255, 0, 255, 28, 206, 255},
        {40, 200, 90, 168, 41, 0}}},
      {"bt601",
       YuvColorimetry(),
       {{90, 60, 200, 0, 51, 199},
        {180, 150, 100, 232, 201, 144},
        {16, 128, 128, 0, 0, 0},
        {235, 16, 240, 28, 204, 255},
        {0, 255, 0, 235, 32, 0},
        {40, 200, 90, 171, 27, 0}}},
      {"bt709",
       bt709,
       {{90, 60, 200, 0, 59, 213},
        {180, 150, 100, 234, 197, 139},
        {235, 16, 240, 17, 216, 255},
        {0, 255, 0, 248, 18, 0},
        {255, 0, 255, 6, 235, 255},
        {40, 200, 90, 178, 29, 0}}},
  };
  for (const auto &c : cases) {
    SCOPED_TRACE(c.name);
    // Each sample as a 2x2 block of an I420 frame 32 samples wide (the vector path and the one-by-one path).
    const int n = static_cast<int>(c.samples.size()), width = 64;
    cv::Mat i420(3, width, CV_8UC1, cv::Scalar(128));
    for (int k = 0; k < width / 2; ++k) {
      const Sample &s = c.samples[k % n];
      i420.at<uchar>(0, 2 * k) = i420.at<uchar>(0, 2 * k + 1) = static_cast<uchar>(s.y);
      i420.at<uchar>(1, 2 * k) = i420.at<uchar>(1, 2 * k + 1) = static_cast<uchar>(s.y);
      i420.at<uchar>(2, k) = static_cast<uchar>(s.u);              // U: the first half of the row
      i420.at<uchar>(2, width / 2 + k) = static_cast<uchar>(s.v);  // V
    }
    cv::Mat bgr;
    yuvToBgr(sampledI420(i420, cv::Size(width, 2), c.colorimetry), cv::Rect(0, 0, width, 2), 1, bgr);
    for (int x = 0; x < width; ++x) {
      const Sample &s = c.samples[(x / 2) % n];
      EXPECT_EQ(bgr.at<cv::Vec3b>(1, x), cv::Vec3b(s.b, s.g, s.r))
          << "column " << x << ": Y " << s.y << " U " << s.u << " V " << s.v;
    }
  }
}

// The same 4:2:0 samples laid out as I420 or NV12 give the same pixels, and YUY2's 4:2:2 its own; each is
// within videoconvert's rounding of the standard matrix, also for a region that starts on an odd pixel and
// for a sample.
TEST(YuvToBgr, EveryLayoutConvertsAsVideoconvertWould) {
  const scene::Scene scene(sceneConfig());
  const YuvLayouts l = makeLayouts(scene.render(7).bgr, jpegColorimetry());
  const cv::Mat reference420 = standardBgr(l.luma, l.u, l.v),
                reference422 = standardBgr(l.luma, l.u422, l.v422);
  const cv::Rect all(cv::Point(), l.luma.size());
  cv::Mat fromI420, fromNv12, fromYuy2;
  yuvToBgr(l.i420Frame, all, 1, fromI420);
  yuvToBgr(l.nv12Frame, all, 1, fromNv12);
  yuvToBgr(l.yuy2Frame, all, 1, fromYuy2);
  EXPECT_EQ(cv::norm(fromI420, fromNv12, cv::NORM_INF), 0);
  EXPECT_LE(cv::norm(fromI420, reference420, cv::NORM_INF), 3);
  EXPECT_LE(cv::norm(fromYuy2, reference422, cv::NORM_INF), 3);
  EXPECT_LT(meanAbsDifference(fromI420, reference420), 2.5);
  EXPECT_LT(meanAbsDifference(fromYuy2, reference422), 2.5);
  for (const SampledFrame *frame : {&l.i420Frame, &l.nv12Frame, &l.yuy2Frame}) {
    const cv::Mat &whole = frame == &l.yuy2Frame ? fromYuy2 : fromI420;
    for (const cv::Rect &rect :
         {cv::Rect(101, 57, 203, 151), cv::Rect(0, 1, 640, 479), cv::Rect(639, 0, 1, 9)}) {
      SCOPED_TRACE(testing::Message() << "rect " << rect);
      cv::Mat region, sampled, everyThird;
      yuvToBgr(*frame, rect, 1, region);
      EXPECT_EQ(cv::norm(region, whole(rect), cv::NORM_INF), 0);
      yuvToBgr(*frame, rect, 3, sampled);
      cv::resize(whole(sampledCover(rect, 3)), everyThird, sampledSize(rect, 3), 0, 0, cv::INTER_NEAREST);
      EXPECT_LE(cv::norm(sampled, everyThird, cv::NORM_INF), 1);
    }
  }
}

// Reading a full-range frame as limited range (what the element did before) is not a small difference.
TEST(YuvToBgr, TheRangeMatters) {
  const YuvLayouts l = makeLayouts(scene::Scene(sceneConfig()).render(3).bgr, jpegColorimetry());
  const cv::Mat reference = standardBgr(l.luma, l.u, l.v);
  SampledFrame misread = l.i420Frame;
  misread.colorimetry.fullRange = false;
  cv::Mat right, wrong;
  const cv::Rect all(cv::Point(), reference.size());
  yuvToBgr(l.i420Frame, all, 1, right);
  yuvToBgr(misread, all, 1, wrong);
  EXPECT_LT(meanAbsDifference(right, reference), 2.5);
  EXPECT_GT(meanAbsDifference(wrong, reference), 5);
}

// The object's HSV histogram from the frame converted upstream with the standard matrix (another library's
// conversion, up to 3 levels from videoconvert's) and from its I420 planes: each channel's intersection at
// least 0.9 (0.94-0.95 for saturation and value: levels that straddle a bin edge move whole pixels between
// bins). From videoconvert's BGRx the bytes, so the histograms, are the same (tests/gst/test_frame_view.cpp).
TEST(YuvToBgr, SameHistogramAsTheFrameConvertedUpstream) {
  const scene::Scene scene(sceneConfig());
  const scene::SceneFrame f = scene.render(30);
  const YuvLayouts l = makeLayouts(f.bgr, jpegColorimetry());
  const cv::Mat reference = standardBgr(l.luma, l.u, l.v);
  cv::Mat fromYuv;
  yuvToBgr(l.i420Frame, cv::Rect(cv::Point(), f.bgr.size()), 1, fromYuv);
  const BinLayout layout;
  const BinMapper mapper(ColorSpace::Hsv, layout);
  BinImage rgbBins, yuvBins;
  mapper.map(reference, rgbBins.bins);
  mapper.map(fromYuv, yuvBins.bins);
  const cv::Rect box = cv::Rect(f.box) & cv::Rect(cv::Point(), f.bgr.size());
  const Histogram a = histogramOf(rgbBins, layout, box), b = histogramOf(yuvBins, layout, box);
  for (int c = 0; c < 3; ++c) EXPECT_GT(intersection(a.channel(c), b.channel(c), layout.bins[c]), 0.9) << c;
}

// The tracker (default method) on the frames converted upstream with the standard matrix and on their I420
// planes: the same track, frame by frame.
TEST(YuvToBgr, SameTrackAsOnTheFramesConvertedUpstream) {
  const scene::Scene scene(sceneConfig());
  Tracker fromRgb, fromYuv;
  double agreement = 0, minAgreement = 1;
  for (int i = 0; i < scene.config().frames; ++i) {
    const scene::SceneFrame f = scene.render(i);
    const YuvLayouts l = makeLayouts(f.bgr, jpegColorimetry());
    const cv::Mat reference = standardBgr(l.luma, l.u, l.v);
    const MatImageSource rgbSource(reference);
    const YuvImageSource yuvSource(l.i420Frame);
    if (i == 0) {
      fromRgb.setTemplateFromBox(rgbSource, scene.initBox());
      fromYuv.setTemplateFromBox(yuvSource, scene.initBox());
    }
    const TrackOutput a = fromRgb.process(rgbSource), b = fromYuv.process(yuvSource);
    ASSERT_TRUE(a.hasBox && b.hasBox) << "frame " << i;
    EXPECT_GT(scene::iou(a.box, f.box), 0.5) << "frame " << i;
    const double same = scene::iou(a.box, b.box);
    agreement += same / scene.config().frames;
    minAgreement = std::min(minAgreement, same);
  }
  // Pixels up to 3 levels apart move the box by a pixel now and then, not more.
  EXPECT_GT(agreement, 0.95);
  EXPECT_GT(minAgreement, 0.8);
}
