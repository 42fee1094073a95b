/* The GL function table of a render context. Every entry is loaded through the context's
 * get-proc-address (eglGetProcAddress or OSMesaGetProcAddress); nothing links libGL. */
#ifndef INDENTMAP_RENDER_GL_H
#define INDENTMAP_RENDER_GL_H

#include <GL/glcorearb.h>

/* X(name, type): every GL function the renderer calls. */
#define IM_GL_FUNCTIONS(X)                                                                                           \
    X(GetString, PFNGLGETSTRINGPROC)                                                                                 \
    X(GetIntegerv, PFNGLGETINTEGERVPROC)                                                                             \
    X(GetError, PFNGLGETERRORPROC)                                                                                   \
    X(Viewport, PFNGLVIEWPORTPROC)                                                                                   \
    X(DrawArrays, PFNGLDRAWARRAYSPROC)                                                                               \
    X(ReadPixels, PFNGLREADPIXELSPROC)                                                                               \
    X(PixelStorei, PFNGLPIXELSTOREIPROC)                                                                             \
    X(Finish, PFNGLFINISHPROC)                                                                                       \
    X(GenTextures, PFNGLGENTEXTURESPROC)                                                                             \
    X(DeleteTextures, PFNGLDELETETEXTURESPROC)                                                                       \
    X(BindTexture, PFNGLBINDTEXTUREPROC)                                                                             \
    X(ActiveTexture, PFNGLACTIVETEXTUREPROC)                                                                         \
    X(TexImage2D, PFNGLTEXIMAGE2DPROC)                                                                               \
    X(TexParameteri, PFNGLTEXPARAMETERIPROC)                                                                         \
    X(GenFramebuffers, PFNGLGENFRAMEBUFFERSPROC)                                                                     \
    X(DeleteFramebuffers, PFNGLDELETEFRAMEBUFFERSPROC)                                                               \
    X(BindFramebuffer, PFNGLBINDFRAMEBUFFERPROC)                                                                     \
    X(CheckFramebufferStatus, PFNGLCHECKFRAMEBUFFERSTATUSPROC)                                                       \
    X(GenRenderbuffers, PFNGLGENRENDERBUFFERSPROC)                                                                   \
    X(DeleteRenderbuffers, PFNGLDELETERENDERBUFFERSPROC)                                                             \
    X(BindRenderbuffer, PFNGLBINDRENDERBUFFERPROC)                                                                   \
    X(RenderbufferStorage, PFNGLRENDERBUFFERSTORAGEPROC)                                                             \
    X(FramebufferRenderbuffer, PFNGLFRAMEBUFFERRENDERBUFFERPROC)                                                     \
    X(CreateShader, PFNGLCREATESHADERPROC)                                                                           \
    X(ShaderSource, PFNGLSHADERSOURCEPROC)                                                                           \
    X(CompileShader, PFNGLCOMPILESHADERPROC)                                                                         \
    X(GetShaderiv, PFNGLGETSHADERIVPROC)                                                                             \
    X(GetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)                                                                   \
    X(DeleteShader, PFNGLDELETESHADERPROC)                                                                           \
    X(CreateProgram, PFNGLCREATEPROGRAMPROC)                                                                         \
    X(AttachShader, PFNGLATTACHSHADERPROC)                                                                           \
    X(LinkProgram, PFNGLLINKPROGRAMPROC)                                                                             \
    X(GetProgramiv, PFNGLGETPROGRAMIVPROC)                                                                           \
    X(GetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)                                                                 \
    X(DeleteProgram, PFNGLDELETEPROGRAMPROC)                                                                         \
    X(UseProgram, PFNGLUSEPROGRAMPROC)                                                                               \
    X(GetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)                                                               \
    X(Uniform1i, PFNGLUNIFORM1IPROC)                                                                                 \
    X(Uniform1f, PFNGLUNIFORM1FPROC)                                                                                 \
    X(Uniform2i, PFNGLUNIFORM2IPROC)                                                                                 \
    X(Uniform3f, PFNGLUNIFORM3FPROC)                                                                                 \
    X(GenVertexArrays, PFNGLGENVERTEXARRAYSPROC)                                                                     \
    X(BindVertexArray, PFNGLBINDVERTEXARRAYPROC)                                                                     \
    X(DeleteVertexArrays, PFNGLDELETEVERTEXARRAYSPROC)                                                               \
    X(Enable, PFNGLENABLEPROC)                                                                                       \
    X(Disable, PFNGLDISABLEPROC)                                                                                     \
    X(Clear, PFNGLCLEARPROC)                                                                                         \
    X(ClearColor, PFNGLCLEARCOLORPROC)                                                                               \
    X(DepthFunc, PFNGLDEPTHFUNCPROC)                                                                                 \
    X(DepthMask, PFNGLDEPTHMASKPROC)                                                                                 \
    X(BlendFunc, PFNGLBLENDFUNCPROC)                                                                                 \
    X(RenderbufferStorageMultisample, PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC)                                       \
    X(BlitFramebuffer, PFNGLBLITFRAMEBUFFERPROC)                                                                     \
    X(UniformMatrix4fv, PFNGLUNIFORMMATRIX4FVPROC)                                                                   \
    X(Uniform2fv, PFNGLUNIFORM2FVPROC)                                                                               \
    X(Uniform2f, PFNGLUNIFORM2FPROC)                                                                                 \
    X(ColorMask, PFNGLCOLORMASKPROC)                                                                                 \
    X(PolygonOffset, PFNGLPOLYGONOFFSETPROC)                                                                         \
    X(GenBuffers, PFNGLGENBUFFERSPROC)                                                                               \
    X(DeleteBuffers, PFNGLDELETEBUFFERSPROC)                                                                         \
    X(BindBuffer, PFNGLBINDBUFFERPROC)                                                                               \
    X(BufferData, PFNGLBUFFERDATAPROC)                                                                               \
    X(DrawElements, PFNGLDRAWELEMENTSPROC)

typedef struct im_gl {
#define IM_GL_MEMBER(name, type) type name;
    IM_GL_FUNCTIONS(IM_GL_MEMBER)
#undef IM_GL_MEMBER
} im_gl;

typedef void (*im_gl_proc)(void);
typedef im_gl_proc (*im_gl_loader)(const char *name);

/* Fills the table through loader; IM_EUNSUPPORTED naming the first missing function. */
int gl_load(im_gl *gl, im_gl_loader loader);

#endif
