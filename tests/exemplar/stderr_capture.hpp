#pragma once
// Captures what this process writes to file descriptor 2 (where libpng, libjpeg and libtiff print
// their own messages when no handler is installed), so a test can require it to stay empty.

#include <cstdio>
#include <string>

#include <unistd.h>

namespace fissure::test {

class StderrCapture {
public:
  StderrCapture() {
    std::fflush(stderr);
    m_file = std::tmpfile();
    m_saved = dup(2);
    dup2(fileno(m_file), 2);
  }
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;
  ~StderrCapture() { restore(); }

  /// Restores fd 2 and returns everything written to it meanwhile.
  std::string finish() {
    restore();
    std::string text;
    if (!m_file) return text;
    std::rewind(m_file);
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, m_file)) > 0) text.append(buffer, n);
    std::fclose(m_file);
    m_file = nullptr;
    return text;
  }

private:
  void restore() {
    if (m_saved < 0) return;
    std::fflush(stderr);
    dup2(m_saved, 2);
    close(m_saved);
    m_saved = -1;
  }
  std::FILE* m_file = nullptr;
  int m_saved = -1;
};

}  // namespace fissure::test
