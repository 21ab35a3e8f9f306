// mdhd trace: placeholder until the interpreter and kinematics land.
#include <ostream>

#include "daemon/cli.h"

namespace mdhd::cli {

int runTrace(const Args&, std::ostream&, std::ostream& err) {
  err << "mdhd trace: not available yet\n";
  return 2;
}

}  // namespace mdhd::cli
