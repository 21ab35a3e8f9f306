#pragma once
// Subcommands of the mdhd executable. Each takes its arguments after the
// subcommand name and returns the process exit status.
#include <iosfwd>
#include <string>
#include <vector>

namespace mdhd::cli {

using Args = std::vector<std::string>;

int runTrace(const Args& args, std::ostream& out, std::ostream& err);
int runCheck(const Args& args, std::ostream& out, std::ostream& err);
int runServe(const Args& args, std::ostream& out, std::ostream& err);
int runModbusSim(const Args& args, std::ostream& out, std::ostream& err);

}  // namespace mdhd::cli
