// SPDX-License-Identifier: LGPL-2.1-or-later
#include "scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace colortrack::scene {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kEdgeGap = 4;  // px kept free between the object's reach, the decoy and the frame edge
// Noise is uniform over a power-of-two range of bytes: OpenCV fills a 1080p frame that way in ~3 ms, ten
// times faster than Gaussian or other ranges.
constexpr int kFrameNoise = 4;       // per-frame sensor noise, +- grey levels
constexpr int kBackgroundGrain = 8;  // fixed fine grain of the background, +- grey levels

// Enlarge a coarse random grid smoothly: bicubic by a small factor, then bilinear to full size (a bicubic
// enlargement straight to 1080p is ~30x slower and looks the same).
cv::Mat smoothEnlarge(const cv::Mat &coarse, int cell, cv::Size size) {
  const int cubicFactor = std::min(cell, 8);
  cv::Mat intermediate, full;
  cv::resize(coarse, intermediate, cv::Size(), cubicFactor, cubicFactor, cv::INTER_CUBIC);
  cv::resize(intermediate, full, cv::Size(coarse.cols * cell, coarse.rows * cell), 0, 0, cv::INTER_LINEAR);
  // Skip the first cell, where the interpolation is one-sided.
  return full(cv::Rect(cv::Point(cell, cell), size)).clone();
}

cv::Mat gridFor(cv::Size size, int cell, int type) {
  return cv::Mat(cv::Size(size.width / cell + 3, size.height / cell + 3), type);
}

// Greens, blues and greys only: nothing in the orange/red family of the object.
cv::Mat makeBackground(cv::Size size, cv::RNG &rng) {
  constexpr int kCoarseCell = 80, kMediumCell = 20;
  cv::Mat hsv = gridFor(size, kCoarseCell, CV_8UC3);
  for (int y = 0; y < hsv.rows; ++y) {
    for (int x = 0; x < hsv.cols; ++x) {
      const int family = rng.uniform(0, 3);  // 0 green, 1 blue, 2 grey
      const int hue = family == 0   ? rng.uniform(35, 80)
                      : family == 1 ? rng.uniform(90, 120)
                                    : rng.uniform(0, 180);
      const int sat = family == 2 ? rng.uniform(0, 25) : rng.uniform(50, 150);
      hsv.at<cv::Vec3b>(y, x) = cv::Vec3b(hue, sat, rng.uniform(80, 190));
    }
  }
  cv::Mat coarseBgr;
  cv::cvtColor(hsv, coarseBgr, cv::COLOR_HSV2BGR);
  // Everything stays in bytes: fresh frame-sized buffers are costly to touch, and float ones are 4x larger.
  cv::Mat background = smoothEnlarge(coarseBgr, kCoarseCell, size);

  // Medium-scale light/dark mottling (same on all channels, so it keeps the hue) plus fine grain, both
  // stored offset by 128 and removed again in the weighted sums.
  constexpr int kMottling = 25;
  cv::Mat mottlingGrid = gridFor(size, kMediumCell, CV_8UC1);
  rng.fill(mottlingGrid, cv::RNG::UNIFORM, 128 - kMottling, 128 + kMottling + 1);
  const cv::Mat mottling = smoothEnlarge(mottlingGrid, kMediumCell, size);
  cv::Mat mottling3;
  cv::merge(std::array<cv::Mat, 3>{mottling, mottling, mottling}.data(), 3, mottling3);
  cv::addWeighted(background, 1.0, mottling3, 1.0, -128, background);
  cv::Mat grain(size, CV_8UC3);
  rng.fill(grain, cv::RNG::UNIFORM, 0, 2 * kBackgroundGrain);
  cv::addWeighted(background, 1.0, grain, 1.0, -(kBackgroundGrain - 0.5), background);
  return background;
}

// Orange/red object: diagonal stripes in two tones plus blobs in two more, all in one hue family, so the
// colour histogram is distinctive and the texture has many clear internal edges.
const cv::Scalar darkRed(25, 35, 150), lightOrange(45, 140, 235), deepRed(20, 20, 110),
    paleOrange(80, 175, 245);

