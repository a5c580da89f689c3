// The restart's GLIBC_TUNABLES (core/huge_page_malloc.hpp): glibc.malloc.hugetlb=1 alone when none
// is set, appended after a ':' to tunables already set, and nothing (no restart) once it is named,
// whatever its value: the restarted process never restarts again.
#include <gtest/gtest.h>

#include "core/huge_page_malloc.hpp"

namespace penink {
namespace {

TEST(HugePageTunables, AppendedOnceToWhatIsSet) {
    EXPECT_EQ(huge_page_tunables(nullptr), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(huge_page_tunables(""), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(huge_page_tunables("glibc.malloc.check=3"), "glibc.malloc.check=3:glibc.malloc.hugetlb=1");
    EXPECT_EQ(huge_page_tunables("glibc.malloc.check=3:glibc.malloc.hugetlb=1"), "");
    EXPECT_EQ(huge_page_tunables("glibc.malloc.hugetlb=0"), "");  // set by hand: left as it is
    EXPECT_EQ(huge_page_tunables(huge_page_tunables("glibc.malloc.check=3").c_str()), "");
}

}  // namespace
}  // namespace penink
