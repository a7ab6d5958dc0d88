// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack-settings.h"

#include <optional>
#include <type_traits>

namespace colortrack_gst {

namespace {

using gstglue::Apply;
using gstglue::getText;
using gstglue::getTextOrNull;
using gstglue::getValue;
using gstglue::setText;
using gstglue::setValue;
using gstglue::textOf;
using Def = gstglue::PropertyDef<Settings, Shared>;
using colortrack::TrackerSettings;

using Change = Settings::Change;

using colortrack::Status;

// Each end is parsed alone. While streaming the pair must also make sense (lower s and v not above upper);
// before, the other end may still be set after this one, so a start rule checks the pair.
template <bool lower>
Status checkHsv(const PropertyStore &store, const GValue *v) {
  const colortrack::Result<colortrack::Hsv> parsed = colortrack::parseHsv(textOf(v));
  if (!parsed) return parsed.status();
  if (!store.running) return {};
  colortrack::HsvRange candidate = store.settings.blobs.range;
  (lower ? candidate.lower : candidate.upper) = *parsed;
  return colortrack::validateRange(candidate);
}
template <bool lower>
void setHsv(Settings &s, const GValue *v) {
  (lower ? s.hsvLower : s.hsvUpper) = textOf(v);
  if (const colortrack::Result<colortrack::Hsv> parsed = colortrack::parseHsv(textOf(v)))
    (lower ? s.blobs.range.lower : s.blobs.range.upper) = *parsed;
}

colortrack::Result<cv::Rect> parseInitBox(const std::string &text) {
  colortrack::Result<cv::Rect> box = colortrack::parseBox(text);
  if (!box) return box;
  if (Status size = colortrack::checkTemplateSize(box->size()); !size) return size;
  return box;
}

// An empty string only clears a box that has not been used yet.
Status checkInitBox(const PropertyStore &, const GValue *v) {
  return textOf(v).empty() ? Status() : parseInitBox(textOf(v)).status();
}
void initBoxAccepted(PropertyStore &store) {
  Requests &requests = store.shared.requests;
  const colortrack::Result<cv::Rect> box = parseInitBox(store.settings.initBox);
  if (!box) {
    requests.initBox.reset();
    return;
  }
  requests.initBox = *box;
  requests.initBoxWhileStreaming = store.running;
  requests.click.reset();  // the latest request wins
}

// Larger than a known frame while playing: nothing could ever be found. Otherwise it is checked against
// every frame, where it is an error.
Status checkMinArea(const PropertyStore &store, const GValue *v) {
  const cv::Size frame = store.shared.frameSize;
  const int minArea = g_value_get_int(v);
  if (!store.running || frame.empty() || minArea <= frame.area()) return {};
  return Status::failure("larger than the " + std::to_string(frame.width) + "x" +
                         std::to_string(frame.height) + " frame (" + std::to_string(frame.area()) +
                         " pixels)");
}

// What the object is: the mode, a template file, a first box.
std::vector<Def> objectRows() {
  return {
      Def::beforeStart([](GParamFlags f) {
        return g_param_spec_enum(
            "mode", "Mode",
            "How the object is defined: 'template' follows one object like a template; 'threshold' "
            "follows every blob of pixels inside an HSV range, each with its own id; fixed while started",
            GST_TYPE_COLOR_TRACK_MODE, static_cast<gint>(Settings{}.mode), f);
      }).field<&Settings::mode>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_string(
            "template-location", "Template location",
            "Image file (PNG, JPEG; a regular file, never a FIFO or device) of the object to track; a "
            "PNG alpha channel selects its pixels. Loaded at start and again when changed",
            nullptr, f);
      })
          .marks({Change::Template})
          .textOrNull<&Settings::templateLocation>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_string(
            "init-box", "Initial box",
            "\"x,y,w,h\" in pixels, at least 8x8: the template is taken from this box of the next frame, "
            "where tracking starts (mode=threshold: hsv-lower/hsv-upper are learnt from the object in it); "
            "cleared once used",
            nullptr, f);
      })
          .textOrNull<&Settings::initBox>()
          .checking(checkInitBox)
          .keepingRefused()
          .onAccepted(initBoxAccepted),
  };
}

