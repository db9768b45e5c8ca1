#pragma once
// The reference side of the lab (docs/lab.md, "The reference beside yours").
// A student's build computes with the student's code, so it cannot also hold
// the reference units it replaced. The reference is another `illum` program,
// built from the reference units (the instructors' release build, or the copy
// an instructor hands out with the student edition): the lab starts it as a
// second lab of its own, `PROGRAM lab SCENE --port 0 ...`, on a free port of
// 127.0.0.1, and forwards /api/reference/<endpoint> to its /api/<endpoint>.
// The page then holds the student's ray tree and radiosity shots against the
// reference's. The child ends with the lab (SIGTERM, and PR_SET_PDEATHSIG
// should the lab itself be killed).
#include <sys/types.h>
#include <filesystem>
#include <string>
#include <vector>

namespace illum::lab {

class ReferenceLab {
 public:
  // No program: no reference. Otherwise starts it and waits for its address
  // (at most 30 s); never throws: a program that does not start, or that is
  // not a reference build (its /api/info names lessons taken from exercises/),
  // leaves available() false and why() saying so.
  ReferenceLab(const std::filesystem::path& program, const std::vector<std::string>& lab_arguments);
  ~ReferenceLab();
  ReferenceLab(const ReferenceLab&) = delete;
  ReferenceLab& operator=(const ReferenceLab&) = delete;

  bool available() const { return port_ > 0; }
  const std::string& why() const { return why_; }
  const std::filesystem::path& program() const { return program_; }

  // GET `target` (path and query) from the reference lab, with the tab header
  // passed on: its status, content type and body; 502 when it does not answer.
  struct Answer {
    int status = 502;
    std::string type, body;
  };
  Answer get(const std::string& target, const std::string& tab) const;

  // Asks the child to stop (SIGTERM), without waiting: on Ctrl-C.
  void terminate() const;
  // Ends the child now (SIGTERM, then SIGKILL after half a second).
  void stop();

 private:
  std::filesystem::path program_;
  std::string why_;
  pid_t child_ = -1;
  int port_ = 0;
};

}  // namespace illum::lab
