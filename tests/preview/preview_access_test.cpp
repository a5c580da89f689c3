// Who a preview server answers: the token (random, compared whole) and the Host header.
#include <gtest/gtest.h>

#include <set>

#include "preview/preview_access.hpp"

using namespace penink;

TEST(PreviewAccess, TokensAre128RandomBitsInHex) {
    std::set<std::string> seen;
    for (int i = 0; i < 50; ++i) {
        const std::string t = random_token();
        ASSERT_EQ(t.size(), 32u);
        EXPECT_EQ(t.find_first_not_of("0123456789abcdef"), std::string::npos) << t;
        seen.insert(t);
    }
    EXPECT_EQ(seen.size(), 50u);  // 50 draws of 128 bits: a repeat would mean no randomness
}

TEST(PreviewAccess, OnlyTheExactTokenMatches) {
    const std::string token = "0123456789abcdef0123456789abcdef";
    EXPECT_TRUE(token_matches(token, token));
    EXPECT_FALSE(token_matches("", token));
    EXPECT_FALSE(token_matches(token.substr(0, 31), token));
    EXPECT_FALSE(token_matches(token + "0", token));
    EXPECT_FALSE(token_matches("0123456789abcdef0123456789abcdee", token));
    EXPECT_FALSE(token_matches("1123456789abcdef0123456789abcdef", token));
    EXPECT_FALSE(token_matches("", ""));  // a server without a token answers nobody
}

TEST(PreviewAccess, HostMustNameTheLoopbackAndThePort) {
    EXPECT_TRUE(host_allowed("127.0.0.1:8123", 8123));
    EXPECT_TRUE(host_allowed("localhost:8123", 8123));
    EXPECT_TRUE(host_allowed("LocalHost:8123", 8123));
    EXPECT_FALSE(host_allowed("127.0.0.1:8124", 8123));
    EXPECT_FALSE(host_allowed("127.0.0.1", 8123));
    EXPECT_FALSE(host_allowed("", 8123));
    EXPECT_FALSE(host_allowed("evil.example:8123", 8123));  // a rebound DNS name
    EXPECT_FALSE(host_allowed("localhost.evil.example:8123", 8123));
    EXPECT_FALSE(host_allowed("127.0.0.1:8123.evil", 8123));
    EXPECT_FALSE(host_allowed("[::1]:8123", 8123));  // the server listens on IPv4 only
}
