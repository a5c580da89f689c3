// append_number's text (export/page.hpp) is std::to_chars' fixed format, trimmed, for every value:
// its exact integer path (|value| < 1e14, 0..4 decimals) against the to_chars text on exact
// binary ties (which round to even), values either side of them, random values of every
// magnitude and sign, and the edges of the path.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <random>
#include <string>

#include "export/page.hpp"

using namespace penink;

namespace {

// The text as to_chars makes it: fixed, `decimals` digits, trailing zeros and a trailing point
// dropped, "-0" read "0".
std::string reference(double value, int decimals) {
    char buf[400];
    if (!std::isfinite(value)) value = 0.0;
    const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, decimals);
    char* end = r.ptr;
    if (decimals > 0) {
        while (end > buf && end[-1] == '0') --end;
        if (end > buf && end[-1] == '.') --end;
    }
    std::string s(buf, end);
    return s == "-0" ? "0" : s;
}

void expect_same(double value, int decimals) {
    std::string got;
    append_number(got, value, decimals);
    EXPECT_EQ(got, reference(value, decimals)) << "value " << value << " (" << std::hexfloat << value
                                                << std::defaultfloat << "), " << decimals << " decimals";
}

}  // namespace

TEST(NumberText, ExactTiesRoundToEvenAsToChars) {
    for (int decimals = 0; decimals <= 5; ++decimals) {
        // every exact tie at `decimals` (an odd multiple of 10^-decimals / 2 that binary holds) is
        // a multiple of 2^-(decimals + 1); these go 4 times finer
        for (int k = -4000; k <= 4000; ++k) {
            const double tie = std::ldexp(double(k), -(decimals + 3));
            for (const double v : {tie, std::nextafter(tie, 1e300), std::nextafter(tie, -1e300)}) expect_same(v, decimals);
        }
        for (const double v : {0.5, 1.5, 2.5, 0.25, 0.75, 0.125, 0.375, 0.0625, 0.03125, 0.005, 0.015, 1.005, -0.125})
            expect_same(v, decimals), expect_same(-v, decimals);
    }
}

TEST(NumberText, EveryMagnitudeAndSign) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-30, 60);
    for (int i = 0; i < 200000; ++i) {
        const double v = std::ldexp(mantissa(rng), exponent(rng));
        expect_same(v, i % 6);
        if (::testing::Test::HasFailure()) return;
    }
    for (const double v : {0.0, -0.0, 1e-320, -1e-320, 99999999999999.99, 1e14, -1e14, 123456789012345.6, 4.5e15, 1e300,
                           -1e300, double(INFINITY), double(NAN), -0.004, -0.005, -0.006})
        for (int decimals = 0; decimals <= 6; ++decimals) expect_same(v, decimals);
}
