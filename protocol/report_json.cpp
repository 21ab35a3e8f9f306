#include "protocol/report_json.h"

#include <cmath>

namespace mdhd::protocol {
namespace {

using nlohmann::json;

// Rounded to a nanometre (or nano-degree): reports compare across runs, not bits.
double clean(double v) {
  if (!std::isfinite(v)) return 0.0;
  // From 1e15 on a double holds no fraction finer than a nanometre anyway, and beyond
  // ~1.8e299 v * 1e9 overflows: a move to X 1e300 reported its overtravel as
  // "depth": null until session 23.
  if (std::abs(v) >= 1e15) return v;
  const double r = std::round(v * 1e9) / 1e9;
  return r == 0.0 ? 0.0 : r;
}

json jointValues(const gcode::AxisValues& q, const kin::Machine* machine) {
  json out = json::object();
  if (machine != nullptr) {
    for (const kin::Joint& j : machine->joints)
      if (const auto axis = kin::axisOfName(j.name)) out[j.name] = clean(q[*axis]);
    return out;
  }
  for (int a = 0; a < gcode::kAxisCount; ++a)
    if (a < 3 || q[a] != 0.0) out[std::string(1, gcode::kAxisLetters[a])] = clean(q[a]);
  return out;
}

json collision(const check::Collision& c, const kin::Machine* machine) {
  json j = {
      {"type", std::string(check::collisionTypeName(c.type))},
      {"line", c.line},
      {"last_line", c.last_line},
      {"block", c.block},
      {"tool", c.tool},
      {"position", json::array({clean(c.position.x), clean(c.position.y), clean(c.position.z)})},
      {"joints", jointValues(c.joints, machine)},
      {"depth", clean(c.depth)}};
  if (!c.file.empty()) j["file"] = c.file;
  if (c.part != check::ToolPartName::kNone) j["part"] = std::string(check::toolPartName(c.part));
  if (c.fixture >= 0) j["fixture"] = c.fixture;
  if (!c.axis.empty()) j["axis"] = c.axis;
  return j;
}

json error(const std::optional<check::ReportError>& e) {
  if (!e) return nullptr;
  if (e->line == 0 && e->file.empty()) return {{"message", e->message}, {"field", e->field}};
  json j = {{"message", e->message}, {"line", e->line}, {"column", e->column}, {"block", e->block}};
  if (!e->file.empty()) j["file"] = e->file;
  return j;
}

json stats(const check::RunStats& s) {
  json tools = json::array();
  for (const check::ToolUse& u : s.tools)
    tools.push_back({{"tool", u.tool},
                     {"cutting_time_s", clean(u.cutting_time_s)},
                     {"removed_volume_mm3", clean(u.removed_volume_mm3)}});
  return {
      {"blocks", s.blocks},
      {"moves", s.moves.total()},
      {"moves_by_kind", {{"rapid", s.moves.rapid}, {"feed", s.moves.feed}, {"arc", s.moves.arc}}},
      {"steps", s.steps},
      {"path_length", clean(s.path_length)},
      {"cycle_time_s", clean(s.cycle_time_s)},
      {"stock_volume_mm3", clean(s.stock_volume_mm3)},
      {"removed_volume_mm3", clean(s.removed_volume_mm3)},
      {"final_volume_mm3", clean(s.final_volume_mm3)},
      {"tools", std::move(tools)}};
}

json mdhBlock(const mdh::Stats& m, double spacing) {
  const auto& d = m.directions;
  return {{"cells", m.cells},
          {"leaves", m.leaves},
          {"splits",
           {{"direct", m.splitsDirect},
            {"indirect", m.splitsIndirect},
            {"sign_conflict", m.splitsSignConflict},
            {"fallback", m.splitsFallback}}},
          {"directions",
           {{"+x", d[0]},
            {"-x", d[1]},
            {"+y", d[2]},
            {"-y", d[3]},
            {"+z", d[4]},
            {"-z", d[5]},
            {"solid", m.solid},
            {"empty", m.empty}}},
          {"two_sided", {{"leaves", m.twoSidedLeaves}, {"flipped_columns", m.flippedColumns}}},
          {"memory_bytes", m.memoryBytes},
          {"pointer_grid_percent", clean(m.pointerGridPercent)},
          {"grid_spacing_mm", clean(spacing)}};
}

}  // namespace

json collisionToJson(const check::Collision& c, const kin::Machine* machine) {
  return collision(c, machine);
}

json jointsToJson(const gcode::AxisValues& q, const kin::Machine* machine) {
  return jointValues(q, machine);
}

json reportToJson(const check::Report& r, const kin::Machine* machine) {
  json collisions = json::array();
  for (const check::Collision& c : r.collisions) collisions.push_back(collision(c, machine));
  json firstLine = nullptr;
  if (r.overhang.first_line) firstLine = *r.overhang.first_line;
  return {{"status", std::string(check::statusName(r.status))},
          {"error", error(r.error)},
          {"collisions", std::move(collisions)},
          {"stats", stats(r.stats)},
          {"mdh", mdhBlock(r.mdh, r.grid_spacing)},
          {"overhang",
           {{"events", r.overhang.events},
            {"first_line", firstLine},
            {"cells_not_plus_z", r.overhang.cells_not_plus_z},
            {"area_mm2", clean(r.overhang.area_mm2)}}},
          {"timing",
           {{"total_ms", clean(r.timing.total_ms)},
            {"load_ms", clean(r.timing.load_ms)},
            {"cut_ms", clean(r.timing.cut_ms)},
            {"probe_ms", clean(r.timing.probe_ms)},
            {"finish_ms", clean(r.timing.finish_ms)}}}};
}

}  // namespace mdhd::protocol
