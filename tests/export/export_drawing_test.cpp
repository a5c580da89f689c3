// Format dispatch, atomic writes (exact error text, no temp files left), page options errors.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.hpp"
#include "export/atomic_file.hpp"
#include "export/export_drawing.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;

namespace {

std::vector<std::string> files_in(const TempDir& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir.path)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

StyledDrawing drawing() { return style_drawing(small_drawing(), default_style()); }

}  // namespace

TEST(ExportDrawing, EveryFormatWritesOnlyItsFile) {
    TempDir dir("formats");
    for (const char* name : {"a.svg", "a.ps", "a.EPS", "a.pdf", "a.png"})
        export_drawing(drawing(), PageOptions{}, dir.file(name));
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.EPS", "a.pdf", "a.png", "a.ps", "a.svg"}));
    EXPECT_EQ(read_text(dir.file("a.EPS")).rfind("%!PS-Adobe-3.0 EPSF-3.0\n", 0), 0u);
    EXPECT_EQ(read_text(dir.file("a.png")).substr(1, 3), "PNG");
    EXPECT_EQ(std::filesystem::status(dir.file("a.svg")).permissions() & std::filesystem::perms::owner_read,
              std::filesystem::perms::owner_read);
}

TEST(ExportDrawing, UnknownFormat) {
    EXPECT_EQ(error_of([] { export_drawing(drawing(), PageOptions{}, "/tmp/x.xyz"); }),
              "penink: export: /tmp/x.xyz: unknown output format \".xyz\" (use .svg, .ps, .eps, .pdf or .png)");
}

TEST(ExportDrawing, MissingDirectoryErrorsForEveryFormat) {
    for (const char* ext : {".svg", ".ps", ".pdf", ".png"}) {
        const std::string path = std::string("/nonexistent-penink-dir/out") + ext;
        EXPECT_EQ(error_of([&] { export_drawing(drawing(), PageOptions{}, path); }),
                  "penink: export: " + path + ": cannot write file (No such file or directory)");
    }
}

TEST(AtomicFile, FailureLeavesNothingAndSuccessReplaces) {
    TempDir dir("atomic");
    const std::string target = dir.file("out.svg");
    write_file_atomically(target, "old");
    EXPECT_THROW(write_atomically(target, [](const std::string& temp) {
        write_text(temp, "partial");
        throw std::runtime_error("writer failed");
    }), std::runtime_error);
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.svg"});
    EXPECT_EQ(read_text(target), "old");  // the previous file survives a failed write
    write_file_atomically(target, "new");
    EXPECT_EQ(read_text(target), "new");
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"out.svg"});
}

TEST(ExportDrawing, PageErrors) {
    PageOptions o;
    o.page = "A9";
    EXPECT_EQ(error_of([&] { export_drawing(drawing(), o, "/tmp/p.svg"); }),
              "penink: export: /tmp/p.svg: unknown page size \"A9\" (use A0-A6, B4, B5, letter, legal, tabloid or WxHmm)");
    o.page = "300x200mm";
    o.margin_mm = 150;
    EXPECT_EQ(error_of([&] { export_drawing(drawing(), o, "/tmp/p.svg"); }),
              "penink: export: /tmp/p.svg: margin leaves no room on the page");
    double w = 0, h = 0;
    page_size_mm("Letter", w, h);
    EXPECT_DOUBLE_EQ(w, 215.9);
    page_size_mm("420x297.5mm", w, h);
    EXPECT_DOUBLE_EQ(h, 297.5);
}
