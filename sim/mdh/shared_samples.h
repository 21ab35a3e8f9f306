#pragma once
// What two leaves say about the grid vertices and grid edges they share.
//
// Neighbouring cells share their boundary vertices (the thesis's duplicate
// boundary samples). The engine guarantees that every leaf holding a grid
// vertex gives it the same state and every leaf holding a grid edge gives it
// the same crossing, so a mesh (or any reader) may ask any of them. A plain
// heightmap stores no crossings across its direction (they are interpolated
// per cell: thesis 4.1's discontinuous seams) and a resample turns such
// interpolated crossings into its new parent heights, so for plain heightmaps
// only the states, and so where crossings are, are shared.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "sim/mdh/stock.h"

namespace mdhd::mdh {

using GridPoint = std::array<int, 3>;

// The state of grid vertex p (inside the leaf's box) as the leaf stores it.
bool leafSolidAt(const LeafView& leaf, const GridPoint& p);

// The crossing on the grid edge from p along `axis` (both ends inside the
// leaf's box) as the leaf stores it, an absolute grid coordinate; NaN where
// the two ends have the same state. `sampled` (optional) tells whether it is a
// stored sample (parent or embedded height) rather than interpolated.
double leafCrossingAt(const LeafView& leaf, const GridPoint& p, int axis, bool* sampled = nullptr);

struct SampleDisagreement {
  GridPoint vertex{};
  int axis = -1;  // -1: the vertex's state; 0..2: the edge from vertex along axis
  GridBox first, second;
  double firstValue = 0.0, secondValue = 0.0;  // state (0/1) or crossing (NaN: none)
  std::string describe() const;
};

// Every shared vertex and shared edge on which two leaves disagree (at most
// `limit` of them). Empty for every stock the engine produces.
std::vector<SampleDisagreement> sharedSampleDisagreements(const Stock& stock,
                                                          std::size_t limit = 16);

}  // namespace mdhd::mdh
