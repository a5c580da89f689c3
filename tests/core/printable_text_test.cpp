#include "core/printable_text.hpp"

#include <gtest/gtest.h>

namespace penink {
namespace {

TEST(PrintableText, EscapesWhatIsNotUtf8OrPrintable) {
    EXPECT_EQ(printable_text("abc 1.5"), "abc 1.5");
    EXPECT_EQ(printable_text("\xff\xfe\x01x"), "\\xff\\xfe\\x01x");
    EXPECT_EQ(printable_text("tab\there\n"), "tab\\x09here\\x0a");
    EXPECT_EQ(printable_text("a\\b"), "a\\\\b");
    EXPECT_EQ(printable_text("Mt Eden \xc3\xa9t\xc3\xa9 \xe2\x82\xac"), "Mt Eden \xc3\xa9t\xc3\xa9 \xe2\x82\xac");  // UTF-8 kept
    EXPECT_EQ(printable_text("\xc3"), "\\xc3");          // cut sequence
    EXPECT_EQ(printable_text("\xc0\xaf"), "\\xc0\\xaf");  // overlong '/'
    EXPECT_EQ(printable_text("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // surrogate
    EXPECT_EQ(printable_text("abcdef", 3), "abc...");
    EXPECT_EQ(printable_text("abc", 3), "abc");
}

TEST(PrintableText, FindsTheFirstByteThatIsNotUtf8) {
    EXPECT_EQ(invalid_utf8_at("plain = 1\n"), npos_utf8);
    EXPECT_EQ(invalid_utf8_at("name = \"\xc3\xa9\xe2\x82\xac\"\n"), npos_utf8);
    EXPECT_EQ(invalid_utf8_at("ab\x8b"), 2u);
    EXPECT_EQ(invalid_utf8_at("a\xe2\x82"), 1u);  // cut short at the end
}

}  // namespace
}  // namespace penink
