// SPDX-License-Identifier: LGPL-2.1-or-later
// What the camera-motion estimate (GlobalMotion: phase correlation of small grey copies, translation only;
// threshold mode's follow-camera runs on it) gets right and wrong on real footage. The reference is a
// similarity transform (shift, rotation, zoom) fitted with RANSAC to ORB features of consecutive frames
// (cv::estimateAffinePartial2D), the target's true box left out of both, as it is left out of GlobalMotion.
// On the frames where the reference is sure, per sequence: how often GlobalMotion calls its shift valid, how
// far that shift is from the reference's at the frame's centre, and how far the reference's rotation and zoom
// move the frame's corners beyond its shift (what a translation model cannot follow).
//
//   colortrack-motion-eval SEQ_DIR_OR_PARENT...
//
// No GStreamer; one pass over each sequence's frames.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "colortrack/global_motion.hpp"
#include "colortrack/image_source.hpp"
#include "sequences.hpp"

namespace {

using namespace colortrack;
using namespace colortrack::eval;

// The reference counts when at least this many matches and this share of them agree with its fit.
constexpr int kMinInliers = 40;
constexpr double kMinInlierShare = 0.5;
// A shift within this many px of the reference's is right.
constexpr double kRightPx = 2.0;
// The target's box is left out with this margin (a share of its size on each side).
constexpr double kBoxMargin = 0.2;

struct Reference {
  bool sure = false;
  cv::Point2d centreShift;  // how far the frame's centre moved
  double cornerSpread = 0;  // the largest distance, over the corners, between their motion and centreShift
  double rotationDeg = 0, zoom = 1;
};

cv::Mat maskWithout(cv::Size size, const GroundTruthBox &box) {
  cv::Mat mask(size, CV_8U, cv::Scalar(255));
  if (!box) return mask;
  const cv::Rect2d grown(box->x - kBoxMargin * box->width, box->y - kBoxMargin * box->height,
                         box->width * (1 + 2 * kBoxMargin), box->height * (1 + 2 * kBoxMargin));
  mask(cv::Rect(grown) & cv::Rect(cv::Point(), size)).setTo(0);
  return mask;
}

Reference reference(const std::vector<cv::KeyPoint> &k0, const cv::Mat &d0,
                    const std::vector<cv::KeyPoint> &k1, const cv::Mat &d1, cv::Size size) {
  Reference r;
  if (d0.empty() || d1.empty()) return r;
  std::vector<cv::DMatch> matches;
  cv::BFMatcher(cv::NORM_HAMMING, true).match(d0, d1, matches);
  if (static_cast<int>(matches.size()) < kMinInliers) return r;
  std::vector<cv::Point2f> from, to;
  for (const cv::DMatch &m : matches) {
    from.push_back(k0[m.queryIdx].pt);
    to.push_back(k1[m.trainIdx].pt);
  }
  std::vector<uchar> inliers;
  const cv::Mat a = cv::estimateAffinePartial2D(from, to, inliers, cv::RANSAC, 2.0);
  const int agreeing = cv::countNonZero(inliers);
  if (a.empty() || agreeing < kMinInliers || agreeing < kMinInlierShare * matches.size()) return r;
  const auto moved = [&](cv::Point2d p) {
    return cv::Point2d(a.at<double>(0, 0) * p.x + a.at<double>(0, 1) * p.y + a.at<double>(0, 2),
                       a.at<double>(1, 0) * p.x + a.at<double>(1, 1) * p.y + a.at<double>(1, 2)) -
           p;
  };
  const cv::Point2d centre(size.width / 2.0, size.height / 2.0);
  r.sure = true;
  r.centreShift = moved(centre);
  for (const cv::Point2d corner : {cv::Point2d(0, 0), cv::Point2d(size.width, 0), cv::Point2d(0, size.height),
                                   cv::Point2d(size.width, size.height)})
    r.cornerSpread = std::max(r.cornerSpread, cv::norm(moved(corner) - r.centreShift));
  r.rotationDeg = std::atan2(a.at<double>(1, 0), a.at<double>(0, 0)) * 180 / CV_PI;
  r.zoom = std::hypot(a.at<double>(0, 0), a.at<double>(1, 0));
  return r;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * (v.size() - 1))];
}