// A template file with an init-box (the box would replace the file's template on the first frame), or in
// threshold mode (which never reads it): a start rule.
Status objectDefinitionConflict(const Settings &s) {
  if (s.templateLocation.empty()) return {};
  std::string conflict;
  if (s.mode == colortrack::TrackingMode::Threshold)
    conflict =
        "property 'template-location' has no use in mode=threshold, which finds the colour range of "
        "'hsv-lower'/'hsv-upper' or learns it from 'init-box': unset 'template-location', or use "
        "mode=template";
  else if (!s.initBox.empty())
    conflict =
        "properties 'template-location' and 'init-box' both give the template (the box's would "
        "replace the file's on the first frame): set one of them";
  return conflict.empty() ? Status() : Status::failure("Contradicting settings: " + conflict + ".");
}

// How frames are searched.
std::vector<Def> methodRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_enum(
            "method", "Method",
            "How frames are searched: 'indexing' is the paper's colour indexing; 'discriminative' "
            "also learns which colours tell the object from its surroundings; 'fused' adds a shape cue (a "
            "correlation filter), a scale filter, a confidence that gates learning, and re-detection",
            GST_TYPE_COLOR_TRACK_METHOD, static_cast<gint>(TrackerSettings{}.method), f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::method>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "likelihood-threshold", "Likelihood threshold",
            "method=discriminative (and fused, while acquiring a template image): minimum mean object "
            "likelihood (0-1) in the box for a detection",
            0.0, 1.0, TrackerSettings{}.likelihoodThreshold, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::likelihoodThreshold>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "model-update-rate", "Model update rate",
            "method=discriminative or fused: how fast the colour likelihood follows appearance changes, "
            "per frame (0 = learn once)",
            0.0, 1.0, TrackerSettings{}.modelUpdateRate, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::modelUpdateRate>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean(
            "adapt-aspect", "Adapt aspect",
            "method=discriminative: let the box's width and height change independently",
            TrackerSettings{}.adaptAspect, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::adaptAspect>(),
  };
}

// The colour histograms and their match.
std::vector<Def> histogramRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_enum("color-space", "Colour space", "Colour space of the histograms",
                                 GST_TYPE_COLOR_TRACK_COLOR_SPACE,
                                 static_cast<gint>(TrackerSettings{}.colorSpace), f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::colorSpace>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_string("bins", "Bins", "Histogram bins per channel, \"c1,c2,c3\", each 1-256",
                                   colortrack::formatBins(TrackerSettings{}.bins).c_str(), f);
      })
          .marks({Change::Tracker})
          .accessors(getText<&Settings::bins>,
                     [](Settings &s, const GValue *v) {
                       s.bins = textOf(v);
                       if (const auto parsed = colortrack::parseBins(s.bins)) s.tracker.bins = *parsed;
                     })
          .checking([](const PropertyStore &, const GValue *v) {
            return colortrack::parseBins(textOf(v)).status();
          })
          .keepingRefused(),
      Def::live([](GParamFlags f) {
        return g_param_spec_string(
            "channel-weights", "Channel weights",
            "Weight of each channel in the match, \"w1,w2,w3\", each 0-1, adding up to "
            "at least 0.001 (V is weighted "
            "down for robustness to lighting)",
            colortrack::formatWeights(TrackerSettings{}.weights).c_str(), f);
      })
          .marks({Change::Tracker})
          .accessors(getText<&Settings::weights>,
                     [](Settings &s, const GValue *v) {
                       s.weights = textOf(v);
                       if (const auto parsed = colortrack::parseWeights(s.weights))
                         s.tracker.weights = *parsed;
                     })
          .checking([](const PropertyStore &, const GValue *v) {
            return colortrack::parseWeights(textOf(v)).status();
          })
          .keepingRefused(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "match-threshold", "Match threshold",
            "method=indexing only: minimum histogram match value (0-1) of a detection (fused uses "
            "its confidence, discriminative likelihood-threshold)",
            0.0, 1.0, TrackerSettings{}.matchThreshold, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::matchThreshold>(),
  };
}

