#include "gmsh_session.hpp"

#include <gmsh.h>

#include <clocale>
#include <locale.h>

#include <vector>

namespace fissure::io_detail {
namespace {

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

void initialise_quietly() {
  // gmsh::initialize calls setlocale(LC_ALL, "") for the whole process; keep the caller's locale.
  const std::string saved = std::setlocale(LC_ALL, nullptr);
  gmsh::initialize(0, nullptr, false);  // no user config files: output must not depend on them
  std::setlocale(LC_ALL, saved.c_str());
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 2);  // errors and warnings only
}

}  // namespace

GmshSession::GmshSession() : m_lock(gmsh_mutex()) {
  // gmsh prints numbers with fprintf: under a decimal-comma locale (the studio's, say) it would
  // write "1,5". The C locale for this thread while gmsh works, restored in the destructor.
  static const locale_t c_locale = newlocale(LC_ALL_MASK, "C", nullptr);
  m_previous_locale = uselocale(c_locale);
  static bool initialised = false;
  if (!initialised) {
    initialise_quietly();
    initialised = true;
  }
  gmsh::logger::stop();
  gmsh::logger::start();
  gmsh::clear();
}

void GmshSession::reset() {
  try {
    gmsh::finalize();
  } catch (...) {
  }
  initialise_quietly();
  gmsh::logger::start();
}

GmshSession::~GmshSession() {
  try {
    gmsh::clear();
  } catch (...) {
  }
  uselocale(m_previous_locale);
}

std::string GmshSession::logged_errors() const {
  std::vector<std::string> log;
  gmsh::logger::get(log);
  std::string out;
  for (const std::string& line : log) {
    if (line.rfind("Error", 0) == 0) out += (out.empty() ? "" : "; ") + line;
  }
  return out;
}

}  // namespace fissure::io_detail
