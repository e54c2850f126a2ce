#define GL_GLEXT_PROTOTYPES 1
#include "canvas.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <png.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#define MSAA_SAMPLES 4
#define FONT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"

static int fail(char *err, size_t errlen, const char *msg)
{
	snprintf(err, errlen, "%s", msg);
	return -1;
}

int canvas_open(canvas *c, int width, int height, rgba_color bg, char *err, size_t errlen)
{
	FT_Library lib;
	FT_Face face;

	memset(c, 0, sizeof *c);
	if (width < 16 || height < 16 || width > CANVAS_MAX_SIDE || height > CANVAS_MAX_SIDE) {
		snprintf(err, errlen, "image size %dx%d is out of range (16 .. %d pixels per side)",
		         width, height, CANVAS_MAX_SIDE);
		return -1;
	}
	c->width = width;
	c->height = height;
	c->osmesa_buf = calloc((size_t)width * (size_t)height, 4);
	c->rgba = calloc((size_t)width * (size_t)height, 4);
	if (!c->osmesa_buf || !c->rgba)
		return fail(err, errlen, "out of memory for the image");
	c->ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, NULL);
	if (!c->ctx)
		return fail(err, errlen, "OSMesaCreateContextExt failed (is libOSMesa installed?)");
	if (!OSMesaMakeCurrent((OSMesaContext)c->ctx, c->osmesa_buf, GL_UNSIGNED_BYTE, width, height))
		return fail(err, errlen, "OSMesaMakeCurrent failed");

	glGenFramebuffers(1, &c->fbo);
	glBindFramebuffer(GL_FRAMEBUFFER, c->fbo);
	glGenRenderbuffers(1, &c->color_rb);
	glBindRenderbuffer(GL_RENDERBUFFER, c->color_rb);
	glRenderbufferStorageMultisample(GL_RENDERBUFFER, MSAA_SAMPLES, GL_RGBA8, width, height);
	glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c->color_rb);
	glGenRenderbuffers(1, &c->depth_rb);
	glBindRenderbuffer(GL_RENDERBUFFER, c->depth_rb);
	glRenderbufferStorageMultisample(GL_RENDERBUFFER, MSAA_SAMPLES, GL_DEPTH_COMPONENT24, width, height);
	glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, c->depth_rb);
	if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
		return fail(err, errlen, "the multisampled framebuffer is incomplete");

	glViewport(0, 0, width, height);
	glClearColor(bg.r, bg.g, bg.b, bg.a);
	glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
	glEnable(GL_BLEND);
	glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

	if (FT_Init_FreeType(&lib) == 0) {
		if (FT_New_Face(lib, FONT_PATH, 0, &face) == 0) {
			c->face_lib = lib;
			c->face = face;
		} else {
			FT_Done_FreeType(lib);
			fprintf(stderr, "hylo-render: warning: font %s not found; no text "
			        "(install fonts-dejavu-core)\n", FONT_PATH);
		}
	}
	return 0;
}

int canvas_finish(canvas *c, char *err, size_t errlen)
{
	int y;
	size_t row = (size_t)c->width * 4;

	glBindFramebuffer(GL_READ_FRAMEBUFFER, c->fbo);
	glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
	glBlitFramebuffer(0, 0, c->width, c->height, 0, 0, c->width, c->height,
	                  GL_COLOR_BUFFER_BIT, GL_NEAREST);
	glFinish();
	if (glGetError() != GL_NO_ERROR)
		return fail(err, errlen, "OpenGL reported an error while drawing");
	/* OSMesa rows run bottom-up; PNG rows top-down. */
	for (y = 0; y < c->height; y++)
		memcpy(c->rgba + (size_t)y * row, c->osmesa_buf + (size_t)(c->height - 1 - y) * row, row);
	return 0;
}

static uint8_t blend(uint8_t dst, float src, float a)
{
	float v = (float)dst * (1.0f - a) + src * 255.0f * a;
	return (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v + 0.5f);
}

static void put(canvas *c, int x, int y, rgba_color col, float a)
{
	uint8_t *p;

	if (x < 0 || y < 0 || x >= c->width || y >= c->height || a <= 0)
		return;
	p = c->rgba + ((size_t)y * (size_t)c->width + (size_t)x) * 4;
	p[0] = blend(p[0], col.r, a);
	p[1] = blend(p[1], col.g, a);
	p[2] = blend(p[2], col.b, a);
}