struct Tally {
  int pairs = 0, sure = 0, valid = 0, right = 0, moving = 0, movingRight = 0;
  std::vector<double> errors, shifts, spreads;

  void add(const Tally &t) {
    pairs += t.pairs, sure += t.sure, valid += t.valid, right += t.right;
    moving += t.moving, movingRight += t.movingRight;
    errors.insert(errors.end(), t.errors.begin(), t.errors.end());
    shifts.insert(shifts.end(), t.shifts.begin(), t.shifts.end());
    spreads.insert(spreads.end(), t.spreads.begin(), t.spreads.end());
  }
  void print(const std::string &name) const {
    const auto share = [](int part, int whole) { return whole > 0 ? 100.0 * part / whole : 0.0; };
    std::printf("%-14s %6d %6.1f %6.1f %6.1f %9.1f %7.2f %7.2f %8.2f %8.2f\n", name.c_str(), pairs,
                share(sure, pairs), share(valid, sure), share(right, valid), share(movingRight, moving),
                percentile(errors, 0.5), percentile(errors, 0.9), percentile(shifts, 0.5),
                percentile(spreads, 0.9));
  }
};

Tally measureSequence(const Sequence &s) {
  Tally t;
  GlobalMotion motion;
  cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
  std::vector<cv::KeyPoint> previousKeys;
  cv::Mat previousDescriptors;
  for (int i = 0; i < static_cast<int>(s.groundTruth.size()); ++i) {
    const cv::Mat bgr = cv::imread(framePath(s, i).string(), cv::IMREAD_COLOR);
    if (bgr.empty()) throw std::runtime_error("cannot decode " + framePath(s, i).string());
    const GroundTruthBox &box = s.groundTruth[i];
    const GlobalMotion::Shift shift = motion.measure(MatImageSource(bgr), box ? *box : cv::Rect2d());
    cv::Mat gray;
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> keys;
    cv::Mat descriptors;
    orb->detectAndCompute(gray, maskWithout(gray.size(), box), keys, descriptors);
    if (i > 0) {
      ++t.pairs;
      const Reference r = reference(previousKeys, previousDescriptors, keys, descriptors, gray.size());
      if (r.sure) {
        ++t.sure;
        t.shifts.push_back(cv::norm(r.centreShift));
        t.spreads.push_back(r.cornerSpread);
        const bool moving = cv::norm(r.centreShift) > kRightPx;
        t.moving += moving;
        if (shift.valid) {
          ++t.valid;
          const double error = cv::norm(shift.offset - r.centreShift);
          t.errors.push_back(error);
          t.right += error <= kRightPx;
          t.movingRight += moving && error <= kRightPx;
        }
      }
    }
    previousKeys = std::move(keys);
    previousDescriptors = descriptors;
  }
  return t;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SEQ_DIR_OR_PARENT...\n", argv[0]);
    return 2;
  }
  try {
    const std::vector<Sequence> sequences =
        findSequences(std::vector<std::string>(argv + 1, argv + argc), 1.0);
    std::printf(
        "Camera motion: GlobalMotion against a RANSAC similarity of ORB features (reference sure: >= %d "
        "agreeing matches, >= %.0f %% of them), the target's box left out of both.\n"
        "sure: pairs where the reference is sure; valid: of those, GlobalMotion calls its shift valid; "
        "right: "
        "of those, within %.0f px of the reference at the frame's centre; moving right: the same over the "
        "pairs where the camera moved more than %.0f px (sure pairs, invalid counted wrong); err p50 / p90: "
        "px; "
        "shift p50: the reference's; corners p90: how far rotation and zoom move a corner beyond the shift, "
        "px.\n\n",
        kMinInliers, 100 * kMinInlierShare, kRightPx, kRightPx);
    std::printf("%-14s %6s %6s %6s %6s %9s %7s %7s %8s %8s\n", "sequence", "pairs", "sure%", "valid%",
                "right%", "movRight%", "errP50", "errP90", "shiftP50", "cornP90");
    Tally all;
    for (const Sequence &s : sequences) {
      const Tally t = measureSequence(s);
      t.print(s.name);
      all.add(t);
    }
    all.print("all");
  } catch (const std::exception &e) {
    std::fprintf(stderr, "colortrack-motion-eval: %s\n", e.what());
    return 1;
  }
  return 0;
}
