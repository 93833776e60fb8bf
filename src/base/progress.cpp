#include "fissure/base/progress.hpp"

#include "fissure/base/error.hpp"

namespace fissure {

void CancelToken::throw_if_cancelled() const {
  if (cancelled()) throw Cancelled();
}

}  // namespace fissure
