/*
 * libFuzzer target: the memory-image validator (host/memimage/mi_validate.c) and, for an image it
 * accepts, the device model on it (tests/image_probe.h: RGS, traversal, list, transformation and
 * intersection units, every traversal algorithm). The input bytes are the image's words
 * (little-endian); they are copied into a buffer of exactly that size, so that ASan reports any
 * read outside the image that the validator let through. Seeds: valid images of the generated
 * scenes (saarcor info SCENE --image FILE).
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "image_probe.h"
#include "memimage.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const size_t n = size / 4;
    uint32_t *w = malloc((n ? n : 1) * sizeof *w);
    if (!w)
        return 0;
    memcpy(w, data, n * 4);
    char err[256];
    if (mi_validate(w, (uint32_t)n, err, sizeof err) == 0)
        image_probe(w, 2);
    free(w);
    return 0;
}
