// SPDX-License-Identifier: LGPL-2.1-or-later
// How much the tracked box still looks like the target at the start (issue 46: a check against the
// never-updated first appearance beside the adapted model). The learners adapt to whatever the box holds, so
// a track that slid onto a team-mate or a passer-by keeps its usual peak and colour cues; the start's colour
// histogram does not adapt, and its match falls. Used to rank frames (the score), not to decide the state:
// appearances change on their own too (a walker into shade), so no bar on it separates right from wrong.
#pragma once

namespace colortrack {

class StartLikeness {
 public:
  // Forgets the reference (a new start).
  void reset();
  // The match value (TemplateModel::matchStart) of this frame's box.
  void observe(double match);
  // What a score is multiplied by: (last match / the start's usual match)^kWeight, at most 1; 1 until the
  // first match.
  double factor() const;

 private:
  double referenceSum_ = 0;  // sum of the first matches, whose mean is the start's usual match
  int referenceCount_ = 0;
  double last_ = -1;  // the last match; negative: none yet
};

}  // namespace colortrack
