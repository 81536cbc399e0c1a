/*
 * libFuzzer target: the glTF loader (host/scene/gltf_load.cpp, tinygltf underneath) for .gltf
 * (JSON) and .glb, with embedded (data: URI) and external buffers and images, followed by the
 * scene evaluation and the memory-image build of what it loaded (small trees). The input is a
 * bundle: the scene file, then optional external files, each introduced by a line
 * "\n#FILE NAME\n" (NAME of letters, digits, '.', '_', '-'). The files are written into a
 * private temporary directory, the sandbox: the loader refuses references outside it, so
 * nothing else on the machine is read. The scene is scene.glb if it starts with the binary
 * magic "glTF", else scene.gltf. Seeds: the generated scenes as .glb, as .gltf with embedded
 * data and as .gltf with external .bin and .png files (tests/fuzz/corpus.sh).
 */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "memimage.h"
#include "scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_FILES = 8 };
static const char MARK[] = "\n#FILE ";
static char sandbox[64];
static char written[MAX_FILES + 1][128]; /* the external files, then the scene */
static int n_written;

static void write_file(const char *name, const uint8_t *p, size_t n)
{
    snprintf(written[n_written], sizeof written[0], "%s/%s", sandbox, name);
    FILE *f = fopen(written[n_written], "wb");
    if (!f)
        return;
    fwrite(p, 1, n, f);
    fclose(f);
    n_written++;
}

static int good_name(const char *s, size_t n)
{
    if (n == 0 || n > 40 || s[0] == '.')
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-", s[i]) || s[i] == 0)
            return 0;
    return 1;
}

/* Writes the bundle's external files (after the scene part); returns the scene part's length. */
static size_t unpack(const uint8_t *data, size_t size)
{
    const uint8_t *m = memmem(data, size, MARK, sizeof MARK - 1);
    const size_t scene_len = m ? (size_t)(m - data) : size;
    while (m) {
        const uint8_t *name = m + sizeof MARK - 1, *end = data + size;
        const uint8_t *nl = memchr(name, '\n', (size_t)(end - name));
        if (!nl)
            break;
        const uint8_t *body = nl + 1;
        m = memmem(body, (size_t)(end - body), MARK, sizeof MARK - 1);
        char fname[48];
        if (n_written < MAX_FILES && good_name((const char *)name, (size_t)(nl - name))) {
            snprintf(fname, sizeof fname, "%.*s", (int)(nl - name), (const char *)name);
            write_file(fname, body, (size_t)((m ? m : end) - body));
        }
    }
    return scene_len;
}

static void remove_sandbox(void) { rmdir(sandbox); } /* its files are removed after each input */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!sandbox[0]) {
        snprintf(sandbox, sizeof sandbox, "/tmp/saarcor-fuzz-gltf-XXXXXX");
        if (!mkdtemp(sandbox))
            abort();
        atexit(remove_sandbox);
    }
    n_written = 0;
    const size_t scene_len = unpack(data, size);
    const char *name = scene_len >= 4 && memcmp(data, "glTF", 4) == 0 ? "scene.glb" : "scene.gltf";
    write_file(name, data, scene_len);
    scene s;
    char err[512];
    if (scene_load_gltf(written[n_written - 1], &s, err, sizeof err) == 0) {
        mi_params p;
        mi_params_default(&p);
        p.width = 16;
        p.height = 16;
        p.bottom.max_depth = p.top.max_depth = 12;
        mi_builder *b = mi_build(&s, &p, err, sizeof err);
        mi_free(b);
        scene_free(&s);
    }
    for (int i = 0; i < n_written; i++)
        unlink(written[i]);
    return 0;
}