void makeObject(cv::Size size, cv::RNG &rng, cv::Mat &texture, cv::Mat &mask) {
  texture.create(size, CV_8UC3);
  const double period = std::max(8.0, std::min(size.width, size.height) / 5.0);
  const double angle = rng.uniform(0.0, kPi);
  const double cosA = std::cos(angle), sinA = std::sin(angle);
  for (int y = 0; y < size.height; ++y) {
    auto *row = texture.ptr<cv::Vec3b>(y);
    for (int x = 0; x < size.width; ++x) {
      const double along = x * cosA + y * sinA;
      const bool dark = std::fmod(along / period + 100.0, 1.0) < 0.5;
      const cv::Scalar &c = dark ? darkRed : lightOrange;
      row[x] = cv::Vec3b(static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2]));
    }
  }
  const int minSide = std::min(size.width, size.height);
  const int blobs = 5;
  for (int i = 0; i < blobs; ++i) {
    const cv::Point centre(rng.uniform(minSide / 6, size.width - minSide / 6),
                           rng.uniform(minSide / 6, size.height - minSide / 6));
    const cv::Size axes(rng.uniform(minSide / 14 + 1, minSide / 7 + 2),
                        rng.uniform(minSide / 14 + 1, minSide / 7 + 2));
    cv::ellipse(texture, centre, axes, rng.uniform(0.0, 180.0), 0, 360, i % 2 ? deepRed : paleOrange,
                cv::FILLED, cv::LINE_AA);
  }

  // An ellipse inscribed in the box; drawn with 4 fractional bits so it is centred on the pixel grid exactly.
  constexpr int kShift = 4, kOne = 1 << kShift;
  mask = cv::Mat::zeros(size, CV_8UC1);
  const cv::Point centre((size.width - 1) * kOne / 2, (size.height - 1) * kOne / 2);
  const cv::Size axes(size.width * kOne / 2, size.height * kOne / 2);
  cv::ellipse(mask, centre, axes, 0, 0, 360, cv::Scalar(255), cv::FILLED, cv::LINE_8, kShift);
}

// The motion script: everything about the object that depends on the frame index, but not on pixels.
struct Pose {
  bool visible = true;
  cv::Point2d centre;
  double scale = 1.0;
  double angleDeg = 0;
  double brightness = 1.0;
};

// Where the object may go and where the decoy sits; derived from the configuration only.
struct Layout {
  cv::Point2d pathCentre;  // centre of the Lissajous figure
  cv::Point2d amplitude;   // its half extent in x and y
  cv::Rect2d centreRange;  // allowed object centres (keeps the object inside and clear of the decoy)
  cv::Rect2d decoyBox;     // empty when there is no decoy
};

Layout makeLayout(const SceneConfig &cfg) {
  Layout layout;
  const double frameW = cfg.frameSize.width, frameH = cfg.frameSize.height;
  const double decoySide = std::max(cfg.objectSize.width, cfg.objectSize.height);
  double usableW = frameW, usableH = frameH;
  if (cfg.decoy) {
    // The decoy takes the far corner of a strip along the longer side; the object never enters that strip.
    layout.decoyBox =
        cv::Rect2d(frameW - kEdgeGap - decoySide, frameH - kEdgeGap - decoySide, decoySide, decoySide);
    if (frameW >= frameH)
      usableW -= decoySide + 2 * kEdgeGap;
    else
      usableH -= decoySide + 2 * kEdgeGap;
  }
  // A rotated ellipse never reaches further from its centre than its larger semi-axis.
  const double reach = decoySide / 2 * std::max(cfg.scaleMax, cfg.scaleMin) + kEdgeGap;
  double x0 = reach, x1 = usableW - reach, y0 = reach, y1 = usableH - reach;
  // Too small a frame to keep the object inside: pin it to the middle of the usable area.
  if (x1 < x0) x0 = x1 = usableW / 2;
  if (y1 < y0) y0 = y1 = usableH / 2;
  layout.centreRange = cv::Rect2d(x0, y0, x1 - x0, y1 - y0);
  layout.pathCentre = cv::Point2d((x0 + x1) / 2, (y0 + y1) / 2);
  // speed 1 sweeps 60% of the room; larger speeds are capped at the room available.
  constexpr double kBaseAmplitude = 0.6;
  layout.amplitude = cv::Point2d(std::min(1.0, kBaseAmplitude * cfg.speed) * (x1 - x0) / 2,
                                 std::min(1.0, kBaseAmplitude * cfg.speed) * (y1 - y0) / 2);
  return layout;
}

