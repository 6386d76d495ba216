/* Pixel checks shared by the tests that render figures (plot.h): colour
 * classes of the paper's palette, and the count of a colour's pixels around
 * a data point.  The including test defines W and H (the image size) first. */
#ifndef HL_PIXELS_H
#define HL_PIXELS_H

#include <stddef.h>

#include "hamlie/plot.h"

#if !defined(W) || !defined(H)
#error "define W and H (the image size) before including hl_pixels.h"
#endif

static inline int is_red(const unsigned char *p) { return p[0] > 180 && p[1] < 110 && p[2] < 110; }
static inline int is_blue(const unsigned char *p) { return p[2] > 180 && p[0] < 110 && p[1] < 110; }
static inline int is_green(const unsigned char *p) { return p[1] > 100 && p[0] < 80 && p[2] < 80; }
static inline int is_black(const unsigned char *p) { return p[0] < 70 && p[1] < 70 && p[2] < 70; }

typedef int (*color_fn)(const unsigned char *);

/* Pixels of a colour within r pixels of the data point (x, y); -1 if the
 * point cannot be placed. */
static inline int near(const unsigned char *img, const hl_plot_frame *fr, double x, double y,
                       int r, color_fn fn)
{
    double px, py;
    if (!hl_plot_frame_pixel(fr, W, H, x, y, &px, &py))
        return -1;
    int n = 0;
    for (int j = (int)py - r; j <= (int)py + r; j++)
        for (int i = (int)px - r; i <= (int)px + r; i++)
            if (i >= 0 && i < W && j >= 0 && j < H)
                n += fn(img + 3 * ((size_t)j * W + i));
    return n;
}

#endif
