// SPDX-License-Identifier: LGPL-2.1-or-later
#include "sequences.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "sre.hpp"

namespace fs = std::filesystem;

namespace colortrack::eval {

namespace {

std::string readFile(const fs::path &path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

const std::vector<std::string> &tuneSplit() {
  static const std::vector<std::string> names = {"Coke",     "Crossing", "bag",       "wakeboard4",
                                                 "person11", "David",    "DragonBaby"};
  return names;
}

// The four sequences added last (basketball, Biker_uav, S1301, wakeboard5) only check, never tune.
const std::vector<std::string> &confirmSplit() {
  static const std::vector<std::string> names = {"Tiger1",       "Couple",  "boat1",     "car16_1",
                                                 "MotorRolling", "Animal1", "Surfing06", "basketball",
                                                 "Biker_uav",    "S1301",   "wakeboard5"};
  return names;
}

const char *halfOf(const std::string &sequenceName) {
  auto in = [&sequenceName](const std::vector<std::string> &list) {
    return std::find(list.begin(), list.end(), sequenceName) != list.end();
  };
  return in(tuneSplit()) ? "tune" : in(confirmSplit()) ? "confirm" : "-";
}

fs::path framePath(const Sequence &sequence, int index) {
  char name[256];
  std::snprintf(name, sizeof name, sequence.pattern.printfPattern().c_str(),
                sequence.pattern.startIndex + index);
  return sequence.dir / "img" / name;
}

Sequence loadSequence(const fs::path &dir, double gtOrigin) {
  Sequence sequence;
  sequence.dir = dir;
  sequence.name = dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();

  std::vector<std::string> names;
  for (const auto &entry : fs::directory_iterator(dir / "img"))
    if (entry.is_regular_file()) names.push_back(entry.path().filename().string());
  std::string error;
  if (!detectFramePattern(names, sequence.pattern, &error))
    throw std::runtime_error(dir.string() + "/img: " + error);

  fs::path gtPath = dir / "groundtruth.txt";
  if (!fs::exists(gtPath)) gtPath = dir / "groundtruth_rect.txt";  // the name in OTB's own downloads
  if (!parseGroundTruth(readFile(gtPath), gtOrigin, sequence.groundTruth, &error))
    throw std::runtime_error(gtPath.string() + ": " + error);
  if (sequence.groundTruth.empty()) throw std::runtime_error(gtPath.string() + ": no boxes");
  if (!sequence.groundTruth[0])
    throw std::runtime_error(gtPath.string() + ": frame 1 has no box to start from");

  const fs::path first = framePath(sequence, 0);
  const cv::Mat image = cv::imread(first.string(), cv::IMREAD_COLOR);
  if (image.empty()) throw std::runtime_error("cannot decode " + first.string());
  sequence.frameSize = image.size();

  sequence.initBox = startRect(*sequence.groundTruth[0], sequence.frameSize);
  if (sequence.initBox.empty())
    throw std::runtime_error(gtPath.string() + ": frame 1's box is outside the frame");
  return sequence;
}

std::vector<Sequence> findSequences(const std::vector<std::string> &inputs, double gtOrigin) {
  std::vector<Sequence> sequences;
  for (const std::string &input : inputs) {
    const fs::path path(input);
    if (fs::is_directory(path / "img")) {
      sequences.push_back(loadSequence(path, gtOrigin));
      continue;
    }
    if (!fs::is_directory(path)) throw std::runtime_error(input + ": not a directory");
    std::vector<fs::path> children;
    for (const auto &entry : fs::directory_iterator(path))
      if (entry.is_directory() && fs::is_directory(entry.path() / "img")) children.push_back(entry.path());
    if (children.empty())
      throw std::runtime_error(input + ": neither a sequence (img/) nor a folder of sequences");
    std::sort(children.begin(), children.end());
    for (const fs::path &child : children) sequences.push_back(loadSequence(child, gtOrigin));
  }
  return sequences;
}

}  // namespace colortrack::eval