double phaseOf(const SceneConfig &cfg, double index) {
  const int frames = std::max(1, cfg.frames);
  return 2 * kPi * index / frames;
}

// Figure-of-eight offset from the path centre at frame `index`.
cv::Point2d lissajous(const SceneConfig &cfg, const Layout &layout, double index) {
  const double phase = phaseOf(cfg, index);
  return cv::Point2d(layout.amplitude.x * std::sin(phase), layout.amplitude.y * std::sin(2 * phase));
}

bool hasLeft(const SceneConfig &cfg) {
  return cfg.leaveFrom >= 0;
}
bool hasReturned(const SceneConfig &cfg, int index) {
  return hasLeft(cfg) && cfg.leaveTo > cfg.leaveFrom && index >= cfg.leaveTo;
}

// After its absence the object follows a displaced copy of the path: a different path centre, a time shift
// and/or a point reflection, picked to make it come back as far as possible from where it left.
struct ReturnPath {
  cv::Point2d centre;
  double timeShift = 0;
  double mirror = 1;
};

ReturnPath chooseReturnPath(const SceneConfig &cfg, const Layout &layout) {
  const int lastSeen = std::max(0, cfg.leaveFrom - 1);
  const cv::Point2d leftAt = layout.pathCentre + lissajous(cfg, layout, lastSeen);
  const cv::Rect2d &r = layout.centreRange;
  const double cx0 = r.x + layout.amplitude.x, cx1 = r.x + r.width - layout.amplitude.x;
  const double cy0 = r.y + layout.amplitude.y, cy1 = r.y + r.height - layout.amplitude.y;
  const std::array<cv::Point2d, 5> centres = {layout.pathCentre, cv::Point2d(cx0, cy0), cv::Point2d(cx1, cy0),
                                              cv::Point2d(cx0, cy1), cv::Point2d(cx1, cy1)};
  const int frames = std::max(1, cfg.frames);
  ReturnPath best;
  double bestDistance = -1;
  for (const cv::Point2d &centre : centres) {
    for (int eighth = 0; eighth < 8; ++eighth) {
      for (double mirror : {1.0, -1.0}) {
        const double shift = frames * eighth / 8.0;
        const cv::Point2d back = centre + mirror * lissajous(cfg, layout, cfg.leaveTo + shift);
        const double distance = cv::norm(back - leftAt);
        if (distance > bestDistance + 1e-9) {
          bestDistance = distance;
          best = ReturnPath{centre, shift, mirror};
        }
      }
    }
  }
  return best;
}

Pose poseAt(const SceneConfig &cfg, const Layout &layout, int index) {
  Pose pose;
  const double phase = phaseOf(cfg, index);
  pose.visible = !(hasLeft(cfg) && index >= cfg.leaveFrom && !hasReturned(cfg, index));
  if (cfg.circleSpeed > 0) {
    const cv::Rect2d &room = layout.centreRange;
    const double radius = 0.8 * std::min(room.width, room.height) / 2;
    const double angle = radius > 0 ? cfg.circleSpeed * index / radius : 0;
    pose.centre = layout.pathCentre + radius * cv::Point2d(std::cos(angle), std::sin(angle));
  } else if (hasReturned(cfg, index)) {
    const ReturnPath path = chooseReturnPath(cfg, layout);
    pose.centre = path.centre + path.mirror * lissajous(cfg, layout, index + path.timeShift);
  } else {
    pose.centre = layout.pathCentre + lissajous(cfg, layout, index);
  }

  // Scale: a sine between scaleMin and scaleMax, phased so frame 0 is at scale 1 whenever 1 is in range.
  const double lo = std::min(cfg.scaleMin, cfg.scaleMax), hi = std::max(cfg.scaleMin, cfg.scaleMax);
  const double mid = (lo + hi) / 2, half = (hi - lo) / 2;
  const double startOffset =
      half > 0 ? std::asin(std::clamp((std::clamp(1.0, lo, hi) - mid) / half, -1.0, 1.0)) : 0;
  pose.scale = mid + half * std::sin(phase + startOffset);
  pose.angleDeg = cfg.rotationDegrees * (1 - std::cos(phase)) / 2;  // 0 -> rotationDegrees -> 0
  pose.brightness = 1 + cfg.brightness * std::sin(2 * phase);
  return pose;
}

