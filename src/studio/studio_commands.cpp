#include "studio_commands.hpp"

namespace fissure::studio {

AssignMaterialCommand::AssignMaterialCommand(StudioDocument* document, Target target, std::string key, std::string material)
    : m_document(document), m_target(target), m_key(std::move(key)), m_after(std::move(material)) {
  const auto& a = document->project().assignments;
  const auto& map = target == Target::SceneMaterial ? a.by_material : a.by_path;
  if (auto it = map.find(m_key); it != map.end()) m_before = it->second;
  const QString what = target == Target::SceneMaterial ? "material " : "";
  setText(m_after.empty() ? QString("Clear the assignment of %1%2").arg(what, QString::fromStdString(m_key))
                          : QString("Assign %1 to %2%3").arg(QString::fromStdString(m_after), what, QString::fromStdString(m_key)));
}

void AssignMaterialCommand::apply(const std::string& material) {
  if (m_target == Target::SceneMaterial) m_document->set_material_assignment(m_key, material);
  else m_document->set_node_assignment(m_key, material);
}

void AssignMaterialCommand::redo() { apply(m_after); }
void AssignMaterialCommand::undo() { apply(m_before); }

ApplyFractureCommand::ApplyFractureCommand(StudioDocument* document, std::map<int, std::shared_ptr<BodyFractureState>> after,
                                           const QString& text)
    : m_document(document), m_after(std::move(after)) {
  for (const auto& [body, state] : m_after)
    m_before[body] = std::const_pointer_cast<BodyFractureState>(document->fracture_of(body));
  setText(text);
}

void ApplyFractureCommand::redo() {
  for (const auto& [body, state] : m_after) m_document->set_fracture(body, state);
}

void ApplyFractureCommand::undo() {
  for (const auto& [body, state] : m_before) m_document->set_fracture(body, state);
}

FragmentEditCommand::FragmentEditCommand(StudioDocument* document, std::vector<std::pair<FragmentRef, FragmentEdit>> after,
                                         const QString& text)
    : m_document(document), m_after(std::move(after)) {
  for (const auto& [ref, edit] : m_after) m_before.emplace_back(ref, document->edit_of(ref));
  setText(text);
}

void FragmentEditCommand::redo() {
  for (const auto& [ref, edit] : m_after) m_document->set_edit(ref, edit);
}

void FragmentEditCommand::undo() {
  for (auto it = m_before.rbegin(); it != m_before.rend(); ++it) m_document->set_edit(it->first, it->second);
}

}  // namespace fissure::studio
