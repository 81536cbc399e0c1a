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
    /* the image into file (path.tmp, img_tmp_path) in the format of path's extension; names NULL:
     * img_write, else img_write_channels */
    int (*write)(const char *path, const char *file, const img_t *img, const char *const *names, char *err,
                 size_t errlen);
    int (*compare)(const char *path_a, const char *path_b, double threshold, const char *diff_path,
                   img_compare_result *res, char *err, size_t errlen);
    const char *(*version)(void);
} img_api;

/* Every image file is written as path.tmp and renamed when complete, so an interrupted or failed
 * write never leaves a truncated image under the real name (render sequences stopped by Ctrl-C
 * keep only whole frames). img_tmp_path: path.tmp into tmp (0; -1 with err set if too long).
 * img_tmp_commit: renames tmp to path when written (0), else removes it; -1 when not written
 * (err set by the writer) or the rename failed (err set here). Defined in img.c. */
enum { IMG_TMP_PATH_MAX = 4200 }; /* the writers' buffer for path.tmp */
int img_tmp_path(const char *path, char *tmp, size_t len, char *err, size_t errlen);
int img_tmp_commit(const char *tmp, const char *path, int written, char *err, size_t errlen);

/* Defined in img_oiio.cpp: in the program when it is linked in, else in libsaarcor_img.so. */
const img_api *img_oiio_api(void);

#ifdef __cplusplus
}
#endif

#endif
