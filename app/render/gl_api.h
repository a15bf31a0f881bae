// Every OpenGL function prep calls, reached through one pointer table filled from the current context's
// get-proc-address (glfwGetProcAddress or OSMesaGetProcAddress).
//
// Why not call gl* directly: a binary that links both libGL (for GLFW) and libOSMesa binds each direct
// call to whichever library comes first, and then one of the two contexts draws nothing
// (shared/notes/graphics-stack.md). With the table, one `prep-demo` drives both a window and an
// off-screen OSMesa context. Dear ImGui's GL3 backend is compiled with this header force-included
// (IMGUI_IMPL_OPENGL_LOADER_CUSTOM), so its calls go through the same table.
//
// The pointers are plain C++ variables in namespace prep::gl (mangled names, so they never collide with
// the gl* symbols libOSMesa exports). Code that draws says `using namespace prep::gl;` and calls
// glClear(...) as usual. Only glcorearb.h's typedefs are used: GL_GLEXT_PROTOTYPES must stay undefined.
#pragma once

#ifdef GL_GLEXT_PROTOTYPES
#error "prep loads GL through prep::gl's pointer table; do not define GL_GLEXT_PROTOTYPES"
#endif
#include <GL/glcorearb.h>

#include "app/render/gl_loader.h"

// X(pointer type, name): the whole list, core OpenGL 3.3.
#define PREP_GL_FUNCTIONS(X)                                              \
  X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                              \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                                \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                                    \
  X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase)                            \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                          \
  X(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer)                        \
  X(PFNGLBINDSAMPLERPROC, glBindSampler)                                  \
  X(PFNGLBINDTEXTUREPROC, glBindTexture)                                  \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                          \
  X(PFNGLBLENDEQUATIONPROC, glBlendEquation)                              \
  X(PFNGLBLENDEQUATIONSEPARATEPROC, glBlendEquationSeparate)              \
  X(PFNGLBLENDFUNCPROC, glBlendFunc)                                      \
  X(PFNGLBLENDFUNCSEPARATEPROC, glBlendFuncSeparate)                      \
  X(PFNGLBLITFRAMEBUFFERPROC, glBlitFramebuffer)                          \
  X(PFNGLBUFFERDATAPROC, glBufferData)                                    \
  X(PFNGLBUFFERSUBDATAPROC, glBufferSubData)                              \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)            \
  X(PFNGLCLEARPROC, glClear)                                              \
  X(PFNGLCLEARCOLORPROC, glClearColor)                                    \
  X(PFNGLCLEARDEPTHPROC, glClearDepth)                                    \
  X(PFNGLCOLORMASKPROC, glColorMask)                                      \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)                              \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                              \
  X(PFNGLCREATESHADERPROC, glCreateShader)                                \
  X(PFNGLCULLFACEPROC, glCullFace)                                        \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                              \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                    \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                              \
  X(PFNGLDELETERENDERBUFFERSPROC, glDeleteRenderbuffers)                  \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                                \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                            \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                    \
  X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                      \
  X(PFNGLDEPTHMASKPROC, glDepthMask)                                      \
  X(PFNGLDETACHSHADERPROC, glDetachShader)                                \
  X(PFNGLDISABLEPROC, glDisable)                                          \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays)                                    \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, glDrawArraysInstanced)                  \
  X(PFNGLDRAWBUFFERPROC, glDrawBuffer)                                    \
  X(PFNGLDRAWELEMENTSPROC, glDrawElements)                                \
  X(PFNGLDRAWELEMENTSBASEVERTEXPROC, glDrawElementsBaseVertex)            \
  X(PFNGLDRAWELEMENTSINSTANCEDPROC, glDrawElementsInstanced)              \
  X(PFNGLENABLEPROC, glEnable)                                            \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray)          \
  X(PFNGLFINISHPROC, glFinish)                                            \
  X(PFNGLFLUSHPROC, glFlush)                                              \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer)          \
  X(PFNGLFRONTFACEPROC, glFrontFace)                                      \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)                \
  X(PFNGLGENBUFFERSPROC, glGenBuffers)                                    \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                          \
  X(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers)                        \
  X(PFNGLGENTEXTURESPROC, glGenTextures)                                  \
  X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                          \
  X(PFNGLGETATTRIBLOCATIONPROC, glGetAttribLocation)                      \
  X(PFNGLGETERRORPROC, glGetError)                                        \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                  \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                      \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                        \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                  \
  X(PFNGLGETSTRINGPROC, glGetString)                                      \
  X(PFNGLGETSTRINGIPROC, glGetStringi)                                    \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                    \
  X(PFNGLGETUNIFORMBLOCKINDEXPROC, glGetUniformBlockIndex)                \
  X(PFNGLISENABLEDPROC, glIsEnabled)                                      \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                  \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                  \
  X(PFNGLPOLYGONMODEPROC, glPolygonMode)                                  \
  X(PFNGLPOLYGONOFFSETPROC, glPolygonOffset)                              \
  X(PFNGLREADBUFFERPROC, glReadBuffer)                                    \
  X(PFNGLREADPIXELSPROC, glReadPixels)                                    \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, glRenderbufferStorageMultisample) \
  X(PFNGLSCISSORPROC, glScissor)                                          \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                                \
  X(PFNGLSTENCILFUNCPROC, glStencilFunc)                                  \
  X(PFNGLSTENCILOPPROC, glStencilOp)                                      \
  X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                                    \
  X(PFNGLTEXPARAMETERFVPROC, glTexParameterfv)                            \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                              \
  X(PFNGLUNIFORM1FPROC, glUniform1f)                                      \
  X(PFNGLUNIFORM1IPROC, glUniform1i)                                      \
  X(PFNGLUNIFORM2FPROC, glUniform2f)                                      \
  X(PFNGLUNIFORM3FPROC, glUniform3f)                                      \
  X(PFNGLUNIFORM3FVPROC, glUniform3fv)                                    \
  X(PFNGLUNIFORM4FPROC, glUniform4f)                                      \
  X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)                        \
  X(PFNGLUNIFORMBLOCKBINDINGPROC, glUniformBlockBinding)                  \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                                    \
  X(PFNGLVERTEXATTRIBDIVISORPROC, glVertexAttribDivisor)                  \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, glVertexAttribIPointer)                \
  X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)                  \
  X(PFNGLVIEWPORTPROC, glViewport)

namespace prep::gl {

#define PREP_GL_DECLARE_POINTER(type, name) extern type name;
PREP_GL_FUNCTIONS(PREP_GL_DECLARE_POINTER)
#undef PREP_GL_DECLARE_POINTER

}  // namespace prep::gl
