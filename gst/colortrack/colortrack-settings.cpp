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

constexpr unsigned kTracker = 1u << kTrackerVersion, kTemplate = 1u << kTemplateVersion,
                   kBlobs = 1u << kBlobsVersion, kRange = 1u << kRangeVersion;

// A text property's check: the parser's error text, or empty when it parses.
template <typename Parse>
std::string parseError(const GValue *v, Parse parse) {
  std::string error;
  return parse(textOf(v), &error) ? std::string() : error;
}

// Each end is parsed alone. While streaming the pair must also make sense (lower s and v not above upper);
// before, the other end may still be set after this one, so start() checks the pair.
template <bool lower>
std::string checkHsv(const PropertyStore &store, const GValue *v, std::string *) {
  std::string error;
  const std::optional<colortrack::Hsv> parsed = colortrack::parseHsv(textOf(v), &error);
  if (!parsed) return error;
  if (!store.running) return {};
  colortrack::HsvRange candidate = store.settings.blobs.range;
  (lower ? candidate.lower : candidate.upper) = *parsed;
  return colortrack::validateRange(candidate);
}
template <bool lower>
void setHsv(Settings &s, const GValue *v) {
  (lower ? s.hsvLower : s.hsvUpper) = textOf(v);
  if (const std::optional<colortrack::Hsv> parsed = colortrack::parseHsv(textOf(v), nullptr))
    (lower ? s.blobs.range.lower : s.blobs.range.upper) = *parsed;
}

std::optional<cv::Rect> parseInitBox(const std::string &text, std::string *error) {
  const std::optional<cv::Rect> box = colortrack::parseBox(text, error);
  if (!box) return box;
  const std::string problem = colortrack::templateSizeProblem(box->size());
  if (problem.empty()) return box;
  if (error) *error = problem;
  return std::nullopt;
}

// An empty string only clears a box that has not been used yet.
std::string checkInitBox(const PropertyStore &, const GValue *v, std::string *) {
  return textOf(v).empty() ? std::string() : parseError(v, parseInitBox);
}
void initBoxAccepted(PropertyStore &store) {
  Requests &requests = store.shared.requests;
  requests.initBox = parseInitBox(store.settings.initBox, nullptr);
  if (!requests.initBox) return;
  requests.initBoxWhileStreaming = store.running;
  requests.click.reset();  // the latest request wins
}

// Larger than a known frame while playing: nothing could ever be found. Otherwise it is checked against
// every frame, where it is an error.
std::string checkMinArea(const PropertyStore &store, const GValue *v, std::string *warning) {
  const cv::Size frame = store.shared.frameSize;
  const int minArea = g_value_get_int(v);
  if (!store.running || frame.empty() || minArea <= frame.area()) return {};
  *warning = "Property 'min-area' " + std::to_string(minArea) + " is larger than the " +
             std::to_string(frame.width) + "x" + std::to_string(frame.height) + " frame (" +
             std::to_string(frame.area()) + " pixels). Keeping " +
             std::to_string(store.settings.blobs.minArea) + ".";
  return "larger than the frame";
}

