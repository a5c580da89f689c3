// Shader assembly from caller-supplied text (render/shader_source.hpp, gl_objects.hpp): its
// `#include`s resolve against the embedded shaders, and compile errors name the file and line.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "render/gl_objects.hpp"
#include "render/shader_source.hpp"
#include "support/gl_test_context.hpp"

using namespace penink;

namespace {

const char* probe_text = "#version 450 core\n"
                         "// line 2\n"
                         "#include \"common.glsl\"\n"
                         "layout(local_size_x = 1) in;\n"
                         "void main() { undeclared_name = 1.0; }\n";

TEST(ShaderSource, CallerTextIncludesTheEmbeddedFiles) {
    const AssembledShader a = assemble_shader(ShaderFile{"probe.comp.glsl", probe_text});
    ASSERT_GE(a.files.size(), 2u);
    EXPECT_EQ(a.files[0], "probe.comp.glsl");
    EXPECT_EQ(a.files[1], "common.glsl");
    EXPECT_EQ(a.text.rfind("#version 450 core\n#line 1 0\n", 0), 0u);
    EXPECT_NE(a.text.find("#line 1 1\n"), std::string::npos);
    EXPECT_NE(a.text.find("#line 4 0\nlayout(local_size_x = 1) in;\n"), std::string::npos);
    EXPECT_NE(a.text.find(shader_text("common.glsl").substr(0, 40)), std::string::npos);
    EXPECT_EQ(map_log_to_files("0:5(15): error: x\n1:12(1): y", a.files),
              "probe.comp.glsl:5(15): error: x\ncommon.glsl:12(1): y");
}

TEST(ShaderSource, EmbeddedFilesAssembleAsBefore) {
    const AssembledShader by_name = assemble_shader("dm.comp.glsl");
    const std::string text = shader_text("dm.comp.glsl");
    const AssembledShader by_text = assemble_shader(ShaderFile{"dm.comp.glsl", text.c_str()});
    EXPECT_EQ(by_name.text, by_text.text);
    EXPECT_EQ(by_name.files, by_text.files);
}

TEST(ShaderSource, CompileErrorOfCallerTextNamesFileAndLine) {
    const GlApi& gl = test::test_context().gl();
    try {
        build_program_from_text(gl, {ShaderFile{"probe.comp.glsl", probe_text}});
        FAIL() << "compiled a shader using an undeclared name";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "probe.comp.glsl");
        EXPECT_NE(std::string(e.what()).find("probe.comp.glsl:5("), std::string::npos) << e.what();
    }
}

TEST(ShaderSource, MissingIncludeIsAnError) {
    EXPECT_THROW(assemble_shader(ShaderFile{"probe.comp.glsl", "#include \"no_such.glsl\"\n"}), Error);
}

}  // namespace
