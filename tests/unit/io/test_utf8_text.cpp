// UTF-8 checks for what goes into a TOML file (the case record): well-formed sequences kept, other
// bytes refused or written as \xNN.
#include <gtest/gtest.h>

#include <string>

#include "io/utf8_text.hpp"

namespace granflow {
namespace {

TEST(Utf8Text, WellFormedSequencesOfOneToFourBytes) {
  EXPECT_TRUE(is_valid_utf8(""));
  EXPECT_TRUE(is_valid_utf8("plain ascii/path.toml"));
  EXPECT_TRUE(is_valid_utf8("caf\xc3\xa9"));           // U+00E9
  EXPECT_TRUE(is_valid_utf8("\xe2\x82\xac"));          // U+20AC
  EXPECT_TRUE(is_valid_utf8("\xed\x9f\xbf"));          // U+D7FF, below the surrogates
  EXPECT_TRUE(is_valid_utf8("\xf0\x9f\x98\x80"));      // U+1F600
  EXPECT_TRUE(is_valid_utf8("\xf4\x8f\xbf\xbf"));      // U+10FFFF, the last
}

TEST(Utf8Text, MalformedSequencesAreRefused) {
  EXPECT_FALSE(is_valid_utf8("caf\xe9"));              // Latin-1
  EXPECT_FALSE(is_valid_utf8("\x80"));                 // a continuation byte alone
  EXPECT_FALSE(is_valid_utf8("\xc3"));                 // cut short at the end
  EXPECT_FALSE(is_valid_utf8("\xc0\xaf"));             // overlong '/'
  EXPECT_FALSE(is_valid_utf8("\xe0\x80\xaf"));         // overlong, three bytes
  EXPECT_FALSE(is_valid_utf8("\xed\xa0\x80"));         // U+D800, a surrogate
  EXPECT_FALSE(is_valid_utf8("\xf4\x90\x80\x80"));     // above U+10FFFF
  EXPECT_FALSE(is_valid_utf8("\xff"));
}

TEST(Utf8Text, OtherBytesAreWrittenAsEscapes) {
  EXPECT_EQ(utf8_or_escaped("caf\xc3\xa9.toml"), "caf\xc3\xa9.toml");
  EXPECT_EQ(utf8_or_escaped("lat\xe9.toml"), "lat\\xE9.toml");
  EXPECT_EQ(utf8_or_escaped("\xe2\x82"), "\\xE2\\x82");  // a sequence cut short: each byte escaped
  EXPECT_EQ(utf8_or_escaped("\xc3\xa9\xff\xc3\xa9"), "\xc3\xa9\\xFF\xc3\xa9");
  EXPECT_TRUE(is_valid_utf8(utf8_or_escaped("\x80\xc0\xaf\xed\xa0\x80\xf4\x90\x80\x80")));
}

}  // namespace
}  // namespace granflow
