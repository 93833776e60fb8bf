// A QApplication on Qt's offscreen platform (no display, no GL) for the studio's logic tests:
// documents, undo stacks and jobs need an event loop, not a window.
#include <QApplication>

#include <gtest/gtest.h>

int main(int argc, char** argv) {
  qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
