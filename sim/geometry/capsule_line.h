#pragma once
// The stretch of a line inside a capsule (the points within `radius` of a segment), in
// closed form: what a ball swept along a straight move fills.
namespace mdhd::geom {

// The line is origin + t e (e a unit vector), the segment runs from its start along the
// unit d for `length` >= 0; the scalars are the dot products of the line's origin m,
// measured from the segment's start, with e, d and itself, and e . d. [lo, hi] in t,
// false if the line misses it or only touches it.
bool capsuleExtent(double me, double md, double mm, double ed, double length, double radius,
                   double& lo, double& hi);

}  // namespace mdhd::geom
