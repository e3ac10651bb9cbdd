// libFuzzer entry: parse and run arbitrary text. Any crash, sanitizer report, leak or hang is
// a bug; ScriptError is the expected outcome for bad input. Files are off and the work is
// bounded by a step limit so that a loop cannot read as a hang.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "language/interpreter.hpp"
#include "language/parser.hpp"

using namespace sculpt::language;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto source = std::make_shared<SourceFile>();
  source->name = "<fuzz>";
  source->text.assign(reinterpret_cast<const char*>(data), size);
  (void)is_unfinished(source->text);
  std::ostringstream out;
  Interpreter interpreter({.out = &out, .allow_files = false, .max_steps = 20000, .core_only = true});
  try {
    interpreter.run(source);
  } catch (const ScriptError& e) {
    (void)format_error(e);
  }
  return 0;
}
