#include "gl/program.h"

#include "gl/program_cache.h"
#include "gl/shader_sources.h"
#include "gl/technique_glsl.h"

#include <atomic>
#include <algorithm>
#include <initializer_list>
#include <optional>
#include <regex>
#include <sstream>

namespace shadow::gpu {

const char* findShaderSource(std::string_view name) {
    for (const ShaderSource& s : embeddedShaderSources()) {
        if (name == s.name) return s.text;
    }
    return nullptr;
}

namespace {

constexpr const char* kVersion = "#version 450 core\n";

/// An expansion in progress: the technique set of shadow_techniques.glsl, the files already
/// expanded (each file is expanded once, as if every file had `#pragma once`), the include
/// stack, and the generated texts (kept alive while expanded).
struct Expansion {
    unsigned techniques = 0;
    bool dropComments = false;  ///< comment-only lines become empty (line numbers stay)
    std::vector<std::string> expanded;
    std::vector<std::string> stack;
};

bool isConditional(const std::string& line) {
    static const std::regex kIf(R"(^\s*#\s*if(n?def)?\b.*)");
    return std::regex_match(line, kIf);
}
bool isEndif(const std::string& line) {
    static const std::regex kEndif(R"(^\s*#\s*endif\b.*)");
    return std::regex_match(line, kEndif);
}

/// Appends `file` to `out`, replacing each `#include "x"` line by x's expansion. Since a file is
/// expanded once, an `#include` under a condition (other than the file's own include guard)
/// could leave a file out that a later, unconditional include needs: it throws instead.
// NOLINTNEXTLINE(misc-no-recursion): as deep as the engine's own shader includes; a cycle throws.
void expandInto(const std::string& file, ExpandedSource& out, Expansion& expansion) {
    if (std::find(expansion.stack.begin(), expansion.stack.end(), file) != expansion.stack.end()) {
        throw GlError("shader include cycle through '" + file + "'");
    }
    if (std::find(expansion.expanded.begin(), expansion.expanded.end(), file) != expansion.expanded.end()) return;
    std::string generated;
    const char* text = nullptr;
    if (file == kTechniquesFile) {
        generated = techniquesGlsl(expansion.techniques);
        text = generated.c_str();
    } else {
        text = findShaderSource(file);
    }
    if (text == nullptr) {
        throw GlError("shader file '" + file + "' not found" +
                      (expansion.stack.empty() ? std::string() : " (included from " + expansion.stack.back() + ")"));
    }
    expansion.expanded.push_back(file);
    expansion.stack.push_back(file);
    const auto fileIndex = static_cast<int>(out.files.size());
    out.files.push_back(file == kTechniquesFile ? file + " (generated)" : file);
    out.text += "#line 1 " + std::to_string(fileIndex) + "\n";

    std::istringstream lines(text);
    std::string line;
    int lineNo = 0;
    int depth = 0;         // open #if/#ifdef/#ifndef blocks
    bool guarded = false;  // the first of them is the file's include guard (#ifndef at the top)
    bool sawCode = false;  // a line other than a comment or a blank came before it
    static const std::regex kInclude(R"re(^\s*#\s*include\s*"([^"]+)"\s*$)re");
    static const std::regex kBlankOrComment(R"(^\s*(//.*)?$)");
    std::smatch m;
    while (std::getline(lines, line)) {
        ++lineNo;
        if (std::regex_match(line, m, kInclude)) {
            if (depth > (guarded ? 1 : 0)) {
                throw GlError("shader file '" + file + "' line " + std::to_string(lineNo) +
                              ": #include under a condition (each file is included once, so a "
                              "conditional include could leave out a file a later include needs)");
            }
            expandInto(m[1].str(), out, expansion);
            out.text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(fileIndex) + "\n";
            continue;
        }
        if (isConditional(line)) {
            if (depth == 0 && !sawCode && line.find("ifndef") != std::string::npos) guarded = true;
            ++depth;
        } else if (isEndif(line)) {
            --depth;
        }
        const bool blankOrComment = std::regex_match(line, kBlankOrComment);
        if (!blankOrComment) sawCode = true;
        if (!(blankOrComment && expansion.dropComments)) out.text += line;
        out.text += '\n';
    }
    expansion.stack.pop_back();
}

GLuint compileStage(GLenum stage, const ExpandedSource& src, const std::string& label) {
    const GLuint shader = gl.CreateShader(stage);
    const char* text = src.text.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint ok = GL_FALSE;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok == GL_TRUE) return shader;
    GLint length = 0;
    gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    GLsizei written = 0;
    gl.GetShaderInfoLog(shader, length, &written, log.data());
    log.resize(static_cast<std::size_t>(std::max(written, 0)));  // without the terminating NUL
    gl.DeleteShader(shader);
    throw GlError("shader compile failed for " + label + ":\n" + mapShaderLog(log, src.files));
}

}  // namespace

ExpandedSource expandShader(const std::string& file, const std::vector<std::string>& defines, unsigned techniques) {
    ExpandedSource out;
    out.text = kVersion;
    for (const std::string& d : defines) out.text += "#define " + d + "\n";
    Expansion expansion{techniques, false, {}, {}};
    expandInto(file, out, expansion);
    return out;
}

ExpandedSource expandShaderBody(const std::string& file, const std::vector<std::string>& defines,
                                const std::string& hostName, unsigned techniques) {
    ExpandedSource out;
    out.files.push_back(hostName);
    for (const std::string& d : defines) out.text += "#define " + d + "\n";
    Expansion expansion{techniques, true, {}, {}};
    expandInto(file, out, expansion);
    return out;
}

std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files) {
    // Mesa prints "F:L(C): ", NVIDIA "F(L) : ". Both start with the file number.
    static const std::regex kPrefix(R"((^|\n)(\d+)([:(]))");
    std::string out;
    auto begin = std::sregex_iterator(log.begin(), log.end(), kPrefix);
    std::size_t last = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
        const std::smatch& m = *it;
        const auto index = static_cast<std::size_t>(std::stoul(m[2].str()));
        out.append(log, last, static_cast<std::size_t>(m.position(0)) - last);
        out += m[1].str();
        out += index < files.size() ? files[index] : m[2].str();
        out += m[3].str();
        last = static_cast<std::size_t>(m.position(0) + m.length(0));
    }
    out.append(log, last, std::string::npos);
    return out;
}

