// Our own minimal OpenGL 3.3 core function table.
//
// We deliberately avoid libepoxy/GLEW and never link libGL/libOpenGL: every
// entry point is fetched from the platform's proc loader (eglGetProcAddress or
// OSMesaGetProcAddress). That keeps the binary independent of which GL vendor
// library is installed and lets one process hold EGL and OSMesa contexts.
#pragma once

// Only the typedefs are wanted; prototypes would invite calling the (unlinked)
// global symbols by accident.
#ifdef GL_GLEXT_PROTOTYPES
#error "glcontext loads GL at run time: do not define GL_GLEXT_PROTOTYPES"
#endif
#include <GL/glcorearb.h>

#include <functional>

namespace glc {

// X-macro list of every function GlApi carries: X(pointer typedef, name).
// One list drives both the struct members and the loader, so they can never
// drift apart.
#define GLC_GL_FUNCTIONS(X)                                                    \
  /* state and queries */                                                      \
  X(PFNGLGETSTRINGPROC, glGetString)                                           \
  X(PFNGLGETSTRINGIPROC, glGetStringi)                                         \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                       \
  X(PFNGLGETINTEGER64VPROC, glGetInteger64v)                                   \
  X(PFNGLGETFLOATVPROC, glGetFloatv)                                           \
  X(PFNGLGETERRORPROC, glGetError)                                             \
  /* shaders and programs */                                                   \
  X(PFNGLCREATESHADERPROC, glCreateShader)                                     \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                                     \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)                                   \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                       \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                             \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                                     \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                   \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                                     \
  X(PFNGLDETACHSHADERPROC, glDetachShader)                                     \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                       \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                     \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                           \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                                   \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                         \
  X(PFNGLGETATTRIBLOCATIONPROC, glGetAttribLocation)                           \
  X(PFNGLBINDATTRIBLOCATIONPROC, glBindAttribLocation)                         \
  X(PFNGLBINDFRAGDATALOCATIONPROC, glBindFragDataLocation)                     \
  X(PFNGLGETUNIFORMBLOCKINDEXPROC, glGetUniformBlockIndex)                     \
  X(PFNGLUNIFORMBLOCKBINDINGPROC, glUniformBlockBinding)                       \
  /* uniforms */                                                               \
  X(PFNGLUNIFORM1IPROC, glUniform1i)                                           \
  X(PFNGLUNIFORM2IPROC, glUniform2i)                                           \
  X(PFNGLUNIFORM3IPROC, glUniform3i)                                           \
  X(PFNGLUNIFORM4IPROC, glUniform4i)                                           \
  X(PFNGLUNIFORM1UIPROC, glUniform1ui)                                         \
  X(PFNGLUNIFORM1FPROC, glUniform1f)                                           \
  X(PFNGLUNIFORM2FPROC, glUniform2f)                                           \
  X(PFNGLUNIFORM3FPROC, glUniform3f)                                           \
  X(PFNGLUNIFORM4FPROC, glUniform4f)                                           \
  X(PFNGLUNIFORM1IVPROC, glUniform1iv)                                         \
  X(PFNGLUNIFORM2IVPROC, glUniform2iv)                                         \
  X(PFNGLUNIFORM1FVPROC, glUniform1fv)                                         \
  X(PFNGLUNIFORM2FVPROC, glUniform2fv)                                         \
  X(PFNGLUNIFORM3FVPROC, glUniform3fv)                                         \
  X(PFNGLUNIFORM4FVPROC, glUniform4fv)                                         \
  X(PFNGLUNIFORMMATRIX3FVPROC, glUniformMatrix3fv)                             \
  X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)                             \
  /* textures */                                                               \
  X(PFNGLGENTEXTURESPROC, glGenTextures)                                       \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                                 \
  X(PFNGLBINDTEXTUREPROC, glBindTexture)                                       \
  X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                                   \
  X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                                         \
  X(PFNGLTEXSUBIMAGE2DPROC, glTexSubImage2D)                                   \
  X(PFNGLTEXIMAGE3DPROC, glTexImage3D)                                         \
  X(PFNGLTEXSUBIMAGE3DPROC, glTexSubImage3D)                                   \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                                   \
  X(PFNGLTEXPARAMETERFVPROC, glTexParameterfv)                                 \
  X(PFNGLGETTEXIMAGEPROC, glGetTexImage)                                       \
  X(PFNGLGETTEXLEVELPARAMETERIVPROC, glGetTexLevelParameteriv)                 \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                       \
  X(PFNGLGENERATEMIPMAPPROC, glGenerateMipmap)                                 \
  /* framebuffers and renderbuffers */                                         \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                               \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                         \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                               \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)                     \
  X(PFNGLFRAMEBUFFERTEXTURELAYERPROC, glFramebufferTextureLayer)               \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer)               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)                 \
  X(PFNGLDRAWBUFFERSPROC, glDrawBuffers)                                       \
  X(PFNGLREADBUFFERPROC, glReadBuffer)                                         \
  X(PFNGLBLITFRAMEBUFFERPROC, glBlitFramebuffer)                               \
  X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv)                                   \
  X(PFNGLCLEARBUFFERIVPROC, glClearBufferiv)                                   \
  X(PFNGLCLEARBUFFERUIVPROC, glClearBufferuiv)                                 \
  X(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers)                             \
  X(PFNGLDELETERENDERBUFFERSPROC, glDeleteRenderbuffers)                       \
  X(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer)                             \
  X(PFNGLRENDERBUFFERSTORAGEPROC, glRenderbufferStorage)                       \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, glRenderbufferStorageMultisample) \
  /* buffers */                                                                \
  X(PFNGLGENBUFFERSPROC, glGenBuffers)                                         \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                   \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                                         \
  X(PFNGLBUFFERDATAPROC, glBufferData)                                         \
  X(PFNGLBUFFERSUBDATAPROC, glBufferSubData)                                   \
  X(PFNGLGETBUFFERSUBDATAPROC, glGetBufferSubData)                             \
  X(PFNGLMAPBUFFERRANGEPROC, glMapBufferRange)                                 \
  X(PFNGLUNMAPBUFFERPROC, glUnmapBuffer)                                       \
  X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase)                                 \
  X(PFNGLBINDBUFFERRANGEPROC, glBindBufferRange)                               \
  /* vertex arrays */                                                          \
  X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                               \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                         \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                               \
  X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)                       \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, glVertexAttribIPointer)                     \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray)               \
  X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, glDisableVertexAttribArray)             \
  X(PFNGLVERTEXATTRIBDIVISORPROC, glVertexAttribDivisor)                       \
  /* transform feedback and texture buffers */                                 \
  X(PFNGLTRANSFORMFEEDBACKVARYINGSPROC, glTransformFeedbackVaryings)           \
  X(PFNGLBEGINTRANSFORMFEEDBACKPROC, glBeginTransformFeedback)                 \
  X(PFNGLENDTRANSFORMFEEDBACKPROC, glEndTransformFeedback)                     \
  X(PFNGLTEXBUFFERPROC, glTexBuffer)                                           \
  /* drawing and fixed-function state */                                       \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays)                                         \
  X(PFNGLDRAWELEMENTSPROC, glDrawElements)                                     \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, glDrawArraysInstanced)                       \
  X(PFNGLVIEWPORTPROC, glViewport)                                             \
  X(PFNGLSCISSORPROC, glScissor)                                               \
  X(PFNGLENABLEPROC, glEnable)                                                 \
  X(PFNGLDISABLEPROC, glDisable)                                               \
  X(PFNGLCLEARPROC, glClear)                                                   \
  X(PFNGLCLEARCOLORPROC, glClearColor)                                         \
  X(PFNGLCLEARDEPTHPROC, glClearDepth)                                         \
  X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, glDepthMask)                                           \
  X(PFNGLCOLORMASKPROC, glColorMask)                                           \
  X(PFNGLBLENDFUNCPROC, glBlendFunc)                                           \
  X(PFNGLBLENDEQUATIONPROC, glBlendEquation)                                   \
  X(PFNGLCULLFACEPROC, glCullFace)                                             \
  X(PFNGLFRONTFACEPROC, glFrontFace)                                           \
  X(PFNGLREADPIXELSPROC, glReadPixels)                                         \
  X(PFNGLFINISHPROC, glFinish)                                                 \
  X(PFNGLFLUSHPROC, glFlush)                                                   \
  /* queries (timers) */                                                       \
  X(PFNGLGENQUERIESPROC, glGenQueries)                                         \
  X(PFNGLDELETEQUERIESPROC, glDeleteQueries)                                   \
  X(PFNGLBEGINQUERYPROC, glBeginQuery)                                         \
  X(PFNGLENDQUERYPROC, glEndQuery)                                             \
  X(PFNGLQUERYCOUNTERPROC, glQueryCounter)                                     \
  X(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v)                       \
  X(PFNGLGETQUERYOBJECTIVPROC, glGetQueryObjectiv)                             \
  X(PFNGLGETQUERYOBJECTUIVPROC, glGetQueryObjectuiv)                           \
  /* fence sync */                                                             \
  X(PFNGLFENCESYNCPROC, glFenceSync)                                           \
  X(PFNGLCLIENTWAITSYNCPROC, glClientWaitSync)                                 \
  X(PFNGLWAITSYNCPROC, glWaitSync)                                             \
  X(PFNGLDELETESYNCPROC, glDeleteSync)

// Function pointers of one context. Members are named exactly like the GL
// functions (gl.glDrawArrays(...)) so code reads like plain GL and greps well.
// A default-constructed GlApi has every pointer null.
struct GlApi {
#define GLC_DECLARE_MEMBER(type, name) type name = nullptr;
  GLC_GL_FUNCTIONS(GLC_DECLARE_MEMBER)
#undef GLC_DECLARE_MEMBER
};

// Resolves a GL function name to its address, or nullptr when unknown.
using ProcLoader = std::function<void*(const char*)>;

// Fills every member of `api` through `loader`. Throws glc::GlError naming
// every function the loader could not resolve (api is then left unchanged).
// Note: glvnd's eglGetProcAddress returns dispatch stubs even for functions
// the driver lacks, so a successful load does not prove driver support; the
// Context checks the GL version separately.
void load(GlApi& api, const ProcLoader& loader);

}  // namespace glc
