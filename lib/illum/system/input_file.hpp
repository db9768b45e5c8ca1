#pragma once
// Reading a file a user named (a scene, an OBJ mesh) safely: only a regular
// file is read, and never more than a stated size.
//
//   const std::string text = read_input_file("scenes/room.json", "scene file", 64 << 20);
//
// A named pipe would block the program for ever, /dev/zero would feed it
// gigabytes, a folder cannot be read at all: each is refused at once, by
// what it is, before a byte is read (docs/bad-input.md, "Input files").
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace illum {

// Why an input file cannot be read; the caller turns it into an InputError
// naming its field or option.
class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "a folder", "a named pipe (FIFO)", "a character device", … for st_mode.
std::string file_kind_name(unsigned mode);

// The whole file. Opens without blocking (O_NONBLOCK: a FIFO with no writer
// does not hang), then refuses anything but a regular file, and a file
// larger than max_bytes, naming what it is: "this is a named pipe (FIFO),
// not a regular file". `what` ("scene file", "OBJ file") starts the messages.
std::string read_input_file(const std::filesystem::path& file, const std::string& what,
                            std::uint64_t max_bytes);

}  // namespace illum
