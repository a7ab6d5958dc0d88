// SPDX-License-Identifier: LGPL-2.1-or-later
// The demo's command line and its output files: what colortrack-demo was asked to do, checked, and files
// written under a temporary name and renamed over their targets only when the run succeeds.
#pragma once

#include <stdexcept>
#include <string>

namespace colortrack::demo {

class DemoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string input;  // empty: the synthetic scene
  std::string output = "colortrack-demo.avi";
  int frames = -1;  // -1: kSceneFrames for the scene, until EOS for real inputs
  std::string initBox;
  std::string templatePath;
  std::string robotDevice;                                // serial port of a real robot (robotctl device=)
  std::string robotOutput = "colortrack-demo-robot.txt";  // else the commands go here (robotctl location=)
  std::string robotLog;  // when each command was sent, and why (default: next to robotOutput)
};

// The robot log's default: the robot file's name with ".log" for its extension; colortrack-demo-robot.log
// when the commands go to a device or to stdout.
std::string defaultRobotLog(const Options &options);

// An output file written under a temporary name next to its target and renamed over it on success only, so
// a failed run keeps the previous file. Targets that are not regular files (a FIFO, a pty, stdout) are
// written directly.
class StagedFile {
 public:
  explicit StagedFile(const std::string &target);
  StagedFile(const StagedFile &) = delete;
  StagedFile &operator=(const StagedFile &) = delete;
  ~StagedFile();
  const std::string &path() const { return path_; }      // where to write now
  const std::string &target() const { return target_; }  // where it ends up
  bool staged() const { return path_ != target_; }
  void commit();

 private:
  std::string target_, path_;
  bool committed_ = false;
};

enum class InputKind { Scene, Device, Uri };
InputKind inputKind(const std::string &input);

// A plain path becomes a file:// URI; anything GStreamer already accepts as a URI is kept.
std::string toUri(const std::string &input);

// The command line (GStreamer's options too: this initialises GStreamer), checked; throws DemoError.
Options parseOptions(int &argc, char **&argv);

}  // namespace colortrack::demo
