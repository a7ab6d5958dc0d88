// SPDX-License-Identifier: LGPL-2.1-or-later
#include "honesty.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "metrics.hpp"

namespace colortrack::eval {

namespace {

// Frames before a crossing whose mean score is the track's usual one.
constexpr int kScoreBeforeFrames = 10;
// The copy and the target are confusable while their centres are closer than this many of the target's
// longer sides (a copy passing beside the target comes within 1.2 heights).
constexpr double kConfusableSides = 1.5;

double iouWith(const FrameReport &report, const std::optional<cv::Rect2d> &box) {
  return report.box && box ? overlap(*report.box, *box) : 0.0;
}

bool isTracking(const FrameReport &report) {
  return report.box && report.state == "tracking";
}

bool isLossState(const std::string &state) {
  return state == "lost" || state == "searching";
}

FrameReport reportAt(const std::vector<FrameReport> &reports, int i) {
  return i >= 0 && i < static_cast<int>(reports.size()) ? reports[i] : FrameReport();
}

std::string percent(int part, int whole) {
  return whole > 0 ? format("%d/%d (%.1f %%)", part, whole, 100.0 * part / whole)
                   : format("%d/%d", part, whole);
}

std::string number(double value) {
  return std::isnan(value) ? "-" : format("%.3f", value);
}

// The kind a run's injection is summarised under: "cut", "cover15", "copy-front", "copy-beside".
std::string groupOf(const Injection &injection) {
  switch (injection.kind) {
    case InjectionKind::Cut:
      return "cut";
    case InjectionKind::Cover:
      return format("cover%d", injection.length);
    case InjectionKind::Copy:
      return injection.beside ? "copy-beside" : "copy-front";
  }
  return "?";
}

// Sums of the outcomes of one group of runs.
struct GroupSums {
  int runs = 0, declared = 0, absentFrames = 0, absentTracking = 0, back = 0, endsOnTarget = 0,
      endsOnCopy = 0;
  double iouAfter = 0, scoreBefore = 0, scoreConfusable = 0;
  void add(const InjectionOutcome &o) {
    ++runs;
    declared += o.declaredAfter >= 1 && o.declaredAfter <= kDeclareWithin;
    absentFrames += o.absentFrames;
    absentTracking += o.absentTracking;
    back += o.backAfter >= 1 && o.backAfter <= kBackWithin;
    endsOnTarget += o.endsOnTarget;
    endsOnCopy += o.endsOnCopyTracking;
    iouAfter += o.meanIouAfter;
    scoreBefore += o.scoreBefore;
    scoreConfusable += o.scoreConfusable;
  }
};

std::string groupLine(const std::string &group, const std::string &half, const GroupSums &g) {
  std::string line = format("%-12s %-8s %4d  ", group.c_str(), half.c_str(), g.runs);
  if (g.runs == 0) return line + "\n";
  if (group == "cut")
    line += "lost within " + std::to_string(kDeclareWithin) + ": " + percent(g.declared, g.runs) +
            "  tracking after grace: " + percent(g.absentTracking, g.absentFrames) + "  back within " +
            std::to_string(kBackWithin) + " of the cut back: " + percent(g.back, g.runs);
  else if (group.rfind("cover", 0) == 0)
    line += "tracking under the cover: " + percent(g.absentTracking, g.absentFrames) + "  back within " +
            std::to_string(kBackWithin) + ": " + percent(g.back, g.runs) +
            format("  mean IoU after %.3f", g.iouAfter / g.runs);
  else
    line += "ends on target: " + percent(g.endsOnTarget, g.runs) +
            "  tracking on the copy at the end: " + percent(g.endsOnCopy, g.runs) +
            format("  score before %.2f, while confusable %.2f", g.scoreBefore / g.runs,
                   g.scoreConfusable / g.runs);
  return line + "\n";
}

// One line of figures after `label` (18 characters: "runs half", or a sequence's name).
std::string figuresLine(const std::string &label, const HonestyFigures &f) {
  const double precision = f.tracking > 0 ? double(f.trackingOnTarget) / f.tracking : NAN;
  const double recall = f.onTarget > 0 ? double(f.trackingOnTarget) / f.onTarget : NAN;
  return format("%-18s %22s  %7s  %9s  %7s\n", label.c_str(),
                percent(f.offTargetTracking, f.offTarget).c_str(), number(auroc(f.scores)).c_str(),
                number(precision).c_str(), number(recall).c_str());
}

// The same figures per sequence, plain and injected runs together, in the order the runs came.
std::string perSequenceLines(const std::vector<RunRecord> &runs) {
  std::vector<std::string> order;
  std::map<std::string, HonestyFigures> bySequence;
  for (const RunRecord &run : runs) {
    if (!bySequence.count(run.sequence)) order.push_back(run.sequence);
    bySequence[run.sequence] += honestyFigures(run.truth, run.reports);
  }
  std::string text = "\nPer sequence, plain and injected runs together:\n";
  for (const std::string &sequence : order) text += figuresLine(sequence, bySequence[sequence]);
  return text;
}

}  // namespace

HonestyFigures &HonestyFigures::operator+=(const HonestyFigures &other) {
  offTarget += other.offTarget;
  offTargetTracking += other.offTargetTracking;
  tracking += other.tracking;
  trackingOnTarget += other.trackingOnTarget;
  onTarget += other.onTarget;
  scores.insert(scores.end(), other.scores.begin(), other.scores.end());
  return *this;
}

HonestyFigures honestyFigures(const std::vector<FrameTruth> &truth, const std::vector<FrameReport> &reports) {
  HonestyFigures f;
  for (int i = 1; i < static_cast<int>(truth.size()); ++i) {
    const FrameTruth &t = truth[i];
    if (t.grace || (!t.absent && !t.target)) continue;
    const FrameReport r = reportAt(reports, i);
    const double iou = t.absent ? 0.0 : iouWith(r, t.target);
    const bool on = !t.absent && iou >= kOnIou;
    const bool off = t.absent ? r.box.has_value() : iou < kWrongIou;
    if (isTracking(r)) {
      ++f.tracking;
      f.trackingOnTarget += on;
    }
    f.onTarget += on;
    if (off) {
      ++f.offTarget;
      f.offTargetTracking += isTracking(r);
    }
    if (r.box && (on || off)) f.scores.emplace_back(r.score, on);
  }
  return f;
}

double auroc(std::vector<std::pair<double, bool>> scores) {
  std::sort(scores.begin(), scores.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
  // Mann-Whitney: the positives' rank sum, tied scores sharing their mean rank.
  double rankSum = 0;
  long positives = 0;
  for (std::size_t i = 0; i < scores.size();) {
    std::size_t j = i;
    while (j < scores.size() && scores[j].first == scores[i].first) ++j;
    const double meanRank = (i + 1 + j) / 2.0;
    for (std::size_t k = i; k < j; ++k)
      if (scores[k].second) {
        rankSum += meanRank;
        ++positives;
      }
    i = j;
  }
  const long negatives = static_cast<long>(scores.size()) - positives;
  if (positives == 0 || negatives == 0) return std::numeric_limits<double>::quiet_NaN();
  return (rankSum - positives * (positives + 1) / 2.0) / (double(positives) * negatives);
}

InjectionOutcome injectionOutcome(const Injection &injection, const std::vector<FrameTruth> &truth,
                                  const std::vector<FrameReport> &reports) {
  InjectionOutcome o;
  const int frames = static_cast<int>(truth.size());
  for (int i = injection.first; i <= injection.last() && i < frames; ++i) {
    const FrameReport r = reportAt(reports, i);
    if (o.declaredAfter < 0 && isLossState(r.state)) o.declaredAfter = i - injection.first + 1;
    if (truth[i].absent && !truth[i].grace) {
      ++o.absentFrames;
      o.absentTracking += isTracking(r);
    }
  }
  const int end = std::min(frames - 1, injection.last() + kFramesAfter);
  for (int i = injection.last() + 1; i <= end; ++i) {
    const double iou = iouWith(reportAt(reports, i), truth[i].target);
    if (o.backAfter < 0 && iou >= kFoundIou) o.backAfter = i - injection.last();
    o.meanIouAfter += iou / kFramesAfter;
  }
  if (injection.kind != InjectionKind::Copy) return o;
  const FrameReport atEnd = reportAt(reports, injection.last());
  const FrameTruth &endTruth = truth[injection.last()];
  o.endsOnTarget = iouWith(atEnd, endTruth.target) >= kOnIou;
  o.endsOnCopyTracking = iouWith(atEnd, endTruth.copy) >= kOnIou && isTracking(atEnd);
  int before = 0, confusable = 0;
  for (int i = std::max(1, injection.first - kScoreBeforeFrames); i < injection.first; ++i, ++before)
    o.scoreBefore += reportAt(reports, i).score;
  for (int i = injection.first; i <= injection.last(); ++i) {
    const FrameTruth &t = truth[i];
    if (!t.target || !t.copy ||
        centreDistance(*t.target, *t.copy) > kConfusableSides * std::max(t.target->width, t.target->height))
      continue;
    o.scoreConfusable += reportAt(reports, i).score;
    ++confusable;
  }
  o.scoreBefore = before > 0 ? o.scoreBefore / before : 0;
  o.scoreConfusable = confusable > 0 ? o.scoreConfusable / confusable : 0;
  return o;
}

std::string honestyReport(const std::vector<RunRecord> &runs) {
  std::string text = format(
      "Honesty (issue 46): off-target frames reported tracking (IoU < %.1f, or a box while the target is cut "
      "away or covered), AUROC of the per-frame score (frames with a box: IoU >= %.1f against off-target), "
      "precision of `tracking` (IoU >= %.1f) and its recall (of the frames on target)\n",
      kWrongIou, kOnIou, kOnIou);
  text += format("%-9s %-8s %22s  %7s  %9s  %7s\n", "runs", "half", "off-target tracking", "AUROC",
                 "precision", "recall");
  const char *halves[] = {"tune", "confirm", "all"};
  for (const char *kind : {"plain", "injected", "both"})
    for (const char *half : halves) {
      HonestyFigures pooled;
      for (const RunRecord &run : runs) {
        const bool injected = run.injection.has_value();
        if ((kind == std::string("plain") && injected) || (kind == std::string("injected") && !injected))
          continue;
        if (half != std::string("all") && run.half != half) continue;
        pooled += honestyFigures(run.truth, run.reports);
      }
      text += figuresLine(format("%-9s %s", kind, half), pooled);
    }

  text += perSequenceLines(runs);
  text += "\nInjected failures, per run:\n";
  text += format("%-14s %-20s %8s %10s %6s %8s %6s %6s %7s\n", "sequence", "injection", "declared",
                 "tracking", "back", "IoU aft", "onTgt", "onCopy", "score");
  std::map<std::string, std::map<std::string, GroupSums>> groups;  // [group][half]
  for (const RunRecord &run : runs) {
    if (!run.injection) continue;
    const InjectionOutcome o = injectionOutcome(*run.injection, run.truth, run.reports);
    const std::string group = groupOf(*run.injection);
    groups[group][run.half].add(o);
    groups[group]["all"].add(o);
    text += format("%-14s %-20s %8d %10s %6d %8.3f %6s %6s %7s\n", run.sequence.c_str(), run.start.c_str(),
                   o.declaredAfter, format("%d/%d", o.absentTracking, o.absentFrames).c_str(), o.backAfter,
                   o.meanIouAfter,
                   run.injection->kind == InjectionKind::Copy ? (o.endsOnTarget ? "yes" : "no") : "",
                   run.injection->kind == InjectionKind::Copy ? (o.endsOnCopyTracking ? "YES" : "no") : "",
                   run.injection->kind == InjectionKind::Copy
                       ? format("%.2f>%.2f", o.scoreBefore, o.scoreConfusable).c_str()
                       : "");
  }
  text +=
      "\nInjected failures, per kind (declared: frames of the cut to lost/searching, -1 never; back: frames "
      "after the injection to IoU >= 0.5, -1 not within 30):\n";
  for (const auto &[group, byHalf] : groups)
    for (const char *half : halves) {
      const auto found = byHalf.find(half);
      text += groupLine(group, half, found == byHalf.end() ? GroupSums() : found->second);
    }
  return text;
}

}  // namespace colortrack::eval
