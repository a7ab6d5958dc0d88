// SPDX-License-Identifier: LGPL-2.1-or-later
// Template mode: the template tracker, brought up to date with the properties and the requests before it
// tracks a frame; the template file read at start and again when template-location changes.
#include <exception>
#include <optional>

#include <gst/gst.h>

#include "colortrack/tracker.hpp"
#include "colortrack-mode.h"
#include "property-table.h"

namespace colortrack_gst {

namespace {

// Reads a template file; on failure fills `why` and says whether the file exists at all.
bool loadTemplateFile(const std::string &path, cv::Mat &bgr, cv::Mat &mask, std::string &why, bool &missing) {
  missing = !g_file_test(path.c_str(), G_FILE_TEST_EXISTS);
  // Said here, before OpenCV is asked: it would log its own "can't open/read file" warning first.
  if (missing) {
    why = "no such file";
    return false;
  }
  try {
    colortrack::loadTemplate(path, bgr, mask);
    return true;
  } catch (const std::exception &e) {
    why = e.what();
    return false;
  }
}

// Whether `image` can be the template of `frame`-sized video, or why not.
colortrack::Status checkTemplateFit(cv::Size image, cv::Size frame) {
  if (const colortrack::Status size = colortrack::checkTemplateSize(image); !size) return size;
  if (image.width <= frame.width && image.height <= frame.height) return {};
  return colortrack::Status::failure("the template is " + std::to_string(image.width) + "x" +
                                     std::to_string(image.height) + " pixels, larger than the " +
                                     std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                     " frame");
}

std::string fromFile(const std::string &location) {
  return "the image '" + location + "' (property 'template-location')";
}

class TemplateMode : public Mode {
 public:
  explicit TemplateMode(std::unique_ptr<ElementSink> sink) : sink_(std::move(sink)) {}

  bool start(const Snapshot &snapshot) override;
  bool prepare(const Snapshot &snapshot, const Requests &requests, const FrameView &view) override;
  Readiness readiness(cv::Size frame) override;
  colortrack::FrameTracker &tracker() override { return *tracker_; }
  bool listsTracks() const override { return false; }

 private:
  void targetChanged(const std::string &origin);
  void reloadTemplate(const std::string &location, cv::Size frame);
  void applyClick(const ClickRequest &click, int boxSize, const FrameView &view);

