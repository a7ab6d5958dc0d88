// Template mode's preparation of a frame: the template tracker brought up to date with the properties and
// the requests before it tracks.
#include <exception>

#include <gst/gst.h>

#include "colortrack-modes.h"
#include "property-table.h"

#define GST_CAT_DEFAULT gst_color_track_debug

namespace colortrack_gst {

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

namespace {

// A new target: its trail starts over and the element leaves the idle state.
void targetChanged(State &state, const std::string &origin) {
  state.templateOrigin = origin;
  state.trails.clear();
  state.warnedNoTemplate = false;
  state.idle = false;
}

// Why `image` cannot be the template of `frame`-sized video, or empty.
std::string templateFitProblem(cv::Size image, cv::Size frame) {
  if (std::string problem = colortrack::templateSizeProblem(image); !problem.empty()) return problem;
  if (image.width <= frame.width && image.height <= frame.height) return "";
  return "the template is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
         " pixels, larger than the " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
         " frame";
}

// The property reads back as the template in use when the value set could not be used (unless it was set
// again meanwhile).
void restoreTemplateLocation(GstColorTrack *self, const std::string &refused, const std::string &inUse) {
  GST_OBJECT_LOCK(self);
  std::string &location = self->priv->store.settings.templateLocation;
  const bool unchanged = location == refused;
  if (unchanged) location = inUse;
  GST_OBJECT_UNLOCK(self);
  if (unchanged) g_object_notify(G_OBJECT(self), "template-location");
}

// A template-location set while streaming: read now; a file that cannot be read, or an image that cannot be
// the template of this video, keeps the previous template and the previous value.
void reloadTemplate(GstColorTrack *self, State &state, const std::string &location, cv::Size frame) {
  cv::Mat bgr, mask;
  std::string why;
  bool missing = false;
  if (loadTemplateFile(location, bgr, mask, why, missing)) {
    why = templateFitProblem(bgr.size(), frame);
    if (why.empty()) {
      try {
        state.templateTracker->setTemplate(bgr, mask);
        state.templateLocation = location;
        targetChanged(state, "the image '" + location + "' (property 'template-location')");
        return;
      } catch (const std::exception &e) {
        why = e.what();
      }
    }
  }
  GST_ELEMENT_WARNING(self, RESOURCE, OPEN_READ,
                      ("Could not use the template image '%s' (property 'template-location'): %s. "
                       "Keeping the previous template.",
                       gstglue::validUtf8(location).c_str(), gstglue::validUtf8(why).c_str()),
                      (missing ? "the file does not exist" : nullptr));
  restoreTemplateLocation(self, location, state.templateLocation);
}

// A left click takes the template from the box around it and starts tracking there, exactly as init-box
// does; a right click stops until a new target is given.
void applyClick(GstColorTrack *self, State &state, const ClickRequest &click, int boxSize,
                const colortrack_gst::FrameView &view) {
  if (click.kind == ClickRequest::Kind::Stop) return stopTracking(state, *state.templateTracker);
  const cv::Rect box = boxAround(click.point, boxSize, view.size());
  if (box.empty()) {
    GST_INFO_OBJECT(self, "click at %.1f,%.1f lies outside the %dx%d frame: ignored", click.point.x,
                    click.point.y, view.size().width, view.size().height);
    return;
  }
  state.templateTracker->setTemplateFromBox(view, box);
  targetChanged(state, describeClick(click, box));
  GST_INFO_OBJECT(self, "template from %s", state.templateOrigin.c_str());
}

}  // namespace

bool prepareTemplateFrame(GstColorTrack *self, const Snapshot &snapshot, const Requests &requests,
                          const colortrack_gst::FrameView &view) {
  State &state = self->priv->state;
  colortrack::Tracker &tracker = *state.templateTracker;

  if (snapshot.trackerGeneration != state.appliedTrackerGeneration) {
    tracker.setSettings(snapshot.tracker);
    state.appliedTrackerGeneration = snapshot.trackerGeneration;
  }
  if (snapshot.templateGeneration != state.appliedTemplateGeneration) {
    state.appliedTemplateGeneration = snapshot.templateGeneration;
    if (!snapshot.templateLocation.empty())
      reloadTemplate(self, state, snapshot.templateLocation, view.size());
  }
  resetIfRequested(self, tracker);
  if (requests.initBox) {
    const InitBoxFit fit =
        checkInitBox(self, *requests.initBox, view.size(), requests.initBoxWhileStreaming, snapshot.initBox);
    if (fit == InitBoxFit::Error) return false;
    if (fit == InitBoxFit::Fits) {
      tracker.setTemplateFromBox(view, *requests.initBox);
      targetChanged(state, "the box '" + snapshot.initBox + "' (property 'init-box')");
    }
  }
  if (requests.click) applyClick(self, state, *requests.click, snapshot.clickBoxSize, view);
  return true;
}

TemplateReadiness templateReadiness(GstColorTrack *self, cv::Size frame) {
  State &state = self->priv->state;
  const colortrack::Tracker &tracker = *state.templateTracker;
  if (!tracker.hasTemplate()) {
    if (!state.warnedNoTemplate) {
      state.warnedNoTemplate = true;
      GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS,
                          ("No template: set 'template-location' or 'init-box', or click the object in the "
                           "video window. Passing video through."),
                          (nullptr));
    }
    return TemplateReadiness::NoTemplate;
  }
  const cv::Size size = tracker.templateSize();
  if (size.width > frame.width || size.height > frame.height) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("The template from %s (%dx%d) is larger than the %dx%d frame.",
                       gstglue::validUtf8(state.templateOrigin).c_str(), size.width, size.height, frame.width,
                       frame.height),
                      (nullptr));
    return TemplateReadiness::Error;
  }
  return TemplateReadiness::Ready;
}

}  // namespace colortrack_gst
