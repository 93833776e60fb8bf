// peak_rss PROGRAM [ARGS...]: runs PROGRAM, then prints "peak_rss_kib N" (its peak resident set)
// on stderr, after anything PROGRAM wrote, and exits with its status. Why a separate program: a process's ru_maxrss is the high-water
// mark over every memory image it had, and a child forked from a large benchmark process starts
// as a copy of it, so wait4() in the benchmark would report the benchmark's own size whenever it
// exceeds the child's. Forked from this small program, the child's figure is its own.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: peak_rss PROGRAM [ARGS...]\n");
    return 2;
  }
  const pid_t pid = fork();
  if (pid < 0) return 126;
  if (pid == 0) {
    execv(argv[1], argv + 1);
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return 126;
  std::fprintf(stderr, "peak_rss_kib %ld\n", usage.ru_maxrss);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}
