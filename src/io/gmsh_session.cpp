#include "gmsh_session.hpp"

#include <gmsh.h>

#include <vector>

namespace fissure::io_detail {
namespace {

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

void initialise_quietly() {
  gmsh::initialize(0, nullptr, false);  // no user config files: output must not depend on them
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 2);  // errors and warnings only
}

}  // namespace

GmshSession::GmshSession() : m_lock(gmsh_mutex()) {
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
