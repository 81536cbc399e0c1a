/*
 * render --heatmap: a false-colour picture of one per-pixel cost channel (pixel_cost.h). The
 * colour map is viridis (perceptually ordered, readable in grey and by colour-blind viewers),
 * linear from the frame's smallest to its largest value; below the image a scale bar of
 * HEATMAP_BAR rows shows the map with the two values and the channel's name and unit in a
 * built-in 3x5 pixel font.
 */
#ifndef SAARCOR_HEATMAP_H
#define SAARCOR_HEATMAP_H

#include <stddef.h>
#include <stdint.h>

#include "pixel_cost.h"

#define HEATMAP_BAR 32

/* The PC_* channel called name, -1 if there is none. */
int heatmap_channel(const char *name);

/* Writes channel kind of the w x h costs as a w x (h + HEATMAP_BAR) image (PNG, or another format
 * by the extension). 0, or -1 with a one-line message in err. */
int heatmap_write(const char *path, const pixel_cost *costs, uint32_t w, uint32_t h, int kind, char *err,
                  size_t errlen);

#endif
