#pragma once
// A scene text the loader must refuse, and the check that it names file, line and attribute
// (shared by the scene error tests).
#include <exception>
#include <string>

#include <gtest/gtest.h>

#include "scenes/scene.h"

namespace testing_scenes {

struct BadScene {
  const char* what;
  const char* xml;  // line 1 is <scene ...>, so the culprit's line is easy to count
  int line;
  const char* attribute;  // "" when the element as a whole is wrong
  const char* says;       // a piece of the message
};

/// Loads c.xml as "bad.xml" and checks the LoadError: file, line, attribute and message.
inline void expectRefused(const BadScene& c) {
  try {
    scenes::loadSceneText(c.xml, "bad.xml");
    ADD_FAILURE() << c.what << ": loaded";
  } catch (const scenes::LoadError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.file(), "bad.xml") << c.what;
    EXPECT_EQ(e.line(), c.line) << c.what << ": " << message;
    EXPECT_EQ(e.attribute(), c.attribute) << c.what << ": " << message;
    EXPECT_EQ(message.rfind("bad.xml:" + std::to_string(c.line) + ": ", 0), 0u) << c.what << ": " << message;
    if (*c.attribute != '\0') {
      EXPECT_NE(message.find(std::string("attribute '") + c.attribute + "'"), std::string::npos) << message;
    }
    EXPECT_NE(message.find(c.says), std::string::npos) << c.what << ": " << message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << c.what << ": wrong exception: " << e.what();
  }
}

}  // namespace testing_scenes
