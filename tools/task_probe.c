// Records the functions a test enters (tools/task_tables.py --derive links it into a test program
// whose units are compiled -finstrument-functions) and writes their addresses to $ILLUM_TASK_PROBE.
#include <stdio.h>
#include <stdlib.h>
#define SLOTS 4096
static void* seen[SLOTS];
static int count;
__attribute__((no_instrument_function)) static void dump(void) {
  const char* path = getenv("ILLUM_TASK_PROBE");
  if (!path) return;
  FILE* f = fopen(path, "w");
  if (!f) return;
  for (int i = 0; i < count; ++i) fprintf(f, "%p\n", seen[i]);
  fclose(f);
}
__attribute__((no_instrument_function)) void __cyg_profile_func_enter(void* fn, void* site) {
  (void)site;
  for (int i = 0; i < count; ++i)
    if (seen[i] == fn) return;
  if (count == 0) atexit(dump);
  if (count < SLOTS) seen[count++] = fn;
}
__attribute__((no_instrument_function)) void __cyg_profile_func_exit(void* fn, void* site) {
  (void)fn;
  (void)site;
}
