// SPDX-License-Identifier: LGPL-2.1-or-later
#include "demo_options.hpp"

#include <glib/gstdio.h>
#include <gst/gst.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

namespace colortrack::demo {

std::string defaultRobotLog(const Options &options) {
  if (!options.robotDevice.empty() || options.robotOutput == "-") return "colortrack-demo-robot.log";
  const std::string &out = options.robotOutput;
  const std::size_t slash = out.rfind('/'), dot = out.rfind('.');
  const bool hasExtension =
      dot != std::string::npos && dot > 0 && (slash == std::string::npos || dot > slash + 1);
  return (hasExtension ? out.substr(0, dot) : out) + ".log";
}

StagedFile::StagedFile(const std::string &target) : target_(target), path_(target) {
  GStatBuf st;
  const bool exists = g_stat(target.c_str(), &st) == 0;
  if (target != "-" && (!exists || S_ISREG(st.st_mode)))
    path_ = target + ".partial-" + std::to_string(static_cast<long>(getpid()));
}

StagedFile::~StagedFile() {
  if (staged() && !committed_) g_unlink(path_.c_str());
}

void StagedFile::commit() {
  if (staged() && g_rename(path_.c_str(), target_.c_str()) != 0)
    throw DemoError("cannot rename " + path_ + " to " + target_ + ": " + g_strerror(errno));
  committed_ = true;
}

InputKind inputKind(const std::string &input) {
  if (input.empty()) return InputKind::Scene;
  if (input.rfind("/dev/video", 0) == 0) return InputKind::Device;
  return InputKind::Uri;
}

std::string toUri(const std::string &input) {
  if (gst_uri_is_valid(input.c_str())) return input;
  if (!g_file_test(input.c_str(), G_FILE_TEST_EXISTS)) throw DemoError("input file not found: " + input);
  GError *error = nullptr;
  gchar *uri = gst_filename_to_uri(input.c_str(), &error);
  if (!uri) {
    std::string text = error ? error->message : "unknown error";
    g_clear_error(&error);
    throw DemoError("cannot make a URI of '" + input + "': " + text);
  }
  std::string result(uri);
  g_free(uri);
  return result;
}

namespace {

// What the command line may not ask: no frames, outputs without a name or on top of each other or of the
// input, a real input without an object to track.
void checkOptions(const Options &options) {
  if (options.frames == 0 || options.frames < -1) throw DemoError("--frames must be a positive number");
  if (options.output.empty()) throw DemoError("--output must name a file");
  if (options.robotLog.empty()) throw DemoError("--robot-log must name a file");
  if (options.robotLog == options.output ||
      (options.robotDevice.empty() && options.robotLog == options.robotOutput))
    throw DemoError("--robot-log must differ from --output and --robot-output");
  if (inputKind(options.input) == InputKind::Uri && !gst_uri_is_valid(options.input.c_str())) {
    // filesink truncates its file at start: writing over the input would destroy it.
    gchar *in = g_canonicalize_filename(options.input.c_str(), nullptr);
    gchar *out = g_canonicalize_filename(options.output.c_str(), nullptr);
    const bool same = g_strcmp0(in, out) == 0;
    g_free(in);
    g_free(out);
    if (same) throw DemoError("the output file is the input file: choose another --output");
  }
  if (!options.initBox.empty() && !options.templatePath.empty())
    throw DemoError("--init-box and --template both define the object: give one of them");
  if (inputKind(options.input) != InputKind::Scene && options.initBox.empty() && options.templatePath.empty())
    throw DemoError(
        "a camera, file or stream input needs --init-box X,Y,W,H or --template FILE to know what "
        "to track");
}

}  // namespace

Options parseOptions(int &argc, char **&argv) {
  gchar *output = nullptr, *initBox = nullptr, *templatePath = nullptr, *robotDevice = nullptr,
        *robotOutput = nullptr, *robotLog = nullptr;
  gchar **positional = nullptr;
  gint frames = -1;
  const GOptionEntry entries[] = {
      {"output", 'o', 0, G_OPTION_ARG_FILENAME, &output, "Output AVI file (default colortrack-demo.avi)",
       "FILE"},
      {"frames", 'n', 0, G_OPTION_ARG_INT, &frames,
       "Frames to process (default 300 for the scene, until end of stream otherwise)", "N"},
      {"init-box", 'b', 0, G_OPTION_ARG_STRING, &initBox, "Object box in the first frame", "X,Y,W,H"},
      {"template", 't', 0, G_OPTION_ARG_FILENAME, &templatePath, "Template image of the object (PNG/JPEG)",
       "FILE"},
      {"robot", 'r', 0, G_OPTION_ARG_FILENAME, &robotDevice,
       "Serial port of a robot to drive (robotctl device=), e.g. /dev/ttyUSB0", "DEVICE"},
      {"robot-output", 0, 0, G_OPTION_ARG_FILENAME, &robotOutput,
       "Without --robot, write the robot commands here, '-' for stdout (default colortrack-demo-robot.txt)",
       "FILE"},
      {"robot-log", 0, 0, G_OPTION_ARG_FILENAME, &robotLog,
       "Write one timestamped line per robot command here (default: the robot file's name with .log, "
       "colortrack-demo-robot.log)",
       "FILE"},
      {G_OPTION_REMAINING, 0, 0, G_OPTION_ARG_FILENAME_ARRAY, &positional, nullptr, nullptr},
      {nullptr, 0, 0, G_OPTION_ARG_NONE, nullptr, nullptr, nullptr}};

  GOptionContext *context = g_option_context_new("[/dev/videoN | FILE | URI]");
  g_option_context_set_summary(
      context,
      "Tracks a coloured object with the colortrack element and writes the annotated "
      "video.\nWithout an input, runs the built-in synthetic scene and reports the "
      "accuracy against its ground truth.");
  g_option_context_add_main_entries(context, entries, nullptr);
  g_option_context_add_group(context, gst_init_get_option_group());  // also initialises GStreamer
  GError *error = nullptr;
  const bool parsed = g_option_context_parse(context, &argc, &argv, &error);
  g_option_context_free(context);

  Options options;
  std::string problem;
  if (!parsed) problem = error ? error->message : "invalid arguments";
  g_clear_error(&error);
  if (output) options.output = output;
  if (initBox) options.initBox = initBox;
  if (templatePath) options.templatePath = templatePath;
  if (robotDevice) options.robotDevice = robotDevice;
  if (robotOutput) options.robotOutput = robotOutput;
  options.robotLog = robotLog ? robotLog : defaultRobotLog(options);
  options.frames = frames;
  if (positional && positional[0]) {
    options.input = positional[0];
    if (positional[1]) problem = std::string("more than one input given: ") + positional[1];
  }
  g_free(output);
  g_free(initBox);
  g_free(templatePath);
  g_free(robotDevice);
  g_free(robotOutput);
  g_free(robotLog);
  g_strfreev(positional);

  if (!problem.empty()) throw DemoError(problem + " (see --help)");
  checkOptions(options);
  return options;
}

}  // namespace colortrack::demo
