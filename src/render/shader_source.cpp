#include "render/shader_source.hpp"

#include <regex>
#include <sstream>

#include "core/error.hpp"

namespace penink {

std::string shader_text(const std::string& name) {
    for (const ShaderFile& f : embedded_shaders())
        if (name == f.name) return f.source;
    throw Error("render", name, "no such embedded shader", ExitCode::internal);
}

namespace {

void append_file(const std::string& name, const std::string& text, AssembledShader& out, int depth) {
    if (depth > 8) throw Error("render", name, "#include nested too deeply", ExitCode::internal);
    const int index = int(out.files.size());
    out.files.push_back(name);
    out.text += "#line 1 " + std::to_string(index) + "\n";
    std::istringstream in(text);
    std::string line;
    static const std::regex include_re(R"(^\s*#include\s+\"([^\"]+)\"\s*$)");
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        std::smatch m;
        if (line.rfind("#version", 0) == 0) {
            out.text += "\n";  // the version line is emitted once, first
        } else if (std::regex_match(line, m, include_re)) {
            append_file(m[1].str(), shader_text(m[1].str()), out, depth + 1);
            out.text += "#line " + std::to_string(number + 1) + " " + std::to_string(index) + "\n";
        } else {
            out.text += line + "\n";
        }
    }
}

}  // namespace

AssembledShader assemble_shader(const std::string& name) {
    const std::string text = shader_text(name);
    return assemble_shader(ShaderFile{name.c_str(), text.c_str()});
}

AssembledShader assemble_shader(const ShaderFile& file) {
    AssembledShader out;
    out.text = "#version 450 core\n";
    append_file(file.name, file.source, out, 0);
    return out;
}

std::string map_log_to_files(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex loc_re(R"((\d+):(\d+)\()");
    std::string result;
    auto begin = std::sregex_iterator(log.begin(), log.end(), loc_re);
    std::size_t last = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
        const std::size_t file = std::stoul((*it)[1].str());
        result += log.substr(last, it->position() - last);
        result += (file < files.size() ? files[file] : (*it)[1].str()) + ":" + (*it)[2].str() + "(";
        last = it->position() + it->length();
    }
    return result + log.substr(last);
}

}  // namespace penink
