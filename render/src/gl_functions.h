// The OpenGL 3.3 core entry points the renderer uses, as a table of function pointers filled
// from a context's GetProcAddress (so nothing links libGL, and any backend can serve the table).
#pragma once

#include <GL/glcorearb.h>  // types, enums and PFN typedefs only: no prototypes without GL_GLEXT_PROTOTYPES

#include <string>

#include "render/context.h"

namespace render {

// X(pointer type, name): the member `Name` is loaded from the entry point "glName".
// Adding an entry point is one line here.
#define BALLBOX_GL_FUNCTIONS(X)                                   \
  X(PFNGLGETSTRINGPROC, GetString)                                \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                            \
  X(PFNGLGETERRORPROC, GetError)                                  \
  X(PFNGLVIEWPORTPROC, Viewport)                                  \
  X(PFNGLCLEARCOLORPROC, ClearColor)                              \
  X(PFNGLCLEARPROC, Clear)                                        \
  X(PFNGLENABLEPROC, Enable)                                      \
  X(PFNGLDISABLEPROC, Disable)                                    \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                            \
  X(PFNGLREADPIXELSPROC, ReadPixels)                              \
  X(PFNGLCREATESHADERPROC, CreateShader)                          \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                          \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                        \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                            \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                  \
  X(PFNGLDELETESHADERPROC, DeleteShader)                          \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                        \
  X(PFNGLATTACHSHADERPROC, AttachShader)                          \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                            \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                          \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                        \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                              \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)              \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                    \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                    \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)              \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                              \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                              \
  X(PFNGLBUFFERDATAPROC, BufferData)                              \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                        \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)    \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)            \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)            \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)            \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                              \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                    \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                    \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)    \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)          \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)      \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)              \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                  \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                  \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)            \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)            \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                    \
  X(PFNGLSCISSORPROC, Scissor)                                    \
  X(PFNGLGENTEXTURESPROC, GenTextures)                            \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                            \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                      \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                              \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                        \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                        \
  X(PFNGLTEXBUFFERPROC, TexBuffer)

struct GlFunctions {
#define BALLBOX_GL_MEMBER(type, name) type name = nullptr;
  BALLBOX_GL_FUNCTIONS(BALLBOX_GL_MEMBER)
#undef BALLBOX_GL_MEMBER
};

/// Fills every entry from `context`. On failure returns false and names the missing entry point
/// in `error`.
bool LoadGlFunctions(const GlContext& context, GlFunctions& gl, std::string& error);

}  // namespace render
