// SPDX-License-Identifier: LGPL-2.1-or-later
/* colortrack-app: the smallest useful C application around the colortrack element.
 *
 * Builds   SOURCE ! videoconvert ! colortrack ! appsink
 * and prints one line per frame with what colortrack attached to the buffer (its
 * GstVideoRegionOfInterestMeta and the meta's "colortrack" parameters):
 *
 *   frame=12 time=0.400000 id=1 state=tracking x=201 y=143 w=40 h=40 score=0.913 verified=1 scale=1.002
 *   frame=13 time=0.433333 id=0 state=none
 *
 * Usage:
 *   colortrack-app [--frames N] [--init-box X,Y,W,H] [FILE-OR-URI]
 *
 * Without FILE-OR-URI the source is `videotestsrc pattern=ball` (a green ball on black, 320x240, 30 fps)
 * and the default init-box is the ball's box at frame 0. With a file or URI (rtsp://, file://, http://)
 * the source is uridecodebin and --init-box should say where the object is in the first frame.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gst/video/video.h>

/* Installed as <colortrack/colortrack-meta.h>; this build compiles against the source tree's gst/. */
#include <colortrack-meta.h>

/* videotestsrc draws a ball of radius 20 whose centre is the frame centre at frame 0. */
#define BALL_INIT_BOX "140,100,40,40"

static void print_frame(guint64 frame, GstBuffer *buffer) {
  const GstClockTime pts = GST_BUFFER_PTS(buffer);
  const double seconds = GST_CLOCK_TIME_IS_VALID(pts) ? (double)pts / GST_SECOND : -1.0;
  const GQuark colortrack_roi = g_quark_from_static_string(COLORTRACK_ROI_TYPE);
  GstVideoRegionOfInterestMeta *roi;
  gpointer state = NULL;
  gboolean printed = FALSE;

  /* A buffer may carry ROI metas from other elements too (face detectors, encoders' ROI hints...). */
  while ((roi = (GstVideoRegionOfInterestMeta *)gst_buffer_iterate_meta_filtered(
              buffer, &state, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) != NULL) {
    if (roi->roi_type != colortrack_roi) continue;
    const GstStructure *params = gst_video_region_of_interest_meta_get_param(roi, COLORTRACK_PARAMS_NAME);
    const char *track_state = NULL;
    double score = 0, scale = 0;
    gboolean verified = FALSE;
    if (params) {
      track_state = gst_structure_get_string(params, COLORTRACK_PARAM_STATE);
      gst_structure_get_double(params, COLORTRACK_PARAM_SCORE, &score);
      gst_structure_get_double(params, COLORTRACK_PARAM_SCALE, &scale);
      gst_structure_get_boolean(params, COLORTRACK_PARAM_VERIFIED, &verified);
    }
    printf("frame=%" G_GUINT64_FORMAT
           " time=%.6f id=%d state=%s x=%u y=%u w=%u h=%u score=%.3f verified=%d "
           "scale=%.3f\n",
           frame, seconds, roi->id, track_state ? track_state : "unknown", roi->x, roi->y, roi->w, roi->h,
           score, verified ? 1 : 0, scale);
    printed = TRUE;
  }
  /* No meta: colortrack is searching (or has no template yet). */
  if (!printed) printf("frame=%" G_GUINT64_FORMAT " time=%.6f id=0 state=none\n", frame, seconds);
}

static gboolean parse_args(int argc, char **argv, int *frames, const char **init_box, const char **input) {
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
      *frames = atoi(argv[++i]);
    } else if (strcmp(argv[i], "--init-box") == 0 && i + 1 < argc) {
      *init_box = argv[++i];
    } else if (strcmp(argv[i], "--help") == 0 || argv[i][0] == '-') {
      return FALSE;
    } else {
      *input = argv[i];
    }
  }
  return TRUE;
}

/* The source part of the pipeline for `input` (NULL: the test pattern, whose ball `init_box` then marks if
 * it is unset), or NULL after saying why on stderr. */
