#include "gl/gl_state.h"

#include <shadow/shared_constants.h>

#include "gl/objects.h"

#include <shadow/context.h>

#include <algorithm>

namespace shadow::gpu {
namespace {

GLboolean enabled(GLenum cap) { return gl.IsEnabled(cap); }

void setEnabled(GLenum cap, GLboolean on) { on ? gl.Enable(cap) : gl.Disable(cap); }

/// `name` when it still names an object of kind `identifier` that the engine did not delete
/// after `mark`; 0 otherwise (what GL itself leaves bound once a bound object is deleted).
GLuint stillNamed(GLenum identifier, GLint name, std::uint64_t mark) {
    const auto n = static_cast<GLuint>(name);
    if (n == 0 || deletedSince(identifier, n, mark)) return 0;
    GLboolean exists = GL_FALSE;
    switch (identifier) {
        case GL_TEXTURE: exists = gl.IsTexture(n); break;
        case GL_BUFFER: exists = gl.IsBuffer(n); break;
        case GL_SAMPLER: exists = gl.IsSampler(n); break;
        case GL_FRAMEBUFFER: exists = gl.IsFramebuffer(n); break;
        case GL_VERTEX_ARRAY: exists = gl.IsVertexArray(n); break;
        case GL_PROGRAM: exists = gl.IsProgram(n); break;
        default: break;
    }
    return exists != GL_FALSE ? n : 0;
}

}  // namespace

void requireLoaded(std::string_view who) {
    if (gl.GetError == nullptr || gl.GetIntegerv == nullptr) {
        throw GlNotLoaded(std::string(who) +
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

void reportHostGlErrors(std::string_view call, std::vector<Warning>& warnings, std::size_t limit) {
    const std::string codes = takePendingErrors();
    if (codes.empty() || warnings.size() >= limit) return;
    warnings.push_back({WarningCode::HostGlError, std::string(call),
                        "the GL context held " + codes + " before " + std::string(call) +
                            " was called (an earlier call of the host's, not the engine's); read and cleared"});
}

void reportHostGlErrors(std::string_view call, FrameStats& stats) { reportHostGlErrors(call, stats.warnings); }

void movePendingWarnings(std::vector<Warning>& pending, std::vector<Warning>& to) {
    for (Warning& w : pending) to.push_back(std::move(w));
    pending.clear();
}

namespace {

/// The raster, depth and blend state of `GlState`.
void captureRaster(GlState& s) {
    gl.GetIntegerv(GL_VIEWPORT, s.viewport.data());
    gl.GetIntegerv(GL_SCISSOR_BOX, s.scissorBox.data());
    s.scissorTest = enabled(GL_SCISSOR_TEST);
    s.depthTest = enabled(GL_DEPTH_TEST);
    gl.GetIntegerv(GL_DEPTH_FUNC, &s.depthFunc);
    gl.GetBooleanv(GL_DEPTH_WRITEMASK, &s.depthMask);
    gl.GetDoublev(GL_DEPTH_RANGE, s.depthRange.data());
    gl.GetIntegerv(GL_CLIP_ORIGIN, &s.clipOrigin);
    gl.GetIntegerv(GL_CLIP_DEPTH_MODE, &s.clipDepthMode);
    gl.GetIntegerv(GL_POLYGON_MODE, s.polygonMode.data());
    s.cullFace = enabled(GL_CULL_FACE);
    gl.GetIntegerv(GL_CULL_FACE_MODE, &s.cullFaceMode);
    gl.GetIntegerv(GL_FRONT_FACE, &s.frontFace);
    s.polygonOffsetFill = enabled(GL_POLYGON_OFFSET_FILL);
    for (GLuint i = 0; i < s.blend.size(); ++i) s.blend[i] = gl.IsEnabledi(GL_BLEND, i);
    const std::array<GLenum, 4> blendQueries{GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA,
                                             GL_BLEND_DST_ALPHA};
    for (std::size_t i = 0; i < blendQueries.size(); ++i) gl.GetIntegerv(blendQueries[i], s.blendFunc.data() + i);
    gl.GetIntegerv(GL_BLEND_EQUATION_RGB, s.blendEquation.data());
    gl.GetIntegerv(GL_BLEND_EQUATION_ALPHA, s.blendEquation.data() + 1);
    gl.GetBooleanv(GL_COLOR_WRITEMASK, s.colorMask.data());
    gl.GetIntegerv(GL_PROVOKING_VERTEX, &s.provokingVertex);
    for (std::size_t i = 0; i < kPassOffCapabilities.size(); ++i)
        s.offCapabilities[i] = enabled(kPassOffCapabilities[i]);
}

/// The pixel-pack and -unpack state of `GlState`.
void capturePack(GlState& s) {
    gl.GetIntegerv(GL_PACK_ALIGNMENT, &s.packAlignment);
    gl.GetIntegerv(GL_PACK_ROW_LENGTH, &s.packRowLength);
    gl.GetIntegerv(GL_PACK_IMAGE_HEIGHT, &s.packImageHeight);
    gl.GetIntegerv(GL_PACK_SKIP_PIXELS, &s.packSkipPixels);
    gl.GetIntegerv(GL_PACK_SKIP_ROWS, &s.packSkipRows);
    gl.GetIntegerv(GL_PACK_SKIP_IMAGES, &s.packSkipImages);
    gl.GetBooleanv(GL_PACK_SWAP_BYTES, &s.packSwapBytes);
    gl.GetBooleanv(GL_PACK_LSB_FIRST, &s.packLsbFirst);
    gl.GetIntegerv(GL_CLAMP_READ_COLOR, &s.clampReadColor);
    gl.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &s.pixelPackBuffer);
    for (std::size_t i = 0; i < kUnpackParameters.size(); ++i) gl.GetIntegerv(kUnpackParameters[i], &s.unpack[i]);
    gl.GetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &s.pixelUnpackBuffer);
}

/// The texture units, uniform-buffer bindings and image units named.
void captureBindings(GlState& s, std::span<const GLint> units, std::span<const GLint> uniformBindings,
                     std::span<const GLint> imageUnits) {
    for (GLint unit : units.first(std::min(units.size(), s.units.size()))) {
        GlState::Unit& u = s.units[s.unitCount++];
        u.unit = unit;
        gl.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        for (std::size_t t = 0; t < kTextureBindingQueries.size(); ++t) {
            gl.GetIntegerv(kTextureBindingQueries[t], &u.textures[t]);
        }
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
}

}  // namespace

GlState captureGlState(std::span<const GLint> units, std::span<const GLint> uniformBindings,
                       std::span<const GLint> imageUnits) {
    GlState s;
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.drawFramebuffer);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.readFramebuffer);
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &s.program);
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vertexArray);
    captureRaster(s);
    capturePack(s);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &s.activeTexture);
    gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &s.uniformBuffer);
    captureBindings(s, units, uniformBindings, imageUnits);
    gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &s.storageBuffer);
    s.meshStorage[0].index = SG_BINDING_JOINTS;
    s.meshStorage[1].index = SG_BINDING_MORPH_DELTAS;
    s.meshStorage[2].index = SG_BINDING_EDGE_COUNTS;
    for (GlState::UniformBinding& b : s.meshStorage) {
        const auto index = static_cast<GLuint>(b.index);
        gl.GetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, index, &b.buffer);
        gl.GetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, index, &b.start);
        gl.GetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, index, &b.size);
    }
    return s;
}

