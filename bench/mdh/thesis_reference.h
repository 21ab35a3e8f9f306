#pragma once
// The thesis's own figures for its eleven cases (tables 6.2 and 6.6), printed
// beside ours. Case order: CS D1 D2 DS1 DS2 MA1 MA2 NA A1 A2 A3.
#include <array>
#include <optional>
#include <string_view>

namespace mdhd::mdh::bench {

inline constexpr int kThesisCases = 11;
using CaseRow = std::array<double, kThesisCases>;

struct ThesisRuleset {
  std::string_view rules;  // as our ruleName() spells them, comma separated
  CaseRow subdivisions;    // table 6.2
};

// Every row of table 6.2 (the thesis's "FESF" is its typo for FEFS).
inline constexpr std::array<ThesisRuleset, 22> kTable62{{
    {"RS", {2893, 528, 508, 2448, 911, 707, 321, 31, 4, 16, 1}},
    {"CTD,RS", {4143, 4928, 4642, 16816, 10946, 683, 150, 43, 3, 14, 1}},
    {"SPT,RS", {1390, 276, 269, 1547, 843, 584, 147, 22, 1, 11, 1}},
    {"FFS,RS", {282, 159, 132, 1246, 286, 562, 224, 12, 10, 5, 2}},
    {"FFS,CTD,RS", {285, 165, 134, 1216, 284, 538, 209, 12, 10, 5, 2}},
    {"FFS,SPT,RS", {279, 155, 133, 1203, 286, 543, 210, 12, 10, 5, 2}},
    {"FFS,CTD,SPT,RS", {285, 165, 134, 1231, 284, 539, 201, 12, 10, 5, 2}},
    {"FFS,SPT,CTD,RS", {279, 157, 133, 1203, 284, 539, 202, 12, 10, 5, 2}},
    {"FEFS,RS", {410, 176, 149, 1208, 313, 641, 240, 15, 8, 22, 1}},
    {"FEFS,CTD,RS", {366, 193, 101, 1151, 356, 626, 138, 15, 8, 19, 1}},
    {"FEFS,SPT,RS", {363, 143, 123, 1052, 278, 543, 148, 10, 1, 13, 1}},
    {"FEFS,CTD,SPT,RS", {358, 120, 96, 1163, 307, 560, 128, 12, 1, 12, 1}},
    {"FEFS,SPT,CTD,RS", {342, 130, 125, 1057, 285, 531, 122, 10, 1, 14, 1}},
    {"FEFS-FFS,RS", {345, 169, 142, 1212, 314, 637, 174, 15, 8, 17, 1}},
    {"FEFS-FFS,CTD,RS", {314, 172, 79, 1148, 339, 635, 174, 15, 8, 17, 1}},
    {"FEFS-FFS,SPT,RS", {384, 147, 125, 1067, 279, 552, 161, 10, 1, 14, 1}},
    {"FEFS-FFS,CTD,SPT,RS", {314, 103, 81, 1109, 293, 550, 163, 12, 1, 12, 1}},
    {"FEFS-FFS,SPT,CTD,RS", {379, 131, 125, 1059, 289, 547, 158, 10, 1, 15, 1}},
    {"SPT,FEFS-FFS,RS", {929, 220, 152, 1228, 399, 554, 136, 28, 1, 15, 1}},
    {"SPT,CTD,RS", {709, 478, 373, 1919, 1393, 537, 122, 30, 1, 15, 1}},
    {"SPT,FEFS-FFS,CTD,RS", {539, 205, 127, 1228, 458, 549, 133, 28, 1, 15, 1}},
    {"SPT,CTD,FEFS-FFS,RS", {701, 468, 370, 1906, 1373, 540, 120, 30, 1, 15, 1}},
}};

struct ThesisMemory {
  std::string_view rules;
  CaseRow totalMb;         // Total (Mb)
  CaseRow pointerGridPct;  // Total (% of 3D pointer grid)
  CaseRow embeddedPct;     // Embedded Height/Normal Samples (% of Total)
};

// Table 6.6, the three rulesets it covers.
inline constexpr std::array<ThesisMemory, 3> kTable66{{
    {"FEFS-FFS,CTD,SPT,RS",
     {17.80, 16.59, 5.64, 14.74, 11.39, 2.87, 2.61, 0.59, 0.54, 3.11, 0.55},
     {31.82, 5.92, 2.13, 5.38, 4.22, 24.62, 22.90, 6.92, 6.24, 4.66, 6.35},
     {64.74, 70.05, 42.14, 44.31, 43.17, 73.72, 74.93, 36.07, 43.46, 44.61, 53.30}},
    {"FEFS-FFS,SPT,CTD,RS",
     {17.75, 16.69, 5.82, 14.08, 10.95, 2.80, 2.54, 0.57, 0.54, 3.20, 0.55},
     {31.70, 5.95, 2.20, 5.13, 4.05, 24.15, 22.35, 6.68, 6.24, 4.79, 6.35},
     {64.30, 70.50, 43.60, 47.45, 44.24, 71.68, 74.92, 36.97, 43.46, 61.26, 53.30}},
    {"RS",
     {28.39, 19.63, 8.53, 20.82, 16.32, 3.45, 3.30, 0.72, 0.67, 3.76, 0.55},
     {46.33, 6.98, 3.22, 7.55, 6.02, 28.90, 28.34, 8.43, 7.76, 5.62, 6.35},
     {47.69, 64.23, 34.30, 37.54, 34.05, 62.29, 60.34, 32.92, 36.75, 36.41, 53.30}},
}};

// Split shares with (FEFS-FFS, CTD, SPT, RS), section 6.2.
inline constexpr double kThesisIndirectPct = 40.20;
inline constexpr double kThesisDirectPct = 44.76;
inline constexpr double kThesisSignConflictPct = 14.94;

inline const ThesisMemory* thesisMemory(std::string_view rules) {
  for (const auto& m : kTable66)
    if (m.rules == rules) return &m;
  return nullptr;
}

inline std::optional<CaseRow> thesisSubdivisions(std::string_view rules) {
  for (const auto& r : kTable62)
    if (r.rules == rules) return r.subdivisions;
  return std::nullopt;
}

}  // namespace mdhd::mdh::bench