static gchar *source_description(const char *input, int frames, const char **init_box) {
  if (!input) {
    if (!*init_box) *init_box = BALL_INIT_BOX;
    return g_strdup_printf(
        "videotestsrc pattern=ball foreground-color=0xff20c020 num-buffers=%d ! "
        "video/x-raw,width=320,height=240,framerate=30/1",
        frames);
  }
  gchar *uri = gst_uri_is_valid(input) ? g_strdup(input) : gst_filename_to_uri(input, NULL);
  if (!uri) {
    fprintf(stderr, "cannot make a URI of '%s'\n", input);
    return NULL;
  }
  gchar *source = g_strdup_printf("uridecodebin uri=\"%s\"", uri);
  g_free(uri);
  return source;
}

/* The pipeline after `source` (taken), or NULL after saying why on stderr. */
static GstElement *build_pipeline(gchar *source, const char *init_box) {
  /* BGR keeps videoconvert's work small; colortrack also takes YUV (I420, NV12, YUY2) directly. */
  gchar *description = g_strdup_printf(
      "%s ! videoconvert ! video/x-raw,format=BGR ! colortrack name=tracker ! "
      "appsink name=sink sync=false max-buffers=4",
      source);
  g_free(source);

  /* Without GST_PARSE_FLAG_FATAL_ERRORS, gst_parse_launch returns a pipeline *and* an error when an element
   * is missing (the pipeline lacks it, so nothing would link): any error is fatal here. */
  GError *error = NULL;
  GstElement *pipeline = gst_parse_launch_full(description, NULL, GST_PARSE_FLAG_FATAL_ERRORS, &error);
  g_free(description);
  if (!pipeline || error) {
    const gboolean missing =
        error && g_error_matches(error, GST_PARSE_ERROR, GST_PARSE_ERROR_NO_SUCH_ELEMENT);
    fprintf(stderr, "pipeline: %s%s\n", error ? error->message : "could not be built",
            missing
                ? " (is the colortrack plugin on GST_PLUGIN_PATH? See the README, \"From your own program\")"
                : "");
    g_clear_error(&error);
    if (pipeline) gst_object_unref(pipeline);
    return NULL;
  }
  GstElement *tracker = gst_bin_get_by_name(GST_BIN(pipeline), "tracker");
  if (init_box) g_object_set(tracker, "init-box", init_box, NULL);
  gst_object_unref(tracker);
  return pipeline;
}

/* Pulls frames in this thread until EOS, an error or `frames` (for a file or URI); returns the exit status.
 */
static int pull_frames(GstAppSink *sink, GstBus *bus, const char *input, int frames) {
  guint64 frame = 0;
  while (input == NULL || frames <= 0 || frame < (guint64)frames) {
    GstSample *sample = gst_app_sink_try_pull_sample(sink, GST_SECOND / 10);
    if (sample) {
      print_frame(frame++, gst_sample_get_buffer(sample));
      gst_sample_unref(sample);
      continue;
    }
    if (gst_app_sink_is_eos(sink)) break;
    GstMessage *message = gst_bus_pop_filtered(bus, GST_MESSAGE_ERROR);
    if (message) {
      GError *error = NULL;
      gchar *debug = NULL;
      gst_message_parse_error(message, &error, &debug);
      fprintf(stderr, "error from %s: %s\n%s\n", GST_OBJECT_NAME(GST_MESSAGE_SRC(message)), error->message,
              debug ? debug : "");
      g_clear_error(&error);
      g_free(debug);
      gst_message_unref(message);
      return 1;
    }
  }
  return 0;
}

int main(int argc, char **argv) {
  int frames = 150;
  const char *init_box = NULL, *input = NULL;

  gst_init(&argc, &argv);
  if (!parse_args(argc, argv, &frames, &init_box, &input)) {
    fprintf(stderr, "usage: %s [--frames N] [--init-box X,Y,W,H] [FILE-OR-URI]\n", argv[0]);
    return 2;
  }
  gchar *source = source_description(input, frames, &init_box);
  if (!source) return 2;
  GstElement *pipeline = build_pipeline(source, init_box);
  if (!pipeline) return 1;

  GstAppSink *sink = GST_APP_SINK(gst_bin_get_by_name(GST_BIN(pipeline), "sink"));
  GstBus *bus = gst_element_get_bus(pipeline);
  int status = 1;
  if (gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE)
    status = pull_frames(sink, bus, input, frames);
  fflush(stdout);

  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(sink);
  gst_object_unref(pipeline);
  return status;
}
