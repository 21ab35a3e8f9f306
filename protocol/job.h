#pragma once
// The job document of the contract (job-format.md section 1) as plain data.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "sim/geometry/line_solid.h"
#include "sim/geometry/tool.h"
#include "sim/kinematics/machine.h"

namespace mdhd::protocol {

// A non-machinable solid in W.
struct Fixture {
  enum class Kind { kBox, kCylinder };
  Kind kind = Kind::kBox;
  geom::Aabb box;                  // kBox
  glm::dvec3 base{0.0};            // kCylinder: centre of the base disc
  glm::dvec3 axis{0.0, 0.0, 1.0};  // kCylinder: unit direction from the base
  double radius = 0.0;
  double height = 0.0;
};

struct JobOptions {
  double density = 10.0;  // samples per mm
  int steps = 0;          // in-between steps per move; 0: adaptive to `tolerance`
  double tolerance = 0.01;
  std::vector<std::string> ruleset{"FEFS-FFS", "CTD", "SPT", "RS"};
  std::uint64_t seed = 1;
  bool three_way = true;
  // Two-sided 3-maps (mdhd extension; thesis 7.4): fewer cell splits, same stock.
  bool two_sided = true;
  std::optional<double> contact_tolerance;  // default: half the grid spacing
  double contactTolerance() const { return contact_tolerance.value_or(0.5 / density); }
  // Raster chains' points dropped within this (mm; mdhd extension): default half of
  // `tolerance`, 0 exact.
  std::optional<double> chain_tolerance;
  double chainTolerance() const { return chain_tolerance.value_or(0.5 * tolerance); }
};

// Work offset slots in G-code order: G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3.
inline constexpr std::array<const char*, 9> kWorkOffsetNames{"G54", "G55",   "G56",   "G57",  "G58",
                                                             "G59", "G59.1", "G59.2", "G59.3"};

struct Job {
  // Exactly one of: machine (inline), machine_name (a registered machine: HTTP only),
  // machine_file (a path relative to the job file: command line only).
  std::optional<kin::Machine> machine;
  std::string machine_name;
  std::string machine_file;
  std::vector<geom::Tool> tools;
  geom::Aabb stock;
  std::vector<Fixture> fixtures;
  std::array<std::array<double, 3>, 9> work_offsets{};
  // Exactly one of program (text) and program_file (path relative to the job file),
  // unless the document is a shadow's cell description, where both may be absent.
  std::optional<std::string> program;
  std::string program_file;
  JobOptions options;
  // The optional `modbus` block of service.md, kept as written: it is decoded by
  // protocol/modbus_map_json against the machine, which may come from a file.
  std::optional<nlohmann::json> modbus;

  const geom::Tool* findTool(int number) const;
};

}  // namespace mdhd::protocol
