#pragma once
// Every OpenGL function vsil calls, one line each, sorted: X(name, type), where type is the
// function-pointer type <GL/glcorearb.h> declares for it (PFN<NAME>PROC). slicing/gl.h makes one
// pointer per line and the current context fills them through its back end's get-proc-address
// (slicing/gl_loader.h), so OSMesa and EGL reach GL the same way.
//
// Using a GL function that is not listed here does not compile: slicing/gl.h declares no
// prototypes (GL_GLEXT_PROTOTYPES stays undefined). Add its line here. A test checks that each
// name and type belong together (tests/slicing/gl_loader_test.cpp).
#define VSIL_GL_FUNCTIONS(X)                                     \
  X(glActiveTexture, PFNGLACTIVETEXTUREPROC)                     \
  X(glAttachShader, PFNGLATTACHSHADERPROC)                       \
  X(glBindBuffer, PFNGLBINDBUFFERPROC)                           \
  X(glBindBufferBase, PFNGLBINDBUFFERBASEPROC)                   \
  X(glBindBufferRange, PFNGLBINDBUFFERRANGEPROC)                 \
  X(glBindFramebuffer, PFNGLBINDFRAMEBUFFERPROC)                 \
  X(glBindImageTexture, PFNGLBINDIMAGETEXTUREPROC)               \
  X(glBindRenderbuffer, PFNGLBINDRENDERBUFFERPROC)               \
  X(glBindTexture, PFNGLBINDTEXTUREPROC)                         \
  X(glBindVertexArray, PFNGLBINDVERTEXARRAYPROC)                 \
  X(glBlendEquation, PFNGLBLENDEQUATIONPROC)                     \
  X(glBlendEquationSeparate, PFNGLBLENDEQUATIONSEPARATEPROC)     \
  X(glBlendFunc, PFNGLBLENDFUNCPROC)                             \
  X(glBlendFuncSeparate, PFNGLBLENDFUNCSEPARATEPROC)             \
  X(glBlitFramebuffer, PFNGLBLITFRAMEBUFFERPROC)                 \
  X(glBufferData, PFNGLBUFFERDATAPROC)                           \
  X(glCheckFramebufferStatus, PFNGLCHECKFRAMEBUFFERSTATUSPROC)   \
  X(glClearBufferfi, PFNGLCLEARBUFFERFIPROC)                     \
  X(glClearBufferfv, PFNGLCLEARBUFFERFVPROC)                     \
  X(glClearBufferuiv, PFNGLCLEARBUFFERUIVPROC)                   \
  X(glColorMask, PFNGLCOLORMASKPROC)                             \
  X(glCompileShader, PFNGLCOMPILESHADERPROC)                     \
  X(glCreateProgram, PFNGLCREATEPROGRAMPROC)                     \
  X(glCreateShader, PFNGLCREATESHADERPROC)                       \
  X(glDeleteBuffers, PFNGLDELETEBUFFERSPROC)                     \
  X(glDeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC)           \
  X(glDeleteProgram, PFNGLDELETEPROGRAMPROC)                     \
  X(glDeleteRenderbuffers, PFNGLDELETERENDERBUFFERSPROC)         \
  X(glDeleteShader, PFNGLDELETESHADERPROC)                       \
  X(glDeleteTextures, PFNGLDELETETEXTURESPROC)                   \
  X(glDeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC)           \
  X(glDepthFunc, PFNGLDEPTHFUNCPROC)                             \
  X(glDepthMask, PFNGLDEPTHMASKPROC)                             \
  X(glDepthRange, PFNGLDEPTHRANGEPROC)                           \
  X(glDisable, PFNGLDISABLEPROC)                                 \
  X(glDispatchCompute, PFNGLDISPATCHCOMPUTEPROC)                 \
  X(glDrawArrays, PFNGLDRAWARRAYSPROC)                           \
  X(glEnable, PFNGLENABLEPROC)                                   \
  X(glEnableVertexAttribArray, PFNGLENABLEVERTEXATTRIBARRAYPROC) \
  X(glFinish, PFNGLFINISHPROC)                                   \
  X(glFramebufferParameteri, PFNGLFRAMEBUFFERPARAMETERIPROC)     \
  X(glFramebufferRenderbuffer, PFNGLFRAMEBUFFERRENDERBUFFERPROC) \
  X(glFramebufferTexture2D, PFNGLFRAMEBUFFERTEXTURE2DPROC)       \
  X(glGenBuffers, PFNGLGENBUFFERSPROC)                           \
  X(glGenFramebuffers, PFNGLGENFRAMEBUFFERSPROC)                 \
  X(glGenRenderbuffers, PFNGLGENRENDERBUFFERSPROC)               \
  X(glGenTextures, PFNGLGENTEXTURESPROC)                         \
  X(glGenVertexArrays, PFNGLGENVERTEXARRAYSPROC)                 \
  X(glGetBooleanv, PFNGLGETBOOLEANVPROC)                         \
  X(glGetDoublev, PFNGLGETDOUBLEVPROC)                           \
  X(glGetError, PFNGLGETERRORPROC)                               \
  X(glGetIntegerv, PFNGLGETINTEGERVPROC)                         \
  X(glGetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)             \
  X(glGetProgramiv, PFNGLGETPROGRAMIVPROC)                       \
  X(glGetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)               \
  X(glGetShaderiv, PFNGLGETSHADERIVPROC)                         \
  X(glGetString, PFNGLGETSTRINGPROC)                             \
  X(glGetStringi, PFNGLGETSTRINGIPROC)                           \
  X(glGetTexImage, PFNGLGETTEXIMAGEPROC)                         \
  X(glGetTexLevelParameteriv, PFNGLGETTEXLEVELPARAMETERIVPROC)   \
  X(glGetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)           \
  X(glIsBuffer, PFNGLISBUFFERPROC)                               \
  X(glIsEnabled, PFNGLISENABLEDPROC)                             \
  X(glIsFramebuffer, PFNGLISFRAMEBUFFERPROC)                     \
  X(glIsProgram, PFNGLISPROGRAMPROC)                             \
  X(glIsShader, PFNGLISSHADERPROC)                               \
  X(glIsTexture, PFNGLISTEXTUREPROC)                             \
  X(glIsVertexArray, PFNGLISVERTEXARRAYPROC)                     \
  X(glLinkProgram, PFNGLLINKPROGRAMPROC)                         \
  X(glMemoryBarrier, PFNGLMEMORYBARRIERPROC)                     \
  X(glPixelStorei, PFNGLPIXELSTOREIPROC)                         \
  X(glReadBuffer, PFNGLREADBUFFERPROC)                           \
  X(glReadPixels, PFNGLREADPIXELSPROC)                           \
  X(glRenderbufferStorage, PFNGLRENDERBUFFERSTORAGEPROC)         \
  X(glScissor, PFNGLSCISSORPROC)                                 \
  X(glShaderSource, PFNGLSHADERSOURCEPROC)                       \
  X(glStencilMask, PFNGLSTENCILMASKPROC)                         \
  X(glTexImage1D, PFNGLTEXIMAGE1DPROC)                           \
  X(glTexImage2D, PFNGLTEXIMAGE2DPROC)                           \
  X(glTexImage3D, PFNGLTEXIMAGE3DPROC)                           \
  X(glTexParameteri, PFNGLTEXPARAMETERIPROC)                     \
  X(glTexSubImage1D, PFNGLTEXSUBIMAGE1DPROC)                     \
  X(glTexSubImage2D, PFNGLTEXSUBIMAGE2DPROC)                     \
  X(glTexSubImage3D, PFNGLTEXSUBIMAGE3DPROC)                     \
  X(glUniform1f, PFNGLUNIFORM1FPROC)                             \
  X(glUniform1fv, PFNGLUNIFORM1FVPROC)                           \
  X(glUniform1i, PFNGLUNIFORM1IPROC)                             \
  X(glUniform1iv, PFNGLUNIFORM1IVPROC)                           \
  X(glUniform1ui, PFNGLUNIFORM1UIPROC)                           \
  X(glUniform2fv, PFNGLUNIFORM2FVPROC)                           \
  X(glUniform2iv, PFNGLUNIFORM2IVPROC)                           \
  X(glUniform3fv, PFNGLUNIFORM3FVPROC)                           \
  X(glUniform4fv, PFNGLUNIFORM4FVPROC)                           \
  X(glUniformMatrix3fv, PFNGLUNIFORMMATRIX3FVPROC)               \
  X(glUniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC)               \
  X(glUseProgram, PFNGLUSEPROGRAMPROC)                           \
  X(glVertexAttribPointer, PFNGLVERTEXATTRIBPOINTERPROC)         \
  X(glViewport, PFNGLVIEWPORTPROC)
