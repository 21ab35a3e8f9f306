// Subcommands whose issues are still open say so plainly instead of pretending.
#include <ostream>

#include "daemon/cli.h"

namespace mdhd::cli {

int runServe(const Args&, std::ostream&, std::ostream& err) {
  err << "mdhd serve: not available yet: the HTTP service is being built "
         "(see the README's status section).\n";
  return 2;
}

}  // namespace mdhd::cli