// The object warped into the frame: the pixels it covers (ROI) with its texture and binary mask.
struct Placement {
  cv::Rect roi;
  cv::Mat texture, mask;
  cv::Rect2d box;
};

Placement placeObject(const cv::Mat &texture, const cv::Mat &mask, const Pose &pose, cv::Size frameSize) {
  Placement out;
  const cv::Point2f templateCentre((texture.cols - 1) / 2.0f, (texture.rows - 1) / 2.0f);
  cv::Mat affine = cv::getRotationMatrix2D(templateCentre, pose.angleDeg, pose.scale);
  affine.at<double>(0, 2) += pose.centre.x - templateCentre.x;
  affine.at<double>(1, 2) += pose.centre.y - templateCentre.y;

  // Only the pixels the warped template can reach are computed.
  std::vector<cv::Point2f> corners = {{-0.5f, -0.5f},
                                      {texture.cols - 0.5f, -0.5f},
                                      {-0.5f, texture.rows - 0.5f},
                                      {texture.cols - 0.5f, texture.rows - 0.5f}};
  cv::transform(corners, corners, affine);
  const cv::Rect reach = cv::boundingRect(corners) + cv::Size(2, 2) - cv::Point(1, 1);
  out.roi = reach & cv::Rect(cv::Point(0, 0), frameSize);
  if (out.roi.empty()) return out;

  affine.at<double>(0, 2) -= out.roi.x;
  affine.at<double>(1, 2) -= out.roi.y;
  cv::warpAffine(texture, out.texture, affine, out.roi.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  cv::Mat softMask;
  cv::warpAffine(mask, softMask, affine, out.roi.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                 cv::Scalar(0));
  cv::threshold(softMask, out.mask, 127, 255, cv::THRESH_BINARY);
  const cv::Rect pixels = cv::boundingRect(out.mask);
  if (!pixels.empty()) out.box = cv::Rect2d(pixels + out.roi.tl());
  return out;
}

bool boardShown(const SceneConfig &cfg, int index) {
  return cfg.occludeFrom >= 0 && index >= cfg.occludeFrom && index < cfg.occludeTo;
}

// The board covers the object's boxes over the whole occlusion, with a margin, so it hides the object all
// the time it is shown.
cv::Rect boardRect(const SceneConfig &cfg, const Layout &layout, const cv::Mat &texture,
                   const cv::Mat &mask) {
  constexpr int kBoardMargin = 8;
  cv::Rect2d covered;
  for (int i = cfg.occludeFrom; i < cfg.occludeTo; ++i) {
    const cv::Rect2d box = placeObject(texture, mask, poseAt(cfg, layout, i), cfg.frameSize).box;
    covered = covered.empty() ? box : (covered | box);
  }
  const cv::Rect r = cv::Rect(covered) + cv::Size(2 * kBoardMargin + 1, 2 * kBoardMargin + 1) -
                     cv::Point(kBoardMargin, kBoardMargin);
  return r & cv::Rect(cv::Point(), cfg.frameSize);
}

// Vertical bands of the object's four colours, each as wide as the object: its colours, none of its texture.
cv::Mat boardPixels(cv::Size size, int band) {
  const cv::Scalar colours[] = {darkRed, lightOrange, deepRed, paleOrange};
  cv::Mat board(size, CV_8UC3);
  for (int x = 0, i = 0; x < size.width; x += band, ++i)
    board(cv::Rect(x, 0, std::min(band, size.width - x), size.height)).setTo(colours[i % 4]);
  return board;
}

// The decoy: the object's own colours rearranged in concentric rings (sorted by brightness, darkest in the
// middle). Its colour histogram is the object's, so colour alone matches it as well as the object, but its
// few ring borders make little edge structure, unlike the object's stripes and blobs.
void makeDecoy(const cv::Mat &objectBgr, const cv::Mat &objectMask, int side, cv::Mat &decoy, cv::Mat &mask) {
  std::vector<std::pair<int, cv::Vec3b>> colours;
  for (int y = 0; y < objectBgr.rows; ++y)
    for (int x = 0; x < objectBgr.cols; ++x)
      if (objectMask.at<uchar>(y, x)) {
        const cv::Vec3b p = objectBgr.at<cv::Vec3b>(y, x);
        colours.emplace_back(p[0] + 6 * p[1] + 3 * p[2], p);
      }
  std::sort(colours.begin(), colours.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
  std::vector<std::pair<double, cv::Point>> disc;
  const double radius = side / 2.0, centre = (side - 1) / 2.0;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const double r = std::hypot(x - centre, y - centre);
      if (r <= radius) disc.emplace_back(r, cv::Point(x, y));
    }
  std::sort(disc.begin(), disc.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
  decoy = cv::Mat(side, side, CV_8UC3, cv::Scalar(0, 0, 0));
  mask = cv::Mat(side, side, CV_8UC1, cv::Scalar(0));
  for (size_t i = 0; i < disc.size() && !colours.empty(); ++i) {
    decoy.at<cv::Vec3b>(disc[i].second) = colours[i * colours.size() / disc.size()].second;
    mask.at<uchar>(disc[i].second) = 255;
  }
  // Soften the ring borders into gradients so the decoy has no internal edges at all ("untextured").
  const double sigma = std::max(1.0, side / 10.0);
  cv::Mat blurred;
  cv::GaussianBlur(decoy, blurred, cv::Size(), sigma);
  cv::Mat weight;
  cv::GaussianBlur(mask, weight, cv::Size(), sigma);  // renormalise so the black outside does not bleed in
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int w = weight.at<uchar>(y, x);
      if (!mask.at<uchar>(y, x) || w == 0) continue;
      const cv::Vec3b b = blurred.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c) decoy.at<cv::Vec3b>(y, x)[c] = cv::saturate_cast<uchar>(b[c] * 255.0 / w);
    }
}

}  // namespace

