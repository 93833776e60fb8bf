#pragma once
// The outliner's tree: the scene's nodes as the file has them, each body with its fracture
// material, and a fractured body's fragments (at the age shown) under it. Rebuilt from the
// document's signals: a whole scene on scene_reset, one body's rows on body_changed.
#include "studio_document.hpp"

#include <QStandardItemModel>

#include <map>
#include <vector>

namespace fissure::studio {

class OutlinerModel : public QStandardItemModel {
  Q_OBJECT
 public:
  enum Role { NodeRole = Qt::UserRole + 1, BodyRole, FragmentRole, CracksRole };
  explicit OutlinerModel(StudioDocument* document, QObject* parent = nullptr);

  /// The item of a node, or null.
  QStandardItem* node_item(int node) const;

 signals:
  /// Around every rebuild of rows, so a selection of rows being replaced is kept.
  void rows_changing();
  void rows_changed();

 private:
  void rebuild();
  void rebuild_rows();
  void update_body(int body);
  void update_body_rows(int body);
  void update_assignments();
  StudioDocument* m_document;
  std::vector<QStandardItem*> m_node_items;
  std::map<int, int> m_listed_cracks;  ///< by body: the crack count its fragment rows are of
};

}  // namespace fissure::studio
