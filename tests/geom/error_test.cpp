#include "vdg/geom/error.h"

#include <gtest/gtest.h>

namespace vdg {
namespace {

TEST(Error, MessageIsAlwaysOnePrintableLine) {
  const std::string name("evil\nname\0with\x1b[31mcolour", 25);
  const Error e(name + ": no such file");
  const std::string what = e.what();
  EXPECT_EQ(what, "evil\\nname\\0with\\x1B[31mcolour: no such file");
  EXPECT_EQ(what.find('\n'), std::string::npos);
  // what() as a C string holds the whole message: the embedded NUL no longer cuts it short.
  EXPECT_EQ(std::string(e.what()).size(), what.size());
}

TEST(Error, PrintableTextIsUnchanged) {
  const std::string text = "model.vdg.json: key 'front' (keys[0]): ünïcödé ok";
  EXPECT_EQ(std::string(Error(text).what()), text);
}

}  // namespace
}  // namespace vdg
