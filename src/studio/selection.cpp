#include "selection.hpp"

namespace fissure::studio {

std::vector<int> Selection::bodies() const {
  std::set<int> out;
  for (const FragmentRef& r : m_items) out.insert(r.body);
  return {out.begin(), out.end()};
}

std::set<FragmentRef> Selection::fragments() const {
  std::set<FragmentRef> out;
  for (const FragmentRef& r : m_items)
    if (r.fragment >= 0) out.insert(r);
  return out;
}

void Selection::set(std::set<FragmentRef> items) {
  if (items == m_items) return;
  m_items = std::move(items);
  emit changed();
}

void Selection::toggle(const FragmentRef& r) {
  auto items = m_items;
  if (!items.erase(r)) items.insert(r);
  set(std::move(items));
}

}  // namespace fissure::studio