// Where the box is looked for, and at which sizes.
std::vector<Def> searchRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_double("scale-min", "Minimum scale step",
                                   "Smallest box size tried per frame, relative to the current box", 0.5, 1.0,
                                   TrackerSettings{}.scale.minFactor, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::minFactor>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("scale-max", "Maximum scale step",
                                   "Largest box size tried per frame, relative to the current box", 1.0, 2.0,
                                   TrackerSettings{}.scale.maxFactor, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::maxFactor>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("scale-step", "Scale step", "Step between the box sizes tried", 0.001, 0.5,
                                   TrackerSettings{}.scale.step, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::step>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("search-margin", "Search margin",
                                   "Search region around the prediction: the box grown on "
                                   "each side by this many half box sizes, plus 3 "
                                   "sigma of the predicted position",
                                   0.0, 20.0, TrackerSettings{}.searchMargin, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::searchMargin>(),
  };
}

// The motion model.
std::vector<Def> motionRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "process-noise", "Process noise",
            "Kalman process noise (jerk spectral density, px^2/frame^5): higher follows "
            "sudden motion faster, lower smooths more",
            0.0, 1e6, TrackerSettings{}.kalman.processNoise, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::kalman, &colortrack::KalmanParams::processNoise>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("measurement-noise", "Measurement noise",
                                   "Kalman measurement noise (variance of a detection's position, px^2)",
                                   1e-6, 1e6, TrackerSettings{}.kalman.measurementNoise, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::kalman, &colortrack::KalmanParams::measurementNoise>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_int("max-coast-frames", "Maximum coasting frames",
                                "Frames without a detection before the track is lost", 0, 10000,
                                TrackerSettings{}.maxCoastFrames, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::maxCoastFrames>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean(
            "follow-camera", "Follow the camera",
            "mode=threshold: measure how the camera moved since the last frame (phase correlation of a "
            "small grey copy, the objects left out) and move the tracks with the picture, so a panning or "
            "turning camera does not carry predictions off their objects",
            TrackerSettings{}.followCamera, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::followCamera>(),
  };
}

// The edge check, and what the overlay shows.
std::vector<Def> verifyAndDrawRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_enum("verify", "Verify",
                                 "Edge check that tells the object from same-coloured look-alikes",
                                 GST_TYPE_COLOR_TRACK_VERIFY, static_cast<gint>(TrackerSettings{}.verify), f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::verify>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "verify-tolerance", "Verify tolerance",
            "Largest relative difference of edge density/energy from the template's for "
            "a verified match",
            0.0, 100.0, TrackerSettings{}.verifyTolerance, f);
      })
          .marks({Change::Tracker})
          .field<&Settings::tracker, &TrackerSettings::verifyTolerance>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_flags("draw", "Draw", "What the overlay shows", GST_TYPE_COLOR_TRACK_DRAW,
                                  Settings{}.draw, f);
      }).flags<&Settings::draw>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_uint("trail-length", "Trail length", "Frames of box-centre history in the trail",
                                 0, 10000, Settings{}.trailLength, f);
      }).field<&Settings::trailLength>(),
  };
}

