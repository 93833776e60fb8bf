#include "outliner_model.hpp"

#include "fissure/scene/fragment_export.hpp"

namespace fissure::studio {

OutlinerModel::OutlinerModel(StudioDocument* document, QObject* parent) : QStandardItemModel(parent), m_document(document) {
  setHorizontalHeaderLabels({"Name", "Fracture material"});
  connect(document, &StudioDocument::scene_reset, this, &OutlinerModel::rebuild);
  connect(document, &StudioDocument::body_changed, this, &OutlinerModel::update_body);
  connect(document, &StudioDocument::edits_changed, this, &OutlinerModel::update_body);  // "(hidden)", deleted rows
  // Only bodies whose shown crack count moved: most slider ticks change none.
  connect(document, &StudioDocument::age_changed, this, [this] {
    for (int b = 0; b < static_cast<int>(m_document->bodies().size()); ++b) {
      int cracks = 0;
      if (m_document->shown_fragments(b, &cracks) && cracks != m_listed_cracks[b]) update_body(b);
    }
  });
  connect(document, &StudioDocument::assignments_changed, this, &OutlinerModel::update_assignments);
  rebuild();
}

QStandardItem* OutlinerModel::node_item(int node) const {
  return node >= 0 && node < static_cast<int>(m_node_items.size()) ? m_node_items[static_cast<std::size_t>(node)] : nullptr;
}

void OutlinerModel::rebuild() {
  emit rows_changing();
  rebuild_rows();
  emit rows_changed();
}

void OutlinerModel::rebuild_rows() {
  removeRows(0, rowCount());
  m_node_items.clear();
  m_listed_cracks.clear();
  if (!m_document->is_open()) return;
  const ImportedScene& scene = m_document->scene();
  m_node_items.assign(scene.nodes.size(), nullptr);
  for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
    const SceneNode& node = scene.nodes[n];
    auto* item = new QStandardItem(QString::fromStdString(node.name));
    item->setEditable(false);
    item->setData(static_cast<int>(n), NodeRole);
    item->setData(m_document->body_of_node(static_cast<int>(n)), BodyRole);
    item->setData(-1, FragmentRole);
    item->setToolTip(QString::fromStdString(node.path));
    auto* material = new QStandardItem();
    material->setEditable(false);
    QStandardItem* parent = node.parent >= 0 ? m_node_items[static_cast<std::size_t>(node.parent)] : invisibleRootItem();
    parent->appendRow({item, material});
    m_node_items[n] = item;
  }
  update_assignments();
  for (int b = 0; b < static_cast<int>(m_document->bodies().size()); ++b)
    if (m_document->fracture_of(b)) update_body_rows(b);
}

void OutlinerModel::update_assignments() {
  for (int b = 0; b < static_cast<int>(m_document->bodies().size()); ++b) {
    QStandardItem* item = node_item(m_document->bodies()[static_cast<std::size_t>(b)].node);
    if (!item) continue;
    QStandardItem* parent = item->parent() ? item->parent() : invisibleRootItem();
    if (QStandardItem* material = parent->child(item->row(), 1))
      material->setText(QString::fromStdString(m_document->material_of(b)));
  }
}

void OutlinerModel::update_body(int body) {
  emit rows_changing();
  update_body_rows(body);
  emit rows_changed();
}

void OutlinerModel::update_body_rows(int body) {
  if (body < 0 || body >= static_cast<int>(m_document->bodies().size())) return;
  QStandardItem* item = node_item(m_document->bodies()[static_cast<std::size_t>(body)].node);
  if (!item) return;
  // A body's own children are scene nodes (kept) followed by its fragment rows (replaced).
  for (int r = item->rowCount() - 1; r >= 0; --r)
    if (item->child(r)->data(FragmentRole).toInt() >= 0) item->removeRow(r);
  int cracks = 0;
  const auto fragments = m_document->shown_fragments(body, &cracks);
  m_listed_cracks[body] = fragments ? cracks : -1;
  if (!fragments) return;
  const int count = static_cast<int>(fragments->size());
  for (int f = 0; f < count; ++f) {
    const FragmentEdit edit = m_document->edit_of({body, cracks, f});
    if (edit.deleted) continue;
    auto* row = new QStandardItem(QString::fromStdString(fragment_name(f, count)) + (edit.hidden ? " (hidden)" : ""));
    row->setEditable(false);
    row->setData(-1, NodeRole);
    row->setData(body, BodyRole);
    row->setData(f, FragmentRole);
    row->setData(cracks, CracksRole);
    auto* volume = new QStandardItem(QString("%1 cm³").arg((*fragments)[static_cast<std::size_t>(f)].volume * 1e6, 0, 'g', 3));
    volume->setEditable(false);
    item->appendRow({row, volume});
  }
}

}  // namespace fissure::studio
