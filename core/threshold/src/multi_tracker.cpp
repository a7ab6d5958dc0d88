// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/multi_tracker.hpp"

#include "colortrack/blob_split.hpp"
#include "colortrack/round_split.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>

namespace colortrack {

namespace {

// Cost of a pair outside the gate: large enough that the solver only uses it when nothing else is left.
constexpr double kForbidden = 1e9;
// How fast the box's aspect ratio follows the blobs (the Kalman state has one size, not two).
constexpr double kAspectRate = 0.3;
constexpr double kAreaRate = 0.5;
// For this many frames after its object was last seen, a track may also take a blob near where it was seen.
constexpr int kLastSeenFrames = 2;
// Frames a track may ride inside another object's blob without counting misses: long enough for one object
// to pass over another, not so long that a track whose object has gone lives on inside a neighbour.
constexpr int kMaxMergedFrames = 40;
// How far (px per frame) from where it left an object may come back in and still be taken for the same.
constexpr double kExitDrift = 2.0;
// A track's share of a split blob corrects it only when it is at least this part of the track's area; a
// smaller share (an object almost wholly behind another) says little about where it is.
constexpr double kMinShare = 0.25;
// Frames over which a track's measured positions give the mean velocity it may start coasting with.
constexpr double kPathFrames = 8;
// How far (px per frame) the filter's velocity may be from that mean before it counts as a jump: more than
// noise and the steady acceleration of a rolling ball make.
constexpr double kVelocityJump = 1.5;

}  // namespace

struct MultiTracker::Track {
  KalmanFilter9 filter;
  int id = 0;
  bool confirmed = false;
  bool measured = false;     // corrected by a blob this frame
  double referenceSide = 1;  // sqrt(box area) at acquisition: scale 1
  double aspect = 1;         // box width / height, smoothed
  double area = 0;           // smoothed blob area
  double lastArea = 0;
  double lastScale = 1;  // the scale last measured on a blob of its own
  double score = 0;
  int hits = 0, misses = 0;
  cv::Point2d lastSeen;            // the centroid of the last blob that fed the track
  int mergedFrames = 0;            // frames coasted inside a merged blob since last measured
  bool left = false;               // coasting, and its prediction has left the frame
  std::optional<int> returningId;  // the id of the track whose object this one seems to be, back in the frame
  KalmanFilter9 beforePrediction;  // the filter before this frame's prediction
  bool measuredBefore = false;     // measured in the previous frame
  double sigmaAfterMeasured = 0;   // position sigma of the prediction made one frame after a measurement
  double clock = 0;                // frames since the track started
  std::deque<std::pair<double, cv::Point2d>> path;  // (clock, centroid) measured over the last kPathFrames