const Def kProperties[] = {
    {Apply::BeforeStart, 0,
     [](GParamFlags f) {
       return g_param_spec_enum(
           "mode", "Mode",
           "How the object is defined: 'template' follows one object like a template; 'threshold' "
           "follows every blob of pixels inside an HSV range, each with its own id; fixed while started",
           GST_TYPE_COLOR_TRACK_MODE, static_cast<gint>(Settings{}.mode), f);
     },
     getValue<&Settings::mode>, setValue<&Settings::mode>},
    {Apply::Live, kTemplate,
     [](GParamFlags f) {
       return g_param_spec_string(
           "template-location", "Template location",
           "Image file (PNG, JPEG; a regular file, never a FIFO or device) of the object to track; a "
           "PNG alpha channel selects its pixels. Loaded at start and again when changed",
           nullptr, f);
     },
     getTextOrNull<&Settings::templateLocation>, setText<&Settings::templateLocation>},
    {Apply::Live, 0,
     [](GParamFlags f) {
       return g_param_spec_string(
           "init-box", "Initial box",
           "\"x,y,w,h\" in pixels, at least 8x8: the template is taken from this box of the next frame, "
           "where tracking starts (mode=threshold: hsv-lower/hsv-upper are learnt from the object in it); "
           "cleared once used",
           nullptr, f);
     },
     getTextOrNull<&Settings::initBox>, setText<&Settings::initBox>, nullptr, checkInitBox, true,
     initBoxAccepted},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_enum(
           "method", "Method",
           "How frames are searched: 'indexing' is the paper's colour indexing; 'discriminative' "
           "also learns which colours tell the object from its surroundings; 'fused' adds a shape cue (a "
           "correlation filter), a scale filter, a confidence that gates learning, and re-detection",
           GST_TYPE_COLOR_TRACK_METHOD, static_cast<gint>(TrackerSettings{}.method), f);
     },
     getValue<&Settings::tracker, &TrackerSettings::method>,
     setValue<&Settings::tracker, &TrackerSettings::method>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double(
           "likelihood-threshold", "Likelihood threshold",
           "method=discriminative (and fused, while acquiring a template image): minimum mean object "
           "likelihood (0-1) in the box for a detection",
           0.0, 1.0, TrackerSettings{}.likelihoodThreshold, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::likelihoodThreshold>,
     setValue<&Settings::tracker, &TrackerSettings::likelihoodThreshold>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double(
           "model-update-rate", "Model update rate",
           "method=discriminative or fused: how fast the colour likelihood follows appearance changes, "
           "per frame (0 = learn once)",
           0.0, 1.0, TrackerSettings{}.modelUpdateRate, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::modelUpdateRate>,
     setValue<&Settings::tracker, &TrackerSettings::modelUpdateRate>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_boolean(
           "adapt-aspect", "Adapt aspect",
           "method=discriminative: let the box's width and height change independently",
           TrackerSettings{}.adaptAspect, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_boolean(v, s.tracker.adaptAspect); },
     [](Settings &s, const GValue *v) { s.tracker.adaptAspect = g_value_get_boolean(v); }},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_enum("color-space", "Colour space", "Colour space of the histograms",
                                GST_TYPE_COLOR_TRACK_COLOR_SPACE,
                                static_cast<gint>(TrackerSettings{}.colorSpace), f);
     },
     getValue<&Settings::tracker, &TrackerSettings::colorSpace>,
     setValue<&Settings::tracker, &TrackerSettings::colorSpace>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_string("bins", "Bins", "Histogram bins per channel, \"c1,c2,c3\", each 1-256",
                                  colortrack::formatBins(TrackerSettings{}.bins).c_str(), f);
     },
     getText<&Settings::bins>,
     [](Settings &s, const GValue *v) {
       s.bins = textOf(v);
       if (const auto parsed = colortrack::parseBins(s.bins, nullptr)) s.tracker.bins = *parsed;
     },
     nullptr,
     [](const PropertyStore &, const GValue *v, std::string *) {
       return parseError(v, [](const std::string &t, std::string *e) { return colortrack::parseBins(t, e); });
     },
     true},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_string("channel-weights", "Channel weights",
                                  "Weight of each channel in the match, \"w1,w2,w3\", each 0-1, adding up to "
                                  "at least 0.001 (V is weighted "
                                  "down for robustness to lighting)",
                                  colortrack::formatWeights(TrackerSettings{}.weights).c_str(), f);
     },
     getText<&Settings::weights>,
     [](Settings &s, const GValue *v) {
       s.weights = textOf(v);
       if (const auto parsed = colortrack::parseWeights(s.weights, nullptr)) s.tracker.weights = *parsed;
     },
     nullptr,
     [](const PropertyStore &, const GValue *v, std::string *) {
       return parseError(v,
                         [](const std::string &t, std::string *e) { return colortrack::parseWeights(t, e); });
     },
     true},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double(
           "match-threshold", "Match threshold",
           "method=indexing only: minimum histogram match value (0-1) of a detection (fused uses "
           "its confidence, discriminative likelihood-threshold)",
           0.0, 1.0, TrackerSettings{}.matchThreshold, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::matchThreshold>,
     setValue<&Settings::tracker, &TrackerSettings::matchThreshold>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double("scale-min", "Minimum scale step",
                                  "Smallest box size tried per frame, relative to the current box", 0.5, 1.0,
                                  TrackerSettings{}.scale.minFactor, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::minFactor>,
     setValue<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::minFactor>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double("scale-max", "Maximum scale step",
                                  "Largest box size tried per frame, relative to the current box", 1.0, 2.0,
                                  TrackerSettings{}.scale.maxFactor, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::maxFactor>,
     setValue<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::maxFactor>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double("scale-step", "Scale step", "Step between the box sizes tried", 0.001, 0.5,
                                  TrackerSettings{}.scale.step, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::step>,
     setValue<&Settings::tracker, &TrackerSettings::scale, &colortrack::ScaleParams::step>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double("search-margin", "Search margin",
                                  "Search region around the prediction: the box grown on "
                                  "each side by this many half box sizes, plus 3 "
                                  "sigma of the predicted position",
                                  0.0, 20.0, TrackerSettings{}.searchMargin, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::searchMargin>,
     setValue<&Settings::tracker, &TrackerSettings::searchMargin>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double(
           "process-noise", "Process noise",
           "Kalman process noise (jerk spectral density, px^2/frame^5): higher follows "
           "sudden motion faster, lower smooths more",
           0.0, 1e6, TrackerSettings{}.kalman.processNoise, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::kalman, &colortrack::KalmanParams::processNoise>,
     setValue<&Settings::tracker, &TrackerSettings::kalman, &colortrack::KalmanParams::processNoise>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double("measurement-noise", "Measurement noise",
                                  "Kalman measurement noise (variance of a detection's position, px^2)", 1e-6,
                                  1e6, TrackerSettings{}.kalman.measurementNoise, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::kalman, &colortrack::KalmanParams::measurementNoise>,
     setValue<&Settings::tracker, &TrackerSettings::kalman, &colortrack::KalmanParams::measurementNoise>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_int("max-coast-frames", "Maximum coasting frames",
                               "Frames without a detection before the track is lost", 0, 10000,
                               TrackerSettings{}.maxCoastFrames, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_int(v, s.tracker.maxCoastFrames); },
     [](Settings &s, const GValue *v) { s.tracker.maxCoastFrames = g_value_get_int(v); }},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_boolean(
           "follow-camera", "Follow the camera",
           "mode=threshold: measure how the camera moved since the last frame (phase correlation of a "
           "small grey copy, the objects left out) and move the tracks with the picture, so a panning or "
           "turning camera does not carry predictions off their objects",
           TrackerSettings{}.followCamera, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_boolean(v, s.tracker.followCamera); },
     [](Settings &s, const GValue *v) { s.tracker.followCamera = g_value_get_boolean(v); }},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_enum("verify", "Verify",
                                "Edge check that tells the object from same-coloured look-alikes",
                                GST_TYPE_COLOR_TRACK_VERIFY, static_cast<gint>(TrackerSettings{}.verify), f);
     },
     getValue<&Settings::tracker, &TrackerSettings::verify>,
     setValue<&Settings::tracker, &TrackerSettings::verify>},
    {Apply::Live, kTracker,
     [](GParamFlags f) {
       return g_param_spec_double(
           "verify-tolerance", "Verify tolerance",
           "Largest relative difference of edge density/energy from the template's for "
           "a verified match",
           0.0, 100.0, TrackerSettings{}.verifyTolerance, f);
     },
     getValue<&Settings::tracker, &TrackerSettings::verifyTolerance>,
     setValue<&Settings::tracker, &TrackerSettings::verifyTolerance>},
    {Apply::Live, 0,
     [](GParamFlags f) {
       return g_param_spec_flags("draw", "Draw", "What the overlay shows", GST_TYPE_COLOR_TRACK_DRAW,
                                 Settings{}.draw, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_flags(v, s.draw); },
     [](Settings &s, const GValue *v) { s.draw = g_value_get_flags(v); }},
    {Apply::Live, 0,
     [](GParamFlags f) {
       return g_param_spec_uint("trail-length", "Trail length", "Frames of box-centre history in the trail",
                                0, 10000, Settings{}.trailLength, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_uint(v, s.trailLength); },
     [](Settings &s, const GValue *v) { s.trailLength = g_value_get_uint(v); }},
    {Apply::Live, kBlobs | kRange,
     [](GParamFlags f) {
       return g_param_spec_string(
           "hsv-lower", "HSV lower bound",
           "mode=threshold: lower end of the colour range, \"h,s,v\" with h in degrees 0-360 and s, v "
           "0-1. A lower hue above the upper one wraps through 0 (340 to 20 is red); 0 to 360 is "
           "every hue. Set by init-box when it learns a range",
           Settings{}.hsvLower.c_str(), f);
     },
     getText<&Settings::hsvLower>, setHsv<true>, nullptr, checkHsv<true>, true},
    {Apply::Live, kBlobs | kRange,
     [](GParamFlags f) {
       return g_param_spec_string(
           "hsv-upper", "HSV upper bound",
           "mode=threshold: upper end of the colour range, \"h,s,v\" (h 0-360, s and v 0-1; s and v "
           "not below hsv-lower's)",
           Settings{}.hsvUpper.c_str(), f);
     },
     getText<&Settings::hsvUpper>, setHsv<false>, nullptr, checkHsv<false>, true},
    {Apply::Live, kBlobs,
     [](GParamFlags f) {
       return g_param_spec_int(
           "morph-size", "Morphology size",
           "mode=threshold: side in pixels of the square opening (removes specks) then closing (fills "
           "small holes) applied to the colour mask; 0 disables",
           0, 255, colortrack::BlobSettings{}.morphSize, f);
     },
     getValue<&Settings::blobs, &colortrack::BlobSettings::morphSize>,
     setValue<&Settings::blobs, &colortrack::BlobSettings::morphSize>},
    {Apply::Live, kBlobs,
     [](GParamFlags f) {
       return g_param_spec_int(
           "min-area", "Minimum area",
           "mode=threshold: smallest blob, in pixels, that counts as an object (must not exceed the "
           "frame's pixel count)",
           1, G_MAXINT, colortrack::BlobSettings{}.minArea, f);
     },
     getValue<&Settings::blobs, &colortrack::BlobSettings::minArea>,
     setValue<&Settings::blobs, &colortrack::BlobSettings::minArea>, nullptr, checkMinArea},
    {Apply::Live, kBlobs,
     [](GParamFlags f) {
       return g_param_spec_int("max-objects", "Maximum objects",
                               "mode=threshold: at most this many blobs (the largest) are tracked per frame",
                               1, 64, colortrack::BlobSettings{}.maxObjects, f);
     },
     getValue<&Settings::blobs, &colortrack::BlobSettings::maxObjects>,
     setValue<&Settings::blobs, &colortrack::BlobSettings::maxObjects>},
    {Apply::Live, 0,
     [](GParamFlags f) {
       return g_param_spec_boolean(
           "click-to-track", "Click to track",
           "Follow mouse clicks in the video window (GstNavigation events from the sink): a left "
           "click starts tracking what was clicked (mode=threshold: learns its colour), a right "
           "click stops until a new target is given. The events are passed upstream either way",
           Settings{}.clickToTrack, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_boolean(v, s.clickToTrack); },
     [](Settings &s, const GValue *v) { s.clickToTrack = g_value_get_boolean(v); }},
    {Apply::Live, 0,
     [](GParamFlags f) {
       return g_param_spec_int(
           "click-box-size", "Click box size",
           "Side in pixels (of this element's frames) of the square centred on a left click, clipped "
           "to the frame, from which the template is taken (mode=threshold: the colour is learnt from "
           "its middle half)",
           colortrack::kMinTemplateSide, 8192, Settings{}.clickBoxSize, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_int(v, s.clickBoxSize); },
     [](Settings &s, const GValue *v) { s.clickBoxSize = g_value_get_int(v); }},
    {Apply::Live, 0,
     [](GParamFlags f) {
       return g_param_spec_boolean("post-messages", "Post messages",
                                   "Post a \"colortrack\" element message with the track for every frame",
                                   Settings{}.postMessages, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_boolean(v, s.postMessages); },
     [](Settings &s, const GValue *v) { s.postMessages = g_value_get_boolean(v); }},
};

}  // namespace

const gstglue::PropertyTable<Settings, Shared> &properties() {
  static const gstglue::PropertyTable<Settings, Shared> table(kProperties);
  return table;
}

std::string objectDefinitionConflict(const Settings &s) {
  if (s.templateLocation.empty()) return "";
  if (s.mode == colortrack::TrackingMode::Threshold)
    return "property 'template-location' has no use in mode=threshold, which finds the colour range of "
           "'hsv-lower'/'hsv-upper' or learns it from 'init-box': unset 'template-location', or use "
           "mode=template";
  if (!s.initBox.empty())
    return "properties 'template-location' and 'init-box' both give the template (the box's would replace "
           "the file's on the first frame): set one of them";
  return "";
}

}  // namespace colortrack_gst