void canvas_fill_rect(canvas *c, int x, int y, int w, int h, rgba_color col)
{
	int i, j;

	for (j = y; j < y + h; j++)
		for (i = x; i < x + w; i++)
			put(c, i, j, col, col.a);
}

static int text_run(canvas *c, int x, int y, int px, const char *text, const rgba_color *col)
{
	FT_Face face = (FT_Face)c->face;
	int pen = x;
	const char *s;

	if (!face)
		return 0;
	FT_Set_Pixel_Sizes(face, 0, (FT_UInt)px);
	for (s = text; *s; s++) {
		FT_GlyphSlot g;
		unsigned i, j;

		if (FT_Load_Char(face, (unsigned char)*s, col ? FT_LOAD_RENDER : FT_LOAD_DEFAULT))
			continue;
		g = face->glyph;
		if (col)
			for (j = 0; j < g->bitmap.rows; j++)
				for (i = 0; i < g->bitmap.width; i++) {
					float a = g->bitmap.buffer[j * (unsigned)g->bitmap.pitch + i] / 255.0f;
					put(c, pen + g->bitmap_left + (int)i, y - g->bitmap_top + (int)j, *col,
					    a * col->a);
				}
		pen += (int)(g->advance.x >> 6);
	}
	return pen - x;
}

int canvas_text(canvas *c, int x, int y, int px, const char *text, rgba_color col)
{
	return text_run(c, x, y, px, text, &col);
}

int canvas_text_width(canvas *c, int px, const char *text)
{
	return text_run(c, 0, 0, px, text, NULL);
}

int canvas_write_png(const canvas *c, const char *path, char *err, size_t errlen)
{
	char tmp[4096];
	FILE *f;
	png_structp png;
	png_infop info;
	uint8_t *row;
	int y, x;

	if (snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid()) >= (int)sizeof tmp)
		return fail(err, errlen, "output path is too long");
	f = fopen(tmp, "wb");
	if (!f) {
		snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
		return -1;
	}
	row = malloc((size_t)c->width * 3);
	png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
	info = png ? png_create_info_struct(png) : NULL;
	if (!row || !png || !info || setjmp(png_jmpbuf(png))) {
		if (png)
			png_destroy_write_struct(&png, info ? &info : NULL);
		free(row);
		fclose(f);
		remove(tmp);
		snprintf(err, errlen, "cannot encode the PNG for %s", path);
		return -1;
	}
	png_init_io(png, f);
	png_set_IHDR(png, info, (png_uint_32)c->width, (png_uint_32)c->height, 8, PNG_COLOR_TYPE_RGB,
	             PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	png_write_info(png, info);
	for (y = 0; y < c->height; y++) {
		const uint8_t *src = c->rgba + (size_t)y * (size_t)c->width * 4;
		for (x = 0; x < c->width; x++)
			memcpy(row + 3 * x, src + 4 * x, 3);
		png_write_row(png, row);
	}
	png_write_end(png, NULL);
	png_destroy_write_struct(&png, &info);
	free(row);
	if (fflush(f) != 0 || fsync(fileno(f)) != 0 || fclose(f) != 0) {
		remove(tmp);
		snprintf(err, errlen, "cannot write %s: %s", path, strerror(errno));
		return -1;
	}
	if (rename(tmp, path) != 0) {
		snprintf(err, errlen, "cannot rename %s to %s: %s", tmp, path, strerror(errno));
		remove(tmp);
		return -1;
	}
	return 0;
}

void canvas_close(canvas *c)
{
	if (c->face)
		FT_Done_Face((FT_Face)c->face);
	if (c->face_lib)
		FT_Done_FreeType((FT_Library)c->face_lib);
	if (c->ctx) {
		if (c->fbo) {
			glDeleteFramebuffers(1, &c->fbo);
			glDeleteRenderbuffers(1, &c->color_rb);
			glDeleteRenderbuffers(1, &c->depth_rb);
		}
		OSMesaDestroyContext((OSMesaContext)c->ctx);
	}
	free(c->osmesa_buf);
	free(c->rgba);
	memset(c, 0, sizeof *c);
}
