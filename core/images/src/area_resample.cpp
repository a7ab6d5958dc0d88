// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/area_resample.hpp"

#include <algorithm>
#include <vector>

#include <opencv2/core/utility.hpp>

namespace colortrack {

namespace {

// Source index and weight of one input to one output along an axis.
struct Tap {
  int source;
  float weight;
};

// For each of `outputs` outputs along an axis of `inputs` pixels: the inputs its interval
// [i * scale, (i + 1) * scale) overlaps, weighted by the overlap over the interval's length. `first[i]` ..
// `first[i + 1]` index the taps of output i.
void areaTaps(int inputs, int outputs, std::vector<Tap> &taps, std::vector<int> &first) {
  const double scale = static_cast<double>(inputs) / outputs;
  taps.clear();
  first.assign(outputs + 1, 0);
  for (int i = 0; i < outputs; ++i) {
    first[i] = static_cast<int>(taps.size());
    const double begin = i * scale, end = std::min<double>(inputs, (i + 1) * scale);
    for (int s = static_cast<int>(begin); s < end; ++s) {
      const double overlap = std::min<double>(s + 1, end) - std::max<double>(s, begin);
      if (overlap > 1e-9) taps.push_back({s, static_cast<float>(overlap / scale)});
    }
  }
  first[outputs] = static_cast<int>(taps.size());
}

// Output row (or, on a transposed image, column) i as the weighted sum of the input rows its interval covers,
// a whole row at a time so the compiler vectorises it. `In` is uchar for the source, float for row sums.
// Only outputs `outputs.start` .. `outputs.end` - 1, into rows 0 .. of `output`.
template <typename In>
void combineRows(const cv::Mat &input, const std::vector<Tap> &taps, const std::vector<int> &first,
                 cv::Range outputs, cv::Mat &output) {
  const int values = input.cols * input.channels();
  for (int i = outputs.start; i < outputs.end; ++i) {
    float *__restrict sum = output.ptr<float>(i - outputs.start);
    // The first tap is stored rather than added to zero: the same value, as w * in is never -0 (weights are
    // positive, inputs non-negative).
    const int begin = first[i], end = first[i + 1];
    if (begin == end) {
      std::fill(sum, sum + values, 0.0f);
      continue;
    }
    {
      const In *__restrict in = input.ptr<In>(taps[begin].source);
      const float w = taps[begin].weight;
      for (int v = 0; v < values; ++v) sum[v] = w * in[v];
    }
    for (int t = begin + 1; t < end; ++t) {
      const In *__restrict in = input.ptr<In>(taps[t].source);
      const float w = taps[t].weight;
      for (int v = 0; v < values; ++v) sum[v] += w * in[v];
    }
  }
}

}  // namespace

// Written here rather than calling cv::resize(INTER_AREA): for a ratio that is not a whole number OpenCV 4.6
// takes a generic path that works one channel value at a time, and the fused method's window (typically
// 1.2-2 source pixels per output pixel) cost a quarter of its frame there. Separable (rows, then columns),
// both passes vectorised over whole rows, this is several times faster and gives the same averages.
void shrinkByArea(const cv::Mat &source, cv::Size size, cv::Mat &out) {
  CV_Assert(source.depth() == CV_8U && source.channels() <= 4 && size.width >= 1 && size.height >= 1 &&
            size.width <= source.cols && size.height <= source.rows);
  const int channels = source.channels();
  // (References, so that the pool's threads read this thread's taps, not their own.)
  thread_local std::vector<Tap> rowTapsStore, columnTapsStore;
  thread_local std::vector<int> rowFirstStore, columnFirstStore;
  std::vector<Tap> &rowTaps = rowTapsStore, &columnTaps = columnTapsStore;
  std::vector<int> &rowFirst = rowFirstStore, &columnFirst = columnFirstStore;
  areaTaps(source.rows, size.height, rowTaps, rowFirst);
  areaTaps(source.cols, size.width, columnTaps, columnFirst);

  // Rows, then columns as rows of the transposed row sums (pixels stay whole: CV_32FC(n) transposes by
  // pixel). Each output value is sum_t weight_t * input_t in tap order, as OpenCV sums them. Two halves of
  // the output rows on OpenCV's thread pool: each value is computed the same way in either half.
  out.create(size, source.type());
  cv::parallel_for_(
      cv::Range(0, size.height),
      [&](const cv::Range &outputRows) {
        thread_local cv::Mat rows, transposed, columns, result;
        rows.create(outputRows.size(), source.cols, CV_32FC(channels));
        combineRows<uchar>(source, rowTaps, rowFirst, outputRows, rows);
        cv::transpose(rows, transposed);
        columns.create(size.width, outputRows.size(), CV_32FC(channels));
        combineRows<float>(transposed, columnTaps, columnFirst, cv::Range(0, size.width), columns);
        cv::transpose(columns, result);
        cv::Mat part = out.rowRange(outputRows.start, outputRows.end);
        result.convertTo(part, source.type());
      },
      2);
}

}  // namespace colortrack
