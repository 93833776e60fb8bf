#pragma once
// What the artist has selected: whole bodies (fragment −1) and fragments, shared by the
// viewport, the outliner and the commands. Cleared when another scene opens.
#include "studio_document.hpp"

#include <QObject>

#include <set>
#include <vector>

namespace fissure::studio {

class Selection : public QObject {
  Q_OBJECT
 public:
  using QObject::QObject;
  const std::set<FragmentRef>& items() const { return m_items; }
  bool empty() const { return m_items.empty(); }
  bool contains(const FragmentRef& r) const { return m_items.count(r) > 0; }
  /// Whole bodies and the bodies of selected fragments, ascending, once each.
  std::vector<int> bodies() const;
  /// The selected fragments (not whole bodies).
  std::set<FragmentRef> fragments() const;
  void set(std::set<FragmentRef> items);
  void toggle(const FragmentRef& r);
  void clear() { set({}); }

 signals:
  void changed();

 private:
  std::set<FragmentRef> m_items;
};

}  // namespace fissure::studio
