// SPDX-License-Identifier: LGPL-2.1-or-later
// The property strings under a locale whose decimal separator is a comma: a host application may switch to
// one, and "1,1,0.3" must not change meaning. On its own so that, where no such locale can be had, meson
// counts it as skipped (exit code 77) rather than the whole settings test passing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <clocale>
#include <cstdlib>
#include <string>

#include <glib.h>

#include "colortrack/settings.hpp"

using namespace colortrack;

namespace {

bool skipped = false;
std::string builtLocales;  // the folder localedef wrote to, removed at the end

// de_DE.UTF-8 if installed, or else built from glibc's locale sources (Debian's `locales`) with localedef
// into a folder of our own, which LOCPATH points setlocale at.
bool switchToCommaDecimals(std::string &why) {
  if (std::setlocale(LC_NUMERIC, "de_DE.UTF-8") || std::setlocale(LC_NUMERIC, "fr_FR.UTF-8")) return true;
  if (access("/usr/share/i18n/locales/de_DE", R_OK) != 0) {
    why =
        "no comma-decimal locale installed, and no /usr/share/i18n/locales/de_DE to build one (package "
        "locales)";
    return false;
  }
  gchar *dir = g_dir_make_tmp("colortrack-locale-XXXXXX", nullptr);
  const std::string folder = dir ? dir : "";
  g_free(dir);
  const std::string command = "localedef -i de_DE -f UTF-8 '" + folder + "/de_DE.UTF-8' > /dev/null 2>&1";
  if (folder.empty() || std::system(command.c_str()) != 0) {
    why = "localedef could not build de_DE.UTF-8";
    return false;
  }
  builtLocales = folder;
  setenv("LOCPATH", folder.c_str(), 1);
  if (std::setlocale(LC_NUMERIC, "de_DE.UTF-8")) return true;
  why = "setlocale refused the de_DE.UTF-8 that localedef built";
  return false;
}

}  // namespace

TEST(Format, IndependentOfTheCLocale) {
  const char *previous = std::setlocale(LC_NUMERIC, nullptr);
  const std::string saved = previous ? previous : "C";
  std::string why;
  if (!switchToCommaDecimals(why)) {
    skipped = true;
    GTEST_SKIP() << why;
  }
  char decimal[16];
  std::snprintf(decimal, sizeof decimal, "%.1f", 0.5);
  ChannelWeights w;
  const std::string text = formatWeights(w);
  const auto back = parseWeights("1,1,0.3");
  std::setlocale(LC_NUMERIC, saved.c_str());
  EXPECT_STREQ(decimal, "0,5") << "the locale switched to does not write a decimal comma";
  EXPECT_EQ(text, "1,1,0.3");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->w[2], 0.3);
}

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  if (!builtLocales.empty()) std::system(("rm -rf '" + builtLocales + "'").c_str());
  return result == 0 && skipped ? 77 : result;
}
