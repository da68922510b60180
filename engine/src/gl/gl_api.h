// The OpenGL function table.
//
// The engine never links libGL or libOSMesa: every GL entry point is resolved at run time from
// the current context's getProcAddress (OSMesaGetProcAddress, glfwGetProcAddress,
// eglGetProcAddress, or the game's own). Engine code calls `gl.Clear(...)`.
// Only core-profile 4.5 functions the engine uses are listed; `loadGl` fails with the name of
// the first one the context lacks.
#pragma once

#include <GL/glcorearb.h>

#include <shadow/context.h>

namespace shadow::gpu {

// X(type, name) for every entry point; `name` is the GL name without its `gl` prefix.
#define SHADOW_GL_FUNCTIONS(X)                                             \
    X(PFNGLGETERRORPROC, GetError)                                         \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                   \
    X(PFNGLGETFLOATVPROC, GetFloatv)                                       \
    X(PFNGLGETBOOLEANVPROC, GetBooleanv)                                   \
    X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                               \
    X(PFNGLGETINTEGER64I_VPROC, GetInteger64i_v)                           \
    X(PFNGLISENABLEDPROC, IsEnabled)                                       \
    X(PFNGLISENABLEDIPROC, IsEnabledi)                                     \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                               \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                                   \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                     \
    X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                       \
    X(PFNGLGETSTRINGPROC, GetString)                                       \
    X(PFNGLGETPROGRAMBINARYPROC, GetProgramBinary)                         \
    X(PFNGLPROGRAMBINARYPROC, ProgramBinary)                               \
    X(PFNGLPROGRAMPARAMETERIPROC, ProgramParameteri)                       \
    X(PFNGLENABLEPROC, Enable)                                             \
    X(PFNGLDISABLEPROC, Disable)                                           \
    X(PFNGLENABLEIPROC, Enablei)                                           \
    X(PFNGLDISABLEIPROC, Disablei)                                         \
    X(PFNGLVIEWPORTPROC, Viewport)                                         \
    X(PFNGLSCISSORPROC, Scissor)                                           \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                       \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                       \
    X(PFNGLCOLORMASKPROC, ColorMask)                                       \
    X(PFNGLCULLFACEPROC, CullFace)                                         \
    X(PFNGLFRONTFACEPROC, FrontFace)                                       \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                               \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                       \
    X(PFNGLBLENDEQUATIONPROC, BlendEquation)                               \
    X(PFNGLFINISHPROC, Finish)                                             \
    X(PFNGLFLUSHPROC, Flush)                                               \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                   \
    X(PFNGLPROVOKINGVERTEXPROC, ProvokingVertex)                           \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                     \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                                 \
    X(PFNGLDRAWELEMENTSBASEVERTEXPROC, DrawElementsBaseVertex)             \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                     \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                           \
    X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                         \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                               \
    X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                               \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                               \
    X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                     \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                     \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)               \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                             \
    X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                           \
    X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                     \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                     \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                           \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)           \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)         \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)           \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)           \
    X(PFNGLVERTEXARRAYATTRIBIFORMATPROC, VertexArrayAttribIFormat)         \
    X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                       \
    X(PFNGLGENERATETEXTUREMIPMAPPROC, GenerateTextureMipmap)               \
    X(PFNGLINVALIDATEBUFFERDATAPROC, InvalidateBufferData)                 \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)         \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                             \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                             \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                         \
    X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                         \
    X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                       \
    X(PFNGLTEXTUREBUFFERPROC, TextureBuffer)                               \
    X(PFNGLCOPYIMAGESUBDATAPROC, CopyImageSubData)                         \
    X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                       \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                   \
    X(PFNGLTEXTUREVIEWPROC, TextureView)                                   \
    X(PFNGLTEXTUREPARAMETERFVPROC, TextureParameterfv)                     \
    X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                           \
    X(PFNGLGETTEXTURESUBIMAGEPROC, GetTextureSubImage)                     \
    X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                             \
    X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                             \
    X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                       \
    X(PFNGLSAMPLERPARAMETERFVPROC, SamplerParameterfv)                     \
    X(PFNGLBINDSAMPLERPROC, BindSampler)                                   \
    X(PFNGLCLEARTEXSUBIMAGEPROC, ClearTexSubImage)                         \
    X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                     \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                     \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                           \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)           \
    X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, NamedFramebufferTextureLayer) \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERPROC, NamedFramebufferDrawBuffer)     \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)   \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)     \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)   \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)           \
    X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, ClearNamedFramebufferuiv)         \
    X(PFNGLBLITNAMEDFRAMEBUFFERPROC, BlitNamedFramebuffer)                 \
    X(PFNGLCREATESHADERPROC, CreateShader)                                 \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                 \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                               \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                   \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                         \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                 \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                               \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                 \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                   \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                 \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                       \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                               \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                     \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                     \
    X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                         \
    X(PFNGLPROGRAMUNIFORM2IPROC, ProgramUniform2i)                         \
    X(PFNGLPROGRAMUNIFORM1IVPROC, ProgramUniform1iv)                       \
    X(PFNGLPROGRAMUNIFORM1FPROC, ProgramUniform1f)                         \
    X(PFNGLPROGRAMUNIFORM2FVPROC, ProgramUniform2fv)                       \
    X(PFNGLPROGRAMUNIFORM3FVPROC, ProgramUniform3fv)                       \
    X(PFNGLPROGRAMUNIFORM4FVPROC, ProgramUniform4fv)                       \
    X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, ProgramUniformMatrix4fv)           \
    X(PFNGLPROGRAMUNIFORMMATRIX3FVPROC, ProgramUniformMatrix3fv)           \
    X(PFNGLPROGRAMUNIFORMMATRIX3X2FVPROC, ProgramUniformMatrix3x2fv)       \
    X(PFNGLPUSHDEBUGGROUPPROC, PushDebugGroup)                             \
    X(PFNGLPOPDEBUGGROUPPROC, PopDebugGroup)                               \
    X(PFNGLOBJECTLABELPROC, ObjectLabel)                                   \
    X(PFNGLFENCESYNCPROC, FenceSync)                                       \
    X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync)                             \
    X(PFNGLDELETESYNCPROC, DeleteSync)                                     \
    X(PFNGLCREATEQUERIESPROC, CreateQueries)                               \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                               \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                                     \
    X(PFNGLENDQUERYPROC, EndQuery)                                         \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                   \
    X(PFNGLGETQUERYOBJECTUIVPROC, GetQueryObjectuiv)                       \
    X(PFNGLGETDOUBLEVPROC, GetDoublev)                                     \
    X(PFNGLISTEXTUREPROC, IsTexture)                                       \
    X(PFNGLISSAMPLERPROC, IsSampler)                                       \
    X(PFNGLISBUFFERPROC, IsBuffer)                                         \
    X(PFNGLISFRAMEBUFFERPROC, IsFramebuffer)                               \
    X(PFNGLISVERTEXARRAYPROC, IsVertexArray)                               \
    X(PFNGLISPROGRAMPROC, IsProgram)                                       \
    X(PFNGLPOLYGONMODEPROC, PolygonMode)                                   \
    X(PFNGLCLIPCONTROLPROC, ClipControl)                                   \
    X(PFNGLDEPTHRANGEPROC, DepthRange)                                     \
    X(PFNGLBLENDEQUATIONSEPARATEPROC, BlendEquationSeparate)               \
    X(PFNGLCLAMPCOLORPROC, ClampColor)

/// Resolved GL entry points of the current context.
struct Api {
#define SHADOW_GL_MEMBER(type, name) type name = nullptr;
    SHADOW_GL_FUNCTIONS(SHADOW_GL_MEMBER)
#undef SHADOW_GL_MEMBER
};

}  // namespace shadow::gpu

namespace shadow {
/// The engine's GL table; filled by `loadGl`.
extern gpu::Api gl;
}  // namespace shadow
