// SPDX-License-Identifier: LGPL-2.1-or-later
#include "eval_report.hpp"

#include <gst/gst.h>

#include <sys/utsname.h>

#include <algorithm>
#include <cctype>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include <opencv2/core/utility.hpp>

namespace fs = std::filesystem;

namespace colortrack::eval {

std::vector<EvalResults::Column> EvalResults::columns() const {
  std::vector<Column> columns;
  for (std::size_t t = 0; t < trackers.size(); ++t) {
    if (runOnce[t]) {
      columns.push_back({t, 0, trackers[t] + " [own caps]"});
      continue;
    }
    for (std::size_t f = 0; f < formats.size(); ++f)
      columns.push_back({t, f, trackers[t] + " [" + formats[f] + "]"});
  }
  return columns;
}

std::string fpsText(double fps) {
  if (fps <= 0) return "-";
  return fps >= 100 ? format("%.0f", fps) : format("%.1f", fps);
}

std::string slug(const std::string &text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.')
      out += c;
    else if (!out.empty() && out.back() != '_')
      out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "tracker" : out;
}

namespace {

Cell cellOf(const std::vector<Evaluation> &starts) {
  Cell cell;
  for (const Evaluation &e : starts) cell.starts.push_back({e.ok, e.score, e.alarm, e.hasStates});
  return cell;
}

const std::vector<Evaluation> &startsOf(const EvalResults &results, std::size_t s,
                                        const EvalResults::Column &c) {
  return results.runs[s][c.tracker][c.format];
}

std::string sequenceTable(const Sequence &seq, std::size_t s, const EvalResults &results) {
  const bool sre = results.startNames.size() > 1;
  std::ostringstream md;
  md << "### " << seq.name << " (" << seq.groundTruth.size() << " frames, " << seq.frameSize.width << "x"
     << seq.frameSize.height << ")\n\n";
  md << "| Tracker | AUC | Precision@20 | fps pipeline | fps element |" << (sre ? " SRE AUC |" : "")
     << "\n|---|---:|---:|---:|---:|" << (sre ? "---:|" : "") << "\n";
  std::vector<std::string> notes;
  for (const EvalResults::Column &c : results.columns()) {
    const std::vector<Evaluation> &starts = startsOf(results, s, c);
    const Evaluation &e = starts.front();
    if (!e.ok)
      md << "| " << c.label << " | failed | | | |";
    else
      md << "| " << c.label << " | " << format("%.3f", e.score.auc) << " | "
         << format("%.3f", e.score.precisionAt20) << " | " << fpsText(e.run.pipelineFps()) << " | "
         << fpsText(e.run.elementFps()) << " |";
    if (sre) md << " " << format("%.3f", sreAuc(cellOf(starts))) << " |";
    md << "\n";
    for (std::size_t i = 0; i < starts.size(); ++i)
      if (!starts[i].warning.empty())
        notes.push_back(c.label + " (" + results.startNames[i] + "): " + starts[i].warning);
  }
  if (!notes.empty()) md << "\n";
  for (const std::string &note : notes) md << "- " << note << "\n";
  return md.str() + "\n";
}

std::string meanTable(const std::vector<Sequence> &sequences, const EvalResults &results) {
  std::ostringstream md;
  md << "### Mean over " << sequences.size() << (sequences.size() == 1 ? " sequence" : " sequences")
     << " (OPE)\n\n";
  md << "| Tracker | AUC | Precision@20 | fps pipeline | fps element | slowest element fps |\n"
        "|---|---:|---:|---:|---:|---:|\n";
  for (const EvalResults::Column &c : results.columns()) {
    std::vector<SequenceScore> scores;
    double frames = 0, wall = 0, inside = 0, slowest = 0;
    std::string slowestName;
    for (std::size_t s = 0; s < sequences.size(); ++s) {
      const Evaluation &e = startsOf(results, s, c).front();
      if (!e.ok) continue;
      scores.push_back(e.score);
      frames += e.run.frames();
      wall += e.run.wallSeconds;
      inside += e.run.elementSeconds;
      if (slowestName.empty() || e.run.elementFps() < slowest) {
        slowest = e.run.elementFps();
        slowestName = sequences[s].name;
      }
    }
    if (scores.empty()) {
      md << "| " << c.label << " | failed | | | | |\n";
      continue;
    }
    const SequenceScore mean = averageScores(scores);
    const std::string coverage = scores.size() == sequences.size()
                                     ? ""
                                     : format(" (%zu of %zu sequences)", scores.size(), sequences.size());
    md << "| " << c.label << coverage << " | " << format("%.3f", mean.auc) << " | "
       << format("%.3f", mean.precisionAt20) << " | " << fpsText(wall > 0 ? frames / wall : 0) << " | "
       << fpsText(inside > 0 ? frames / inside : 0) << " | " << fpsText(slowest) << " (" << slowestName
       << ") |\n";
  }
  md << "\nAUC and precision: mean of the sequences. fps: all frames over all time. fps element: time inside "
        "the tracker element only (sink pad to src pad). [own caps]: the tracker negotiates its own input "
        "format, so it ran once per sequence and start and that run stands for every format.\n";
  return md.str();
}

std::string quoted(const std::string &text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string markdownTables(const std::vector<Sequence> &sequences, const EvalResults &results) {
  std::string md;
  for (std::size_t s = 0; s < sequences.size(); ++s) md += sequenceTable(sequences[s], s, results);
  return md + meanTable(sequences, results);
}

void writeCsv(const fs::path &path, const std::vector<Sequence> &sequences, const EvalResults &results) {
  std::ofstream csv(path);
  csv << "sequence,tracker,format,start,gt_frames,frames,scored_frames,frames_with_box,auc,precision20,"
         "fps_pipeline,fps_element,wall_s,element_s,status\n";
  for (std::size_t s = 0; s < sequences.size(); ++s)
    for (const EvalResults::Column &c : results.columns()) {
      const std::string formatName = results.runOnce[c.tracker] ? "own caps" : results.formats[c.format];
      const std::vector<Evaluation> &starts = startsOf(results, s, c);
      for (std::size_t i = 0; i < starts.size(); ++i) {
        const Evaluation &e = starts[i];
        const long withBox =
            std::count_if(e.run.boxes.begin(), e.run.boxes.end(), [](const auto &b) { return b; });
        csv << quoted(sequences[s].name) << "," << quoted(results.trackers[c.tracker]) << ","
            << quoted(formatName) << "," << results.startNames[i] << "," << sequences[s].groundTruth.size()
            << "," << e.run.frames() << "," << e.score.scoredFrames << "," << withBox << ","
            << format("%.4f,%.4f,%.2f,%.2f,%.3f,%.3f,", e.score.auc, e.score.precisionAt20,
                      e.run.pipelineFps(), e.run.elementFps(), e.run.wallSeconds, e.run.elementSeconds)
            << quoted(e.ok ? (e.warning.empty() ? "ok" : e.warning) : "failed: " + e.warning) << "\n";
      }
    }
}

std::string framesFolder(const EvalResults &results, std::size_t tracker, std::size_t format) {
  return slug(results.trackers[tracker]) + (results.runOnce[tracker] ? "" : "_" + results.formats[format]);
}

void writeFrames(const fs::path &path, const Sequence &sequence, const cv::Rect &start,
                 const RunResult &run) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path);
  out << "frame,gt_x,gt_y,gt_w,gt_h,x,y,w,h,iou,centre_error,state,score\n";
  const std::size_t n = std::max(sequence.groundTruth.size(), run.boxes.size());
  for (std::size_t i = 0; i < n; ++i) {
    const GroundTruthBox gt = i < sequence.groundTruth.size() ? sequence.groundTruth[i] : std::nullopt;
    std::optional<cv::Rect2d> box = i < run.boxes.size() ? run.boxes[i] : std::nullopt;
    if (i == 0) box = cv::Rect2d(start);
    out << i + 1;
    for (const auto &b : {gt, box}) {
      if (b)
        out << format(",%.2f,%.2f,%.2f,%.2f", b->x, b->y, b->width, b->height);
      else
        out << ",,,,";
    }
    if (gt && box)
      out << format(",%.4f,%.2f", overlap(*box, *gt), centreDistance(*box, *gt));
    else
      out << (gt ? ",0,inf" : ",,");
    out << "," << (i < run.states.size() ? run.states[i] : "");
    out << "," << (i < run.scores.size() ? format("%.4f", run.scores[i]) : "") << "\n";
  }
}

void writeCurves(const fs::path &path, const std::vector<std::string> &labels,
                 const std::vector<SequenceScore> &means) {
  std::ofstream csv(path);
  csv << "tracker,curve,threshold,value\n";
  for (std::size_t t = 0; t < labels.size(); ++t) {
    for (int k = 0; k < kSuccessSteps; ++k)
      csv << quoted(labels[t]) << ",success," << format("%.2f", k / double(kSuccessSteps - 1)) << ","
          << format("%.4f", means[t].success[k]) << "\n";
    for (int k = 0; k < kPrecisionSteps; ++k)
      csv << quoted(labels[t]) << ",precision," << k << "," << format("%.4f", means[t].precision[k]) << "\n";
  }
}

RobustnessTable robustnessTable(const std::vector<Sequence> &sequences, const EvalResults &results) {
  RobustnessTable table;
  for (const Sequence &sequence : sequences) table.sequences.push_back(sequence.name);
  table.startNames = results.startNames;
  table.trackers = results.trackers;
  table.formats = results.formats;
  table.runOnce = results.runOnce;
  table.cells.resize(sequences.size());
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    table.cells[s].resize(results.trackers.size());
    for (std::size_t t = 0; t < results.trackers.size(); ++t)
      for (const std::vector<Evaluation> &starts : results.runs[s][t])
        table.cells[s][t].push_back(cellOf(starts));
  }
  return table;
}

