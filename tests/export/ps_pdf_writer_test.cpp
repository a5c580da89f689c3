// PostScript/EPS DSC structure and layer comments; PDF optional content groups and xref; text from
// input escaped in both.
#include <gtest/gtest.h>

#include <cstring>
#include <regex>

#include "core/version.hpp"
#include "export/pdf_writer.hpp"
#include "export/ps_writer.hpp"
#include "fixture.hpp"

using namespace penink;
using namespace penink::test;

namespace {

const std::vector<std::string> kLayers = {"surface", "coastline", "hachures", "ridges", "creases", "pels",
                                          "textures", "feature-edges", "silhouettes"};

StyledDrawing drawing(LayerSplit split = LayerSplit::kind) {
    return style_drawing(small_drawing(), visible_style(), split);
}

std::vector<std::string> matches(const std::string& text, const std::string& pattern) {
    std::vector<std::string> out;
    const std::regex re(pattern);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
        out.push_back((*it)[1]);
    return out;
}

}  // namespace

TEST(PsWriter, DscHeaderAndLayers) {
    const std::string ps = ps_document(drawing(), PageOptions{}, false, "x.ps");
    EXPECT_EQ(ps.rfind(std::string("%!PS-Adobe-3.0\n%%Creator: penink ") + penink_version +
                           "\n%%Title: x.ps\n%%BoundingBox: 0 0 150 120\n%%HiResBoundingBox: 0 0 150 120\n",
                       0),
              0u);
    EXPECT_NE(ps.find("%%Pages: 1\n"), std::string::npos);
    EXPECT_NE(ps.find("<< /PageSize [150 120] >> setpagedevice"), std::string::npos);
    EXPECT_EQ(matches(ps, "%%BeginLayer: ([^\n]+)\n"), kLayers);
    EXPECT_EQ(matches(ps, "\\(([^)]+)\\) Ln\n"), kLayers);
    EXPECT_EQ(matches(ps, "(%%EndLayer)\n").size(), 9u);
    EXPECT_EQ(ps.substr(ps.size() - 6), "%%EOF\n");
    // y flipped once: image pixel (0, 0) is the page's top-left corner (120 pt up).
    EXPECT_NE(ps.find("0.75 0 0 -0.75 0 120 cm\n1 J 1 j\n"), std::string::npos);
    // Opacity 0.5 of #b03020 blended toward white.
    EXPECT_NE(ps.find(format_number(0xd8 / 255.0, 3) + " " + format_number(0x98 / 255.0, 3) + " " +
                      format_number(0x90 / 255.0, 3) + " RG"), std::string::npos);
}

TEST(PsWriter, EpsHeaderAndSublayers) {
    const std::string eps = ps_document(drawing(LayerSplit::kind_distance), PageOptions{}, true, "x.eps");
    EXPECT_EQ(eps.rfind("%!PS-Adobe-3.0 EPSF-3.0\n", 0), 0u);
    EXPECT_EQ(eps.find("setpagedevice"), std::string::npos);
    const auto names = matches(eps, "%%BeginLayer: ([^\n]+)\n");
    ASSERT_EQ(names.size(), 36u);
    EXPECT_EQ(names[32], "silhouettes");
    EXPECT_EQ(names[35], "silhouettes-far");
}

TEST(PdfWriter, OptionalContentGroups) {
    const std::string pdf = pdf_document(drawing(), PageOptions{}, "x.pdf");
    EXPECT_EQ(pdf.rfind("%PDF-1.5\n", 0), 0u);
    EXPECT_EQ(matches(pdf, "<< /Type /OCG /Name \\(([^)]+)\\) >>"), kLayers);
    EXPECT_NE(pdf.find("/OCProperties << /OCGs [6 0 R 7 0 R 8 0 R 9 0 R 10 0 R 11 0 R 12 0 R 13 0 R 14 0 R] /D << "
                       "/Name (penink layers) /Order [6 0 R 7 0 R 8 0 R 9 0 R 10 0 R 11 0 R 12 0 R 13 0 R 14 0 R] "
                       "/ON [6 0 R 7 0 R 8 0 R 9 0 R 10 0 R 11 0 R 12 0 R 13 0 R 14 0 R] /OFF [] >> >>"),
              std::string::npos);
    EXPECT_EQ(matches(pdf, "/OC (/oc[0-9]+) BDC").size(), 9u);
    EXPECT_NE(pdf.find("/Properties << /oc0 6 0 R"), std::string::npos);
    EXPECT_NE(pdf.find("/GS0 << /Type /ExtGState /CA 0.5 >>"), std::string::npos);
    EXPECT_EQ(pdf.find("CreationDate"), std::string::npos);
    EXPECT_NE(pdf.find("/MediaBox [0 0 150 120]"), std::string::npos);
}

