// Attack (a fault, in otherwise correct code): System V and POSIX shared memory, which a
// process's own memory limit does not count and which outlives the program: seven segments of
// 100 MB filled and left behind, a 100 MB file in /dev/shm, a file in /run/lock.
#include <fcntl.h>
#include <sys/ipc.h>
#include <sys/mman.h>
#include <sys/shm.h>
#include <unistd.h>

#include <cstring>

namespace {

void attack_hook() {
  static bool done = false;
  if (done) return;
  done = true;
  constexpr std::size_t size = 100u << 20;
  for (int i = 0; i < 7; ++i) {
    const int id = shmget(IPC_PRIVATE, size, IPC_CREAT | 0600);
    if (id < 0) break;
    void* memory = shmat(id, nullptr, 0);
    if (memory == reinterpret_cast<void*>(-1)) break;
    std::memset(memory, 1, size);
    shmdt(memory);
  }
  const int file = shm_open("/illum-attack", O_CREAT | O_RDWR, 0600);
  if (file >= 0) {
    if (ftruncate(file, static_cast<off_t>(size)) == 0) {
      void* memory = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, file, 0);
      if (memory != MAP_FAILED) std::memset(memory, 1, size);
    }
    close(file);
  }
  const int lock = open("/run/lock/illum-attack", O_CREAT | O_WRONLY, 0600);
  if (lock >= 0) close(lock);
}

}  // namespace
