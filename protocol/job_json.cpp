#include "protocol/job_json.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "protocol/machine_json.h"
#include "protocol/tool_json.h"

namespace mdhd::protocol {
namespace {

using nlohmann::json;
using namespace fields;

const std::array<const char*, 6> kRuleNames{"FFS", "FEFS", "FEFS-FFS", "CTD", "SPT", "RS"};

geom::Aabb box(const json& j, const std::string& field) {
  requireObject(j, field, {"min", "max"});
  geom::Aabb b{vec3(required(j, "min", field), field + ".min"),
               vec3(required(j, "max", field), field + ".max")};
  for (int i = 0; i < 3; ++i) {
    if (!(b.lo[i] < b.hi[i])) {
      throw FieldError(
          field, "min must be below max on every axis (axis " + std::string(1, "xyz"[i]) + ")");
    }
  }
  return b;
}

Fixture fixture(const json& j, const std::string& field) {
  requireObject(j, field, {"box", "cylinder"});
  if (j.size() != 1) throw FieldError(field, "expected exactly one of box, cylinder");
  Fixture f;
  if (const json* b = optional(j, "box")) {
    f.kind = Fixture::Kind::kBox;
    f.box = box(*b, field + ".box");
    return f;
  }
  const std::string c = field + ".cylinder";
  const json& cyl = j.at("cylinder");
  requireObject(cyl, c, {"base", "axis", "radius", "height"});
  f.kind = Fixture::Kind::kCylinder;
  f.base = vec3(required(cyl, "base", c), c + ".base");
  f.axis = vec3(required(cyl, "axis", c), c + ".axis");
  const double len = std::sqrt(f.axis.x * f.axis.x + f.axis.y * f.axis.y + f.axis.z * f.axis.z);
  if (!(len > 1e-12)) throw FieldError(c + ".axis", "must not be the zero vector");
  f.axis /= len;
  f.radius = positive(required(cyl, "radius", c), c + ".radius");
  f.height = positive(required(cyl, "height", c), c + ".height");
  return f;
}

std::array<std::array<double, 3>, 9> workOffsets(const json& j, const std::string& field) {
  if (!j.is_object()) fail(field, "an object keyed G54 .. G59.3", j);
  std::array<std::array<double, 3>, 9> out{};
  for (const auto& item : j.items()) {
    const auto it = std::find_if(kWorkOffsetNames.begin(), kWorkOffsetNames.end(),
                                 [&](const char* n) { return item.key() == n; });
    const std::string f = field + "." + item.key();
    if (it == kWorkOffsetNames.end()) {
      throw FieldError(f, "unknown work offset (known: G54 G55 G56 G57 G58 G59 G59.1 G59.2 G59.3)");
    }
    const glm::dvec3 v = vec3(item.value(), f);
    out[static_cast<std::size_t>(it - kWorkOffsetNames.begin())] = {v.x, v.y, v.z};
  }
  return out;
}

JobOptions options(const json& j, const std::string& field) {
  requireObject(j, field,
                {"density", "steps", "tolerance", "ruleset", "seed", "three_way", "two_sided",
                 "contact_tolerance", "chain_tolerance"});
  JobOptions o;
  if (const json* v = optional(j, "density")) {
    o.density = positive(*v, field + ".density");
    if (o.density > 1000.0) throw FieldError(field + ".density", "must be at most 1000 samples/mm");
  }
  if (const json* v = optional(j, "steps")) {
    o.steps = integer(*v, field + ".steps");
    if (o.steps < 0 || o.steps > 100000) {
      throw FieldError(field + ".steps", "must be between 0 (adaptive) and 100000");
    }
  }
  if (const json* v = optional(j, "tolerance")) o.tolerance = positive(*v, field + ".tolerance");
  if (const json* v = optional(j, "ruleset")) {
    const std::string f = field + ".ruleset";
    if (!v->is_array() || v->empty()) fail(f, "a non-empty array of rule names", *v);
    o.ruleset.clear();
    std::set<std::string> seen;
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string name = string((*v)[i], f + "[" + std::to_string(i) + "]");
      if (std::find(kRuleNames.begin(), kRuleNames.end(), name) == kRuleNames.end()) {
        throw FieldError(f + "[" + std::to_string(i) + "]",
                         "unknown rule \"" + name + "\" (known: FFS FEFS FEFS-FFS CTD SPT RS)");
      }
      if (!seen.insert(name).second) {
        throw FieldError(f + "[" + std::to_string(i) + "]", "rule \"" + name + "\" listed twice");
      }
      o.ruleset.push_back(name);
    }
  }
  if (const json* v = optional(j, "seed")) {
    if (!v->is_number_integer() ||
        (v->is_number_integer() && !v->is_number_unsigned() && v->get<std::int64_t>() < 0)) {
      fail(field + ".seed", "a non-negative integer", *v);
    }
    o.seed = v->get<std::uint64_t>();
  }
  if (const json* v = optional(j, "three_way")) o.three_way = boolean(*v, field + ".three_way");
  if (const json* v = optional(j, "two_sided")) {
    o.two_sided = boolean(*v, field + ".two_sided");
    if (o.two_sided && !o.three_way) {
      throw FieldError(field + ".two_sided", "needs three_way (two-sided maps are 3-maps)");
    }
  } else {
    o.two_sided = o.three_way;  // plain heightmaps are one-sided
  }
  if (const json* v = optional(j, "contact_tolerance")) {
    const double t = number(*v, field + ".contact_tolerance");
    if (t < 0.0) throw FieldError(field + ".contact_tolerance", "must be >= 0");
    o.contact_tolerance = t;
  }
  if (const json* v = optional(j, "chain_tolerance")) {
    const double t = number(*v, field + ".chain_tolerance");
    if (t < 0.0) throw FieldError(field + ".chain_tolerance", "must be >= 0");
    if (t > o.tolerance) {
      throw FieldError(field + ".chain_tolerance", "must be at most options.tolerance");
    }
    o.chain_tolerance = t;
  }
  return o;
}

// The engine snaps the stock's max corner to the nearest grid plane; a grid spacing
// longer than a side of the stock would grow or shrink that side by most of a spacing
// (a 40 mm stock at 0.001 points/mm became a 1 m cube and ran "clean").
void gridFitsStock(const geom::Aabb& stock, double density) {
  int a = 0;  // the shortest side decides
  for (int b = 1; b < 3; ++b)
    if (stock.hi[b] - stock.lo[b] < stock.hi[a] - stock.lo[a]) a = b;
  const double extent = stock.hi[a] - stock.lo[a];
  if (extent * density >= 1.0) return;
  char text[200];
  std::snprintf(text, sizeof text,
                "a grid spacing of %g mm (%g points/mm) is longer than the stock's %g mm along "
                "%c: give at least %g points/mm",
                1.0 / density, density, extent, "xyz"[a], 1.0 / extent);
  throw FieldError("options.density", text);
}

}  // namespace

