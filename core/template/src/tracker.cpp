// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/tracker.hpp"

#include <algorithm>
#include <string>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "colortrack/detection_method.hpp"
#include "colortrack/kalman_track.hpp"
#include "colortrack/regular_file.hpp"
#include "colortrack/scene_cut.hpp"
#include "colortrack/template_model.hpp"

namespace colortrack {

// What the methods share, and the method for the current settings (created through the registry).
struct Tracker::Impl {
  explicit Impl(const TrackerSettings &settings) : context{settings, model, track} {}

  TemplateModel model;
  KalmanTrack track;
  MethodContext context;
  std::unique_ptr<DetectionMethod> method;
  SceneCut sceneCut;
};

Tracker::Tracker(const TrackerSettings &settings)
    : settings_(settings), impl_(std::make_unique<Impl>(settings_)) {
  impl_->track.kalman.setParams(settings_.kalman);
  impl_->model.rebuild(settings_);
  impl_->method = createDetectionMethod(settings_.method, impl_->context);
}

Tracker::~Tracker() = default;

void Tracker::setSettings(const TrackerSettings &settings) {
  const bool modelChanged = settings.colorSpace != settings_.colorSpace || !(settings.bins == settings_.bins);
  const bool methodChanged = settings.method != settings_.method;
  settings_ = settings;
  impl_->track.kalman.setParams(settings_.kalman);
  if (modelChanged) impl_->model.rebuild(settings_);
  // A method's filters were learnt with the old colour model; a new method starts from nothing (and what
  // the old one learnt would have gone stale while the new one tracks).
  if (methodChanged)
    impl_->method = createDetectionMethod(settings_.method, impl_->context);
  else if (modelChanged)
    impl_->method->forget();
}

Status checkTemplateSize(cv::Size size) {
  if (size.width >= kMinTemplateSide && size.height >= kMinTemplateSide) return {};
  return Status::failure("the template is " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                         " pixels; it must be at least " + std::to_string(kMinTemplateSide) + "x" +
                         std::to_string(kMinTemplateSide));
}

void Tracker::setTemplate(const cv::Mat &bgr, const cv::Mat &mask) {
  if (bgr.empty() || bgr.type() != CV_8UC3)
    throw TrackerError("the template must be a non-empty 8-bit colour image");
  if (const Status size = checkTemplateSize(bgr.size()); !size) throw TrackerError(size.message());
  if (!mask.empty() && (mask.size() != bgr.size() || mask.type() != CV_8UC1))
    throw TrackerError("the template mask must be 8-bit, one channel, the template's size");
  if (!mask.empty() && cv::countNonZero(mask) == 0) throw TrackerError("the template mask selects no pixel");
  impl_->model.setTemplate(bgr, mask, settings_);
  impl_->method->forget();
  impl_->track.newTemplate(bgr.size());
  reset();
}

void Tracker::setTemplateFromBox(const ImageSource &frame, const cv::Rect &box) {
  const cv::Rect frameRect(cv::Point(), frame.size());
  if (box.width <= 0 || box.height <= 0)
    throw TrackerError("the box " + std::to_string(box.width) + "x" + std::to_string(box.height) +
                       " is empty");
  if ((box & frameRect) != box)
    throw TrackerError("the box " + std::to_string(box.x) + "," + std::to_string(box.y) + "," +
                       std::to_string(box.width) + "," + std::to_string(box.height) +
                       " does not lie inside the " + std::to_string(frameRect.width) + "x" +
                       std::to_string(frameRect.height) + " frame");
  cv::Mat bgr;
  frame.bgr(box, bgr);
  setTemplate(bgr);
  impl_->track.start(box, settings_.kalman);
  impl_->method->start(frame, box);
  // The first process() call predicts one frame ahead; start from zero motion at the box.
}

bool Tracker::hasTemplate() const {
  return impl_->model.hasTemplate();
}

cv::Size Tracker::templateSize() const {
  return impl_->model.templateSize();
}

void Tracker::reset() {
  impl_->track.reset(settings_.kalman);
}

TrackOutput Tracker::process(const ImageSource &frame, double dt) {
  TrackOutput out;
  if (!impl_->model.hasTemplate()) return out;
  const cv::Size frameSize = frame.size();
  const cv::Size templateSize = impl_->model.templateSize();
  if (templateSize.width > frameSize.width || templateSize.height > frameSize.height)
    throw TrackerError("the template (" + std::to_string(templateSize.width) + "x" +
                       std::to_string(templateSize.height) + ") is larger than the frame (" +
                       std::to_string(frameSize.width) + "x" + std::to_string(frameSize.height) + ")");
  KalmanTrack &track = impl_->track;
  // A lost track is reported for one frame; the frame after it searches again.
  if (track.state == TrackState::Lost) track.state = TrackState::Searching;
  // The frame of a cut is not searched either: what is found on the other scene is found on the next frames,
  // and the method may hold it to a higher bar (DetectionMethod::sceneCut).
  if (impl_->sceneCut.observe(frame)) {
    if (track.active()) track.state = TrackState::Lost;
    impl_->method->sceneCut();
    track.report(out);
    return out;
  }
  impl_->method->process(frame, dt, out);
  track.report(out);
  return out;
}

FrameReport Tracker::track(const ImageSource &frame, double dt) {
  const TrackOutput out = process(frame, dt);
  FrameReport report;
  TrackReport &r = report.primary;
  r.id = out.id;
  r.state = out.state;
  if (out.hasBox) {
    r.box = out.box;
    r.centre = cv::Point2d(out.box.x + out.box.width / 2, out.box.y + out.box.height / 2);
  }
  r.score = out.score;
  r.verified = out.verified;
  r.scale = out.scale;
  r.vx = out.vx;
  r.vy = out.vy;
  if (out.hasBox) report.tracks.push_back(r);
  report.searchRegion = out.searchRegion;
  return report;
}

void startWorkerThreads() {
  cv::parallel_for_(cv::Range(0, std::max(1, cv::getNumThreads())), [](const cv::Range &) {});
}

// A template is a small picture of the object; a file larger than this is not one.
constexpr std::size_t kMaxTemplateFileBytes = 64u << 20;

void loadTemplate(const std::string &path, cv::Mat &bgr, cv::Mat &mask) {
  // Read here rather than by cv::imread, which would wait in open() for ever on a FIFO without a writer.
  const Result<std::vector<unsigned char>> read = readRegularFile(path, kMaxTemplateFileBytes);
  if (!read) throw TrackerError("cannot read the template image \"" + path + "\": " + read.error());
  const std::vector<unsigned char> &bytes = *read;
  cv::Mat image;
  try {
    if (!bytes.empty()) image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception &e) {
    throw TrackerError("cannot read the template image \"" + path + "\": " + e.what());
  }
  if (image.empty())
    throw TrackerError("cannot read the template image \"" + path + "\" (not a PNG or JPEG image)");
  if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 257);
  mask.release();
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
      break;
    case 3:
      bgr = image;
      break;
    case 4: {
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      cv::extractChannel(image, mask, 3);
      cv::threshold(mask, mask, 127, 255, cv::THRESH_BINARY);
      if (cv::countNonZero(mask) == 0)
        throw TrackerError("the template image \"" + path + "\" is fully transparent");
      break;
    }
    default:
      throw TrackerError("the template image \"" + path + "\" has an unsupported number of channels");
  }
}

}  // namespace colortrack
