// SPDX-License-Identifier: LGPL-2.1-or-later
#include "injection.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace colortrack::eval {

namespace {

// The cover reaches this far past each side of the true box, so no edge of the target shows round it.
constexpr double kCoverMargin = 0.15;
// The copy passes beside the target this many heights from its centre.
constexpr double kBesideOffset = 1.2;

cv::Point2d centreOf(const cv::Rect2d &box) {
  return {box.x + box.width / 2, box.y + box.height / 2};
}

cv::Rect wholeRect(const cv::Rect2d &box) {
  const int x0 = static_cast<int>(std::floor(box.x)), y0 = static_cast<int>(std::floor(box.y));
  const int x1 = static_cast<int>(std::ceil(box.x + box.width));
  const int y1 = static_cast<int>(std::ceil(box.y + box.height));
  return {cv::Point(x0, y0), cv::Point(x1, y1)};
}

bool inView(const GroundTruthBox &box, cv::Size frame) {
  if (!box) return false;
  const cv::Rect2d inside = *box & cv::Rect2d(0, 0, frame.width, frame.height);
  return inside.area() >= 0.5 * box->area();
}

// Whether frames [first - 1, first + length) all have the target annotated and at least half in view, and
// `fits` holds on each (a cover has somewhere to take its background from).
bool placeFits(const Sequence &s, int first, int length, const std::function<bool(int)> &fits) {
  const int frames = static_cast<int>(s.groundTruth.size());
  if (first < 1 || first + length + kFramesAfter > frames) return false;
  for (int i = first - 1; i < first + length; ++i)
    if (!inView(s.groundTruth[i], s.frameSize) || !fits(i)) return false;
  return true;
}

// The first place from `start` on (in steps of 5 frames, up to two thirds of the sequence) that fits.
std::optional<int> findPlace(
    const Sequence &s, int start, int length,
    const std::function<bool(int)> &fits = [](int) { return true; }) {
  const int frames = static_cast<int>(s.groundTruth.size());
  for (int first = start; first <= frames * 2 / 3; first += 5)
    if (placeFits(s, first, length, fits)) return first;
  return std::nullopt;
}

void pasteClipped(const cv::Mat &patch, cv::Mat &image, cv::Point at) {
  const cv::Rect target = cv::Rect(at, patch.size()) & cv::Rect(cv::Point(), image.size());
  if (target.empty()) return;
  patch(cv::Rect(target.tl() - at, target.size())).copyTo(image(target));
}

}  // namespace

std::vector<Injection> planInjections(const std::vector<Sequence> &sequences, std::size_t index) {
  const Sequence &s = sequences.at(index);
  const int frames = static_cast<int>(s.groundTruth.size());
  std::vector<Injection> plan;
  if (sequences.size() > 1)
    for (int start : {frames / 4, frames / 2})
      if (std::optional<int> at = findPlace(s, start, kCutFrames)) {
        Injection cut{InjectionKind::Cut, "cut@" + std::to_string(*at + 1), *at, kCutFrames};
        cut.otherSequence = (index + sequences.size() / 2) % sequences.size();
        if (plan.empty() || plan.back().first != *at) plan.push_back(cut);
      }
  for (int length : kCoverLengths) {
    const auto coverFits = [&](int i) {
      return InjectedRun::coverPlaces(*s.groundTruth[i], s.frameSize).has_value();
    };
    if (std::optional<int> at = findPlace(s, frames / 3, length, coverFits))
      plan.push_back({InjectionKind::Cover, format("cover%d@%d", length, *at + 1), *at, length});
  }
  for (const auto &[length, beside] : {std::pair{kCopySlowFrames, false}, std::pair{kCopyFastFrames, false},
                                       std::pair{kCopySlowFrames, true}})
    if (std::optional<int> at = findPlace(s, frames / 2, length)) {
      Injection copy{InjectionKind::Copy,
                     format("copy-%s%d@%d", beside ? "beside" : "front", length, *at + 1), *at, length};
      copy.beside = beside;
      plan.push_back(copy);
    }
  return plan;
}

std::vector<FrameTruth> plainTruth(const Sequence &sequence) {
  std::vector<FrameTruth> truth(sequence.groundTruth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) truth[i].target = sequence.groundTruth[i];
  return truth;
}

InjectedRun::InjectedRun(const std::vector<Sequence> &sequences, std::size_t index, Injection injection)
    : sequences_(sequences), index_(index), injection_(std::move(injection)) {}

