// libFuzzer entry point for the G-code reader: any bytes as a program, read to
// the end with small budgets. A GcodeError is a proper rejection; any other
// exception, crash, hang or sanitizer report is a bug. The same function is
// replayed over the seed corpus by tests/gcode/test_reader_corpus_replay.cpp.
#include <cstddef>
#include <cstdint>
#include <string>

#include "sim/gcode/reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace mdhd::gcode;
  const std::string program(reinterpret_cast<const char*>(data), size);
  ReaderOptions options;
  options.max_steps = 20'000;
  options.max_loop_iterations = 2'000;
  options.block_delete = size % 2 == 1;
  ParameterStore params;
  params.setPredefined([](std::string_view name) -> std::optional<double> {
    if (name == "_x") return 1.5;
    return std::nullopt;
  });
  // Every external subroutine is the program itself, so loading is exercised.
  SubroutineLoader loader = [&program](std::string_view) { return makeStringSource(program); };
  try {
    Reader reader(makeStringSource(program), params, loader, options);
    Block block;
    while (reader.next(block)) {
    }
  } catch (const GcodeError&) {
  }
  return 0;
}
