#pragma once
// Private to io: serialised access to gmsh's global state. gmsh is initialised once, quietly,
// with errors thrown (General.AbortOnError 2 throws a std::string); every call holds the lock and
// starts from an empty model.

#include <locale.h>
#include <mutex>
#include <string>

namespace fissure::io_detail {

class GmshSession {
public:
  /// Locks the gmsh mutex, initialises gmsh on first use, clears models, views and the log.
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// Runs `body` and turns whatever gmsh throws (a std::string under AbortOnError 2, or a
  /// std::exception) or logs as an error into a message; returns the empty string on success.
  /// After a failure gmsh is finalised and re-initialised: an exception in the middle of a read
  /// leaves its state broken (later reads then silently return no elements).
  template <class F>
  std::string run(F&& body) {
    std::string error;
    try {
      body();
    } catch (const std::string& message) {
      error = message.empty() ? "gmsh failed" : message;
    } catch (const std::exception& e) {
      error = e.what();
    } catch (...) {
      error = "gmsh failed";
    }
    if (error.empty()) error = logged_errors();
    if (!error.empty()) reset();
    return error;
  }

private:
  std::string logged_errors() const;
  void reset();
  std::unique_lock<std::mutex> m_lock;
  locale_t m_previous_locale = nullptr;
};

}  // namespace fissure::io_detail
