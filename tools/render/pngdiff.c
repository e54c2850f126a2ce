/*
 * hylo-pngdiff: the golden-image comparator. Two images match when at most
 * a given fraction of their pixels differ by more than a per-channel
 * tolerance (goldens are tied to the Mesa version, docs/deps.md, so exact bytes
 * are too strict across machines). On a mismatch it says how many pixels,
 * where and by how much, and can write a diff image. --within MASK also
 * requires every differing pixel to lie on MASK's drawn pixels (grown by a
 * few pixels), for tests like "adding the path changes exactly the path".
 * Exit codes: 0 match, 1 differ, 2 usage or file error.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <png.h>

typedef struct {
	png_image img;
	unsigned char *px;   /* RGB */
} picture;

static int load(const char *path, picture *p)
{
	memset(p, 0, sizeof *p);
	p->img.version = PNG_IMAGE_VERSION;
	if (!png_image_begin_read_from_file(&p->img, path)) {
		fprintf(stderr, "hylo-pngdiff: cannot read %s: %s\n", path, p->img.message);
		return -1;
	}
	p->img.format = PNG_FORMAT_RGB;
	p->px = malloc(PNG_IMAGE_SIZE(p->img));
	if (!p->px || !png_image_finish_read(&p->img, NULL, p->px, 0, NULL)) {
		fprintf(stderr, "hylo-pngdiff: cannot decode %s: %s\n", path, p->img.message);
		free(p->px);
		p->px = NULL;
		return -1;
	}
	return 0;
}

static int channel_diff(const unsigned char *a, const unsigned char *b)
{
	int k, d, m = 0;

	for (k = 0; k < 3; k++) {
		d = abs((int)a[k] - (int)b[k]);
		if (d > m)
			m = d;
	}
	return m;
}

static void usage(FILE *f)
{
	fprintf(f,
		"usage: hylo-pngdiff A.png B.png [options]\n"
		"Compares two images: they match when at most --max-fraction of the pixels\n"
		"differ by more than --tolerance in some channel.\n"
		"\n"
		"  --tolerance T     per-channel difference (0-255) still counted equal (default: 8)\n"
		"  --max-fraction F  largest fraction of differing pixels that matches (default: 0.001)\n"
		"  --diff OUT.png    on a mismatch, write A dimmed with differing pixels in red\n"
		"  --within MASK.png also require every differing pixel to lie within --grow\n"
		"                    pixels of a drawn pixel of MASK (one whose colour differs\n"
		"                    from MASK's top-left pixel), and report the fraction of\n"
		"                    drawn pixels that changed\n"
		"  --grow N          see --within (default: 2)\n"
		"  --min-changed F   with --within: fail unless at least this fraction of\n"
		"                    MASK's drawn pixels differ between A and B (default: 0)\n"
		"  --help            this text\n"
		"Exit codes: 0 match, 1 differ, 2 usage or file error.\n");
}

