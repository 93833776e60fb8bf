// fissure-studio [SCENE|PROJECT]: the desktop modeller (issue 14).
#include "main_window.hpp"

#include <QApplication>

int main(int argc, char** argv) {
  fissure::studio::use_gl33_core_by_default();
  QApplication app(argc, argv);
  QApplication::setApplicationName("Fissure Studio");
  QApplication::setOrganizationName("Fissure");
  fissure::studio::MainWindow window;
  window.show();
  const QStringList args = QApplication::arguments();
  if (args.size() > 1) window.open_file(args.at(1));
  return app.exec();
}
