// mdhd: verification of 5-axis CNC programs on multidirectional heightmaps.
#include <iostream>
#include <string>

#include "daemon/cli.h"

namespace {

constexpr const char* kUsage =
    "usage: mdhd <command> [args]\n"
    "  check JOB.json [--report REPORT.json] [--mesh RESULT.stl]  simulate a job\n"
    "  trace JOB.json                                             print the interpreted motion\n"
    "  serve [--config FILE]                                      run the HTTP service\n"
    "  modbus-sim JOB.json --port P [--speed S] [--host H] [--map MAP.json] [--loop]\n"
    "             [--exit-after SEC]   a simulated controller serving Modbus TCP\n";

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << kUsage;
    return 2;
  }
  const std::string command = argv[1];
  mdhd::cli::Args args(argv + 2, argv + argc);
  if (command == "trace") return mdhd::cli::runTrace(args, std::cout, std::cerr);
  if (command == "check") return mdhd::cli::runCheck(args, std::cout, std::cerr);
  if (command == "serve") return mdhd::cli::runServe(args, std::cout, std::cerr);
  if (command == "modbus-sim") return mdhd::cli::runModbusSim(args, std::cout, std::cerr);
  if (command == "--help" || command == "-h" || command == "help") {
    std::cout << kUsage;
    return 0;
  }
  std::cerr << "mdhd: unknown command '" << command << "'\n" << kUsage;
  return 2;
}
