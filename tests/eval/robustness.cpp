// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robustness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "sequences.hpp"

namespace colortrack::eval {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

std::string columnName(const RobustnessTable &table, std::size_t t, std::size_t f) {
  if (table.formats[f].empty()) return table.trackers[t];
  return table.trackers[t] + (table.runOnce[t] ? " [own caps]" : " [" + table.formats[f] + "]");
}

// The (tracker, format) pairs the tables show: a run-once tracker once, its cells being equal in every
// format.
struct Column {
  std::size_t tracker, format;
};

std::vector<Column> columns(const RobustnessTable &table) {
  std::vector<Column> out;
  for (std::size_t t = 0; t < table.trackers.size(); ++t)
    for (std::size_t f = 0; f < (table.runOnce[t] ? 1 : table.formats.size()); ++f) out.push_back({t, f});
  return out;
}

std::string score(double value) {
  return std::isnan(value) ? "   fail" : format("%7.3f", value);
}

std::string share(int part, int whole) {
  return whole > 0 ? format("%5.1f %% of %d", 100.0 * part / whole, whole) : "-";
}

// Range of the AUCs over the starts that ran, and the starts where it is lowest and highest.
struct StartRange {
  double low = 0, high = 0;
  std::size_t lowStart = 0, highStart = 0;
  bool valid = false;
};

StartRange startRange(const Cell &cell) {
  StartRange range;
  for (std::size_t i = 0; i < cell.starts.size(); ++i) {
    if (!cell.starts[i].ok) continue;
    const double auc = cell.starts[i].score.auc;
    if (!range.valid || auc < range.low) range.low = auc, range.lowStart = i;
    if (!range.valid || auc > range.high) range.high = auc, range.highStart = i;
    range.valid = true;
  }
  return range;
}

std::string perSequenceTable(const RobustnessTable &table) {
  std::ostringstream out;
  out << "Success AUC per sequence (OPE: frame 1's box"
      << (table.sre() ? "; SRE: mean of the 8 perturbed starts" : "") << ")\n";
  const std::vector<Column> shown = columns(table);
  for (std::size_t c = 0; c < shown.size(); ++c)
    out << format("  [%zu] ", c + 1) << columnName(table, shown[c].tracker, shown[c].format) << "\n";
  out << format("%-14s %-7s", "sequence", "half");
  for (std::size_t c = 0; c < shown.size(); ++c)
    out << format(" %7s", format("[%zu]OPE", c + 1).c_str()) << (table.sre() ? format(" %7s", "SRE") : "");
  out << "\n";
  for (std::size_t s = 0; s < table.sequences.size(); ++s) {
    out << format("%-14s %-7s", table.sequences[s].c_str(), halfOf(table.sequences[s]));
    for (const Column &c : shown) {
      const Cell &cell = table.cells[s][c.tracker][c.format];
      out << " " << score(opeAuc(cell)) << (table.sre() ? " " + score(sreAuc(cell)) : "");
    }
    out << "\n";
  }
  return out.str();
}

std::string meansTable(const RobustnessTable &table) {
  std::ostringstream out;
  out << "\nMean AUC per half (n = sequences that ran: tune/confirm/all)\n";
  out << format("%-44s %7s %7s %7s", "", "OPE tun", "confirm", "all");
  if (table.sre()) out << format(" | %7s %7s %7s", "SRE tun", "confirm", "all");
  out << "\n";
  for (const Column &c : columns(table)) {
    const HalfMeans ope = halfMeans(table, c.tracker, c.format, false);
    out << format("%-44.44s %s %s %s", columnName(table, c.tracker, c.format).c_str(),
                  score(ope.tune).c_str(), score(ope.confirm).c_str(), score(ope.all).c_str());
    if (table.sre()) {
      const HalfMeans sre = halfMeans(table, c.tracker, c.format, true);
      out << " | " << score(sre.tune) << " " << score(sre.confirm) << " " << score(sre.all);
    }
    out << format("  n=%d/%d/%d\n", ope.tuneCount, ope.confirmCount, ope.allCount);
  }
  return out.str();
}

// Mean AUC of each start (OPE and every SRE perturbation) per half: shows which kind of misplaced first box
// costs most, which the SRE score alone hides.
std::string perStartTable(const RobustnessTable &table) {
  std::ostringstream out;
  out << "\nMean AUC per start (tune / confirm / all)\n";
  out << format("%-44s", "");
  for (const std::string &name : table.startNames) out << format(" %17s", name.c_str());
  out << "\n";
  for (const Column &c : columns(table)) {
    out << format("%-44.44s", columnName(table, c.tracker, c.format).c_str());
    for (std::size_t i = 0; i < table.startNames.size(); ++i) {
      double sum[3] = {0, 0, 0};  // tune, confirm, all
      int count[3] = {0, 0, 0};
      for (std::size_t s = 0; s < table.sequences.size(); ++s) {
        const Cell &cell = table.cells[s][c.tracker][c.format];
        if (i >= cell.starts.size() || !cell.starts[i].ok) continue;
        const std::string half = halfOf(table.sequences[s]);
        for (int h : {half == "tune" ? 0 : -1, half == "confirm" ? 1 : -1, 2})
          if (h >= 0) sum[h] += cell.starts[i].score.auc, ++count[h];
      }
      std::string means;
      for (int h = 0; h < 3; ++h)
        means += (h ? "/" : "") + score(count[h] > 0 ? sum[h] / count[h] : kNan).substr(2);
      out << " " << means;
    }
    out << "\n";
  }
  return out.str();
}

// Mean over the sequences of |a - b| for formats `a` and `b`, over the sequences where both ran.
double meanSequenceDelta(const RobustnessTable &table, std::size_t t, std::size_t a, std::size_t b,
                         bool sre) {
  double sum = 0;
  int count = 0;
  for (const auto &bySequence : table.cells) {
    const Cell &x = bySequence[t][a], &y = bySequence[t][b];
    const double dx = sre ? sreAuc(x) : opeAuc(x), dy = sre ? sreAuc(y) : opeAuc(y);
    if (std::isnan(dx) || std::isnan(dy)) continue;
    sum += std::abs(dx - dy);
    ++count;
  }
  return count > 0 ? sum / count : kNan;
}

std::string formatSpread(const RobustnessTable &table) {
  const auto &formats = table.formats;
  const auto bgrx = std::find(formats.begin(), formats.end(), "BGRx") - formats.begin();
  const auto i420 = std::find(formats.begin(), formats.end(), "I420") - formats.begin();
  const bool pair = bgrx < static_cast<long>(formats.size()) && i420 < static_cast<long>(formats.size());
  std::ostringstream out;
  out << "\nSpread between formats: max |delta| of the mean over all sequences between any two formats; mean "
         "per-sequence |delta AUC| between BGRx and I420\n";
  out << format("%-36s %9s %9s %13s %13s\n", "tracker", "OPE max", "SRE max", "OPE BGRx-I420",
                "SRE BGRx-I420");
  for (std::size_t t = 0; t < table.trackers.size(); ++t) {
    out << format("%-36.36s", table.trackers[t].c_str());
    if (table.runOnce[t]) {
      out << " run once per sequence and start; the same result in every format column\n";
      continue;
    }
    for (bool sre : {false, true}) {
      double low = kNan, high = kNan;
      for (std::size_t f = 0; f < formats.size(); ++f) {
        const double all = halfMeans(table, t, f, sre).all;
        if (std::isnan(all)) continue;
        low = std::isnan(low) ? all : std::min(low, all);
        high = std::isnan(high) ? all : std::max(high, all);
      }
      out << (sre && !table.sre() ? format(" %9s", "-") : format(" %9.3f", high - low));
    }
    for (bool sre : {false, true})
      out << (!pair || (sre && !table.sre())
                  ? format(" %13s", "-")
                  : format(" %13.3f", meanSequenceDelta(table, t, bgrx, i420, sre)));
    out << "\n";
  }
  return out.str();
}

// One line per tracker and sequence whose score moves by more than kFlagMove between formats.
void flagFormats(const RobustnessTable &table, std::size_t s, std::size_t t, std::ostringstream &out) {
  for (bool sre : {false, true}) {
    if (sre && !table.sre()) continue;
    std::string values;
    double low = kNan, high = kNan;
    for (std::size_t f = 0; f < table.formats.size(); ++f) {
      const Cell &cell = table.cells[s][t][f];
      const double auc = sre ? sreAuc(cell) : opeAuc(cell);
      values += format(" %s %.3f", table.formats[f].c_str(), auc);
      if (std::isnan(auc)) continue;
      low = std::isnan(low) ? auc : std::min(low, auc);
      high = std::isnan(high) ? auc : std::max(high, auc);
    }
    if (high - low > kFlagMove)
      out << format("FLAG %-14s %s: %s moves %.3f between formats (%s )\n", table.sequences[s].c_str(),
                    table.trackers[t].c_str(), sre ? "SRE score" : "OPE AUC", high - low, values.c_str() + 1);
  }
}

std::string flags(const RobustnessTable &table) {
  std::ostringstream out;
  for (std::size_t s = 0; s < table.sequences.size(); ++s) {
    for (std::size_t t = 0; t < table.trackers.size(); ++t)
      if (table.formats.size() > 1 && !table.runOnce[t]) flagFormats(table, s, t, out);
    if (!table.sre()) continue;
    for (const Column &c : columns(table)) {
      const StartRange range = startRange(table.cells[s][c.tracker][c.format]);
      if (!range.valid || range.high - range.low <= kFlagMove) continue;
      out << format("FLAG %-14s %s: AUC moves %.3f between starts (%.3f %s .. %.3f %s)\n",
                    table.sequences[s].c_str(), columnName(table, c.tracker, c.format).c_str(),
                    range.high - range.low, range.low, table.startNames[range.lowStart].c_str(), range.high,
                    table.startNames[range.highStart].c_str());
    }
  }
  const std::string lines = out.str();
  return format("\nSequences that move by more than %.1f AUC between formats or between starts:\n",
                kFlagMove) +
         (lines.empty() ? "  none\n" : lines);
}

// The alarm figures of one tracker and format, added over the OPE runs or over the SRE runs.
AlarmFigures pooledAlarms(const RobustnessTable &table, std::size_t t, std::size_t f, bool sre, bool *any) {
  AlarmFigures pooled;
  *any = false;
  for (const auto &bySequence : table.cells) {
    const Cell &cell = bySequence[t][f];
    for (std::size_t i = sre ? 1 : 0;
         i < (sre ? cell.starts.size() : std::min<std::size_t>(1, cell.starts.size())); ++i) {
      if (!cell.starts[i].ok || !cell.starts[i].hasStates) continue;
      pooled += cell.starts[i].alarm;
      *any = true;
    }
  }
  return pooled;
}

std::string alarmsTable(const RobustnessTable &table) {
  std::ostringstream out;
  out << format(
      "\nHonest alarms and re-acquisition (trackers that report a state). wrong: frames with IoU < %.1f; "
      "as tracking: of those, reported \"tracking\"; loss: runs that declared \"lost\"/\"searching\"; "
      "back: of those, runs with IoU >= %.1f after the first loss; found: frames after the first "
      "loss with IoU >= %.1f, all and with the target in view (>= half its box in the frame)\n",
      kWrongIou, kFoundIou, kFoundIou);
  out << format("%-40s %-4s %4s %20s %5s %5s %20s %20s\n", "", "", "runs", "as tracking / wrong", "loss",
                "back", "found / after loss", "found, in view");
  bool anyRow = false;
  for (const Column &c : columns(table))
    for (bool sre : {false, true}) {
      if (sre && !table.sre()) continue;
      bool any = false;
      const AlarmFigures a = pooledAlarms(table, c.tracker, c.format, sre, &any);
      if (!any) continue;
      anyRow = true;
      out << format("%-40.40s %-4s %4d %20s %5d %5d %20s %20s\n",
                    columnName(table, c.tracker, c.format).c_str(), sre ? "SRE" : "OPE", a.runs,
                    share(a.wrongTracking, a.wrongFrames).c_str(), a.lossRuns, a.reacquiredRuns,
                    share(a.afterLossFound, a.afterLossFrames).c_str(),
                    share(a.afterLossInViewFound, a.afterLossInView).c_str());
    }
  return anyRow ? out.str() : "";
}

}  // namespace