namespace {

/// Throws `GlError` with the link log of `program` (its messages mapped onto `files`) unless it
/// linked; labels it `label` when it did.
void requireLinked(const Program& program, const std::string& label, const std::vector<std::string>& files) {
    GLint ok = GL_FALSE;
    gl.GetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        gl.GetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        GLsizei written = 0;
        gl.GetProgramInfoLog(program.get(), length, &written, log.data());
        log.resize(static_cast<std::size_t>(std::max(written, 0)));  // without the terminating NUL
        throw GlError("shader link failed for " + label + ":\n" + mapShaderLog(log, files));
    }
    program.label(label);
}

}  // namespace

namespace {

/// One stage of a program: its type and its expanded source.
struct Stage {
    GLenum type;
    const ExpandedSource* source;
};

/// Compiles `stages`, links them into a program labelled `label` (or loads it from the program
/// cache), and throws `GlError` naming the file and line of the first error; link messages are
/// mapped onto the last stage's files.
/// Programs made by linkStages in this process (compiled, or loaded from the program cache).
std::atomic<std::uint64_t> programsMade{0};

Program linkStages(const std::string& label, std::initializer_list<Stage> stages) {
    ++programsMade;
    std::vector<const std::string*> texts;
    for (const Stage& s : stages) texts.push_back(&s.source->text);
    const std::string key = programKey(label, texts);
    if (std::optional<Program> cached = loadCachedProgram(key)) {
        cached->label(label);
        return std::move(*cached);
    }
    std::vector<GLuint> shaders;
    try {
        for (const Stage& s : stages) {
            shaders.push_back(compileStage(s.type, *s.source, label + " (" + s.source->files.front() + ")"));
        }
    } catch (...) {
        for (GLuint shader : shaders) gl.DeleteShader(shader);
        throw;
    }
    Program program(gl.CreateProgram());
    for (GLuint shader : shaders) gl.AttachShader(program.get(), shader);
    markRetrievable(program);
    gl.LinkProgram(program.get());
    for (GLuint shader : shaders) gl.DeleteShader(shader);
    requireLinked(program, label, (stages.end() - 1)->source->files);
    storeCachedProgram(key, program);
    return program;
}

}  // namespace

std::uint64_t programsBuilt() { return programsMade.load(); }

Program linkProgram(const std::string& label, const ExpandedSource& vertex, const ExpandedSource& fragment) {
    return linkStages(label, {{GL_VERTEX_SHADER, &vertex}, {GL_FRAGMENT_SHADER, &fragment}});
}

Program linkComputeProgram(const std::string& label, const ExpandedSource& compute) {
    return linkStages(label, {{GL_COMPUTE_SHADER, &compute}});
}

Program buildComputeProgram(const std::string& label, const std::string& file,
                            const std::vector<std::string>& defines) {
    return linkComputeProgram(label, expandShader(file, defines, 0));
}

Program buildProgram(const ProgramDesc& desc) {
    return linkProgram(desc.label, expandShader(desc.vertexFile, desc.defines, desc.techniques),
                       expandShader(desc.fragmentFile, desc.defines, desc.techniques));
}

}  // namespace shadow::gpu