const geom::Tool* Job::findTool(int number) const {
  for (const geom::Tool& t : tools) {
    if (t.number == number) return &t;
  }
  return nullptr;
}

Job jobFromJson(const json& j, ProgramRequirement program) {
  requireObject(j, "",
                {"machine", "machine_file", "tools", "stock", "fixtures", "work_offsets", "program",
                 "program_file", "options", "modbus"});
  Job job;
  const json* machine = optional(j, "machine");
  const json* machine_file = optional(j, "machine_file");
  if ((machine != nullptr) == (machine_file != nullptr)) {
    throw FieldError("machine", "give exactly one of machine and machine_file");
  }
  if (machine != nullptr && machine->is_string()) {
    job.machine_name = machine->get<std::string>();
    if (job.machine_name.empty()) throw FieldError("machine", "empty machine name");
  } else if (machine != nullptr) {
    job.machine = machineFromJson(*machine, "machine");
  } else {
    job.machine_file = string(*machine_file, "machine_file");
  }

  job.tools = toolsFromJson(required(j, "tools", ""), "tools");

  const json& stock = required(j, "stock", "");
  requireObject(stock, "stock", {"box"});
  job.stock = box(required(stock, "box", "stock"), "stock.box");

  if (const json* f = optional(j, "fixtures")) {
    if (!f->is_array()) fail("fixtures", "an array", *f);
    for (std::size_t i = 0; i < f->size(); ++i) {
      job.fixtures.push_back(fixture((*f)[i], "fixtures[" + std::to_string(i) + "]"));
    }
  }
  if (const json* w = optional(j, "work_offsets"))
    job.work_offsets = workOffsets(*w, "work_offsets");

  const json* text = optional(j, "program");
  const json* file = optional(j, "program_file");
  if (text != nullptr && file != nullptr) {
    throw FieldError("program", "give only one of program and program_file");
  }
  if (text != nullptr) job.program = string(*text, "program");
  if (file != nullptr) job.program_file = string(*file, "program_file");
  if (program == ProgramRequirement::kRequired && text == nullptr && file == nullptr) {
    throw FieldError("program", "missing (give program or program_file)");
  }
  if (const json* o = optional(j, "options")) job.options = options(*o, "options");
  gridFitsStock(job.stock, job.options.density);
  if (const json* m = optional(j, "modbus")) {
    if (!m->is_object()) fail("modbus", "an object (the register map of service.md)", *m);
    job.modbus = *m;
  }
  return job;
}