std::optional<std::pair<cv::Rect, cv::Rect>> InjectedRun::coverPlaces(const cv::Rect2d &target,
                                                                      cv::Size frame) {
  const cv::Rect2d grown(target.x - kCoverMargin * target.width, target.y - kCoverMargin * target.height,
                         target.width * (1 + 2 * kCoverMargin), target.height * (1 + 2 * kCoverMargin));
  const cv::Rect whole(cv::Point(), frame);
  const cv::Rect cover = wholeRect(grown) & whole;
  if (cover.empty()) return std::nullopt;
  // Background from right beside the cover, in the first direction that stays inside the frame.
  const int dx = cover.width + 2, dy = cover.height + 2;
  for (const cv::Point shift : {cv::Point(dx, 0), cv::Point(-dx, 0), cv::Point(0, dy), cv::Point(0, -dy),
                                cv::Point(2 * dx, 0), cv::Point(-2 * dx, 0)}) {
    const cv::Rect source = cover + shift;
    if ((source & whole) == source) return std::make_pair(cover, source);
  }
  return std::nullopt;
}

cv::Rect2d InjectedRun::copyBox(int i, const cv::Rect2d &target, cv::Size copySize) const {
  const double t = injection_.length > 1 ? double(i - injection_.first) / (injection_.length - 1) : 0.5;
  const double dx = (2 * t - 1) * kCopyReach * target.width;
  double dy = 0;
  if (injection_.beside) {
    // Below the target when there is room at the crossing's start, else above it.
    const cv::Rect2d &start = *sequences_[index_].groundTruth[injection_.first - 1];
    const bool below = start.y + start.height * (1 + kBesideOffset) < sequences_[index_].frameSize.height;
    dy = (below ? 1 : -1) * kBesideOffset * target.height;
  }
  const cv::Point2d centre = centreOf(target) + cv::Point2d(dx, dy);
  return {centre.x - copySize.width / 2.0, centre.y - copySize.height / 2.0, double(copySize.width),
          double(copySize.height)};
}

cv::Mat InjectedRun::frame(int i, const FrameReader &read) {
  const Sequence &s = sequences_[index_];
  if (!injection_.covers(i)) return read(index_, i);
  switch (injection_.kind) {
    case InjectionKind::Cut: {
      const Sequence &other = sequences_[injection_.otherSequence];
      const int count = static_cast<int>(other.groundTruth.size());
      cv::Mat shown;
      cv::resize(read(injection_.otherSequence, (i - injection_.first) % std::max(count, 1)), shown,
                 s.frameSize, 0, 0, cv::INTER_AREA);
      return shown;
    }
    case InjectionKind::Cover: {
      cv::Mat image = read(index_, i).clone();
      if (const auto places = coverPlaces(*s.groundTruth[i], image.size()))
        image(places->second).clone().copyTo(image(places->first));
      return image;
    }
    case InjectionKind::Copy: {
      if (copy_.empty()) copy_ = read(index_, injection_.first - 1)(copySource()).clone();
      cv::Mat image = read(index_, i).clone();
      const cv::Rect2d box = copyBox(i, *s.groundTruth[i], copy_.size());
      pasteClipped(copy_, image,
                   cv::Point(static_cast<int>(std::lround(box.x)), static_cast<int>(std::lround(box.y))));
      return image;
    }
  }
  return read(index_, i);
}

std::vector<FrameTruth> InjectedRun::truth() const {
  const Sequence &s = sequences_[index_];
  std::vector<FrameTruth> truth = plainTruth(s);
  for (int i = injection_.first; i <= injection_.last(); ++i) {
    FrameTruth &t = truth[i];
    switch (injection_.kind) {
      case InjectionKind::Cut:
      case InjectionKind::Cover:
        t.target.reset();
        t.absent = true;
        t.grace = injection_.kind == InjectionKind::Cut && i - injection_.first < kCutGrace;
        break;
      case InjectionKind::Copy: {
        const cv::Size size = copySource().size();
        const cv::Rect2d box = copyBox(i, *s.groundTruth[i], size);
        // The box as pasted: whole pixels, inside the frame.
        const cv::Rect pasted =
            cv::Rect(cv::Point(static_cast<int>(std::lround(box.x)), static_cast<int>(std::lround(box.y))),
                     size) &
            cv::Rect(cv::Point(), s.frameSize);
        if (!pasted.empty()) t.copy = cv::Rect2d(pasted);
        break;
      }
    }
  }
  return truth;
}

cv::Rect InjectedRun::copySource() const {
  const Sequence &s = sequences_[index_];
  return wholeRect(*s.groundTruth[injection_.first - 1]) & cv::Rect(cv::Point(), s.frameSize);
}

cv::Mat readSequenceFrame(const std::vector<Sequence> &sequences, std::size_t sequence, int index) {
  const auto path = framePath(sequences.at(sequence), index);
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty()) throw std::runtime_error("cannot decode " + path.string());
  return image;
}

}  // namespace colortrack::eval