std::string machineDescription() {
  std::string cpu = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  struct utsname system {};
  uname(&system);
  gchar *gstVersion = gst_version_string();
  std::string text = format("%s, %u logical cores (OpenCV threads: %d); %s %s; %s; OpenCV %s", cpu.c_str(),
                            std::thread::hardware_concurrency(), cv::getNumThreads(), system.sysname,
                            system.release, gstVersion, cv::getVersionString().c_str());
  g_free(gstVersion);
  // Other processes compete for the cores; the load says how much the fps figures can be trusted.
  std::ifstream loadavg("/proc/loadavg");
  double load1 = 0;
  if (loadavg >> load1) text += format("; load average %.2f at the start", load1);
  return text;
}

std::string pluginOf(const char *factoryName) {
  GstElementFactory *factory = gst_element_factory_find(factoryName);
  if (!factory) return "not found";
  GstPlugin *plugin = gst_plugin_feature_get_plugin(GST_PLUGIN_FEATURE(factory));
  std::string text = plugin && gst_plugin_get_filename(plugin) ? gst_plugin_get_filename(plugin) : "?";
  if (plugin) {
    text += std::string(" (") + gst_plugin_get_version(plugin) + ")";
    gst_object_unref(plugin);
  }
  gst_object_unref(factory);
  return text;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[64];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return text;
}

}  // namespace colortrack::eval
