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

// Written together, each file holds the bytes it holds written alone.
TEST(ExportDrawing, FilesWrittenTogetherHoldWhatEachHoldsAlone) {
    TempDir together("together"), alone("alone");
    const std::vector<std::string> names = {"a.svg", "a.ps", "a.eps", "a.pdf", "a.png", "b.png", "a.tif"};
    std::vector<std::string> paths;
    for (const std::string& n : names) paths.push_back(together.file(n));
    export_drawings(drawing(), PageOptions{}, paths);
    for (const std::string& n : names) {
        export_drawing(drawing(), PageOptions{}, alone.file(n));
        EXPECT_EQ(read_text(together.file(n)), read_text(alone.file(n))) << n;
    }
    EXPECT_EQ(files_in(together), files_in(alone));
}

TEST(ExportDrawing, UnknownFormat) {
    EXPECT_EQ(error_of([] { export_drawing(drawing(), PageOptions{}, "/tmp/x.xyz"); }),
              "penink: export: /tmp/x.xyz: unknown output format \".xyz\" (use .svg .ps .eps .pdf, or a raster: .png .tif .tiff .jpg .jpeg .webp .exr)");
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
    EXPECT_THROW(write_files_together({target}, [](std::size_t) -> std::string {
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

TEST(AtomicFile, FilesWrittenTogetherOrNotAtAll) {
    TempDir dir("together");
    const std::vector<std::string> paths = {dir.file("a.svg"), dir.file("b.png"), dir.file("c.pdf")};
    write_file_atomically(paths[0], "old");
    EXPECT_THROW(write_files_together(paths, [](std::size_t i) -> std::string {
        if (i == 2) throw Error("export", "c.pdf", "writer failed");
        return "new " + std::to_string(i);
    }), Error);
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"a.svg"});  // no temp file, b.png not made
    EXPECT_EQ(read_text(paths[0]), "old");
    write_files_together(paths, [](std::size_t i) { return "new " + std::to_string(i); });
    EXPECT_EQ(files_in(dir), (std::vector<std::string>{"a.svg", "b.png", "c.pdf"}));
    EXPECT_EQ(read_text(paths[0]), "new 0");
    EXPECT_EQ(read_text(paths[2]), "new 2");
}

TEST(ExportDrawing, OneFailingOutputLeavesNoneOfThem) {
    TempDir dir("all_or_none");
    const std::vector<std::string> paths = {dir.file("a.svg"), dir.file("b.png")};
    PageOptions huge;
    huge.dpi = 2e6;  // 200x160 image pixels: the PNG would be 4166667x3333333 pixels
    EXPECT_EQ(error_of([&] { export_drawings(drawing(), huge, paths); }),
              "penink: export: " + paths[1] + ": PNG of 4166667x3333333 pixels is too large (lower --dpi)");
    EXPECT_TRUE(files_in(dir).empty());
}

TEST(ExportDrawing, TargetsCheckedBeforeDrawing) {
    TempDir dir("targets");
    std::filesystem::create_directory(dir.file("folder.png"));
    const PageOptions page;
    EXPECT_EQ(error_of([&] { check_output_targets({dir.file("a.svg"), dir.file("folder.png")}, page, 100, 100); }),
              "penink: export: " + dir.file("folder.png") + ": cannot write file (is a directory)");
    EXPECT_EQ(error_of([&] { check_output_targets({dir.file("no/a.svg")}, page, 100, 100); }),
              "penink: export: " + dir.file("no/a.svg") + ": cannot write file (no such directory)");
    PageOptions dpi;
    dpi.dpi = 100000;
    EXPECT_EQ(error_of([&] { check_output_targets({dir.file("a.svg"), dir.file("b.png")}, dpi, 1000, 750); }),
              "penink: export: " + dir.file("b.png") + ": PNG of 1041667x781250 pixels is too large (lower --dpi)");
    PageOptions page_big;
    page_big.page = "100000x100000mm";
    EXPECT_EQ(error_of([&] { check_output_targets({dir.file("a.svg")}, page_big, 1000, 750); }),
              "penink: export: " + dir.file("a.svg") + ": page \"100000x100000mm\" is too large (at most 5000 mm a side)");
    EXPECT_EQ(error_of([&] { check_output_targets({dir.file("a.svg"), dir.file("b.png")}, page, 1000, 750); }), "no error");
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"folder.png"});
}
