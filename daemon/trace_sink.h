#pragma once
// The sink behind `mdhd trace`: each interpreted motion as one JSON line with the
// machine joint values at its end (job-format.md section 4).
#include <ostream>

#include "protocol/job.h"
#include "sim/gcode/motion.h"
#include "sim/kinematics/kinematics.h"

namespace mdhd::cli {

class TraceSink : public gcode::MotionSink {
 public:
  TraceSink(const kin::Kinematics& kin, const protocol::Job& job, std::ostream& out)
      : kin_(kin), job_(job), out_(out) {}
  void motion(const gcode::Motion& m) override;
  std::uint64_t motions() const { return motions_; }

 private:
  const kin::Kinematics& kin_;
  const protocol::Job& job_;
  std::ostream& out_;
  std::uint64_t motions_ = 0;
};

// Shortest text that reads back as `v` rounded to 1e-9 (no "-0").
void appendNumber(std::string& out, double v);

}  // namespace mdhd::cli
