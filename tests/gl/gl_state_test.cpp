// The state guard itself (engine/src/gl/gl_state.h): what it captures comes back, every texture
// target of a unit included, and an object the engine deleted under it is left unbound, also when
// GL hands its name out again before the guard ends.
#include "gl/gl_state.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <vector>

#include "render/render_test_support.h"

namespace shadow {
namespace {

const std::array<GLint, 2> kUnits{3, 4};

/// Unbinds what a test bound on the units it used (other tests share the context).
void unbindUnits() {
    for (GLint u : kUnits) {
        gl.BindTextureUnit(static_cast<GLuint>(u), 0);
        gl.BindSampler(static_cast<GLuint>(u), 0);
    }
    gl.ActiveTexture(GL_TEXTURE0);
}

TEST(GlState, EveryTextureTargetOfAUnitComesBack) {
    test::glContext();
    gl.ActiveTexture(GL_TEXTURE3);
    std::vector<GLuint> textures;
    for (const GLenum target : {GL_TEXTURE_2D, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP, GL_TEXTURE_2D_ARRAY}) {
        GLuint t = 0;
        gl.CreateTextures(target, 1, &t);
        gl.BindTexture(target, t);
        textures.push_back(t);
    }
    const gpu::GlState before = gpu::captureGlState(kUnits, {});
    {
        const gpu::GlStateGuard guard(kUnits, {});
        gl.BindTextureUnit(3, 0);  // what a pass does to a unit it borrows: every target unbound
        gpu::Texture own = gpu::makeTexture("test/own", GL_TEXTURE_2D_ARRAY);
        gl.BindTextureUnit(3, own.get());
    }
    const gpu::GlState after = gpu::captureGlState(kUnits, {});
    EXPECT_EQ(after.units[0].textures, before.units[0].textures);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    unbindUnits();
    gl.DeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
}

TEST(GlState, ATextureTheEngineDeletedIsLeftUnboundEvenWhenItsNameComesBack) {
    test::glContext();
    gpu::Texture map = gpu::makeTexture("test/map", GL_TEXTURE_2D_ARRAY);
    gl.TextureStorage3D(map.get(), 1, GL_R8, 4, 4, 1);
    const GLuint old = map.get();
    gl.BindTextureUnit(4, old);  // the host samples the engine's map
    GLuint reused = 0;
    {
        const gpu::GlStateGuard guard(kUnits, {});
        map.reset();  // the engine frees the map and makes another, which may get the same name
        map = gpu::makeTexture("test/map", GL_TEXTURE_2D_ARRAY);
        reused = map.get();
    }
    const gpu::GlState after = gpu::captureGlState(kUnits, {});
    // GL's own rule for a deleted texture: unbound. Not bound back, not the new map either.
    EXPECT_EQ(after.units[1].textures, (std::array<GLint, gpu::kTextureTargets.size()>{}))
        << "old name " << old << ", new name " << reused;
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    std::printf("deleted texture %u, next one made %u (%s)\n", old, reused, old == reused ? "reused" : "new name");
    unbindUnits();
}

TEST(GlState, ObjectsDeletedOutsideTheEngineAreLeftUnboundToo) {
    // A draw callback of the host's may delete its own objects during a shadow pass.
    test::glContext();
    GLuint texture = 0, sampler = 0;
    gl.CreateTextures(GL_TEXTURE_CUBE_MAP, 1, &texture);
    gl.CreateSamplers(1, &sampler);
    gl.BindTextureUnit(3, texture);
    gl.BindSampler(3, sampler);
    {
        const gpu::GlStateGuard guard(kUnits, {});
        gl.DeleteTextures(1, &texture);
        gl.DeleteSamplers(1, &sampler);
    }
    const gpu::GlState after = gpu::captureGlState(kUnits, {});
    EXPECT_EQ(after.units[0].textures, (std::array<GLint, gpu::kTextureTargets.size()>{}));
    EXPECT_EQ(after.units[0].sampler, 0);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    unbindUnits();
}

TEST(GlState, PassDefaultsUndoEveryCapabilityAHostLeftOn) {
    test::glContext();
    const gpu::GlState initial = gpu::captureGlState({}, {});
    for (const GLenum cap : gpu::kPassOffCapabilities) gl.Enable(cap);
    gl.PolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    gl.ClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    gl.DepthRange(0.25, 0.5);
    gl.BlendEquationSeparate(GL_MIN, GL_MAX);
    const gpu::GlState hostile = gpu::captureGlState({}, {});
    gpu::setPassDefaults();
    const gpu::GlState pass = gpu::captureGlState({}, {});
    for (std::size_t i = 0; i < gpu::kPassOffCapabilities.size(); ++i) {
        EXPECT_EQ(hostile.offCapabilities[i], GL_TRUE) << "capability " << i << " did not turn on";
        EXPECT_EQ(pass.offCapabilities[i], GL_FALSE) << "capability " << i;
    }
    EXPECT_EQ(pass.polygonMode[0], GL_FILL);
    EXPECT_EQ(pass.clipOrigin, GL_LOWER_LEFT);
    EXPECT_EQ(pass.clipDepthMode, GL_NEGATIVE_ONE_TO_ONE);
    EXPECT_EQ(pass.depthRange, (std::array<GLdouble, 2>{0.0, 1.0}));
    EXPECT_EQ(pass.blendEquation, (std::array<GLint, 2>{GL_FUNC_ADD, GL_FUNC_ADD}));
    gpu::restoreGlState(hostile);
    EXPECT_TRUE(gpu::captureGlState({}, {}) == hostile);
    gpu::restoreGlState(initial);
    EXPECT_EQ(gl.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace shadow