// mode=threshold: the colour range, its clean-up and the blob limits.
std::vector<Def> thresholdRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_string(
            "hsv-lower", "HSV lower bound",
            "mode=threshold: lower end of the colour range, \"h,s,v\" with h in degrees 0-360 and s, v "
            "0-1. A lower hue above the upper one wraps through 0 (340 to 20 is red); 0 to 360 is "
            "every hue. Set by init-box when it learns a range",
            Settings{}.hsvLower.c_str(), f);
      })
          .marks({Change::Blobs, Change::Range})
          .accessors(getText<&Settings::hsvLower>, setHsv<true>)
          .checking(checkHsv<true>)
          .keepingRefused(),
      Def::live([](GParamFlags f) {
        return g_param_spec_string(
            "hsv-upper", "HSV upper bound",
            "mode=threshold: upper end of the colour range, \"h,s,v\" (h 0-360, s and v 0-1; s and v "
            "not below hsv-lower's)",
            Settings{}.hsvUpper.c_str(), f);
      })
          .marks({Change::Blobs, Change::Range})
          .accessors(getText<&Settings::hsvUpper>, setHsv<false>)
          .checking(checkHsv<false>)
          .keepingRefused(),
      Def::live([](GParamFlags f) {
        return g_param_spec_int(
            "morph-size", "Morphology size",
            "mode=threshold: side in pixels of the square opening (removes specks) then closing (fills "
            "small holes) applied to the colour mask; 0 disables",
            0, 255, colortrack::BlobSettings{}.morphSize, f);
      })
          .marks({Change::Blobs})
          .field<&Settings::blobs, &colortrack::BlobSettings::morphSize>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_int(
            "min-area", "Minimum area",
            "mode=threshold: smallest blob, in pixels, that counts as an object (must not exceed the "
            "frame's pixel count)",
            1, G_MAXINT, colortrack::BlobSettings{}.minArea, f);
      })
          .marks({Change::Blobs})
          .field<&Settings::blobs, &colortrack::BlobSettings::minArea>()
          .checking(checkMinArea),
      Def::live([](GParamFlags f) {
        return g_param_spec_int("max-objects", "Maximum objects",
                                "mode=threshold: at most this many blobs (the largest) are tracked per frame",
                                1, 64, colortrack::BlobSettings{}.maxObjects, f);
      })
          .marks({Change::Blobs})
          .field<&Settings::blobs, &colortrack::BlobSettings::maxObjects>(),
  };
}

// Each end of the range was parsed alone when set: the pair, at start.
Status rangeProblem(const Settings &s) {
  const Status range = colortrack::validateRange(s.blobs.range);
  if (range) return range;
  return Status::failure("Properties 'hsv-lower' '" + s.hsvLower + "' and 'hsv-upper' '" + s.hsvUpper +
                         "' do not make a range: " + range.message());
}

// Clicks in the video window, and the per-frame message.
std::vector<Def> clickAndMessageRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean(
            "click-to-track", "Click to track",
            "Follow mouse clicks in the video window (GstNavigation events from the sink): a left "
            "click starts tracking what was clicked (mode=threshold: learns its colour), a right "
            "click stops until a new target is given. The events are passed upstream either way",
            Settings{}.clickToTrack, f);
      }).field<&Settings::clickToTrack>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_int(
            "click-box-size", "Click box size",
            "Side in pixels (of this element's frames) of the square centred on a left click, clipped "
            "to the frame, from which the template is taken (mode=threshold: the colour is learnt from "
            "its middle half)",
            colortrack::kMinTemplateSide, 8192, Settings{}.clickBoxSize, f);
      }).field<&Settings::clickBoxSize>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean("post-messages", "Post messages",
                                    "Post a \"colortrack\" element message with the track for every frame",
                                    Settings{}.postMessages, f);
      }).field<&Settings::postMessages>(),
  };
}

}  // namespace

const gstglue::PropertyTable<Settings, Shared> &properties() {
  static const gstglue::PropertyTable<Settings, Shared> table(
      gstglue::rowsOf<Def>(objectRows(), methodRows(), histogramRows(), searchRows(), motionRows(),
                           verifyAndDrawRows(), thresholdRows(), clickAndMessageRows()),
      {{rangeProblem}, {objectDefinitionConflict}});
  return table;
}

}  // namespace colortrack_gst