  double side() const { return filter.scale() * referenceSide; }
  cv::Size2d size() const {
    const double root = std::sqrt(std::max(aspect, 1e-3));
    return cv::Size2d(std::max(1.0, side() * root), std::max(1.0, side() / root));
  }
};

int primaryIndex(const std::vector<TrackedObject> &objects) {
  int best = -1;
  for (int i = 0; i < static_cast<int>(objects.size()); ++i)
    if (best < 0 || objects[i].area > objects[best].area) best = i;
  return best;
}

MultiTracker::MultiTracker() = default;
MultiTracker::MultiTracker(const MultiTrackerSettings &settings) : settings_(settings) {}
MultiTracker::~MultiTracker() = default;
MultiTracker::MultiTracker(const MultiTracker &) = default;
MultiTracker &MultiTracker::operator=(const MultiTracker &) = default;
MultiTracker::MultiTracker(MultiTracker &&) noexcept = default;
MultiTracker &MultiTracker::operator=(MultiTracker &&) noexcept = default;

void MultiTracker::setSettings(const MultiTrackerSettings &settings) {
  settings_ = settings;
  for (Track &t : tracks_) t.filter.setParams(settings.kalman);
}

void MultiTracker::reset() {
  tracks_.clear();
  exits_.clear();
}

void MultiTracker::predict(Track &track, cv::Size frame, double dt) const {
  track.beforePrediction = track.filter;
  track.measuredBefore = track.measured;
  track.clock += dt;
  // A track not measured last frame (coasting or merged) keeps velocity and size but no acceleration.
  if (!track.measured) {
    track.filter.holdForCoasting();
  }
  track.filter.predict(dt);
  if (track.measured) track.sigmaAfterMeasured = std::max(track.filter.stdX(), track.filter.stdY());
  // A coasting track whose prediction runs out of the frame has followed its object out: it ends (see
  // update()) rather than waiting at the border, where it would grab the next object to come in.
  const double x = track.filter.x(), y = track.filter.y();
  track.left = !track.measured && (x < 0 || y < 0 || x >= frame.width || y >= frame.height);
}

double MultiTracker::gateRadius(const Track &track) const {
  const cv::Size2d size = track.size();
  const double halfDiagonal = 0.5 * std::hypot(size.width, size.height);
  double sigma = std::max(track.filter.stdX(), track.filter.stdY());
  // Without measurements the filter's uncertainty grows like the fifth power of time (white-noise jerk):
  // within ten frames a gate covers the frame, and a track hidden in a merged blob took far-away blobs that
  // were other tracks' objects. Hidden, its object may have gone at its speed in any direction (turned back,
  // say): the uncertainty it had one frame after its last measurement grows by that speed each frame.
  if (track.mergedFrames > 0)
    sigma = std::min(sigma, track.sigmaAfterMeasured +
                                std::hypot(track.filter.vx(), track.filter.vy()) * track.mergedFrames);
  return std::max(settings_.minGate, settings_.gateSize * halfDiagonal) + 3.0 * sigma +
         settings_.coastGrowth * halfDiagonal * track.misses;
}

bool MultiTracker::touchesBorder(const Blob &blob) const {
  return blob.box.x <= 0 || blob.box.y <= 0 || blob.box.x + blob.box.width >= frame_.width ||
         blob.box.y + blob.box.height >= frame_.height;
}

double MultiTracker::cost(const Track &track, const Blob &blob) const {
  const double gate = gateRadius(track);
  // From the prediction, or, for a track seen a moment ago on its own, from where it was seen: an object that
  // stopped or turned back is near there while the prediction runs on.
  double distance = std::hypot(blob.centroid.x - track.filter.x(), blob.centroid.y - track.filter.y());
  if (track.misses <= kLastSeenFrames && track.mergedFrames == 0)
    distance = std::min(distance, cv::norm(blob.centroid - track.lastSeen));
  if (distance > gate) return kForbidden;
  const double ratio = std::max(blob.area, 1.0) / std::max(track.area, 1.0);
  const double logLimit = std::log(std::max(settings_.maxAreaRatio, 1.0001));
  // A blob cut by the frame's edge (an object leaving or coming back) may be any amount smaller.
  const double logRatio = touchesBorder(blob) && ratio < 1 ? 0.0 : std::abs(std::log(ratio));
  if (logRatio > logLimit) return kForbidden;
  // Distance dominates; size breaks ties between blobs at similar distances.
  const double d = distance / gate, a = logRatio / logLimit;
  return d * d + 0.25 * a * a;
}

TrackedObject MultiTracker::report(const Track &track) const {
  TrackedObject o;
  o.id = track.id;
  o.confirmed = track.confirmed;
  o.state = track.measured ? TrackState::Tracking : TrackState::Coasting;
  o.centre = cv::Point2d(track.filter.x(), track.filter.y());
  const cv::Size2d size = track.size();
  o.box = cv::Rect2d(o.centre.x - size.width / 2, o.centre.y - size.height / 2, size.width, size.height);
  o.area = track.lastArea;
  o.score = track.measured ? track.score : 0;
  o.scale = track.filter.scale();
  o.vx = track.filter.vx();
  o.vy = track.filter.vy();
  o.hits = track.hits;
  o.misses = track.misses;
  return o;
}

// Objects that touch when they appear make one blob, which would give them one track until they part. A blob
// that at most one reported track is predicted in, and whose shape is several round objects, is taken as
// those objects. A blob that two or more reported tracks share is left whole: they split it by their
// predictions (correctShared), which know which object is which; a split by shape there, flickering as the
// objects overlap more or less, swaps their ids.
std::vector<Blob> MultiTracker::splitNewObjects(const std::vector<Blob> &blobs,
                                                const BlobLabels &labels) const {
  if (labels.empty()) return blobs;
  std::vector<Blob> out;
  for (const Blob &blob : blobs) {
    const cv::Rect2d box(blob.box);
    const auto known = std::count_if(tracks_.begin(), tracks_.end(), [&](const Track &t) {
      return t.confirmed && box.contains(cv::Point2d(t.filter.x(), t.filter.y()));
    });
    std::vector<Blob> parts;
    if (known <= 1) parts = splitRound(blob, labels, settings_.minObjectArea);
    if (parts.empty())
      out.push_back(blob);
    else
      out.insert(out.end(), parts.begin(), parts.end());
  }
  return out;
}

// Assigns the still-free blobs to the tracks that are (or are not yet) confirmed, by minimum total cost.
void MultiTracker::associate(const std::vector<Blob> &blobs, bool confirmed,
                             std::vector<int> &blobTrack) const {
  std::vector<int> rows, cols;
  for (int i = 0; i < static_cast<int>(tracks_.size()); ++i)
    if (tracks_[i].confirmed == confirmed) rows.push_back(i);
  for (int j = 0; j < static_cast<int>(blobs.size()); ++j)
    if (blobTrack[j] < 0) cols.push_back(j);
  if (rows.empty() || cols.empty()) return;
  cv::Mat costs(static_cast<int>(rows.size()), static_cast<int>(cols.size()), CV_64FC1);
  for (int r = 0; r < costs.rows; ++r)
    for (int c = 0; c < costs.cols; ++c) costs.at<double>(r, c) = cost(tracks_[rows[r]], blobs[cols[c]]);
  const std::vector<int> assignment = solveAssignment(costs);
  for (int r = 0; r < costs.rows; ++r)
    if (assignment[r] >= 0 && costs.at<double>(r, assignment[r]) < kForbidden)
      blobTrack[cols[assignment[r]]] = rows[r];
}

// Two objects crossing make one blob. When the blob is much larger than the track it was given (two objects
// of similar size), its centroid lies between them: correcting that track would drag it towards the other
// object and swap ids when they part, so both tracks ride on their predictions. When a small object passes
// over a large one, the blob is the large one's and corrects it, and the small one's track, whose prediction
// lies inside the blob, rides on its prediction. Either way the objects are still seen, so these tracks
// coast without counting misses (for a while: see kMaxMergedFrames).
void MultiTracker::findMerges(const std::vector<Blob> &blobs, const std::vector<int> &blobTrack,
                              std::vector<char> &merged, std::vector<int> &occludedIn) const {
  merged.assign(blobs.size(), 0);
  occludedIn.assign(tracks_.size(), -1);
  for (int j = 0; j < static_cast<int>(blobs.size()); ++j) {
    const int owner = blobTrack[j];
    if (owner < 0) continue;
    const bool muchLarger = blobs[j].area >= settings_.mergeAreaRatio * tracks_[owner].area;
    const cv::Rect2d blobBox(blobs[j].box);
    for (int i = 0; i < static_cast<int>(tracks_.size()); ++i) {
      if (i == owner || !tracks_[i].confirmed) continue;
      if (std::find(blobTrack.begin(), blobTrack.end(), i) != blobTrack.end()) continue;  // has its own blob
      const cv::Point2d predicted(tracks_[i].filter.x(), tracks_[i].filter.y());
      if (muchLarger && cv::norm(blobs[j].centroid - predicted) < gateRadius(tracks_[i])) {
        merged[j] = 1;
        occludedIn[owner] = occludedIn[i] = j;
      } else if (blobBox.contains(predicted)) {
        occludedIn[i] = j;
      }
    }
  }
}

// A blob shared by its owner and the tracks occluded in it, split between them by their pixels: each track
// whose share is large enough is corrected by it; the others ride on their predictions. False when there is
// nothing to split (no other track in the blob, or no pixels).
bool MultiTracker::correctShared(int blob, const std::vector<Blob> &blobs, const BlobLabels &labels,
                                 int owner, const std::vector<int> &occludedIn) {
  // Only tracks predicted inside the blob's box share it: one merely near it (a long-coasting track with a
  // wide gate) has no claim on its pixels.
  const cv::Rect2d box(blobs[blob].box);
  std::vector<int> members{owner};
  for (int i = 0; i < static_cast<int>(tracks_.size()); ++i)
    if (i != owner && occludedIn[i] == blob &&
        box.contains(cv::Point2d(tracks_[i].filter.x(), tracks_[i].filter.y())))
      members.push_back(i);
  if (members.size() < 2 || labels.empty()) return false;
  std::vector<SplitSeed> seeds;
  for (int i : members)
    seeds.push_back(
        SplitSeed{cv::Point2d(tracks_[i].filter.x(), tracks_[i].filter.y()), tracks_[i].side() / 2});
  const std::vector<BlobShare> shares = splitBlob(blobs[blob], labels, seeds);
  for (size_t m = 0; m < members.size(); ++m) {
    Track &t = tracks_[members[m]];
    // Only a share with enough pixels that no other object could have made says where this object is: one
    // wholly behind another leaves a share of the other's pixels, which would drag it along.
    if (shares[m].ownArea < kMinShare * t.area) continue;
    Blob part = shares[m].blob;
    // The share's centroid lies off the object's centre when a neighbour covers part of it; the edge away
    // from the nearest neighbour is still the object's own, so the centre is placed a half size from it.
    size_t nearest = m == 0 ? 1 : 0;
    for (size_t o = 0; o < seeds.size(); ++o)
      if (o != m &&
          cv::norm(seeds[o].centre - seeds[m].centre) < cv::norm(seeds[nearest].centre - seeds[m].centre))
        nearest = o;
    const cv::Size2d size = t.size();
    const cv::Point2d away = seeds[m].centre - seeds[nearest].centre;
    if (part.box.width < 0.9 * size.width)
      part.centroid.x =
          away.x >= 0 ? part.box.x + part.box.width - size.width / 2 : part.box.x + size.width / 2;
    if (part.box.height < 0.9 * size.height)
      part.centroid.y =
          away.y >= 0 ? part.box.y + part.box.height - size.height / 2 : part.box.y + size.height / 2;
    correct(t, part, true);
  }
  return true;
}

// The filter's velocity follows a sudden jump of the object in the image within two frames (the camera's own
// turn makes one). Coasting on it would carry the track away from an object that has not moved, so where the
// velocity is far from its mean over the last kPathFrames, a track starts coasting at the slower of the two
// (per axis; at rest when they disagree in direction, as after a bounce).
void MultiTracker::coastingVelocity(Track &t) const {
  if (t.path.size() < 2) return;
  const double span = t.path.back().first - t.path.front().first;
  if (span < kPathFrames / 2) return;
  const cv::Point2d mean = (t.path.back().second - t.path.front().second) / span;
  const auto slower = [](double filtered, double windowed) {
    if (std::abs(filtered - windowed) <= kVelocityJump) return filtered;
    if (filtered * windowed <= 0) return 0.0;
    return std::abs(filtered) < std::abs(windowed) ? filtered : windowed;
  };
  t.filter.setVelocity(slower(t.filter.vx(), mean.x), slower(t.filter.vy(), mean.y));
}

void MultiTracker::correct(Track &t, const Blob &b, bool shared) {
  t.lastSeen = b.centroid;
  t.path.emplace_back(t.clock, b.centroid);
  while (t.path.front().first < t.clock - kPathFrames) t.path.pop_front();
  if (shared) {
    // Part of the object may be hidden: its size is kept (a shrinking share would shrink the track, which
    // would then take fewer pixels still), and so is its velocity: the share's centroid moves as the other
    // object covers more or less of it, and a velocity learnt from that would carry the track away from
    // its object when the blobs merge and it coasts.
    t.filter.correctPosition(b.centroid.x, b.centroid.y, t.lastScale);
  } else {
    const double side = std::sqrt(static_cast<double>(b.box.area()));
    t.lastScale = side / t.referenceSide;
    t.filter.correct(b.centroid.x, b.centroid.y, t.lastScale);
    t.aspect += kAspectRate * (static_cast<double>(b.box.width) / std::max(1, b.box.height) - t.aspect);
    t.area += kAreaRate * (b.area - t.area);
    t.lastArea = b.area;
  }
  t.score = b.fill;
  t.measured = true;
  ++t.hits;
  t.misses = 0;
  t.mergedFrames = 0;
  if (!t.confirmed && t.hits >= settings_.confirmFrames) confirm(t);
}

// A new blob may be an object that left the frame a moment ago (no more than maxCoastFrames, the time a track
// may go unseen), coming back in where it left and about its size: it is given that track's id when it is
// confirmed. Otherwise it gets a new id.
std::optional<int> MultiTracker::returningId(const Blob &blob) {
  auto best = exits_.end();
  double bestDistance = 0;
  for (auto e = exits_.begin(); e != exits_.end(); ++e) {
    // Coming in, the object is cut by the frame's edge: it may be any amount smaller, not larger.
    const double ratio = blob.area / std::max(1.0, e->area);
    const double distance = cv::norm(blob.centroid - e->position);
    if ((ratio < 0.5 && !touchesBorder(blob)) || ratio > 2.0 || distance > 2 * e->side + kExitDrift * e->age)
      continue;
    if (best == exits_.end() || distance < bestDistance) {
      best = e;
      bestDistance = distance;
    }
  }
  if (best == exits_.end()) return std::nullopt;
  const int id = best->id;
  exits_.erase(best);
  return id;
}

void MultiTracker::confirm(Track &t) {
  t.confirmed = true;
  t.id = t.returningId ? *t.returningId : nextId_++;
}

void MultiTracker::startTrack(const Blob &b) {
  Track t;
  t.filter.setParams(settings_.kalman);
  t.referenceSide = std::max(1.0, std::sqrt(static_cast<double>(b.box.area())));
  t.filter.init(b.centroid.x, b.centroid.y, 1.0);
  t.lastSeen = b.centroid;
  t.path.emplace_back(0.0, b.centroid);
  t.aspect = static_cast<double>(b.box.width) / std::max(1, b.box.height);
  t.area = t.lastArea = b.area;
  t.score = b.fill;
  t.measured = true;
  t.hits = 1;
  t.returningId = returningId(b);
  tracks_.push_back(t);
  if (settings_.confirmFrames <= 1) confirm(tracks_.back());
}

std::vector<TrackedObject> MultiTracker::update(const std::vector<Blob> &detected, cv::Size frame, double dt,
                                                const BlobLabels &labels) {
  frame_ = frame;
  for (Track &t : tracks_) {
    predict(t, frame, dt);
    t.measured = false;
  }
  const std::vector<Blob> blobs = splitNewObjects(detected, labels);

  // Confirmed tracks choose first, so a noise blob next to a real object never steals it; tentative tracks
  // get what is left; the rest start new tentative tracks.
  std::vector<int> blobTrack(blobs.size(), -1);
  associate(blobs, true, blobTrack);
  std::vector<char> merged;
  std::vector<int> occludedIn;
  findMerges(blobs, blobTrack, merged, occludedIn);
  associate(blobs, false, blobTrack);

  std::vector<char> used(blobs.size(), 0);
  for (int j = 0; j < static_cast<int>(blobs.size()); ++j) {
    const int owner = blobTrack[j];
    if (owner < 0) continue;
    used[j] = 1;
    if (merged[j] && correctShared(j, blobs, labels, owner, occludedIn)) continue;
    if (!merged[j]) correct(tracks_[owner], blobs[j]);  // a merged blob's owner coasts, see findMerges
  }
  // A track that has just lost its object coasts from where it was seen without the acceleration the filter
  // had then: right after a turn that estimate overshoots, and coasting would carry the error on.
  // Nor with a velocity that followed a jump in the image (see coastingVelocity).
  for (Track &t : tracks_)
    if (!t.measured && t.measuredBefore) {
      t.filter = t.beforePrediction;
      t.filter.dropAcceleration();
      coastingVelocity(t);
      t.filter.predict(dt);
    }
  for (int i = 0; i < static_cast<int>(tracks_.size()); ++i)
    if (!tracks_[i].measured && !(occludedIn[i] >= 0 && ++tracks_[i].mergedFrames <= kMaxMergedFrames))
      ++tracks_[i].misses;

  // Tentative tracks must be seen every frame; reported ones may coast for maxCoastFrames, and end when their
  // prediction leaves the frame (remembered for a while, in case the object comes back where it left).
  for (Exit &e : exits_) ++e.age;
  exits_.erase(std::remove_if(exits_.begin(), exits_.end(),
                              [&](const Exit &e) { return e.age > settings_.maxCoastFrames; }),
               exits_.end());
  for (const Track &t : tracks_)
    if (t.confirmed && t.left && t.misses <= settings_.maxCoastFrames)
      exits_.push_back(Exit{t.id, cv::Point2d(t.filter.x(), t.filter.y()), t.area, t.side(), 0});
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const Track &t) {
                                 return t.left ||
                                        (t.confirmed ? t.misses > settings_.maxCoastFrames : t.misses > 0);
                               }),
                tracks_.end());
  for (int j = 0; j < static_cast<int>(blobs.size()); ++j)
    if (!used[j]) startTrack(blobs[j]);

  std::vector<TrackedObject> out;
  for (const Track &t : tracks_)
    if (t.confirmed) out.push_back(report(t));
  std::sort(out.begin(), out.end(),
            [](const TrackedObject &a, const TrackedObject &b) { return a.id < b.id; });
  return out;
}

void MultiTracker::followCamera(cv::Point2d shift) {
  for (Track &t : tracks_) {
    t.filter.translate(shift.x, shift.y);
    t.lastSeen += shift;
    for (auto &[clock, centroid] : t.path) centroid += shift;
  }
  for (Exit &e : exits_) e.position += shift;
}

std::vector<TrackedObject> MultiTracker::allTracks() const {
  std::vector<TrackedObject> out;
  for (const Track &t : tracks_) out.push_back(report(t));
  return out;
}

}  // namespace colortrack
