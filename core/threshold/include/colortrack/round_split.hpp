// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode: one blob that is several round objects side by side. Balls that touch or overlap when they
// first appear make one blob, and no track yet tells them apart; their shape does (a disc each, joined by a
// narrower neck).
#pragma once

#include <vector>

#include "colortrack/blob_split.hpp"
#include "colortrack/blobs.hpp"

namespace colortrack {

// The discs `blob` is made of, when it is two or more round objects: each disc the largest one inscribed
// around a peak of the blob's distance transform, neighbouring discs joined by a neck clearly narrower than
// either, and the discs together covering nearly the whole blob. Empty when the blob is one object, or not
// round objects at all (a partly hidden object, an irregular shape). Radii under minRadius (frame pixels)
// do not count as objects.
std::vector<SplitSeed> roundParts(const Blob &blob, const BlobLabels &labels, double minRadius);

// The blobs `blob` is, one per object, when roundParts() finds it several objects of at least minArea
// (frame pixels) each, its pixels shared by splitBlob(); else empty.
// Each part is placed and sized by its disc (its box clipped to the blob's), with its own pixel count.
std::vector<Blob> splitRound(const Blob &blob, const BlobLabels &labels, int minArea);

}  // namespace colortrack
