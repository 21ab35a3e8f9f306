// libFuzzer target for the machine codec: any bytes either fail with a FieldError
// (or are not JSON) or give a machine whose kinematics build, evaluate and round-trip.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "protocol/machine_json.h"
#include "sim/kinematics/kinematics.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto j = nlohmann::json::parse(data, data + size, nullptr, false);
  if (j.is_discarded()) return 0;
  mdhd::kin::Machine m;
  try {
    m = mdhd::protocol::machineFromJson(j);
  } catch (const mdhd::protocol::FieldError&) {
    return 0;
  }
  const mdhd::kin::Kinematics kin(m);  // a machine the codec accepts must build
  mdhd::kin::JointValues q{};
  for (std::size_t a = 0; a < q.size(); ++a) q[a] = 10.0 * static_cast<double>(a) - 17.5;
  const mdhd::kin::ToolPose p = kin.toolPose(q, 50);
  (void)p;
  if (mdhd::protocol::machineToJson(mdhd::protocol::machineFromJson(
          mdhd::protocol::machineToJson(m))) != mdhd::protocol::machineToJson(m)) {
    std::abort();
  }
  return 0;
}
