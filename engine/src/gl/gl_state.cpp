#include "gl/gl_state.h"

#include "gl/objects.h"

#include <shadow/context.h>

#include <algorithm>

namespace shadow::gpu {
namespace {

GLboolean enabled(GLenum cap) { return gl.IsEnabled(cap); }

void setEnabled(GLenum cap, GLboolean on) { on ? gl.Enable(cap) : gl.Disable(cap); }

}  // namespace

void requireLoaded(std::string_view who) {
    if (gl.GetError == nullptr || gl.GetIntegerv == nullptr) {
        throw GlError(std::string(who) +
                      ": OpenGL is not loaded; make a 4.5 core context current and call loadGl first");
    }
}

std::string takePendingErrors() {
    std::string codes;
    // A lost context can report errors forever: read a bounded number.
    for (int i = 0; i < 16; ++i) {
        const GLenum e = gl.GetError();
        if (e == GL_NO_ERROR) break;
        if (!codes.empty()) codes += ", ";
        codes += glErrorName(e);
    }
    return codes;
}

void reportHostGlErrors(std::string_view call, FrameStats& stats) {
    const std::string codes = takePendingErrors();
    if (codes.empty()) return;
    stats.warnings.push_back({WarningCode::HostGlError, std::string(call),
                              "the GL context held " + codes + " before " + std::string(call) +
                                  " was called (an earlier call of the host's, not the engine's); read and cleared"});
}

GlState captureGlState(std::span<const GLint> units, std::span<const GLint> uniformBindings,
                       std::span<const GLint> imageUnits) {
    GlState s;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.drawFramebuffer);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.readFramebuffer);
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &s.program);
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vertexArray);
    gl.GetIntegerv(GL_VIEWPORT, s.viewport.data());
    gl.GetIntegerv(GL_SCISSOR_BOX, s.scissorBox.data());
    s.scissorTest = enabled(GL_SCISSOR_TEST);
    s.depthTest = enabled(GL_DEPTH_TEST);
    gl.GetIntegerv(GL_DEPTH_FUNC, &s.depthFunc);
    gl.GetBooleanv(GL_DEPTH_WRITEMASK, &s.depthMask);
    s.cullFace = enabled(GL_CULL_FACE);
    gl.GetIntegerv(GL_CULL_FACE_MODE, &s.cullFaceMode);
    gl.GetIntegerv(GL_FRONT_FACE, &s.frontFace);
    s.polygonOffsetFill = enabled(GL_POLYGON_OFFSET_FILL);
    for (GLuint i = 0; i < s.blend.size(); ++i) s.blend[i] = gl.IsEnabledi(GL_BLEND, i);
    const std::array<GLenum, 4> blendQueries{GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA,
                                             GL_BLEND_DST_ALPHA};
    for (std::size_t i = 0; i < blendQueries.size(); ++i) gl.GetIntegerv(blendQueries[i], s.blendFunc.data() + i);
    gl.GetBooleanv(GL_COLOR_WRITEMASK, s.colorMask.data());
    gl.GetIntegerv(GL_PACK_ALIGNMENT, &s.packAlignment);
    gl.GetIntegerv(GL_PACK_ROW_LENGTH, &s.packRowLength);
    gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &s.pixelPackBuffer);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &s.activeTexture);
    gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s.uniformBuffer);
    for (GLint unit : units.first(std::min(units.size(), s.units.size()))) {
        GlState::Unit& u = s.units[s.unitCount++];
        u.unit = unit;
        gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &u.texture2D);
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &u.texture2DArray);
        gl.GetIntegerv(GL_SAMPLER_BINDING, &u.sampler);
    }
    gl.ActiveTexture(static_cast<GLenum>(s.activeTexture));
    for (GLint index : uniformBindings.first(std::min(uniformBindings.size(), s.uniformBindings.size()))) {
        GlState::UniformBinding& b = s.uniformBindings[s.uniformBindingCount++];
        b.index = index;
        const auto i = static_cast<GLuint>(index);
        gl.GetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, i, &b.buffer);
        gl.GetInteger64i_v(GL_UNIFORM_BUFFER_START, i, &b.start);
        gl.GetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, i, &b.size);
    }
    for (GLint unit : imageUnits.first(std::min(imageUnits.size(), s.images.size()))) {
        GlState::ImageBinding& b = s.images[s.imageCount++];
        b.unit = unit;
        const auto i = static_cast<GLuint>(unit);
        GLint layered = 0;
        gl.GetIntegeri_v(GL_IMAGE_BINDING_NAME, i, &b.texture);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_LEVEL, i, &b.level);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYERED, i, &layered);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYER, i, &b.layer);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_ACCESS, i, &b.access);
        gl.GetIntegeri_v(GL_IMAGE_BINDING_FORMAT, i, &b.format);
        b.layered = layered != 0 ? GL_TRUE : GL_FALSE;
    }
    return s;
}

