// Fuzz target: the reader of the course's one scene format (io/scene_file,
// every primitive kind). Any bytes give either a Scene or an
// illum::InputError; never a crash, a hang, another exception or undefined
// behaviour (the build adds ASan, UBSan and float-cast-overflow).
#include <cstddef>
#include <cstdint>
#include <string>

#include "illum/core/error.hpp"
#include "illum/io/json_reader.hpp"
#include "illum/io/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // OBJ files of "mesh" primitives are looked up beside a file that does not exist.
    (void)illum::read_scene(illum::JsonReader::parse_text(text, "fuzz.json"), "/nonexistent-fuzz-folder");
  } catch (const illum::InputError&) {
    // the expected refusal
  }
  return 0;
}
