// Shader sources and programs: shader_sources.hpp.
#include "gpu/shader_sources.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace isolux::app {

fs::path shader_folder() {
    if (const char* env = std::getenv("ISOLUX_SHADERS"); env && *env && fs::exists(fs::path(env) / "composite.frag"))
        return env;
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        fs::path installed = exe.parent_path().parent_path() / "share" / "isolux" / "shaders";
        if (fs::exists(installed / "composite.frag")) return installed;
    }
    fs::path source = ISOLUX_SOURCE_SHADERS;
    if (fs::exists(source / "composite.frag")) return source;
    return {};
}

std::string shader_source(const fs::path& folder, const std::string& name) {
    if (!folder.empty()) {
        std::ifstream f(folder / name, std::ios::binary);
        if (f) {
            std::ostringstream ss;
            ss << f.rdbuf();
            return ss.str();
        }
    }
    for (const EmbeddedShader& s : embedded_shaders())
        if (name == s.name) return s.source;
    return {};
}

GLuint build_program(const fs::path& folder, std::initializer_list<ShaderStage> stages, std::string& error) {
    std::string names;
    for (const ShaderStage& st : stages) names += (names.empty() ? "" : " + ") + st.name;
    std::vector<GLuint> shaders;
    auto fail = [&](const std::string& what) {
        for (GLuint s : shaders) glDeleteShader(s);
        error = what;
        return GLuint(0);
    };
    for (const ShaderStage& st : stages) {
        const std::string src = shader_source(folder, st.name);
        if (src.empty()) return fail("missing shader " + st.name);
        const GLuint s = glCreateShader(st.type);
        shaders.push_back(s);
        const char* text = src.c_str();
        glShaderSource(s, 1, &text, nullptr);
        glCompileShader(s);
        GLint ok = 0;
        glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[2048] = {0};
            glGetShaderInfoLog(s, sizeof log, nullptr, log);
            return fail(st.name + ": " + log);
        }
    }
    const GLuint p = glCreateProgram();
    for (GLuint s : shaders) glAttachShader(p, s);
    glLinkProgram(p);
    for (GLuint s : shaders) glDeleteShader(s);
    shaders.clear();
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {0};
        glGetProgramInfoLog(p, sizeof log, nullptr, log);
        glDeleteProgram(p);
        return fail(names + ": " + log);
    }
    return p;
}

}  // namespace isolux::app
