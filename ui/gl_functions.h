// The OpenGL 3.3 core entry points the renderer uses, loaded through the current context's
// get-proc-address (OSMesaGetProcAddress, QOpenGLContext::getProcAddress). Binaries that render
// under OSMesa must not link libGL: its exported gl* would shadow OSMesa's (PLATFORM.md).
#pragma once

#include <GL/glcorearb.h>

#include <string>

namespace pbm::gl {

// OpenGL 1.0/1.1 entry points by our own names: when Qt's <GL/gl.h> comes first, glcorearb.h
// skips its 1.1 block and these PFN types do not exist.
using PolygonOffsetProc = void(APIENTRYP)(GLfloat factor, GLfloat units);
using DrawElementsProc = void(APIENTRYP)(GLenum mode, GLsizei count, GLenum type,
                                         const void* indices);
using DrawArraysProc = void(APIENTRYP)(GLenum mode, GLint first, GLsizei count);
using GenTexturesProc = void(APIENTRYP)(GLsizei n, GLuint* textures);
using BindTextureProc = void(APIENTRYP)(GLenum target, GLuint texture);
using DeleteTexturesProc = void(APIENTRYP)(GLsizei n, const GLuint* textures);

#define PBM_GL_FUNCTIONS(X)                                                  \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLVIEWPORTPROC, Viewport)                                             \
  X(PFNGLSCISSORPROC, Scissor)                                               \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLCULLFACEPROC, CullFace)                                             \
  X(PolygonOffsetProc, PolygonOffset)                                        \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                           \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                           \
  X(PFNGLBLENDEQUATIONPROC, BlendEquation)                                   \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                           \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                           \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                             \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                                   \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
  X(DrawElementsProc, DrawElements)                                          \
  X(DrawArraysProc, DrawArrays)                                              \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                     \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                       \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
  X(GenTexturesProc, GenTextures)                                            \
  X(BindTextureProc, BindTexture)                                            \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
  X(PFNGLTEXPARAMETERFVPROC, TexParameterfv)                                 \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(DeleteTexturesProc, DeleteTextures)                                      \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                         \
  X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                         \
  X(PFNGLFINISHPROC, Finish)

struct Functions {
#define PBM_GL_MEMBER(type, name) type name = nullptr;
  PBM_GL_FUNCTIONS(PBM_GL_MEMBER)
#undef PBM_GL_MEMBER
};

using GetProcAddress = void* (*)(const char* name);

// Fills every entry from get_proc ("gl" + name); throws std::runtime_error naming the first one
// the context does not provide.
Functions load_functions(GetProcAddress get_proc);

// Throws std::runtime_error with the GL version found if the current context is below 3.3.
void require_version(const Functions& gl, int major, int minor);

}  // namespace pbm::gl