void setPassDefaults() {
    gl.Disable(GL_SCISSOR_TEST);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.FrontFace(GL_CCW);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.Disable(GL_BLEND);
}

void setReadbackDefaults() {
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
}

void restoreGlState(const GlState& s) {
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(s.drawFramebuffer));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(s.readFramebuffer));
    gl.UseProgram(static_cast<GLuint>(s.program));
    gl.BindVertexArray(static_cast<GLuint>(s.vertexArray));
    gl.Viewport(s.viewport[0], s.viewport[1], s.viewport[2], s.viewport[3]);
    gl.Scissor(s.scissorBox[0], s.scissorBox[1], s.scissorBox[2], s.scissorBox[3]);
    setEnabled(GL_SCISSOR_TEST, s.scissorTest);
    setEnabled(GL_DEPTH_TEST, s.depthTest);
    gl.DepthFunc(static_cast<GLenum>(s.depthFunc));
    gl.DepthMask(s.depthMask);
    setEnabled(GL_CULL_FACE, s.cullFace);
    gl.CullFace(static_cast<GLenum>(s.cullFaceMode));
    gl.FrontFace(static_cast<GLenum>(s.frontFace));
    setEnabled(GL_POLYGON_OFFSET_FILL, s.polygonOffsetFill);
    for (GLuint i = 0; i < s.blend.size(); ++i) s.blend[i] ? gl.Enablei(GL_BLEND, i) : gl.Disablei(GL_BLEND, i);
    gl.BlendFuncSeparate(static_cast<GLenum>(s.blendFunc[0]), static_cast<GLenum>(s.blendFunc[1]),
                         static_cast<GLenum>(s.blendFunc[2]), static_cast<GLenum>(s.blendFunc[3]));
    gl.ColorMask(s.colorMask[0], s.colorMask[1], s.colorMask[2], s.colorMask[3]);
    gl.PixelStorei(GL_PACK_ALIGNMENT, s.packAlignment);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, s.packRowLength);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(s.pixelPackBuffer));
    for (const GlState::Unit& u : std::span(s.units).first(s.unitCount)) {
        // Unbinds every target of the unit, then binds the host's textures back by target.
        gl.BindTextureUnit(static_cast<GLuint>(u.unit), 0);
        if (u.texture2D != 0 || u.texture2DArray != 0) {
            gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(u.unit));
            if (u.texture2D != 0) gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(u.texture2D));
            if (u.texture2DArray != 0) gl.BindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(u.texture2DArray));
        }
        gl.BindSampler(static_cast<GLuint>(u.unit), static_cast<GLuint>(u.sampler));
    }
    gl.ActiveTexture(static_cast<GLenum>(s.activeTexture));
    for (const GlState::UniformBinding& b : std::span(s.uniformBindings).first(s.uniformBindingCount)) {
        const auto i = static_cast<GLuint>(b.index);
        if (b.buffer != 0 && b.size > 0) {
            gl.BindBufferRange(GL_UNIFORM_BUFFER, i, static_cast<GLuint>(b.buffer), static_cast<GLintptr>(b.start),
                               static_cast<GLsizeiptr>(b.size));
        } else {
            gl.BindBufferBase(GL_UNIFORM_BUFFER, i, static_cast<GLuint>(b.buffer));
        }
    }
    for (const GlState::ImageBinding& b : std::span(s.images).first(s.imageCount)) {
        gl.BindImageTexture(static_cast<GLuint>(b.unit), static_cast<GLuint>(b.texture), b.level, b.layered, b.layer,
                            static_cast<GLenum>(b.access), static_cast<GLenum>(b.format));
    }
    // Indexed binds also set the generic binding: it goes back last.
    gl.BindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(s.uniformBuffer));
}

}  // namespace shadow::gpu