TEST(PdfWriter, XrefOffsetsPointAtObjects) {
    const std::string pdf = pdf_document(drawing(LayerSplit::kind_distance), PageOptions{}, "x.pdf");
    const size_t sx = pdf.rfind("startxref\n");
    const size_t xref = std::stoul(pdf.substr(sx + 10));
    ASSERT_EQ(pdf.compare(xref, 5, "xref\n"), 0);
    const auto offsets = matches(pdf.substr(xref), "([0-9]{10}) 00000 n \n");
    ASSERT_EQ(offsets.size(), 5u + 36u);
    for (size_t i = 0; i < offsets.size(); ++i)
        EXPECT_EQ(pdf.compare(std::stoul(offsets[i]), std::to_string(i + 1).size() + 6,
                              std::to_string(i + 1) + " 0 obj"), 0) << i;
    EXPECT_NE(pdf.find("/Order [6 0 R [7 0 R 8 0 R 9 0 R] 10 0 R [11 0 R 12 0 R 13 0 R] 14 0 R ["), std::string::npos);
}

TEST(PdfWriter, StringEscapes) {
    EXPECT_EQ(pdf_string("a(b)c\\d\xc3\xa9"), "(a\\(b\\)c\\\\d\\303\\251)");
}

namespace {

// Every byte value, the delimiters of PostScript and PDF strings and markup among them: what a
// title, a file name or a CRS name read from input may hold.
std::string hostile_text() {
    std::string s = "a(b))((c\\d<svg>&amp;%%EOF\n%!PS\r";
    for (int b = 0; b < 256; ++b) s += char(b);
    return s + "\\";
}

// The PDF literal string starting at `at` (its "(") read back: escapes \ddd, \n, \\, \(, \)
// and balanced parentheses (PDF 32000-1, 7.3.4.2). `end` gets the offset after its ")".
std::string pdf_literal(const std::string& pdf, std::size_t at, std::size_t& end) {
    std::string out;
    int depth = 0;
    for (std::size_t i = at; i < pdf.size(); ++i) {
        const char c = pdf[i];
        if (c == '\\') {
            const char n = pdf[++i];
            if (n >= '0' && n <= '7') {
                int v = 0, k = 0;
                for (; k < 3 && pdf[i] >= '0' && pdf[i] <= '7'; ++k, ++i) v = v * 8 + (pdf[i] - '0');
                --i;
                out += char(v);
            } else {
                out += n == 'n' ? '\n' : n == 'r' ? '\r' : n == 't' ? '\t' : n;
            }
            continue;
        }
        if (c == '(' && depth++ == 0) continue;
        if (c == ')' && --depth == 0) {
            end = i + 1;
            return out;
        }
        out += c;
    }
    end = std::string::npos;
    return out;
}

}  // namespace

// Text from input goes into PostScript only as 7-bit comment text (one line each) and into PDF as
// literal strings that read back to the same bytes: no byte ends a string, a comment or the file
// early, whatever the title, the metadata or the CRS's WKT hold.
TEST(PsPdfWriter, TextFromInputIsEscaped) {
    StyledDrawing d = drawing();
    const std::string text = hostile_text();
    d.metadata["title"] = text;
    d.metadata["description"] = text;
    d.metadata["source"] = text;
    d.metadata[text] = "key";
    for (const bool eps : {false, true}) {
        const std::string ps = ps_document(d, PageOptions{}, eps, "x.ps");
        for (const char c : ps)
            ASSERT_TRUE(c == '\n' || (c >= 32 && c < 127)) << int(static_cast<unsigned char>(c));  // Clean7Bit
        const std::size_t title = ps.find("%%Title: ");
        ASSERT_NE(title, std::string::npos);
        EXPECT_LT(ps.find('\n', title), ps.find("%%BoundingBox"));  // one line
        EXPECT_EQ(ps.find("\n%%EOF"), ps.size() - 7);  // the text's own %%EOF is not at a line's start
        EXPECT_EQ(ps.find("\n%!PS"), std::string::npos);
        EXPECT_EQ(matches(ps, "\\(([^)]+)\\) Ln\n"), kLayers);
    }
    const std::string pdf = pdf_document(d, PageOptions{}, "x.pdf");
    for (const char* key : {"/Title ", "/Subject ", "/penink_source "}) {
        const std::size_t at = pdf.find(key);
        ASSERT_NE(at, std::string::npos) << key;
        std::size_t end = 0;
        EXPECT_EQ(pdf_literal(pdf, at + std::strlen(key), end), text) << key;
        ASSERT_NE(end, std::string::npos);
        EXPECT_EQ(pdf[end], ' ') << key;  // the dictionary goes on after the string
    }
    EXPECT_NE(pdf.find("/Title ("), std::string::npos);
    EXPECT_EQ(pdf.find(text.substr(0, 4)), std::string::npos);  // "a(b)" only ever escaped
    const std::size_t xref = std::stoul(pdf.substr(pdf.rfind("startxref\n") + 10));
    EXPECT_EQ(pdf.compare(xref, 5, "xref\n"), 0);
}
