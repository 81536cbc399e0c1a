/*
 * OpenEXR files through the OpenEXR core library's C API (img_exr.h says why not OpenImageIO):
 * one scanline part, ZIP compression (16 lines a chunk), the interleaved float pixels handed to
 * the library channel by channel with their strides, so it converts to half itself. A file is
 * written as path.tmp and renamed when complete (img_api.h), as every image file of the program.
 */
#define _POSIX_C_SOURCE 200809L /* gmtime_r */
#include "img_exr.h"
#include "img_api.h"

#include <OpenEXR/openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

int img_exr_path(const char *path)
{
    const size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

int img_exr_writes(const char *path, int channels, int named)
{
    return img_exr_path(path) && (named || channels == 3 || channels == 4);
}

/* The library's last message (its default handler prints to stderr; the program reports it in
 * its own one line instead). */
static _Thread_local char exr_message[256];

static void keep_message(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(exr_message, sizeof exr_message, "%s", msg ? msg : exr_get_default_error_message(code));
}

/* capDate, as OpenImageIO's DateTime: SOURCE_DATE_EPOCH (the reproducible-builds convention:
 * seconds since 1970) when set, so two runs write the same bytes, else now; UTC. */
static exr_result_t set_date(exr_context_t f)
{
    const char *epoch = getenv("SOURCE_DATE_EPOCH");
    char *end = NULL;
    const long long s = epoch ? strtoll(epoch, &end, 10) : -1;
    const time_t t = epoch && end != epoch && !*end && s >= 0 ? (time_t)s : time(NULL);
    struct tm tm;
    char date[32];
    if (!gmtime_r(&t, &tm) || !strftime(date, sizeof date, "%Y:%m:%d %H:%M:%S", &tm))
        return EXR_ERR_SUCCESS;
    return exr_attr_set_string(f, 0, "capDate", date);
}

/* the channels of an image written without names, as OpenImageIO names them */
static const char *const rgba[] = { "R", "G", "B", "A" };

static exr_result_t write_header(exr_context_t f, const img_t *img, const char *const *names)
{
    int part;
    exr_result_t rc = exr_add_part(f, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rc == EXR_ERR_SUCCESS)
        rc = exr_initialize_required_attr_simple(f, part, img->width, img->height, EXR_COMPRESSION_ZIP);
    for (int c = 0; c < img->channels && rc == EXR_ERR_SUCCESS; c++)
        rc = exr_add_channel(f, part, names ? names[c] : rgba[c], names ? EXR_PIXEL_FLOAT : EXR_PIXEL_HALF,
                             EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rc == EXR_ERR_SUCCESS)
        rc = set_date(f);
    return rc == EXR_ERR_SUCCESS ? exr_write_header(f) : rc;
}

/* The channel of the header (sorted by name, as EXR requires) in the interleaved pixels. */
static int channel_index(const char *name, const img_t *img, const char *const *names)
{
    for (int c = 0; c < img->channels; c++)
        if (strcmp(name, names ? names[c] : rgba[c]) == 0)
            return c;
    return 0; /* not reached: the header's channels are img's */
}

/* Points each channel of the chunk at its first value in the interleaved pixels. */
static void point_channels(exr_encode_pipeline_t *enc, const img_t *img, const char *const *names, int y)
{
    const int32_t pixel = img->channels * (int32_t)sizeof(float);
    for (int k = 0; k < enc->channel_count; k++) {
        exr_coding_channel_info_t *ch = &enc->channels[k];
        const int c = channel_index(ch->channel_name, img, names);
        ch->user_bytes_per_element = sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_pixel_stride = pixel;
        ch->user_line_stride = pixel * img->width;
        ch->encode_from_ptr = (const uint8_t *)(img->pixels + ((size_t)y * (size_t)img->width) * (size_t)img->channels + c);
    }
}

static exr_result_t write_chunks(exr_context_t f, const img_t *img, const char *const *names)
{
    int32_t lines = 1;
    exr_result_t rc = exr_get_scanlines_per_chunk(f, 0, &lines);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    for (int y = 0, first = 1; y < img->height && rc == EXR_ERR_SUCCESS; y += lines, first = 0) {
        exr_chunk_info_t chunk;
        rc = exr_write_scanline_chunk_info(f, 0, y, &chunk);
        if (rc == EXR_ERR_SUCCESS)
            rc = first ? exr_encoding_initialize(f, 0, &chunk, &enc) : exr_encoding_update(f, 0, &chunk, &enc);
        if (rc != EXR_ERR_SUCCESS)
            break;
        point_channels(&enc, img, names, y);
        if (first)
            rc = exr_encoding_choose_default_routines(f, 0, &enc);
        if (rc == EXR_ERR_SUCCESS)
            rc = exr_encoding_run(f, 0, &enc);
    }
    exr_encoding_destroy(f, &enc);
    return rc;
}

int img_exr_write(const char *path, const img_t *img, const char *const *names, char *err, size_t errlen)
{
    char tmp[IMG_TMP_PATH_MAX];
    if (img_tmp_path(path, tmp, sizeof tmp, err, errlen) != 0)
        return -1;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = keep_message;
    exr_context_t f = NULL;
    exr_message[0] = 0;
    exr_result_t rc = exr_start_write(&f, tmp, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rc == EXR_ERR_SUCCESS)
        rc = write_header(f, img, names);
    if (rc == EXR_ERR_SUCCESS)
        rc = write_chunks(f, img, names);
    const exr_result_t closed = f ? exr_finish(&f) : EXR_ERR_SUCCESS;
    if (rc == EXR_ERR_SUCCESS)
        rc = closed;
    if (rc != EXR_ERR_SUCCESS)
        snprintf(err, errlen, "cannot write '%s': %s", path,
                 exr_message[0] ? exr_message : exr_get_default_error_message(rc));
    return img_tmp_commit(tmp, path, rc == EXR_ERR_SUCCESS, err, errlen);
}
