#include "protocol/tool_json.h"

namespace mdhd::protocol {

using nlohmann::json;

namespace {

std::vector<geom::HolderSection> holderFromJson(const json& j, const std::string& path) {
  if (!j.is_array()) fields::fail(path, "an array of {diameter, length}", j);
  std::vector<geom::HolderSection> holder;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = path + "[" + std::to_string(i) + "]";
    fields::requireObject(j[i], at, {"diameter", "length"});
    holder.push_back({fields::number(fields::required(j[i], "diameter", at), at + ".diameter"),
                      fields::number(fields::required(j[i], "length", at), at + ".length")});
  }
  return holder;
}

double optionalNumber(const json& j, const char* key, const std::string& path, double fallback) {
  const json* v = fields::optional(j, key);
  return v ? fields::number(*v, path + "." + key) : fallback;
}

}  // namespace

geom::Tool toolFromJson(const json& j, const std::string& path) {
  fields::requireObject(j, path,
                        {"number", "shape", "diameter", "flute_length", "length", "shank_diameter",
                         "corner_radius", "tip_angle", "holder"});
  auto at = [&](const char* key) { return path + "." + key; };
  geom::Tool t;
  t.number = fields::integer(fields::required(j, "number", path), at("number"));
  const std::string shape = fields::string(fields::required(j, "shape", path), at("shape"));
  const auto parsed = geom::toolShapeFromName(shape);
  if (!parsed) fields::fail(at("shape"), "one of flat, ball, bull, drill", j["shape"]);
  t.shape = *parsed;
  t.diameter = fields::number(fields::required(j, "diameter", path), at("diameter"));
  t.flute_length = fields::number(fields::required(j, "flute_length", path), at("flute_length"));
  t.length = fields::number(fields::required(j, "length", path), at("length"));
  t.shank_diameter = optionalNumber(j, "shank_diameter", path, t.diameter);
  // The shape's own size is required where it is used, so a bull never silently turns flat.
  if (t.shape == geom::ToolShape::kBull) fields::required(j, "corner_radius", path);
  if (t.shape == geom::ToolShape::kDrill) fields::required(j, "tip_angle", path);
  t.corner_radius = optionalNumber(j, "corner_radius", path, 0.0);
  t.tip_angle = optionalNumber(j, "tip_angle", path, 0.0);
  if (const json* h = fields::optional(j, "holder")) t.holder = holderFromJson(*h, at("holder"));
  if (const auto problem = geom::validateTool(t))
    throw FieldError(path + "." + problem->field, problem->message);
  return t;
}

std::vector<geom::Tool> toolsFromJson(const json& j, const std::string& path) {
  if (!j.is_array()) fields::fail(path, "an array of tools", j);
  std::vector<geom::Tool> tools;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string at = path + "[" + std::to_string(i) + "]";
    tools.push_back(toolFromJson(j[i], at));
    for (size_t k = 0; k < i; ++k)
      if (tools[k].number == tools[i].number)
        throw FieldError(at + ".number", "tool " + std::to_string(tools[i].number) +
                                             " is already defined by " + path + "[" +
                                             std::to_string(k) + "]");
  }
  return tools;
}

json toolToJson(const geom::Tool& t) {
  json j = {{"number", t.number},     {"shape", std::string(geom::toolShapeName(t.shape))},
            {"diameter", t.diameter}, {"flute_length", t.flute_length},
            {"length", t.length},     {"shank_diameter", t.shank_diameter}};
  if (t.shape == geom::ToolShape::kBull) j["corner_radius"] = t.corner_radius;
  if (t.shape == geom::ToolShape::kDrill) j["tip_angle"] = t.tip_angle;
  json holder = json::array();
  for (const geom::HolderSection& h : t.holder)
    holder.push_back({{"diameter", h.diameter}, {"length", h.length}});
  j["holder"] = holder;
  return j;
}

}  // namespace mdhd::protocol