void setPassDefaults() {
    gl.Disable(GL_SCISSOR_TEST);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.FrontFace(GL_CCW);
    gl.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    gl.ClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    gl.DepthRange(0.0, 1.0);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.Disable(GL_BLEND);
    gl.BlendEquationSeparate(GL_FUNC_ADD, GL_FUNC_ADD);
    gl.ProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    for (const GLenum cap : kPassOffCapabilities) gl.Disable(cap);
}

namespace {
/// Tightly packed client memory: alignment 1, the rest 0 or false (kUnpackParameters' order).
constexpr std::array<GLint, 8> kUnpackDefaults{1, 0, 0, 0, 0, 0, GL_FALSE, GL_FALSE};
}  // namespace

UnpackDefaults::UnpackDefaults() {
    for (std::size_t i = 0; i < kUnpackParameters.size(); ++i) gl.GetIntegerv(kUnpackParameters[i], &saved_[i]);
    gl.GetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &buffer_);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    for (std::size_t i = 0; i < kUnpackParameters.size(); ++i) gl.PixelStorei(kUnpackParameters[i], kUnpackDefaults[i]);
}

UnpackDefaults::~UnpackDefaults() {
    for (std::size_t i = 0; i < kUnpackParameters.size(); ++i) gl.PixelStorei(kUnpackParameters[i], saved_[i]);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(buffer_));
}

