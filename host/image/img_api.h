/*
 * The table of image functions OpenImageIO serves (img_oiio.cpp), behind img.h's API (img.c):
 * private to host/image.
 */
#ifndef SAARCOR_IMG_API_H
#define SAARCOR_IMG_API_H

#include "img.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int (*read)(const char *path, img_t *out, char *err, size_t errlen);
    /* names NULL: img_write, else img_write_channels */
    int (*write)(const char *path, const img_t *img, const char *const *names, char *err, size_t errlen);
    int (*compare)(const char *path_a, const char *path_b, double threshold, const char *diff_path,
                   img_compare_result *res, char *err, size_t errlen);
    const char *(*version)(void);
} img_api;

/* Defined in img_oiio.cpp: in the program when it is linked in, else in libsaarcor_img.so. */
const img_api *img_oiio_api(void);

#ifdef __cplusplus
}
#endif

#endif
