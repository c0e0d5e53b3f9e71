/* GLES 2.0 core headers plus the extension tokens jade may use when present. */
#ifndef JD_GL_H
#define JD_GL_H
#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
#endif
