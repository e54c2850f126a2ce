/*
 * An offscreen OpenGL canvas (OSMesa, llvmpipe): a 4x multisampled FBO that
 * is resolved into a caller-sized RGBA image, text drawn with FreeType onto
 * the resolved image, and an atomic PNG writer. Legacy (compatibility
 * profile) GL is used for drawing: the pictures are a few thousand
 * primitives, far from any performance concern.
 */
#ifndef HYLO_RENDER_CANVAS_H
#define HYLO_RENDER_CANVAS_H

#include <stddef.h>
#include <stdint.h>

#define CANVAS_MAX_SIDE 8192   /* larger images are refused */

typedef struct {
	int width, height;
	uint8_t *osmesa_buf;     /* OSMesa's default framebuffer (bottom-up RGBA) */
	uint8_t *rgba;           /* the resolved image, top-down RGBA */
	void *ctx;               /* OSMesaContext */
	unsigned fbo, color_rb, depth_rb;
	void *face_lib, *face;   /* FreeType library and face; NULL without a font */
} canvas;

typedef struct { float r, g, b, a; } rgba_color;

/* Creates the GL context and the multisampled FBO, bound for drawing and
 * cleared to bg. Returns 0, or -1 with a message in err. */
int canvas_open(canvas *c, int width, int height, rgba_color bg, char *err, size_t errlen);

/* Resolves the multisampled FBO into c->rgba (top-down). */
int canvas_finish(canvas *c, char *err, size_t errlen);

/* Draws UTF-8-free (ASCII) text with its baseline's left end at pixel
 * (x, y) of the resolved image (y down), height px pixels. No-op without a
 * font. Returns the advance width in pixels. */
int canvas_text(canvas *c, int x, int y, int px, const char *text, rgba_color col);

/* Width in pixels that canvas_text would advance. */
int canvas_text_width(canvas *c, int px, const char *text);

/* Fills a rectangle of the resolved image (pixels, y down). */
void canvas_fill_rect(canvas *c, int x, int y, int w, int h, rgba_color col);

/* Writes c->rgba as an 8-bit RGB PNG via a temporary file renamed into place,
 * so that a failure never leaves a partial file at path. */
int canvas_write_png(const canvas *c, const char *path, char *err, size_t errlen);

void canvas_close(canvas *c);

#endif
