#include "colortrack/area_resample.hpp"

#include <algorithm>
#include <vector>

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

// Each output pixel of row sums `rows` (output rows, source columns x C values) from the source pixels its
// column interval covers, rounded back to 8 bits. C is a template parameter so the channel loops unroll.
template <int C>
void shrinkColumns(const std::vector<float> &rows, int rowValues, const std::vector<Tap> &taps,
                   const std::vector<int> &first, cv::Mat &out) {
  for (int y = 0; y < out.rows; ++y) {
    const float *sum = &rows[static_cast<size_t>(y) * rowValues];
    uchar *o = out.ptr<uchar>(y);
    for (int x = 0; x < out.cols; ++x) {
      float value[C] = {};
      for (int t = first[x]; t < first[x + 1]; ++t) {
        const float *pixel = sum + taps[t].source * C;
        for (int c = 0; c < C; ++c) value[c] += taps[t].weight * pixel[c];
      }
      for (int c = 0; c < C; ++c) o[x * C + c] = cv::saturate_cast<uchar>(value[c]);
    }
  }
}

}  // namespace

// Written here rather than calling cv::resize(INTER_AREA): for a ratio that is not a whole number OpenCV 4.6
// takes a generic path that works one channel value at a time, and the fused method's window (typically
// 1.2-2 source pixels per output pixel) cost a quarter of its frame there. Separable (rows, then columns),
// with the row pass vectorised over whole rows, this is several times faster and gives the same averages.
void shrinkByArea(const cv::Mat &source, cv::Size size, cv::Mat &out) {
  CV_Assert(source.depth() == CV_8U && source.channels() <= 4 && size.width >= 1 && size.height >= 1 &&
            size.width <= source.cols && size.height <= source.rows);
  const int channels = source.channels(), rowValues = source.cols * channels;
  thread_local std::vector<Tap> rowTaps, columnTaps;
  thread_local std::vector<int> rowFirst, columnFirst;
  thread_local std::vector<float> rows;
  areaTaps(source.rows, size.height, rowTaps, rowFirst);
  areaTaps(source.cols, size.width, columnTaps, columnFirst);

  // Rows: output row y is the weighted sum of the source rows its interval covers, whole rows at a time
  // (__restrict__: 8-bit pixels may otherwise alias the sums, which keeps the compiler from vectorising).
  rows.assign(static_cast<size_t>(size.height) * rowValues, 0.0f);
  for (int y = 0; y < size.height; ++y) {
    float *__restrict__ sum = &rows[static_cast<size_t>(y) * rowValues];
    for (int t = rowFirst[y]; t < rowFirst[y + 1]; ++t) {
      const uchar *__restrict__ in = source.ptr<uchar>(rowTaps[t].source);
      const float w = rowTaps[t].weight;
      for (int v = 0; v < rowValues; ++v) sum[v] += w * in[v];
    }
  }

  out.create(size, source.type());
  switch (channels) {
    case 1:
      return shrinkColumns<1>(rows, rowValues, columnTaps, columnFirst, out);
    case 2:
      return shrinkColumns<2>(rows, rowValues, columnTaps, columnFirst, out);
    case 3:
      return shrinkColumns<3>(rows, rowValues, columnTaps, columnFirst, out);
    default:
      return shrinkColumns<4>(rows, rowValues, columnTaps, columnFirst, out);
  }
}

}  // namespace colortrack
