// The one-line error text and the numbers it quotes (core/error.hpp).
#include <gtest/gtest.h>

#include "core/error.hpp"

namespace penink {
namespace {

TEST(ErrorText, FileLeftOutWhenEmpty) {
    EXPECT_EQ(format_error("scene", "a.toml", "bad key"), "penink: scene: a.toml: bad key");
    EXPECT_EQ(format_error("cli", "", "no input"), "penink: cli: no input");
    const Error e("input", "dem.tif", "no such file");
    EXPECT_STREQ(e.what(), "penink: input: dem.tif: no such file");
    EXPECT_EQ(e.code(), ExitCode::bad_input);
}

TEST(ErrorText, NumbersAsPrintfG) {
    EXPECT_EQ(message_number(0.1), "0.1");
    EXPECT_EQ(message_number(1000.0), "1000");
    EXPECT_EQ(message_number(1e6), "1e+06");
    EXPECT_EQ(message_number(-2.5e-9), "-2.5e-09");
    EXPECT_EQ(message_number(1.0 / 3.0), "0.333333");
}

}  // namespace
}  // namespace penink
