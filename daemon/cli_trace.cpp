// mdhd trace JOB.json: the interpreted motion of a job, one JSON line per move.
#include <ostream>

#include "daemon/cli.h"
#include "daemon/job_files.h"
#include "daemon/trace_sink.h"
#include "protocol/json_fields.h"
#include "sim/gcode/interpreter.h"

namespace mdhd::cli {

int runTrace(const Args& args, std::ostream& out, std::ostream& err) {
  if (args.size() != 1 || args[0].empty() || args[0][0] == '-') {
    err << "usage: mdhd trace JOB.json\n";
    return 2;
  }
  try {
    const LoadedJob loaded = loadJobFile(args[0]);
    const kin::Kinematics kin(*loaded.job.machine);
    TraceSink sink(kin, loaded.job, out);
    gcode::Interpreter interp(interpreterConfig(loaded), sink);
    interp.run(openProgram(loaded));
    out.flush();
    return 0;
  } catch (const gcode::GcodeError& e) {
    out.flush();
    const std::string where = e.pos().file.empty() ? "program" : e.pos().file;
    err << "mdhd trace: " << where << ", line " << e.line() << ", column " << e.column() << ": "
        << e.what() << "\n";
  } catch (const protocol::FieldError& e) {
    err << "mdhd trace: " << args[0] << ": " << e.what() << "\n";
  } catch (const kin::KinematicsError& e) {
    err << "mdhd trace: machine: " << e.what() << "\n";
  }
  return 2;
}

}  // namespace mdhd::cli