Scene::Scene(const SceneConfig &config) : config_(config) {
  config_.frameSize.width = std::max(1, config_.frameSize.width);
  config_.frameSize.height = std::max(1, config_.frameSize.height);
  config_.objectSize.width = std::max(4, config_.objectSize.width);
  config_.objectSize.height = std::max(4, config_.objectSize.height);

  cv::RNG backgroundRng(config_.seed * 2654435761u + 1);
  const cv::Point &v = config_.backgroundVelocity;
  const int pass = std::max(1, config_.frames);
  background_ =
      makeBackground(config_.frameSize + cv::Size(std::abs(v.x) * pass, std::abs(v.y) * pass), backgroundRng);
  cv::RNG objectRng(config_.seed * 2246822519u + 7);
  makeObject(config_.objectSize, objectRng, objectTexture_, objectMask_);
  const int decoySide = std::max(config_.objectSize.width, config_.objectSize.height);
  makeDecoy(objectTexture_, objectMask_, decoySide, decoyTexture_, decoyMask_);
}

SceneFrame Scene::render(int index) const {
  const Layout layout = makeLayout(config_);
  const Pose pose = poseAt(config_, layout, index);
  const cv::Rect frameRect(cv::Point(0, 0), config_.frameSize);

  // The part of the background in view: it moves by backgroundVelocity a frame.
  const cv::Point &v = config_.backgroundVelocity;
  const int pass = std::max(1, config_.frames), step = index % pass;
  const cv::Point viewOrigin((v.x > 0 ? v.x * pass : 0) - v.x * step,
                             (v.y > 0 ? v.y * pass : 0) - v.y * step);
  const cv::Mat background = background_(cv::Rect(viewOrigin, config_.frameSize));

  SceneFrame frame;
  frame.objectScale = pose.scale;
  frame.decoyBox = layout.decoyBox;

  Placement placed;
  if (pose.visible) placed = placeObject(objectTexture_, objectMask_, pose, config_.frameSize);
  if (boardShown(config_, index)) frame.boardBox = boardRect(config_, layout, objectTexture_, objectMask_);
  frame.objectVisible = !placed.box.empty() && frame.boardBox.empty();
  if (frame.objectVisible) frame.box = placed.box;

  // Only the output frame is allocated at full size (touching fresh frame-sized buffers dominates the cost
  // at 1080p): the noise is drawn straight into it, the decoy and the object are composed on small copies of
  // the background, and the lighting is applied to both with out = pixels * brightness + noise.
  cv::RNG noiseRng(config_.seed * 2654435761u ^ (static_cast<std::uint32_t>(index) * 40503u + 12345u));
  frame.bgr.create(config_.frameSize, CV_8UC3);
  noiseRng.fill(frame.bgr, cv::RNG::UNIFORM, 0, 2 * kFrameNoise);
  const double noiseOffset = -(kFrameNoise - 0.5);  // centres the noise on zero

  const cv::Rect decoyRect =
      config_.decoy ? (cv::Rect(layout.decoyBox) + cv::Size(2, 2) - cv::Point(1, 1)) & frameRect : cv::Rect();
  const cv::Rect objectRect = frame.objectVisible ? placed.roi : cv::Rect();
  std::vector<cv::Rect> patches;
  if (!decoyRect.empty() && !objectRect.empty() && (decoyRect & objectRect).area() > 0) {
    patches.push_back(decoyRect | objectRect);  // only in frames too small to keep them apart
  } else {
    if (!decoyRect.empty()) patches.push_back(decoyRect);
    if (!objectRect.empty()) patches.push_back(objectRect);
  }

  std::vector<cv::Mat> composed;
  for (const cv::Rect &patchRect : patches) {
    cv::Mat patch = background(patchRect).clone();
    if (config_.decoy && (patchRect & decoyRect) == decoyRect) {
      const cv::Rect at = cv::Rect(layout.decoyBox) - patchRect.tl();
      decoyTexture_.copyTo(patch(at), decoyMask_);
    }
    if (frame.objectVisible && (patchRect & objectRect) == objectRect)
      placed.texture.copyTo(patch(objectRect - patchRect.tl()), placed.mask);
    cv::Mat lit;
    cv::addWeighted(patch, pose.brightness, frame.bgr(patchRect), 1.0, noiseOffset, lit);
    composed.push_back(lit);
  }
  cv::Mat board;
  if (!frame.boardBox.empty())
    cv::addWeighted(boardPixels(frame.boardBox.size(), config_.objectSize.width), pose.brightness,
                    frame.bgr(frame.boardBox), 1.0, noiseOffset, board);
  cv::addWeighted(background, pose.brightness, frame.bgr, 1.0, noiseOffset, frame.bgr);
  for (size_t i = 0; i < patches.size(); ++i) composed[i].copyTo(frame.bgr(patches[i]));
  if (!board.empty()) board.copyTo(frame.bgr(frame.boardBox));
  return frame;
}

void Scene::objectTemplate(cv::Mat &bgr, cv::Mat &mask) const {
  bgr = cv::Mat::zeros(objectTexture_.size(), CV_8UC3);
  objectTexture_.copyTo(bgr, objectMask_);
  mask = objectMask_.clone();
}

cv::Rect Scene::initBox() const {
  const Layout layout = makeLayout(config_);
  const Placement placed =
      placeObject(objectTexture_, objectMask_, poseAt(config_, layout, 0), config_.frameSize);
  const cv::Rect2d &b = placed.box;
  return cv::Rect(cvRound(b.x), cvRound(b.y), cvRound(b.width), cvRound(b.height));
}

double iou(const cv::Rect2d &a, const cv::Rect2d &b) {
  if (a.empty() || b.empty()) return 0;
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0;
}

double centreError(const cv::Rect2d &a, const cv::Rect2d &b) {
  const cv::Point2d ca(a.x + a.width / 2, a.y + a.height / 2), cb(b.x + b.width / 2, b.y + b.height / 2);
  return cv::norm(ca - cb);
}

}  // namespace colortrack::scene
