#pragma once
// The document's edits as QUndoCommands: each stores what it replaces, so undo and redo swap
// states and never recompute anything (undoing a fracture brings back the whole body at once;
// redoing it brings back the same fragments, not a new simulation).
#include "studio_document.hpp"

#include <QUndoCommand>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace fissure::studio {

/// Assigns a fracture material ("" removes the assignment) to a scene material or to a node path.
class AssignMaterialCommand : public QUndoCommand {
 public:
  enum class Target { SceneMaterial, Node };
  AssignMaterialCommand(StudioDocument* document, Target target, std::string key, std::string material);
  void redo() override;
  void undo() override;

 private:
  void apply(const std::string& material);
  StudioDocument* m_document;
  Target m_target;
  std::string m_key, m_after, m_before;
};

/// Replaces bodies' fracture results (null: whole again).
class ApplyFractureCommand : public QUndoCommand {
 public:
  ApplyFractureCommand(StudioDocument* document, std::map<int, std::shared_ptr<BodyFractureState>> after, const QString& text);
  void redo() override;
  void undo() override;

 private:
  StudioDocument* m_document;
  std::map<int, std::shared_ptr<BodyFractureState>> m_after, m_before;
};

/// Sets fragments' edits (a move, hide, show or delete of the selection).
class FragmentEditCommand : public QUndoCommand {
 public:
  FragmentEditCommand(StudioDocument* document, std::vector<std::pair<FragmentRef, FragmentEdit>> after, const QString& text);
  void redo() override;
  void undo() override;

 private:
  StudioDocument* m_document;
  std::vector<std::pair<FragmentRef, FragmentEdit>> m_after, m_before;
};

}  // namespace fissure::studio