void setReadbackDefaults() {
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl.PixelStorei(GL_PACK_IMAGE_HEIGHT, 0);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, 0);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, 0);
    gl.PixelStorei(GL_PACK_SKIP_IMAGES, 0);
    gl.PixelStorei(GL_PACK_SWAP_BYTES, GL_FALSE);
    gl.PixelStorei(GL_PACK_LSB_FIRST, GL_FALSE);
    gl.ClampColor(GL_CLAMP_READ_COLOR, GL_FIXED_ONLY);
}

namespace {

void restoreRaster(const GlState& s) {
    gl.Viewport(s.viewport[0], s.viewport[1], s.viewport[2], s.viewport[3]);
    gl.Scissor(s.scissorBox[0], s.scissorBox[1], s.scissorBox[2], s.scissorBox[3]);
    setEnabled(GL_SCISSOR_TEST, s.scissorTest);
    setEnabled(GL_DEPTH_TEST, s.depthTest);
    gl.DepthFunc(static_cast<GLenum>(s.depthFunc));
    gl.DepthMask(s.depthMask);
    gl.DepthRange(s.depthRange[0], s.depthRange[1]);
    gl.ClipControl(static_cast<GLenum>(s.clipOrigin), static_cast<GLenum>(s.clipDepthMode));
    gl.PolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(s.polygonMode[0]));
    setEnabled(GL_CULL_FACE, s.cullFace);
    gl.CullFace(static_cast<GLenum>(s.cullFaceMode));
    gl.FrontFace(static_cast<GLenum>(s.frontFace));
    setEnabled(GL_POLYGON_OFFSET_FILL, s.polygonOffsetFill);
    for (GLuint i = 0; i < s.blend.size(); ++i) s.blend[i] ? gl.Enablei(GL_BLEND, i) : gl.Disablei(GL_BLEND, i);
    gl.BlendFuncSeparate(static_cast<GLenum>(s.blendFunc[0]), static_cast<GLenum>(s.blendFunc[1]),
                         static_cast<GLenum>(s.blendFunc[2]), static_cast<GLenum>(s.blendFunc[3]));
    gl.BlendEquationSeparate(static_cast<GLenum>(s.blendEquation[0]), static_cast<GLenum>(s.blendEquation[1]));
    gl.ColorMask(s.colorMask[0], s.colorMask[1], s.colorMask[2], s.colorMask[3]);
    gl.ProvokingVertex(static_cast<GLenum>(s.provokingVertex));
    for (std::size_t i = 0; i < kPassOffCapabilities.size(); ++i)
        setEnabled(kPassOffCapabilities[i], s.offCapabilities[i]);
}

