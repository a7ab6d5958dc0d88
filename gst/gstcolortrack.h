// GstColorTrack: the `colortrack` element, a GstVideoFilter that tracks a coloured object in place.
#pragma once

#include <gst/gst.h>
#include <gst/video/gstvideofilter.h>
#include <gst/video/video.h>

G_BEGIN_DECLS

#define GST_TYPE_COLOR_TRACK (gst_color_track_get_type())
#define GST_COLOR_TRACK(obj) (G_TYPE_CHECK_INSTANCE_CAST((obj), GST_TYPE_COLOR_TRACK, GstColorTrack))
#define GST_COLOR_TRACK_CLASS(klass) \
  (G_TYPE_CHECK_CLASS_CAST((klass), GST_TYPE_COLOR_TRACK, GstColorTrackClass))
#define GST_IS_COLOR_TRACK(obj) (G_TYPE_CHECK_INSTANCE_TYPE((obj), GST_TYPE_COLOR_TRACK))

typedef struct _GstColorTrack GstColorTrack;
typedef struct _GstColorTrackClass GstColorTrackClass;

/**
 * GstColorTrackMode:
 * @GST_COLOR_TRACK_MODE_TEMPLATE: track the object described by a template (a file or a box of a frame)
 * @GST_COLOR_TRACK_MODE_THRESHOLD: track every blob of pixels inside an HSV range (#GstColorTrack:hsv-lower,
 *     #GstColorTrack:hsv-upper, or learnt from #GstColorTrack:init-box), each with its own id
 *
 * How the object to track is defined.
 */
typedef enum {
  GST_COLOR_TRACK_MODE_TEMPLATE = 0,
  GST_COLOR_TRACK_MODE_THRESHOLD = 1,
} GstColorTrackMode;

/**
 * GstColorTrackColorSpace:
 * @GST_COLOR_TRACK_COLOR_SPACE_RGB: histograms of R, G and B (original colour indexing)
 * @GST_COLOR_TRACK_COLOR_SPACE_HSV: histograms of H, S and V (modified colour indexing)
 */
typedef enum {
  GST_COLOR_TRACK_COLOR_SPACE_RGB = 0,
  GST_COLOR_TRACK_COLOR_SPACE_HSV = 1,
} GstColorTrackColorSpace;

/**
 * GstColorTrackMethod:
 * @GST_COLOR_TRACK_METHOD_INDEXING: the paper's modified colour indexing (template histograms, histogram
 *     intersection, window-versus-ring scale)
 * @GST_COLOR_TRACK_METHOD_DISCRIMINATIVE: object-versus-surroundings colour likelihood learnt from the
 *     target and the ring around it, with a motion prior and adaptive aspect; detections are still accepted
 *     by the template's colour-indexing match value
 * @GST_COLOR_TRACK_METHOD_FUSED: a correlation filter over gradient-orientation cells and intensity (shape)
 *     fused with the colour likelihood, a scale filter, a confidence that decides tracking / coasting / lost
 *     and gates learning, and re-detection over the whole frame once lost (the default)
 */
typedef enum {
  GST_COLOR_TRACK_METHOD_INDEXING = 0,
  GST_COLOR_TRACK_METHOD_DISCRIMINATIVE = 1,
  GST_COLOR_TRACK_METHOD_FUSED = 2,
} GstColorTrackMethod;

/**
 * GstColorTrackVerify:
 * @GST_COLOR_TRACK_VERIFY_NONE: accept every colour match
 * @GST_COLOR_TRACK_VERIFY_EDGE_DENSITY: compare the edge density with the template's
 * @GST_COLOR_TRACK_VERIFY_EDGE_ENERGY: compare the edge energy with the template's
 * @GST_COLOR_TRACK_VERIFY_BOTH: both must agree
 */
typedef enum {
  GST_COLOR_TRACK_VERIFY_NONE = 0,
  GST_COLOR_TRACK_VERIFY_EDGE_DENSITY = 1,
  GST_COLOR_TRACK_VERIFY_EDGE_ENERGY = 2,
  GST_COLOR_TRACK_VERIFY_BOTH = 3,
} GstColorTrackVerify;

/**
 * GstColorTrackDraw:
 * @GST_COLOR_TRACK_DRAW_NONE: no overlay: frames are only read, never written (no copy behind a tee)
 * @GST_COLOR_TRACK_DRAW_BOX: the tracked box (red: colour match, green: verified, orange: coasting)
 * @GST_COLOR_TRACK_DRAW_TRAIL: the path of the box centre (yellow)
 * @GST_COLOR_TRACK_DRAW_SEARCH_WINDOW: the region searched in this frame (blue)
 * @GST_COLOR_TRACK_DRAW_LABEL: "id score state" above the box
 * @GST_COLOR_TRACK_DRAW_MASK: mode=threshold: the pixels inside the HSV range, tinted magenta (for tuning)
 */
typedef enum {
  GST_COLOR_TRACK_DRAW_NONE = 0,
  GST_COLOR_TRACK_DRAW_BOX = (1 << 0),
  GST_COLOR_TRACK_DRAW_TRAIL = (1 << 1),
  GST_COLOR_TRACK_DRAW_SEARCH_WINDOW = (1 << 2),
  GST_COLOR_TRACK_DRAW_LABEL = (1 << 3),
  GST_COLOR_TRACK_DRAW_MASK = (1 << 4),
} GstColorTrackDraw;

// C++ data (settings and streaming state); defined in gstcolortrack.cpp.
typedef struct _GstColorTrackPrivate GstColorTrackPrivate;

struct _GstColorTrack {
  GstVideoFilter parent;
  GstColorTrackPrivate *priv;
};

struct _GstColorTrackClass {
  GstVideoFilterClass parent_class;
  /* action signals */
  void (*reset)(GstColorTrack *self);
};

GType gst_color_track_get_type(void);
#define GST_TYPE_COLOR_TRACK_MODE (gst_color_track_mode_get_type())
#define GST_TYPE_COLOR_TRACK_COLOR_SPACE (gst_color_track_color_space_get_type())
#define GST_TYPE_COLOR_TRACK_VERIFY (gst_color_track_verify_get_type())
#define GST_TYPE_COLOR_TRACK_DRAW (gst_color_track_draw_get_type())
GType gst_color_track_mode_get_type(void);
GType gst_color_track_color_space_get_type(void);
GType gst_color_track_verify_get_type(void);
#define GST_TYPE_COLOR_TRACK_METHOD (gst_color_track_method_get_type())
GType gst_color_track_method_get_type(void);
GType gst_color_track_draw_get_type(void);

GST_ELEMENT_REGISTER_DECLARE(colortrack);

G_END_DECLS