int main(int argc, char **argv)
{
	const char *files[2] = {NULL, NULL}, *diff_out = NULL, *mask_path = NULL;
	double tol = 8, max_frac = 0.001, min_changed = 0;
	long grow = 2;
	int n_files = 0, i, rc = 0;
	picture a, b, mask;
	unsigned w, h, x, y;
	unsigned long n_diff = 0, n_outside = 0, n_drawn = 0, n_drawn_changed = 0;
	unsigned x0 = ~0u, y0 = ~0u, x1 = 0, y1 = 0;
	int max_d = 0;
	unsigned char *drawn = NULL;

	for (i = 1; i < argc; i++) {
		const char *s = argv[i];
		char *end = NULL;
		if (strcmp(s, "--help") == 0) {
			usage(stdout);
			return 0;
		}
		if (s[0] == '-' && s[1] == '-') {
			if (i + 1 >= argc) {
				fprintf(stderr, "hylo-pngdiff: %s needs a value (see --help)\n", s);
				return 2;
			}
			if (strcmp(s, "--tolerance") == 0)
				tol = strtod(argv[i + 1], &end);
			else if (strcmp(s, "--max-fraction") == 0)
				max_frac = strtod(argv[i + 1], &end);
			else if (strcmp(s, "--min-changed") == 0)
				min_changed = strtod(argv[i + 1], &end);
			else if (strcmp(s, "--grow") == 0)
				grow = strtol(argv[i + 1], &end, 10);
			else if (strcmp(s, "--diff") == 0)
				diff_out = argv[i + 1];
			else if (strcmp(s, "--within") == 0)
				mask_path = argv[i + 1];
			else {
				fprintf(stderr, "hylo-pngdiff: unknown option %s (see --help)\n", s);
				return 2;
			}
			if (end && (end == argv[i + 1] || *end || tol < 0 || max_frac < 0 || max_frac > 1 ||
			            grow < 0 || grow > 64 || min_changed < 0 || min_changed > 1)) {
				fprintf(stderr, "hylo-pngdiff: bad value '%s' for %s\n", argv[i + 1], s);
				return 2;
			}
			i++;
		} else if (n_files < 2) {
			files[n_files++] = s;
		} else {
			fprintf(stderr, "hylo-pngdiff: more than two images given (see --help)\n");
			return 2;
		}
	}
	if (n_files != 2) {
		usage(stderr);
		return 2;
	}
	if (load(files[0], &a) != 0 || load(files[1], &b) != 0)
		return 2;
	w = a.img.width;
	h = a.img.height;
	if (w != b.img.width || h != b.img.height) {
		printf("sizes differ: %s is %ux%u, %s is %ux%u\n", files[0], w, h, files[1], b.img.width,
		       b.img.height);
		return 1;
	}
	if (mask_path) {
		if (load(mask_path, &mask) != 0)
			return 2;
		if (mask.img.width != w || mask.img.height != h) {
			fprintf(stderr, "hylo-pngdiff: mask %s is %ux%u, the images %ux%u\n", mask_path,
			        mask.img.width, mask.img.height, w, h);
			return 2;
		}
		drawn = calloc((size_t)w * h, 1);
		if (!drawn)
			return 2;
		for (y = 0; y < h; y++)
			for (x = 0; x < w; x++)
				if (channel_diff(mask.px + 3 * ((size_t)y * w + x), mask.px) > (int)tol) {
					long dx, dy;
					n_drawn++;
					for (dy = -grow; dy <= grow; dy++)
						for (dx = -grow; dx <= grow; dx++) {
							long xx = (long)x + dx, yy = (long)y + dy;
							if (xx >= 0 && yy >= 0 && xx < (long)w && yy < (long)h)
								drawn[(size_t)yy * w + (size_t)xx] |= (dx == 0 && dy == 0) ? 3 : 1;
						}
				}
	}
	for (y = 0; y < h; y++)
		for (x = 0; x < w; x++) {
			size_t k = (size_t)y * w + x;
			int d = channel_diff(a.px + 3 * k, b.px + 3 * k);
			if (d <= (int)tol)
				continue;
			n_diff++;
			if (d > max_d)
				max_d = d;
			if (x < x0) x0 = x;
			if (y < y0) y0 = y;
			if (x > x1) x1 = x;
			if (y > y1) y1 = y;
			if (drawn) {
				if (!(drawn[k] & 1))
					n_outside++;
				if (drawn[k] & 2)
					n_drawn_changed++;
			}
		}
	if (n_diff > 0)
		printf("%lu of %u pixels (%.4f%%) differ by more than %g (largest difference %d), within "
		       "x %u..%u, y %u..%u\n", n_diff, w * h, 100.0 * n_diff / ((double)w * h), tol, max_d,
		       x0, x1, y0, y1);
	if (drawn) {
		/* the differences must be the mask's pixels, not their amount */
		double changed = n_drawn ? (double)n_drawn_changed / n_drawn : 0;
		printf("mask: %lu drawn pixels, %.1f%% of them changed; %lu differing pixel(s) outside "
		       "the mask\n", n_drawn, 100 * changed, n_outside);
		rc = n_outside > 0 || changed < min_changed;
	} else {
		rc = (double)n_diff > max_frac * (double)w * h;
	}
	if (rc && diff_out) {
		png_image out;
		memset(&out, 0, sizeof out);
		out.version = PNG_IMAGE_VERSION;
		out.width = w;
		out.height = h;
		out.format = PNG_FORMAT_RGB;
		for (y = 0; y < h; y++)
			for (x = 0; x < w; x++) {
				size_t k = (size_t)y * w + x;
				unsigned char *p = a.px + 3 * k;
				if (channel_diff(p, b.px + 3 * k) > (int)tol) {
					p[0] = 255; p[1] = 0; p[2] = 0;
				} else {
					p[0] = (unsigned char)(128 + p[0] / 2);
					p[1] = (unsigned char)(128 + p[1] / 2);
					p[2] = (unsigned char)(128 + p[2] / 2);
				}
			}
		if (png_image_write_to_file(&out, diff_out, 0, a.px, 0, NULL))
			printf("diff image: %s\n", diff_out);
		else
			fprintf(stderr, "hylo-pngdiff: cannot write %s: %s\n", diff_out, out.message);
	}
	printf("%s\n", rc ? "DIFFER" : "match");
	free(drawn);
	free(a.px);
	free(b.px);
	return rc;
}