  std::unique_ptr<ElementSink> sink_;
  std::optional<colortrack::Tracker> tracker_;
  std::string templateOrigin_;    // "the image 'x.png' (...)" or "the box '1,2,3,4' (...)", for messages
  std::string templateLocation_;  // the template-location last loaded (what a refused one reads back as)
  bool warnedNoTemplate_ = false;
};

bool TemplateMode::start(const Snapshot &snapshot) {
  tracker_.emplace(snapshot.tracker);
  // (Threshold mode makes no TemplateMode: a template-location is not even read there.)
  if (snapshot.templateLocation.empty()) return true;
  const std::string shown = gstglue::validUtf8(snapshot.templateLocation);
  cv::Mat bgr, mask;
  std::string why;
  bool missing = false;
  if (!loadTemplateFile(snapshot.templateLocation, bgr, mask, why, missing)) {
    if (missing)
      sink_->error(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_NOT_FOUND,
                   "Template file '" + shown + "' (property 'template-location') does not exist.",
                   why.c_str());
    else
      sink_->error(
          GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_OPEN_READ,
          "Could not read the template image '" + shown + "' (property 'template-location'): " + why);
    return false;
  }
  if (const colortrack::Status size = colortrack::checkTemplateSize(bgr.size()); !size) {
    sink_->error(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_SETTINGS,
                 "Cannot use the template image '" + shown +
                     "' (property 'template-location'): " + size.message() + ".");
    return false;
  }
  tracker_->setTemplate(bgr, mask);
  templateOrigin_ = fromFile(snapshot.templateLocation);
  templateLocation_ = snapshot.templateLocation;
  return true;
}

bool TemplateMode::prepare(const Snapshot &snapshot, const Requests &requests, const FrameView &view) {
  if (snapshot.changed.has(Settings::Change::Tracker)) tracker_->setSettings(snapshot.tracker);
  if (snapshot.changed.has(Settings::Change::Template) && !snapshot.templateLocation.empty())
    reloadTemplate(snapshot.templateLocation, view.size());
  resetIfRequested(*sink_, *tracker_);
  if (requests.initBox) {
    const InitBoxFit fit = checkInitBox(*sink_, *requests.initBox, view.size(),
                                        requests.initBoxWhileStreaming, snapshot.initBox);
    if (fit == InitBoxFit::Error) return false;
    if (fit == InitBoxFit::Fits) {
      tracker_->setTemplateFromBox(view, *requests.initBox);
      targetChanged("the box '" + snapshot.initBox + "' (property 'init-box')");
    }
  }
  if (requests.click) applyClick(*requests.click, snapshot.clickBoxSize, view);
  return true;
}

Mode::Readiness TemplateMode::readiness(cv::Size frame) {
  if (!tracker_->hasTemplate()) {
    if (!warnedNoTemplate_) {
      warnedNoTemplate_ = true;
      sink_->warning(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_SETTINGS,
                     "No template: set 'template-location' or 'init-box', or click the object in the video "
                     "window. Passing video through.");
    }
    return Readiness::Waiting;
  }
  const cv::Size size = tracker_->templateSize();
  if (size.width <= frame.width && size.height <= frame.height) return Readiness::Ready;
  sink_->error(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_SETTINGS,
               "The template from " + gstglue::validUtf8(templateOrigin_) + " (" +
                   std::to_string(size.width) + "x" + std::to_string(size.height) + ") is larger than the " +
                   std::to_string(frame.width) + "x" + std::to_string(frame.height) + " frame.");
  return Readiness::Error;
}

void TemplateMode::targetChanged(const std::string &origin) {
  templateOrigin_ = origin;
  warnedNoTemplate_ = false;
  sink_->targetChanged();
}

// A template-location set while streaming: read now; a file that cannot be read, or an image that cannot be
// the template of this video, keeps the previous template and the previous value.
void TemplateMode::reloadTemplate(const std::string &location, cv::Size frame) {
  cv::Mat bgr, mask;
  std::string why;
  bool missing = false;
  if (loadTemplateFile(location, bgr, mask, why, missing)) {
    const colortrack::Status fit = checkTemplateFit(bgr.size(), frame);
    why = fit.message();
    if (fit) {
      try {
        tracker_->setTemplate(bgr, mask);
        templateLocation_ = location;
        targetChanged(fromFile(location));
        return;
      } catch (const std::exception &e) {
        why = e.what();
      }
    }
  }
  sink_->warning(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_OPEN_READ,
                 "Could not use the template image '" + gstglue::validUtf8(location) +
                     "' (property 'template-location'): " + gstglue::validUtf8(why) +
                     ". Keeping the previous template.",
                 missing ? "the file does not exist" : nullptr);
  sink_->restoreTemplateLocation(location, templateLocation_);
}

// A left click takes the template from the box around it and starts tracking there, exactly as init-box
// does; a right click stops until a new target is given.
void TemplateMode::applyClick(const ClickRequest &click, int boxSize, const FrameView &view) {
  if (click.kind == ClickRequest::Kind::Stop) return stopTracking(*sink_, *tracker_);
  const cv::Rect box = boxAround(click.point, boxSize, view.size());
  if (box.empty()) return ignoreClickOutside(*sink_, click, view.size());
  tracker_->setTemplateFromBox(view, box);
  targetChanged(describeClick(click, box));
  sink_->info("template from " + templateOrigin_);
}

}  // namespace

std::unique_ptr<Mode> makeTemplateMode(std::unique_ptr<ElementSink> sink) {
  return std::make_unique<TemplateMode>(std::move(sink));
}

}  // namespace colortrack_gst
