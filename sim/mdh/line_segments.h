#pragma once
// Interval arithmetic along one grid line, in grid units. Stock segments are
// closed; tool intervals are open, so a vertex exactly on the tool's surface
// stays solid (a flat end mill whose face sits on a grid level leaves that
// level's vertices in place).
#include <cstdint>
#include <span>
#include <vector>

namespace mdhd::mdh {

struct Span {
  double lo = 0.0;
  double hi = 0.0;
};

// out = segments minus the open tool intervals (both sorted, disjoint).
void subtractOpen(std::span<const Span> segments, std::span<const Span> tool,
                  std::vector<Span>& out);

// Decodes the solid segments of a line from vertex states and edge crossings.
// `solid[i]` is vertex first+i; `crossing[i]` the surface point on edge
// (first+i, first+i+1) where the two states differ.
void segmentsFromSamples(int first, std::span<const std::uint8_t> solid,
                         std::span<const double> crossing, std::vector<Span>& out);

// A tool interval that reaches less than this (grid units) into a line's solid
// leaves it as it was: the same surface computed from two sweeps (a step's end
// pose and the next step's start) differs in the last bits, and a cut must not
// move a crossing by that much in one cell and not in its neighbour (Stock::cut
// with a fresh region looks at fewer lines than the tool's box holds).
inline constexpr double kToolSlack = 1e-9;

// Whether x lies strictly inside one of the open tool intervals (sorted, disjoint).
bool strictlyInside(std::span<const Span> tool, double x);

// Where the surface crosses the grid edge [k, k+1] of a line after a cut,
// given the end states before (o0, o1) and after (n0, n1, which must differ),
// the crossing before (oc, if o0 != o1) and the tool's open intervals along
// the line: the end of what is left of the edge's solid next to its solid
// end. Every cell holding the edge computes its crossing here, whatever its
// direction, so they all store the same number. When the line's intervals
// disagree with the end states (these may come from another line, a tangency
// within rounding) the surface is put at the solid end. The result lies in
// [solid end, empty end): a parent height and an embedded height of the same
// edge are then the same number.
double edgeCrossingAfterCut(bool o0, bool o1, double oc, bool n0, bool n1, int k,
                            std::span<const Span> tool);

}  // namespace mdhd::mdh
