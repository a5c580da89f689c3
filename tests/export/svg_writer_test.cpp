// SVG: golden snapshot, byte determinism, Inkscape layers by exact name and order, number format.
#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>

#include "export/export_drawing.hpp"
#include "export/svg_writer.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;

namespace {

StyledDrawing golden_drawing(LayerSplit split = LayerSplit::kind) {
    return style_drawing(small_drawing(), visible_style(), split);
}

// inkscape:label values of the layer groups, in document order.
std::vector<std::string> svg_layers(const std::string& svg) {
    std::vector<std::string> names;
    const std::regex re("<g inkscape:groupmode=\"layer\" inkscape:label=\"([^\"]+)\" id=\"([^\"]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), re); it != std::sregex_iterator(); ++it) {
        EXPECT_EQ((*it)[1], (*it)[2]);
        names.push_back((*it)[1]);
    }
    return names;
}

}  // namespace

TEST(SvgWriter, MatchesGolden) {
    const std::string golden = PENINK_SOURCE_DIR "/tests/export/golden/small.svg";
    const std::string svg = svg_document(golden_drawing(), PageOptions{});
    if (const char* u = std::getenv("PENINK_UPDATE_GOLDEN"); u && std::string(u) == "1")
        write_text(golden, svg);
    EXPECT_EQ(svg, read_text(golden)) << "regenerate with PENINK_UPDATE_GOLDEN=1 (see golden/README.md)";
}

TEST(SvgWriter, ByteDeterministic) {
    TempDir dir("svgdet");
    export_drawing(golden_drawing(), PageOptions{}, dir.file("a.svg"));
    export_drawing(golden_drawing(), PageOptions{}, dir.file("b.svg"));
    const std::string a = read_text(dir.file("a.svg"));
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, read_text(dir.file("b.svg")));
}

TEST(SvgWriter, LayersInConventionOrder) {
    const std::string svg = svg_document(golden_drawing(), PageOptions{});
    EXPECT_EQ(svg_layers(svg), (std::vector<std::string>{"surface", "coastline", "hachures", "ridges", "creases", "pels",
                                                         "textures", "feature-edges", "silhouettes"}));
    EXPECT_NE(svg.find("<g inkscape:groupmode=\"layer\" inkscape:label=\"pels\" id=\"pels\" fill=\"none\" "
                       "stroke=\"#000000\" stroke-width=\"3\" stroke-linecap=\"round\" "
                       "stroke-linejoin=\"round\">\n</g>"),
              std::string::npos);  // empty layers are still written
    const std::vector<std::string> split = svg_layers(svg_document(golden_drawing(LayerSplit::kind_distance), {}));
    ASSERT_EQ(split.size(), 36u);
    EXPECT_EQ(split[4], "coastline");
    EXPECT_EQ(split[8], "hachures");
    EXPECT_EQ(split[12], "ridges");
    EXPECT_EQ(split[13], "ridges-near");
    EXPECT_EQ(split[14], "ridges-middle");
    EXPECT_EQ(split[15], "ridges-far");
}

TEST(SvgWriter, HeaderPageAndMetadata) {
    const std::string svg = svg_document(golden_drawing(), PageOptions{});
    EXPECT_EQ(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n", 0), 0u);
    EXPECT_NE(svg.find("width=\"52.9167mm\" height=\"42.3333mm\" viewBox=\"0 0 200 160\""), std::string::npos);
    EXPECT_NE(svg.find("<penink:param name=\"camera\">eye &lt;0 0 10&gt; &amp; &quot;test&quot;</penink:param>"),
              std::string::npos);
    EXPECT_NE(svg.find("<path fill=\"#d8d8d8\" fill-rule=\"evenodd\" stroke=\"none\" "
                       "d=\"M10 60 L190 60 190 150 10 150ZM80 90 L120 90 120 130 80 130Z\"/>"),
              std::string::npos);
    PageOptions a4;
    a4.page = "A4";
    a4.margin_mm = 10;
    const std::string paged = svg_document(golden_drawing(), a4);
    // Landscape A4 for a wide image; 277 x 190 mm usable: height limits, 1.1875 mm per px.
    EXPECT_NE(paged.find("width=\"297mm\" height=\"210mm\" viewBox=\"-25.0526 -8.4211 250.1053 176.8421\""),
              std::string::npos);
}

TEST(SvgWriter, PathAttributes) {
    const std::string svg = svg_document(golden_drawing(), PageOptions{});
    EXPECT_NE(svg.find("<path d=\"M30 120 L70 110 110 140\" stroke-width=\"2.5\" opacity=\"0.5\" "
                       "data-kind=\"crease\" data-depth=\"300\" data-strength=\"0.25\"/>"),
              std::string::npos);
    EXPECT_NE(svg.find("stroke-dasharray=\"8,6\""), std::string::npos);
    EXPECT_NE(svg.find("<path d=\"M40 30 L40 30\" data-kind=\"peak\""), std::string::npos);  // a dot, layer width 8
}

TEST(SvgWriter, NumberFormat) {
    EXPECT_EQ(format_number(12.5), "12.5");
    EXPECT_EQ(format_number(12.499), "12.5");
    EXPECT_EQ(format_number(3.0), "3");
    EXPECT_EQ(format_number(-0.001), "0");
    EXPECT_EQ(format_number(-2.25), "-2.25");
    EXPECT_EQ(format_number(0.1234, 3), "0.123");
    EXPECT_EQ(format_number(1e6), "1000000");
}

TEST(SvgWriter, XmlEscapeMakesAnyBytesWellFormed) {
    // markup escaped, UTF-8 kept, invalid bytes and XML-forbidden control characters as U+FFFD
    EXPECT_EQ(xml_escape("<a href=\"x\">&'</a>"), "&lt;a href=&quot;x&quot;&gt;&amp;&apos;&lt;/a&gt;");
    EXPECT_EQ(xml_escape("Zürich\tà\n"), "Zürich\tà\n");
    EXPECT_EQ(xml_escape("a\xff\xfe" "b"), "a\xEF\xBF\xBD\xEF\xBF\xBD" "b");
    EXPECT_EQ(xml_escape(std::string("x\x01y\x1b", 4)), "x\xEF\xBF\xBDy\xEF\xBF\xBD");
    EXPECT_EQ(xml_escape("\xed\xa0\x80"), "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");  // a surrogate: three bad bytes
    EXPECT_EQ(xml_escape("\xc3"), "\xEF\xBF\xBD");  // cut sequence
    EXPECT_EQ(xml_escape("\xf0\x9f\x97\xbb"), "\xf0\x9f\x97\xbb");  // 4-byte character kept
}