void restorePack(const GlState& s, std::uint64_t mark) {
    gl.PixelStorei(GL_PACK_ALIGNMENT, s.packAlignment);
    gl.PixelStorei(GL_PACK_ROW_LENGTH, s.packRowLength);
    gl.PixelStorei(GL_PACK_IMAGE_HEIGHT, s.packImageHeight);
    gl.PixelStorei(GL_PACK_SKIP_PIXELS, s.packSkipPixels);
    gl.PixelStorei(GL_PACK_SKIP_ROWS, s.packSkipRows);
    gl.PixelStorei(GL_PACK_SKIP_IMAGES, s.packSkipImages);
    gl.PixelStorei(GL_PACK_SWAP_BYTES, s.packSwapBytes);
    gl.PixelStorei(GL_PACK_LSB_FIRST, s.packLsbFirst);
    gl.ClampColor(GL_CLAMP_READ_COLOR, static_cast<GLenum>(s.clampReadColor));
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, stillNamed(GL_BUFFER, s.pixelPackBuffer, mark));
    for (std::size_t i = 0; i < kUnpackParameters.size(); ++i) gl.PixelStorei(kUnpackParameters[i], s.unpack[i]);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, stillNamed(GL_BUFFER, s.pixelUnpackBuffer, mark));
}

void restoreBindings(const GlState& s, std::uint64_t mark) {
    for (const GlState::Unit& u : std::span(s.units).first(s.unitCount)) {
        // Unbinds every target of the unit, then binds the host's textures back by target.
        const auto unit = static_cast<GLuint>(u.unit);
        gl.BindTextureUnit(unit, 0);
        bool active = false;
        for (std::size_t t = 0; t < kTextureTargets.size(); ++t) {
            const GLuint texture = stillNamed(GL_TEXTURE, u.textures[t], mark);
            if (texture == 0) continue;
            if (!active) gl.ActiveTexture(GL_TEXTURE0 + unit);
            active = true;
            gl.BindTexture(kTextureTargets[t], texture);
        }
        gl.BindSampler(unit, stillNamed(GL_SAMPLER, u.sampler, mark));
    }
    gl.ActiveTexture(static_cast<GLenum>(s.activeTexture));
    for (const GlState::UniformBinding& b : std::span(s.uniformBindings).first(s.uniformBindingCount)) {
        const auto i = static_cast<GLuint>(b.index);
        const GLuint buffer = stillNamed(GL_BUFFER, b.buffer, mark);
        if (buffer != 0 && b.size > 0) {
            gl.BindBufferRange(GL_UNIFORM_BUFFER, i, buffer, static_cast<GLintptr>(b.start),
                               static_cast<GLsizeiptr>(b.size));
        } else {
            gl.BindBufferBase(GL_UNIFORM_BUFFER, i, buffer);
        }
    }
    for (const GlState::ImageBinding& b : std::span(s.images).first(s.imageCount)) {
        const GLuint texture = stillNamed(GL_TEXTURE, b.texture, mark);
        gl.BindImageTexture(static_cast<GLuint>(b.unit), texture, texture != 0 ? b.level : 0,
                            texture != 0 ? b.layered : GL_FALSE, texture != 0 ? b.layer : 0,
                            static_cast<GLenum>(b.access), static_cast<GLenum>(b.format));
    }
    for (const GlState::UniformBinding& b : s.meshStorage) {
        const GLuint buffer = stillNamed(GL_BUFFER, b.buffer, mark);
        const auto index = static_cast<GLuint>(b.index);
        if (buffer != 0 && b.size > 0) {
            gl.BindBufferRange(GL_SHADER_STORAGE_BUFFER, index, buffer, static_cast<GLintptr>(b.start),
                               static_cast<GLsizeiptr>(b.size));
        } else {
            gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, index, buffer);
        }
    }
    // Indexed binds also set the generic binding: it goes back last.
    gl.BindBuffer(GL_UNIFORM_BUFFER, stillNamed(GL_BUFFER, s.uniformBuffer, mark));
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, stillNamed(GL_BUFFER, s.storageBuffer, mark));
}

}  // namespace

void restoreGlState(const GlState& s, std::uint64_t mark) {
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, stillNamed(GL_FRAMEBUFFER, s.drawFramebuffer, mark));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, stillNamed(GL_FRAMEBUFFER, s.readFramebuffer, mark));
    gl.UseProgram(stillNamed(GL_PROGRAM, s.program, mark));
    gl.BindVertexArray(stillNamed(GL_VERTEX_ARRAY, s.vertexArray, mark));
    restoreRaster(s);
    restorePack(s, mark);
    restoreBindings(s, mark);
}

}  // namespace shadow::gpu
