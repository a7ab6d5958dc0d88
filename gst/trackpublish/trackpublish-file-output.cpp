// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's file output (location): JSON lines to a file, a FIFO, a character device or stdout, written
// by DocumentFile's thread, never the streaming thread.
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>

#include "colortrack/output_file.hpp"
#include "document-file.h"
#include "trackpublish-output.h"

#define GST_CAT_DEFAULT gst_track_publish_debug

namespace trackpublish {

namespace {

using std::chrono::milliseconds;

class FileOutput : public DocumentOutput {
 public:
  FileOutput(GstElement *element, std::string location, int fd, bool owned, std::size_t maxQueued)
      : element_(element), shown_(gstglue::validUtf8(location)), file_(fd, owned, maxQueued) {}

  // A write that failed is an error (once the writer thread has seen it: a document or a few later); drops
  // (the file did not keep up with max-queued documents waiting) a warning at most once a second.
  GstFlowReturn publish(const std::string &document) override {
    if (postFailure()) return GST_FLOW_ERROR;
    const std::uint64_t dropped = file_.droppedCount();
    const gint64 now = g_get_monotonic_time();
    if (dropped > dropsReported_ && now - dropWarning_ >= G_USEC_PER_SEC) {
      GST_ELEMENT_WARNING(
          element_, RESOURCE, WRITE,
          ("'%s' (property 'location') does not keep up: documents dropped so far: %" G_GUINT64_FORMAT
           ", the oldest first (max-queued waiting).",
           shownLocation(), dropped),
          (nullptr));
      dropsReported_ = dropped;
      dropWarning_ = now;
    }
    file_.write(document);
    return GST_FLOW_OK;
  }

  // A write that failed after the last document (the stream ends before another publish() could say it) is
  // the error here.
  void drainAtEos(milliseconds drain) override {
    if (file_.waitWritten(drain) || postFailure()) return;
    GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                        ("%zu documents not yet written to '%s' (property 'location') at EOS after "
                         "drain-timeout.",
                         file_.queued(), shownLocation()),
                        (nullptr));
  }

  void close(milliseconds drain) override {
    file_.stop(drain);
    if (const std::size_t left = file_.queued())
      GST_WARNING_OBJECT(element_, "%zu documents not written to '%s' when stopping (drain-timeout)", left,
                         shownLocation());
  }

 private:
  const char *shownLocation() const { return shown_.c_str(); }

  // Posts the writer thread's failure, once; true when there is one.
  bool postFailure() {
    const std::string failure = file_.failure();
    if (failure.empty()) return false;
    if (!failurePosted_)
      GST_ELEMENT_ERROR(
          element_, RESOURCE, WRITE,
          ("Could not write to '%s' (property 'location'): %s", shownLocation(), failure.c_str()), (nullptr));
    failurePosted_ = true;
    return true;
  }

  GstElement *element_;
  const std::string shown_;  // the location as messages show it (valid UTF-8)
  DocumentFile file_;
  std::uint64_t dropsReported_ = 0;
  bool failurePosted_ = false;
  gint64 dropWarning_ = 0;  // monotonic µs of the last warning about drops
};

}  // namespace

std::unique_ptr<DocumentOutput> openFileOutput(const OutputContext &c) {
  const std::string &location = c.settings.location;
  if (location == "-")
    return std::make_unique<FileOutput>(c.element, "stdout", STDOUT_FILENO, false, c.settings.maxQueued);
  // Opened without waiting: a FIFO nobody reads is refused at once instead of holding the state change in
  // open(). It stays non-blocking: the writer thread waits for a slow reader, never the stream.
  std::string why;
  mode_t kind = 0;
  const int fd = colortrack::openOutputFile(location, O_CREAT | O_APPEND, kind, why);
  if (fd < 0) {
    GST_ELEMENT_ERROR(c.element, RESOURCE, OPEN_WRITE,
                      ("Could not open '%s' (property 'location') for writing: %s",
                       gstglue::validUtf8(location).c_str(), gstglue::validUtf8(why).c_str()),
                      (nullptr));
    return nullptr;
  }
  return std::make_unique<FileOutput>(c.element, location, fd, true, c.settings.maxQueued);
}

}  // namespace trackpublish