double opeAuc(const Cell &cell) {
  return !cell.starts.empty() && cell.starts[0].ok ? cell.starts[0].score.auc : kNan;
}

double sreAuc(const Cell &cell) {
  double sum = 0;
  int count = 0;
  for (std::size_t i = 1; i < cell.starts.size(); ++i)
    if (cell.starts[i].ok) sum += cell.starts[i].score.auc, ++count;
  return count > 0 ? sum / count : kNan;
}

HalfMeans halfMeans(const RobustnessTable &table, std::size_t tracker, std::size_t fmt, bool sre) {
  double tune = 0, confirm = 0, all = 0;
  HalfMeans means;
  for (std::size_t s = 0; s < table.sequences.size(); ++s) {
    const Cell &cell = table.cells[s][tracker][fmt];
    const double auc = sre ? sreAuc(cell) : opeAuc(cell);
    if (std::isnan(auc)) continue;
    const std::string half = halfOf(table.sequences[s]);
    if (half == "tune") tune += auc, ++means.tuneCount;
    if (half == "confirm") confirm += auc, ++means.confirmCount;
    all += auc;
    ++means.allCount;
  }
  means.tune = means.tuneCount > 0 ? tune / means.tuneCount : kNan;
  means.confirm = means.confirmCount > 0 ? confirm / means.confirmCount : kNan;
  means.all = means.allCount > 0 ? all / means.allCount : kNan;
  return means;
}

std::string robustnessReport(const RobustnessTable &table) {
  std::string report = perSequenceTable(table) + meansTable(table);
  if (table.sre()) report += perStartTable(table);
  if (table.formats.size() > 1) report += formatSpread(table);
  if (table.formats.size() > 1 || table.sre()) report += flags(table);
  return report + alarmsTable(table);
}

}  // namespace colortrack::eval
