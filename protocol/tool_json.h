#pragma once
// The tool object of the job format (job-format.md section 3) <-> geom::Tool. Strict:
// unknown fields, wrong types and tools that describe no solid are FieldErrors naming
// the field's path ("tools[1].corner_radius: must be <= diameter/2").
//
// Required: number (integer >= 1), shape (flat|ball|bull|drill), diameter,
// flute_length, length. Optional: shank_diameter (default: diameter), corner_radius
// (bull only, required there), tip_angle (drill only, required there), holder (default:
// none; cylinders {diameter, length} from the gauge point downwards).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "protocol/json_fields.h"
#include "sim/geometry/tool.h"

namespace mdhd::protocol {

// One tool at `path` in the document. Throws FieldError.
geom::Tool toolFromJson(const nlohmann::json& j, const std::string& path);

// The job's "tools" array; tool numbers must be unique. Throws FieldError.
std::vector<geom::Tool> toolsFromJson(const nlohmann::json& j, const std::string& path = "tools");

// The tool as the job writes it; toolFromJson reads it back equal.
nlohmann::json toolToJson(const geom::Tool& tool);

}  // namespace mdhd::protocol
