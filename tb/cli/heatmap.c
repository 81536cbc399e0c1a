/* render --heatmap: see heatmap.h. */
#include "heatmap.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "img.h"

/* viridis (matplotlib) at 0, 0.1, ..., 1 as 0xRRGGBB; linear in between */
static const uint32_t viridis[11] = { 0x440154, 0x482475, 0x414487, 0x355f8d, 0x2a788e, 0x21918c,
                                      0x22a884, 0x44bf70, 0x7ad151, 0xbddf26, 0xfde725 };

static void colour_of(double t, float rgb[3])
{
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    const double x = t * 10;
    const int i = x >= 10 ? 9 : (int)x;
    const double f = x - i;
    for (int c = 0; c < 3; c++) {
        const int sh = 16 - 8 * c;
        const double a = viridis[i] >> sh & 0xFF, b = viridis[i + 1] >> sh & 0xFF;
        rgb[c] = (float)((a + f * (b - a)) / 255.0);
    }
}

/* 3x5 glyphs, one octal digit per row (bit 2: left column) */
static uint32_t glyph(char ch)
{
    static const char digits[] = "0123456789", letters[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    static const uint32_t digit_rows[10] = { 075557, 026227, 071747, 071717, 055711,
                                             074717, 074757, 071111, 075757, 075717 };
    static const uint32_t letter_rows[26] = { 025755, 065656, 034443, 065556, 074647, 074644, 034553,
                                              055755, 072227, 011152, 055655, 044447, 057755, 065555,
                                              025552, 065644, 025563, 065655, 034216, 072222, 055557,
                                              055552, 055775, 055255, 055222, 071247 };
    const char u = (char)toupper((unsigned char)ch);
    const char *d = strchr(digits, u), *l = strchr(letters, u);
    if (u && d)
        return digit_rows[d - digits];
    if (u && l)
        return letter_rows[l - letters];
    switch (u) {
    case '.': return 000002;
    case '-': return 000700;
    case '_': return 000007;
    case '/': return 011244;
    case '[': return 064446;
    case ']': return 031113;
    default: return 0;
    }
}

/* Text in white at (x, y) with glyphs scaled by s (advance 4 s), clipped to the image. */
static void draw_text(img_t *img, int x, int y, int s, const char *text)
{
    for (; *text; text++, x += 4 * s) {
        const uint32_t g = glyph(*text);
        for (int py = 0; py < 5 * s; py++)
            for (int px = 0; px < 3 * s; px++) {
                const int X = x + px, Y = y + py;
                if (!(g >> (3 * (4 - py / s) + 2 - px / s) & 1u) || X < 0 || Y < 0 || X >= img->width ||
                    Y >= img->height)
                    continue;
                float *o = &img->pixels[3 * ((size_t)Y * (size_t)img->width + (size_t)X)];
                o[0] = o[1] = o[2] = 1.0f;
            }
    }
}

/* A value in twelfths as the shortest decimal of at most 2 places. */
static void format_value(uint64_t twelfths, char *buf, size_t n)
{
    snprintf(buf, n, "%.2f", (double)twelfths / PC_UNIT);
    char *end = buf + strlen(buf) - 1;
    while (*end == '0')
        *end-- = 0;
    if (*end == '.')
        *end = 0;
}

static int text_width(const char *text, int s) { return (int)strlen(text) * 4 * s - s; }

/* The scale bar below the image: the colour map from lo to hi, their values, name and unit. */
static void draw_bar(img_t *img, uint32_t h, int kind, uint64_t lo, uint64_t hi)
{
    const int w = img->width, m = 4, s = w >= 320 ? 2 : 1, text_y = (int)h + 18;
    for (int x = m; x < w - m; x++) {
        float rgb[3];
        colour_of((double)(x - m) / (w - 2 * m - 1 > 0 ? w - 2 * m - 1 : 1), rgb);
        for (int y = (int)h + 4; y < (int)h + 14; y++)
            memcpy(&img->pixels[3 * ((size_t)y * (size_t)w + (size_t)x)], rgb, sizeof rgb);
    }
    char a[32], b[32], label[80];
    format_value(lo, a, sizeof a);
    format_value(hi, b, sizeof b);
    snprintf(label, sizeof label, "%s [%s/px]", pc_names[kind], pc_units[kind]);
    draw_text(img, m, text_y, s, a);
    draw_text(img, w - m - text_width(b, s), text_y, s, b);
    draw_text(img, (w - text_width(label, s)) / 2, text_y, s, label);
}

int heatmap_channel(const char *name)
{
    for (int k = 0; k < PC_KINDS; k++)
        if (strcmp(name, pc_names[k]) == 0)
            return k;
    return -1;
}

int heatmap_write(const char *path, const pixel_cost *costs, uint32_t w, uint32_t h, int kind, char *err,
                  size_t errlen)
{
    const size_t n = (size_t)w * h;
    img_t img = { (int)w, (int)(h + HEATMAP_BAR), 3, calloc((size_t)w * (h + HEATMAP_BAR) * 3, sizeof(float)) };
    if (!img.pixels) {
        snprintf(err, errlen, "out of memory for the heatmap");
        return -1;
    }
    uint64_t lo = UINT64_MAX, hi = 0;
    for (size_t p = 0; p < n; p++) {
        const uint64_t v = costs[p].v[kind];
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    lo = n ? lo : 0;
    for (size_t p = 0; p < n; p++)
        colour_of(hi > lo ? (double)(costs[p].v[kind] - lo) / (double)(hi - lo) : 0.0, &img.pixels[3 * p]);
    draw_bar(&img, h, kind, lo, hi);
    const int rc = img_write(path, &img, err, errlen);
    img_free(&img);
    return rc;
}