namespace {

// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string jsonMessage(const json::exception& e) {
  std::string message = e.what();
  if (const auto p = message.find("] ");
      message.rfind("[json.exception", 0) == 0 && p != std::string::npos) {
    message.erase(0, p + 2);
  }
  return message;
}

// "line L, column C" of the first occurrence of `token` in `text` ("" if absent).
std::string placeOf(std::string_view text, std::string_view token) {
  const std::size_t at = token.empty() ? std::string_view::npos : text.find(token);
  if (at == std::string_view::npos) return {};
  const std::string_view before = text.substr(0, at);
  const std::size_t line =
      1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t lineStart = before.rfind('\n');
  const std::size_t column = at - (lineStart == std::string_view::npos ? 0 : lineStart + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column) + ": ";
}

// Where the parser is: the enclosing objects' current keys and arrays' current
// indices, to name a repeated key the way FieldError names fields.
struct JsonPlace {
  bool object = false;
  std::set<std::string> keys;
  std::string key;
  long index = -1;
};

// A second, DOM-less pass over a text that parsed: a key given twice in one object
// is refused (nlohmann keeps the last one, so a job with two "options" or two
// "machine" silently lost the first). A SAX pass, because nlohmann's parse
// callback rescans the parent container at every object's end (quadratic: a
// 15 MB array of small objects took 70-90 s).
class DuplicateKeys final : public json::json_sax_t {
 public:
  bool null() override { return element(); }
  bool boolean(bool) override { return element(); }
  bool number_integer(number_integer_t) override { return element(); }
  bool number_unsigned(number_unsigned_t) override { return element(); }
  bool number_float(number_float_t, const string_t&) override { return element(); }
  bool string(string_t&) override { return element(); }
  bool binary(binary_t&) override { return element(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    JsonPlace& top = stack_.back();
    top.key = k;
    if (!top.keys.insert(k).second) {
      std::string field;
      for (const JsonPlace& p : stack_) {
        field +=
            p.object ? (field.empty() ? "" : ".") + p.key : "[" + std::to_string(p.index) + "]";
      }
      throw FieldError(field, "the key \"" + k + "\" appears twice in one object");
    }
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

 private:
  bool element() {
    if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
    return true;
  }
  bool open(bool object) {
    element();
    stack_.push_back({object, {}, {}, -1});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }
  std::vector<JsonPlace> stack_;
};

}  // namespace

json parseJsonText(std::string_view text) {
  try {
    json doc = json::parse(text.begin(), text.end());
    DuplicateKeys keys;
    json::sax_parse(text.begin(), text.end(), &keys);
    return doc;
  } catch (const json::parse_error& e) {
    // nlohmann's message already says "parse error at line L, column C: ...".
    throw FieldError("(document)", "invalid JSON: " + jsonMessage(e));
  } catch (const json::out_of_range& e) {
    // A number no double holds ("number overflow parsing '1e400'"): nlohmann names the
    // number but not its place, so find it.
    const std::string message = jsonMessage(e);
    const std::size_t open = message.find('\''), close = message.rfind('\'');
    const std::string_view token =
        open != std::string::npos && close > open
            ? std::string_view(message).substr(open + 1, close - open - 1)
            : std::string_view();
    throw FieldError("(document)", "invalid JSON: " + placeOf(text, token) + message);
  } catch (const json::exception& e) {
    throw FieldError("(document)", "invalid JSON: " + jsonMessage(e));
  }
}

}  // namespace mdhd::protocol
