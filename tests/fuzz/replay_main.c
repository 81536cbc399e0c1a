/*
 * Replays fuzz inputs without libFuzzer: calls the harness's LLVMFuzzerTestOneInput once per file
 * named on the command line, as libFuzzer does in its file mode (arguments starting with '-' are
 * libFuzzer options and are ignored). `make test` links the harnesses with this main and the
 * AddressSanitizer + UndefinedBehaviorSanitizer objects of build/asan, so that the regression
 * suite (tests/test_fuzz.sh) needs no second, clang-built copy of everything; `make fuzz` builds
 * the real libFuzzer harnesses with clang.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The whole file, or NULL (a message on stderr). */
static uint8_t *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay: cannot open %s\n", path);
        return NULL;
    }
    uint8_t *buf = NULL;
    size_t cap = 0;
    *size = 0;
    for (;;) {
        if (*size == cap) {
            cap = cap ? 2 * cap : 1 << 16;
            uint8_t *b = realloc(buf, cap);
            if (!b) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = b;
        }
        const size_t n = fread(buf + *size, 1, cap - *size, f);
        *size += n;
        if (n == 0)
            break;
    }
    fclose(f);
    return buf;
}

int main(int argc, char **argv)
{
    int ran = 0;
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] == '-')
            continue;
        size_t size;
        uint8_t *data = read_file(argv[i], &size);
        if (!data)
            return 1;
        fprintf(stderr, "Running: %s\n", argv[i]);
        LLVMFuzzerTestOneInput(data, size);
        free(data);
        ran++;
    }
    fprintf(stderr, "replay: %d input(s)\n", ran);
    return 0;
}
